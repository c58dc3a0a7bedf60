#!/usr/bin/env bash
# Friction's cost, side by side in one run (docs/performance.md, "Friction"): a = 20 with
# 10 000 spheres (seed 1) frictionless and at mu = 0.02, 0.1 and 0.3 (spheres and walls), then
# a = 10 with 4 000 spheres frictionless and with --target-void-fraction 0.40, 0.42 and 0.45.
# One line per run: what, steps (or whole beds and calibration runs), seconds, seconds over the
# frictionless run's.
#
# Usage: bench/time_friction.sh PACKBED OUT    (OUT is replaced)
set -euo pipefail
exe=$(realpath "$1")
out=$2
rm -rf "$out"
mkdir -p "$out"
run() { # name, then generate's options
  local name=$1
  shift
  /usr/bin/time -f "%e" -o "$out/$name.time" "$exe" generate "$@" -o "$out/$name" -q --no-analysis
}
report() { # name, the frictionless run's name
  python3 - "$out" "$1" "$2" <<'PY'
import json, sys
out, name, base = sys.argv[1:]
s = json.load(open(f"{out}/{name}/summary.json"))
t = float(open(f"{out}/{name}.time").read())
t0 = float(open(f"{out}/{base}.time").read())
search = s.get("target_void_fraction")
steps = (f"{len(search['runs'])} whole, {len(search['calibration'])} calibration"
         if search else f"{s['iterations']} steps")
print(f"{name}: e {s['void_fraction']:.4f}, {steps}, {t:.2f} s, {t / t0:.2f} x", flush=True)
PY
}
run a20-mu0 -a 20 -n 10000 -s 1
report a20-mu0 a20-mu0
for mu in 0.02 0.1 0.3; do
  run a20-mu$mu -a 20 -n 10000 -s 1 --friction $mu --wall-friction $mu
  report a20-mu$mu a20-mu0
done
run a10-mu0 -a 10 -n 4000 -s 1
report a10-mu0 a10-mu0
for e in 0.40 0.42 0.45; do
  run a10-e$e -a 10 -n 4000 -s 1 --target-void-fraction $e
  report a10-e$e a10-mu0
done
