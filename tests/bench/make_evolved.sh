#!/usr/bin/env bash
# Makes the evolved populations of bench_evolved (issue 42): for each paper preset, a run of the
# preset with its full settings (1 s settle + 10 s, the early end on) but population 5, seed 1,
# for 21 generations (0..20); its last checkpoint is kept as
# tests/bench/evolved/<preset>.checkpoint.json. Made with db6afc9's bhm (checkpoint format 3,
# which that baseline and every later build read), so the benchmark can resume the same
# population on both.
#   tests/bench/make_evolved.sh [BUILD_DIR] [PRESET...]   (run from the repository root)
set -euo pipefail
build=${1:-build}
shift || true
presets=("$@")
[ ${#presets[@]} -gt 0 ] || presets=(paper-exp1 paper-exp2 paper-exp3)
bhm="$build/bin/bhm"
[ -x "$bhm" ] || { echo "make_evolved.sh: $bhm not built" >&2; exit 1; }
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
mkdir -p tests/bench/evolved
for preset in "${presets[@]}"; do
    python3 - "assets/experiments/$preset.json" "$work/$preset.json" <<'PY'
import json, sys
e = json.load(open(sys.argv[1]))
e["evolution"]["population"] = 5
json.dump(e, open(sys.argv[2], "w"), indent=2)
PY
    "$bhm" evolve "$work/$preset.json" --out "$work/$preset" --seed 1 --threads 2 \
        --generations 21 >/dev/null
    cp "$work/$preset/checkpoint.json" "tests/bench/evolved/$preset.checkpoint.json"
    tail -n 1 "$work/$preset/fitness.csv" >&2
done
