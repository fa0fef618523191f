#!/usr/bin/env bash
# bhm calibrate under mpirun -n 2 (docs/cluster.md, docs/calibration.md): the scan's and the
# Jacobian's simulations spread over the ranks give the single-process result bit for bit:
# report.json (but its wall_s and threads), calibrated-experiment.json and the simulated tracks
# are equal. A short fit of E on the shipped example (16 simulations of ~0.3 s).
# usage: mpi_calibrate_test.sh BHM MPIEXEC WORKDIR   (MPIEXEC "none": bhm built without MPI)
set -euo pipefail
bhm=$1 mpiexec=$2 work=$3
root=$(cd "$(dirname "$0")/../.." && pwd)
if [ "$mpiexec" = none ] || [ ! -x "$mpiexec" ]; then
    echo "SKIP: bhm was built without MPI (libopenmpi-dev), so bhm calibrate cannot run under mpirun"
    exit 77
fi
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
export OMPI_MCA_rmaps_base_oversubscribe=1
export OMPI_MCA_btl=self,vader OMPI_MCA_btl_vader_single_copy_mechanism=none

rm -rf "$work"
mkdir -p "$work"
cd "$work"
fail() {
    echo "FAIL: $*" >&2
    exit 1
}
args=("$root/assets/experiments/quick-demo.json"
      --body "$root/assets/tracks/quick-demo-bilayer.body.json"
      --track "$root/assets/tracks/quick-demo-tip.csv"
      --fit E --max-simulations 12 --threads 1)

if ! "$bhm" calibrate "${args[@]}" --out alone > alone.log 2>&1; then
    if grep -q "without NLopt" alone.log; then
        echo "SKIP: bhm was built without NLopt, so it cannot calibrate"
        exit 77
    fi
    cat alone.log
    fail "alone"
fi
timeout 240 "$mpiexec" -n 2 "$bhm" calibrate "${args[@]}" --out ranks > ranks.log 2>&1 ||
    { cat ranks.log; fail "mpirun -n 2"; }
grep -q "bhm calibrate: 2 MPI ranks" ranks.log || { cat ranks.log; fail "no MPI ranks line"; }

python3 - alone/report.json ranks/report.json <<'PY' || fail "report.json differs"
import json, sys
a, b = (json.load(open(p)) for p in sys.argv[1:3])
for r in (a, b):
    for k in ("wall_s", "threads"):
        r.pop(k)
if a != b:
    for k in a:
        if a[k] != b.get(k):
            print("differs:", k, a[k], b.get(k))
    sys.exit(1)
print("report.json equal:", a["fit"][0]["name"], a["fit"][0]["fitted"], a["simulations"]["total"],
      "simulations")
PY
# The calibrated experiment's description names its own report (alone/ or ranks/).
sed 's#ranks/report.json#alone/report.json#' ranks/calibrated-experiment.json > ranks-experiment.json
cmp -s alone/calibrated-experiment.json ranks-experiment.json || fail "calibrated-experiment.json differs"
for f in simulated-before.csv simulated-after.csv; do
    cmp -s "alone/$f" "ranks/$f" || fail "$f differs"
done
echo "PASS: bhm calibrate on 2 ranks equals one process"
