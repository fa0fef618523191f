#!/usr/bin/env bash
# bhm evolve under mpirun on a tiny experiment (tests/mpi/tiny-experiment.json, seconds per run).
# usage: mpi_evolve_test.sh CASE BHM MPIEXEC WORKDIR
#   same-run  the same seed gives the same run on 1 process and on 1, 2, 3 ranks x 1-2 threads
#   hung-rank a rank that stops answering: exit 3 with a clear message, the last complete
#             generation checkpointed; --resume on another number of ranks finishes the same run
#   dead-rank a rank that exits: the job ends, the checkpoint is complete, a single-process
#             --resume finishes the same run
#   failing-rank a rank that reports an error: rank 0 stops with that rank's message (exit 1),
#             every other rank leaves cleanly, and --resume on 2 ranks finishes the same run
#   stop      SIGTERM to rank 0 while the ranks simulate: the generation is abandoned everywhere,
#             every rank exits 0, and --resume on 3 ranks finishes the same run
# "The same run" = fitness.csv, champion.json and checkpoint.json equal once the wall-clock fields
# (wall_s, elapsed_s, sim_wall_s: the only machine-dependent ones) are removed.
set -euo pipefail
case_name=$1 bhm=$2 mpiexec=$3 work=$4
here=$(cd "$(dirname "$0")" && pwd)
experiment=$here/tiny-experiment.json
generations=5
# CI runs as root on 2 cores: Open MPI refuses root without these, and more ranks than cores
# without --oversubscribe.
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
export OMPI_MCA_rmaps_base_oversubscribe=1
# Loopback only, shared memory without the ptrace-based single copy (refused in containers).
export OMPI_MCA_btl=self,vader OMPI_MCA_btl_vader_single_copy_mechanism=none

rm -rf "$work"
mkdir -p "$work"
cd "$work"
if [ "$case_name" = stop ]; then
    # Simulations of ~0.1 s instead of milliseconds, so the signal lands inside a generation.
    python3 - "$experiment" slow.json <<'PY'
import json, sys
e = json.load(open(sys.argv[1]))
e["simulation"]["evaluate_s"] = 1.0
json.dump(e, open(sys.argv[2], "w"))
PY
    experiment=$work/slow.json
    generations=3
fi

fail() {
    echo "FAIL: $*" >&2
    exit 1
}

evolve_alone() {  # DIR ARGS...
    local dir=$1
    shift
    "$bhm" evolve "$experiment" --out "$dir" --generations $generations "$@"
}

evolve_mpi() {  # RANKS DIR ARGS...
    local ranks=$1 dir=$2
    shift 2
    timeout 120 "$mpiexec" -n "$ranks" "$bhm" evolve "$experiment" --out "$dir" \
        --generations $generations "$@"
}

same_run() {  # REFERENCE OTHER
    python3 - "$1" "$2" <<'PY' || fail "$2 differs from $1"
import json, sys
# checksum: checkpoint format 2 wraps the payload with its CRC-32, which covers the timings
TIMING = {"wall_s", "elapsed_s", "sim_wall_s", "checksum"}
def strip(v):
    if isinstance(v, dict):
        return {k: strip(x) for k, x in v.items() if k not in TIMING}
    if isinstance(v, list):
        return [strip(x) for x in v]
    return v
def csv(path):
    lines = open(path).read().splitlines()
    column = lines[0].split(",").index("wall_s")
    return [[c for i, c in enumerate(l.split(",")) if i != column] for l in lines]
a, b = sys.argv[1], sys.argv[2]
ok = True
for name in ("champion.json", "checkpoint.json"):
    if strip(json.load(open(f"{a}/{name}"))) != strip(json.load(open(f"{b}/{name}"))):
        print(f"{name} differs", file=sys.stderr); ok = False
if csv(f"{a}/fitness.csv") != csv(f"{b}/fitness.csv"):
    print("fitness.csv differs", file=sys.stderr); ok = False
sys.exit(0 if ok else 1)
PY
}

checkpoint_generation() {  # DIR
    python3 -c 'import json,sys; j=json.load(open(sys.argv[1])); print(j.get("payload", j)["generation"])' \
        "$1/checkpoint.json"
}

evolve_alone reference --threads 2 >/dev/null 2>&1 || fail "the single-process reference run"

case $case_name in
same-run)
    for setting in "1 1" "2 1" "2 2" "3 1"; do
        read -r ranks threads <<<"$setting"
        dir=ranks$ranks-threads$threads
        evolve_mpi "$ranks" "$dir" --threads "$threads" 2>"$dir.log" ||
            { cat "$dir.log"; fail "mpirun -n $ranks --threads $threads"; }
        if [ "$ranks" -gt 1 ]; then
            grep -q "$ranks MPI ranks" "$dir.log" || { cat "$dir.log"; fail "no rank summary"; }
        fi
        same_run reference "$dir"
        echo "same run on $ranks rank(s) x $threads thread(s)"
    done
    ;;
hung-rank)
    # Rank 2 goes silent at its first result of batch 3 (generation 2).
    status=0
    BHM_MPI_TEST_FAULT=2:3:hang evolve_mpi 3 hung --threads 1 --rank-timeout 3 2>hung.log ||
        status=$?
    cat hung.log
    [ "$status" -eq 3 ] || fail "exit status $status, expected 3"
    grep -q "rank 2 on .* sent nothing for [0-9]* s while simulating" hung.log ||
        fail "no message naming the lost rank"
    grep -q "checkpoint of generation 1 .* is complete: continue with --resume" hung.log ||
        fail "no message naming the checkpoint"
    [ "$(checkpoint_generation hung)" -eq 1 ] || fail "checkpoint is not generation 1"
    evolve_mpi 2 hung --threads 1 --resume 2>resume.log || { cat resume.log; fail "resume"; }
    same_run reference hung
    echo "hung rank detected; resumed on 2 ranks: same run"
    ;;
dead-rank)
    # Rank 1 exits at its first result of batch 2 (generation 1); mpirun ends the job.
    status=0
    BHM_MPI_TEST_FAULT=1:2:exit evolve_mpi 3 dead --threads 1 --rank-timeout 5 2>dead.log ||
        status=$?
    cat dead.log
    [ "$status" -ne 0 ] || fail "exit status 0 after a rank died"
    [ "$(checkpoint_generation dead)" -eq 0 ] || fail "checkpoint is not generation 0"
    evolve_alone dead --threads 1 --resume 2>resume.log || { cat resume.log; fail "resume"; }
    same_run reference dead
    echo "dead rank ended the job; resumed on one process: same run"
    ;;
failing-rank)
    # Rank 1 reports an error instead of its first result of batch 2 (generation 1).
    status=0
    BHM_MPI_TEST_FAULT=1:2:fail evolve_mpi 3 failing --threads 1 2>failing.log || status=$?
    cat failing.log
    [ "$status" -eq 1 ] || fail "exit status $status, expected 1"
    grep -q "bhm evolve: rank 1 on .*: injected failure" failing.log ||
        fail "no message naming rank 1"
    [ "$(checkpoint_generation failing)" -eq 0 ] || fail "checkpoint is not generation 0"
    evolve_mpi 2 failing --threads 1 --resume 2>resume.log || { cat resume.log; fail "resume"; }
    same_run reference failing
    echo "failing rank stopped the run; resumed on 2 ranks: same run"
    ;;
stop)
    # shellcheck disable=SC2016  # $$ and $OMPI_COMM_WORLD_RANK belong to the rank shell
    timeout 120 "$mpiexec" -n 2 bash -c 'echo $$ >"rank$OMPI_COMM_WORLD_RANK.pid"; exec "$@"' \
        rank "$bhm" evolve "$experiment" --out stopped --generations $generations --threads 1 \
        2>stopped.log &
    launcher=$!
    # Once generation 0 is on disk, generation 1 is being simulated.
    for _ in $(seq 2400); do  # up to 2 minutes on a loaded machine
        [ -f stopped/fitness.csv ] && [ "$(wc -l <stopped/fitness.csv)" -ge 2 ] && break
        sleep 0.05
    done
    kill -TERM "$(cat rank0.pid)"
    status=0
    wait "$launcher" || status=$?
    cat stopped.log
    [ "$status" -eq 0 ] || fail "exit status $status after a stop, expected 0"
    grep -q "stopped; .*continue with --resume" stopped.log || fail "no stop message"
    evolve_mpi 3 stopped --threads 1 --resume 2>resume.log || { cat resume.log; fail "resume"; }
    same_run reference stopped
    echo "stop on 2 ranks, resumed on 3: same run"
    ;;
*)
    fail "unknown case $case_name"
    ;;
esac
rm -rf "$work"
