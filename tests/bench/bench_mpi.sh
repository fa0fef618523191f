#!/usr/bin/env bash
# bench_mpi: simulations per second of `bhm evolve` on 1..N MPI ranks (docs/cluster.md), as CSV
# (one row per setting). CMake copies this script to <build>/bin/bench_mpi when MPI is built, so
# scripts/bench.sh runs it with the others; run it from the repository root.
#
#   bench_mpi [EXPERIMENT.json] [GENERATIONS] [MAX_RANKS]
#
# Defaults: assets/experiments/quick-demo.json, 4 generations, ranks 1..3, one simulation thread
# per rank, the same seed every time (so every setting simulates the same bodies). Also one row of
# a single process (no mpirun) with MAX_RANKS threads: what MPI costs against threads on one
# machine. simulations_per_s = the run's simulations / its evolution wall time (fitness.csv's
# wall_s: MPI start-up excluded). speedup_vs_1 is against the 1-rank row of the same invocation.
# cpu_s_per_simulation = user + system CPU time of the whole process tree (every rank, start-up
# included) per simulation: what MPI costs in CPU, and a figure a loaded machine does not distort
# the way it distorts wall time.
# More ranks than cores are oversubscribed: on a 2-core machine 3 ranks cannot beat 2.
set -euo pipefail
bin=$(cd "$(dirname "$0")" && pwd)
experiment=${1:-assets/experiments/quick-demo.json}
generations=${2:-4}
max_ranks=${3:-3}
commit=${BHM_COMMIT:-unknown}
machine="$(uname -m) $(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2 | sed 's/^ //; s/,/ /g')"
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
export OMPI_MCA_rmaps_base_oversubscribe=1 OMPI_MCA_btl_vader_single_copy_mechanism=none
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT

# "SIMULATIONS WALL_S" of a finished run directory.
totals() {
    awk -F, 'NR == 1 { for (i = 1; i <= NF; i++) { if ($i == "simulations") s = i; if ($i == "wall_s") w = i } next }
             { sims += $s; wall = $w } END { print sims, wall }' "$1/fitness.csv"
}

echo "experiment,mode,ranks,threads_per_rank,generations,simulations,wall_s,simulations_per_s,speedup_vs_1,cpu_s_per_simulation,load_avg,machine,commit"
base_rate=""
row() {  # MODE RANKS THREADS DIR CPU_S
    local load sims wall rate speedup cpu
    load=$(cut -d' ' -f1 /proc/loadavg)
    read -r sims wall < <(totals "$4")
    rate=$(awk -v s="$sims" -v w="$wall" 'BEGIN { printf "%.3f", s / w }')
    [ -n "$base_rate" ] || base_rate=$rate
    speedup=$(awk -v r="$rate" -v b="$base_rate" 'BEGIN { printf "%.2f", r / b }')
    cpu=$(awk -v c="$5" -v s="$sims" 'BEGIN { printf "%.4f", c / s }')
    echo "$(basename "$experiment"),$1,$2,$3,$generations,$sims,$wall,$rate,$speedup,$cpu,$load,$machine,$commit"
    echo "bench_mpi: $1 $2 rank(s) x $3 thread(s): $rate simulations/s (x$speedup), $cpu CPU s per simulation, load $load" >&2
}

# Runs a command; the user + system CPU seconds of it and all its children land in $cpu_s.
timed() {
    local before status=0
    children_cpu_s
    before=$children
    "$@" || status=$?
    children_cpu_s
    cpu_s=$(awk -v a="$children" -v b="$before" 'BEGIN { printf "%.3f", a - b }')
    return $status
}
# $children = user + system seconds of this shell's finished children. `times` must run in this
# shell, not in a $(...) subshell (which has its own, empty, child times): it writes a file whose
# second line is the children's "XmY.YYYs XmY.YYYs".
children_cpu_s() {
    times >"$work/times"
    children=$(tail -n 1 "$work/times" | awk '{ split($1, u, "m"); split($2, s, "m");
        print u[1] * 60 + u[2] + s[1] * 60 + s[2] }')
}

for ((ranks = 1; ranks <= max_ranks; ranks++)); do
    dir=$work/mpi-$ranks
    timed mpirun -n "$ranks" "$bin/bhm" evolve "$experiment" --out "$dir" \
        --generations "$generations" --threads 1 --seed 1 2>"$dir.log" >/dev/null ||
        { cat "$dir.log" >&2; exit 1; }
    row mpi "$ranks" 1 "$dir" "$cpu_s"
done
dir=$work/process
timed "$bin/bhm" evolve "$experiment" --out "$dir" --generations "$generations" \
    --threads "$max_ranks" --seed 1 2>"$dir.log" >/dev/null || { cat "$dir.log" >&2; exit 1; }
row process 1 "$max_ranks" "$dir" "$cpu_s"
