#!/usr/bin/env bash
# A pellet bed's cost beside a sphere bed's, side by side in one run (docs/performance.md,
# "Pellets"): 40 cylinders L = D (cylinder:1,1) and 40 spheres of Dp = 1 in a tube of a = 4,
# seed 1, one thread. One line per run: steps, the relaxation's seconds (summary.json's),
# milliseconds per particle-step, and the pellet's cost per particle-step over the sphere's.
#
# Usage: bench/time_pellets.sh PACKBED OUT    (OUT is replaced)
set -euo pipefail
exe=$(realpath "$1")
out=$2
rm -rf "$out"
mkdir -p "$out"
/usr/bin/time -f "%e" -o "$out/spheres.time" "$exe" generate -a 4 -n 40 -s 1 --threads 1 \
  --no-analysis -q -o "$out/spheres"
/usr/bin/time -f "%e" -o "$out/pellets.time" "$exe" generate --shape cylinder:1,1 -a 4 -n 40 \
  -s 1 --threads 1 -q -o "$out/pellets"
python3 - "$out" <<'PY'
import json, sys
out = sys.argv[1]
cost = {}
for name, key in (("spheres", "iterations"), ("pellets", "steps")):
    s = json.load(open(f"{out}/{name}/summary.json"))
    t = s["seconds"]  # the relaxation's own, without the start and the files
    steps = s[key]
    cost[name] = t / steps / s["particles"]
    print(f"{name}: {steps} steps, {t:.4g} s, {1e3 * t / steps / s['particles']:.4f} ms a "
          f"particle-step, e {s.get('void_fraction', float('nan')):.4f}", flush=True)
print(f"pellet over sphere, per particle-step: {cost['pellets'] / cost['spheres']:.0f} x")
PY
