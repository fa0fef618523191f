#!/usr/bin/env bash
# Sets up, builds and runs the whole test suite (the README's second command; .ci/run calls it).
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/setup.sh
scripts/build.sh
cd "${BHM_BUILD_DIR:-build}"
export GALLIUM_DRIVER=llvmpipe MESA_SHADER_CACHE_DISABLE=true
ctest --output-on-failure -j"$(nproc)" --timeout 600
