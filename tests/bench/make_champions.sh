#!/usr/bin/env bash
# Adds champions of short evolution runs to the benchmark corpus: for each paper preset, a run of
# a shortened copy (population 10, 2 generations, 0.25 s settle + 1.25 s evaluation, seeds 1 and 2),
# whose champion body is written to tests/bench/corpus/<preset>-champions.json in the corpus
# format of make_bench_corpus (simulated by bench_engine with the preset's own full settings).
#   tests/bench/make_champions.sh [BUILD_DIR]     (run from the repository root)
set -euo pipefail
build=${1:-build}
bhm="$build/bin/bhm"
[ -x "$bhm" ] || { echo "make_champions.sh: $bhm not built" >&2; exit 1; }
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
for preset in paper-exp1 paper-exp1-attached paper-exp2 paper-exp3; do
    for seed in 1 2; do
        python3 - "assets/experiments/$preset.json" "$work/$preset.json" <<'EOF'
import json, sys
e = json.load(open(sys.argv[1]))
e["evolution"]["population"] = 10
e["evolution"]["generations"] = 2
e["simulation"]["settle_s"] = 0.25
e["simulation"]["evaluate_s"] = 1.25
json.dump(e, open(sys.argv[2], "w"), indent=2)
EOF
        "$bhm" evolve "$work/$preset.json" --out "$work/$preset-$seed" --seed "$seed" --threads 2 \
            >/dev/null
        "$bhm" export "$work/$preset-$seed" --body-out "$work/$preset-$seed.body.json" >/dev/null
    done
    python3 - "$preset" "$work" <<'EOF'
import json, sys
preset, work = sys.argv[1], sys.argv[2]
bodies = []
for seed in (1, 2):
    body = json.load(open(f"{work}/{preset}-{seed}.body.json"))
    voxels = sum(ch != "0" for layer in body["layers"] for ch in layer)
    bodies.append({"name": f"champion-seed{seed}", "voxels": voxels, "body": body})
out = {"experiment": preset, "seed": None, "bodies": bodies,
       "note": "champions of 2-generation runs (population 10, 0.25 s + 1.25 s), seeds 1-2"}
path = f"tests/bench/corpus/{preset}-champions.json"
with open(path + ".tmp", "w") as f:
    f.write(json.dumps(out, indent=1) + "\n")
import os
os.replace(path + ".tmp", path)
print(path, [b["voxels"] for b in bodies], file=sys.stderr)
EOF
done
