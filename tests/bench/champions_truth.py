#!/usr/bin/env python3
"""Champions against the continuum (issue 40): how true the engine is where evolution goes.

For each paper preset, short runs (a shortened copy of the preset: population 10, G
generations, 0.25 s settle + 1.25 s evaluation, seeds 1, 2, ..., or from --first-seed) each hand over their
champion until N distinct bodies are in hand (short runs often hand over the same body, most often
the full workspace; a body equal to an earlier seed's is named on stderr and not verified again; at
most --max-seeds runs per preset), and `bhm verify` compares each body, under the preset's own experiment, with CalculiX at rest and at
+A and -A (docs/verify.md). One row per champion: the verdict's measure, ours / CalculiX on the
tip and the centre of mass (vertical component, signed: > 0 is ours moving more) at rest, +A
and -A, the verdict's worst relative difference (its own measures, docs/verify.md), and for
nonlinear steps the continuum law it was judged on, the other law's difference and the laws' spread.

    tests/bench/champions_truth.py [--build build] [--per-preset 10] [--first-seed 1] [--generations 3]
                                   [--presets paper-exp1,...] [--work DIR] [--csv PATH]
                                   [-- extra bhm verify options, e.g. --no-mesh-error]

The runs and reports stay in --work (default: a fresh temporary folder, kept and named at the end)
so a report can be opened in the studio; the table goes to stdout and, with --csv, to a file.
"""
import argparse
import csv
import hashlib
import json
import os
import subprocess
import sys
import tempfile
import time

PRESETS = ["paper-exp1", "paper-exp1-attached", "paper-exp2", "paper-exp3"]
COLUMNS = ["preset", "seed", "voxels", "held", "agrees", "verdict", "worst_pct", "rest_tip_pct",
           "rest_com_pct", "plusA_tip_pct", "plusA_com_pct", "minusA_tip_pct", "minusA_com_pct",
           "law", "other_law", "other_law_pct", "law_spread_pct", "fem_element", "fem_nodes", "wall_s"]


def shortened(preset_path, out_path, generations):
    e = json.load(open(preset_path))
    e["evolution"]["population"] = 10
    e["evolution"]["generations"] = generations
    e["simulation"]["settle_s"] = 0.25
    e["simulation"]["evaluate_s"] = 1.25
    with open(out_path, "w") as f:
        json.dump(e, f, indent=2)


def signed_pct(load, measure):
    """Ours against CalculiX on the vertical (z) component, signed: > 0 is the engine moving more."""
    fem = load["fem"][measure][-1]
    ours = load["engine"][measure][-1]
    if abs(fem) < 1e-12:
        return None
    return 100.0 * (ours - fem) / abs(fem)


def pct(fraction):
    """A relative difference as a percentage with one decimal, or empty when there is none."""
    return "" if fraction is None else f"{100.0 * fraction:.1f}"


def run(cmd, log):
    with open(log, "a") as f:
        f.write("$ " + " ".join(cmd) + "\n")
        f.flush()
        return subprocess.run(cmd, stdout=f, stderr=subprocess.STDOUT).returncode


def main():
    argv = sys.argv[1:]
    extra = []
    if "--" in argv:
        extra = argv[argv.index("--") + 1:]
        argv = argv[:argv.index("--")]
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("--build", default="build")
    p.add_argument("--per-preset", type=int, default=10)
    p.add_argument("--first-seed", type=int, default=1,
                   help="the first seed (to add champions to a table)")
    p.add_argument("--max-seeds", type=int, default=0,
                   help="runs per preset at most, to find --per-preset distinct bodies (default 3 x per-preset)")
    p.add_argument("--generations", type=int, default=3)
    p.add_argument("--presets", default=",".join(PRESETS))
    p.add_argument("--work")
    p.add_argument("--csv")
    a = p.parse_args(argv)
    bhm = os.path.join(a.build, "bin", "bhm")
    if not os.access(bhm, os.X_OK):
        sys.exit(f"champions_truth.py: {bhm}: not built (cmake --build {a.build} --target bhm)")
    work = a.work or tempfile.mkdtemp(prefix="champions-truth-")
    os.makedirs(work, exist_ok=True)
    log = os.path.join(work, "log.txt")
    rows = []
    out = csv.writer(sys.stdout)
    out.writerow(COLUMNS)
    for preset in a.presets.split(","):
        preset_path = os.path.join("assets", "experiments", preset + ".json")
        if not os.path.exists(preset_path):
            sys.exit(f"champions_truth.py: --presets: no preset {preset_path}")
        short = os.path.join(work, preset + "-short.json")
        shortened(preset_path, short, a.generations)
        seen = {}  # body file's digest -> the first seed that handed it over
        max_seeds = a.max_seeds or 3 * a.per_preset
        for seed in range(a.first_seed, a.first_seed + max_seeds):
            if len(seen) >= a.per_preset:
                break
            run_dir = os.path.join(work, f"{preset}-{seed}")
            body = run_dir + ".body.json"
            report_dir = run_dir + "-verify"
            started = time.time()
            if not os.path.exists(body):
                if run(["nice", bhm, "evolve", short, "--out", run_dir, "--seed", str(seed),
                        "--threads", "2"], log) != 0 or \
                   run([bhm, "export", run_dir, "--body-out", body], log) != 0:
                    print(f"# {preset} seed {seed}: evolve or export failed (see {log})",
                          file=sys.stderr)
                    continue
            # The body file holds only the body (size, layers, fibres, controller), so equal
            # files are equal bodies.
            digest = hashlib.sha256(open(body, "rb").read()).hexdigest()
            if digest in seen:
                print(f"# {preset} seed {seed}: the same body as seed {seen[digest]}, not verified again",
                      file=sys.stderr)
                continue
            seen[digest] = seed
            code = run(["nice", bhm, "verify", preset_path, "--body", body, "--out", report_dir]
                       + extra, log)
            report_path = os.path.join(report_dir, "report.json")
            if code != 0 or not os.path.exists(report_path):
                print(f"# {preset} seed {seed}: verify failed (exit {code}, see {log})",
                      file=sys.stderr)
                continue
            r = json.load(open(report_path))
            loads = {load["load"]: load for load in r.get("loads", [])}
            fem = r.get("fem", {})
            row = {"preset": preset, "seed": seed, "voxels": r.get("voxels"),
                   "held": r.get("held_voxels"), "agrees": r.get("agrees"),
                   "verdict": r.get("verdict", r.get("status")),
                   "worst_pct": "" if r.get("worst_relative_difference") is None
                   else f"{100.0 * r['worst_relative_difference']:.1f}",
                   "law": fem.get("material_law", ""),
                   "other_law": (fem.get("other_law") or {}).get("law", ""),
                   "other_law_pct": pct((fem.get("other_law") or {}).get("worst")),
                   "law_spread_pct": pct(fem.get("law_spread")),
                   "fem_element": r.get("fem", {}).get("element"),
                   "fem_nodes": r.get("fem", {}).get("nodes"),
                   "wall_s": round(time.time() - started, 1)}
            for name, key in (("rest", "rest"), ("plusA", "+A"), ("minusA", "-A")):
                load = loads.get(key)
                for measure, column in (("tip_displacement_m", "tip"),
                                        ("com_displacement_m", "com")):
                    value = signed_pct(load, measure) if load else None
                    row[f"{name}_{column}_pct"] = "" if value is None else f"{value:+.1f}"
            rows.append(row)
            out.writerow([row.get(c, "") for c in COLUMNS])
            sys.stdout.flush()
    if a.csv:
        with open(a.csv + ".tmp", "w", newline="") as f:
            w = csv.writer(f)
            w.writerow(COLUMNS)
            for row in rows:
                w.writerow([row.get(c, "") for c in COLUMNS])
        os.replace(a.csv + ".tmp", a.csv)
    # Summary per preset: the spread of the rest and +A differences on the tip.
    for preset in a.presets.split(","):
        mine = [r for r in rows if r["preset"] == preset]
        if not mine:
            continue
        agrees = sum(1 for r in mine if r["agrees"])
        def spread(key):
            v = [float(r[key]) for r in mine if r[key] != ""]
            return f"{min(v):+.1f}..{max(v):+.1f} %" if v else "-"
        print(f"# {preset}: {agrees}/{len(mine)} distinct bodies agree; tip at rest {spread('rest_tip_pct')}, "
              f"at +A {spread('plusA_tip_pct')}", file=sys.stderr)
    print(f"# runs and reports kept in {work}", file=sys.stderr)


if __name__ == "__main__":
    main()
