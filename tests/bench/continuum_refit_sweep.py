#!/usr/bin/env python3
"""The refit of issue 40 (docs/physics.md, "The relaxed split on every link"): sweeps the penalty x
on the split of links of one material and the confinement's constants over the continuum suite
at rest, and prints per setting the fitting half's and the held-out half's worst and rms of
max(|tip|, |com|) % (the fit chose on the fitting half only); every row goes to
$BHM_SWEEP_ROWS (default continuum_sweep_rows.jsonl). Run from the repository root.

The shipped engine reads no environment: the sweep ran a probe build in which
engine/internal/poisson.cpp read x from BHM_PROBE_X ("inf": the equal split, no d on links of one
material) and engine/internal/link_confinement.cpp read c (BHM_PROBE_CA axial, BHM_PROBE_CB
bending and torsion) and the exponents of M / E (BHM_PROBE_QA, BHM_PROBE_QB) in
kappa = 1 + c n (M / E)^q (unset: the build's own constants). A value "=NAME" copies another key.
  python3 tests/bench/continuum_refit_sweep.py '{"BHM_PROBE_X": [3, 10, 30], "BHM_PROBE_QA": [-0.5, 0, 0.5]}'
With BHM_SWEEP_JUDGE=limit (2026-12-08, issue 40) a row that has a third mesh
(continuum_references_six.inc) is judged against its 2/4/6 Richardson limit (the "limit of 2/4/6
per edge" line the test prints under it) instead of the 4-per-edge reference.
"""
import itertools, json, os, re, subprocess, sys
FIT = ["p1c", "p2y", "p4sq", "p4liney", "neck1", "neck2x2", "p8", "full", "p1side"]  # as kFittingHalf
BIN = os.environ.get("BHM_TEST_ENGINE", "build/bin/test_engine")
ROW = re.compile(r"^(\S+)\s+nu (\S+)\s+tip .*?(?<!\+)([+-]\d+\.\d) %(?!\)).*com .*?(?<!\+)([+-]\d+\.\d) %(?!\))")
LIMIT = re.compile(r"^\s+limit of 2/4/6 per edge: tip .*?(?<!\+)([+-]\d+\.\d) %(?!\)).*com .*?(?<!\+)([+-]\d+\.\d) %(?!\))")

def run(env, tc="continuum: every case*"):
    e = dict(os.environ); e.update({k: str(v) for k, v in env.items()})
    out = subprocess.run(["nice", BIN, "-tc=" + tc, "--no-skip"], env=e, capture_output=True, text=True).stdout
    rows, last = {}, None
    against_limit = os.environ.get("BHM_SWEEP_JUDGE") == "limit"
    for line in out.splitlines():
        m = ROW.match(line)
        if m and "actuated" not in line:
            last = (m.group(1), float(m.group(2)))
            rows[last] = (float(m.group(3)), float(m.group(4)))
        elif against_limit and last and (m := LIMIT.match(line)):
            rows[last] = (float(m.group(1)), float(m.group(2)))
    return rows

def score(rows, names):
    w = [max(abs(t), abs(c)) for (n, nu), (t, c) in rows.items() if n in names]
    return max(w), (sum(x * x for x in w) / len(w)) ** 0.5

if __name__ == "__main__":
    grid = json.loads(sys.argv[1])  # {"BHM_PROBE_X": [...], ...}
    keys = list(grid)
    for vals in itertools.product(*[grid[k] for k in keys]):
        env = dict(zip(keys, vals))
        for k, v in list(env.items()):
            if isinstance(v, str) and v.startswith('='): env[k] = env[v[1:]]
        rows = run(env)
        held = [n for (n, _) in rows if n not in FIT]
        fmax, frms = score(rows, FIT)
        hmax, hrms = score(rows, set(held))
        print(json.dumps({"env": env, "fit_max": fmax, "fit_rms": round(frms, 2),
                          "held_max": hmax, "held_rms": round(hrms, 2)}), flush=True)
        with open(os.environ.get("BHM_SWEEP_ROWS", "continuum_sweep_rows.jsonl"), "a") as f:
            f.write(json.dumps({"env": env, "rows": {f"{n}@{nu}": v for (n, nu), v in rows.items()}}) + "\n")
