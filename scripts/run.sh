#!/usr/bin/env bash
# The README's first command: installs what is missing, builds, and runs the main job.
# With a display: opens BHM Studio on the quick demo. Without one: a short headless evolution of the
# quick demo preset, then a rendered PNG of its champion; prints where both are.
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/setup.sh
scripts/build.sh
bhm=build/bin/bhm
preset=assets/experiments/quick-demo.json
if [ -n "${DISPLAY:-}${WAYLAND_DISPLAY:-}" ] && [ -z "${BHM_HEADLESS:-}" ]; then
  exec "$bhm" studio "$preset"
fi
out=${BHM_OUT:-runs/quick-demo-$(date +%Y%m%d-%H%M%S)}
echo "No display: running a short headless evolution of $preset into $out" >&2
"$bhm" evolve "$preset" --out "$out"
"$bhm" export "$out" --body-out "$out/champion-body.json" >/dev/null
GALLIUM_DRIVER=${GALLIUM_DRIVER:-llvmpipe} "$bhm" render "$preset" --body "$out/champion-body.json" --out "$out/champion.png"
echo
echo "Results:        $out (fitness.csv, champion.json, champion.vxa, checkpoints)"
echo "Champion image: $out/champion.png"
