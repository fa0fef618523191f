#!/usr/bin/env bash
# Builds Release and runs every benchmark program (<build>/bin/bench_*), appending their CSV to
# tests/bench/results/<host>.csv. Each bench prints CSV on stdout (a header line, then rows) and
# notes on stderr, and reads the commit from $BHM_COMMIT. A header is written only when the
# results file does not hold it yet, so benches with different columns share one file as blocks.
#   scripts/bench.sh [BENCH_NAME...]   e.g. scripts/bench.sh bench_engine
# Environment: BHM_BUILD_DIR (default build), extra cmake args in BHM_CMAKE_ARGS (-DBHM_NATIVE=ON).
set -euo pipefail
cd "$(dirname "$0")/.."
build_dir=${BHM_BUILD_DIR:-build}
# shellcheck disable=SC2086
scripts/build.sh ${BHM_CMAKE_ARGS:-}

commit=$(git rev-parse --short HEAD 2>/dev/null || echo unknown)
# Uncommitted changes make the figures belong to no commit: say so.
if ! git diff --quiet HEAD -- 2>/dev/null; then commit="$commit-dirty"; fi
export BHM_COMMIT=$commit

host=$(hostname -s 2>/dev/null || hostname)
results_dir=tests/bench/results
mkdir -p "$results_dir"
results="$results_dir/$host.csv"

if [ $# -gt 0 ]; then
    benches=()
    for name in "$@"; do benches+=("$build_dir/bin/$name"); done
else
    benches=("$build_dir"/bin/bench_*)
fi

status=0
for bench in "${benches[@]}"; do
    [ -x "$bench" ] || { echo "bench.sh: $bench: no such benchmark program" >&2; status=1; continue; }
    echo "== $(basename "$bench") (commit $commit)" >&2
    if ! output=$("$bench"); then
        echo "bench.sh: $(basename "$bench") failed; nothing appended for it" >&2
        status=1
        continue
    fi
    header=$(printf '%s\n' "$output" | head -n 1)
    # Append to a temp copy, then rename: an interrupted run never leaves half a file.
    tmp="$results.tmp$$"
    if [ -f "$results" ]; then cp "$results" "$tmp"; else : >"$tmp"; fi
    grep -qxF "$header" "$tmp" || printf '%s\n' "$header" >>"$tmp"
    printf '%s\n' "$output" | tail -n +2 >>"$tmp"
    mv "$tmp" "$results"
    printf '%s\n' "$output"
done
echo "bench.sh: appended to $results" >&2
exit $status
