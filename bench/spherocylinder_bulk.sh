#!/usr/bin/env bash
# The bulk packing fraction of frictionless spherocylinders poured into a periodic cell,
# against L / D (L the cylindrical part): one bed per L / D, D chosen so that d_v = 1, the cell
# W d_v wide, the solid fraction 1 - e in the band clear of the floor and the top by C d_v.
# Beside the maximally random jammed packings of Imaz Gonzalez et al. 2023 (0.721 at L / D =
# 0.45) in docs/validation.md.
#
# Usage: bench/spherocylinder_bulk.sh PACKBED OUT [N] [W] [C] [SEED]   (OUT is replaced)
set -euo pipefail
exe=$(realpath "$1")
out=$2
n=${3:-500}
w=${4:-6}
c=${5:-2.5}
seed=${6:-1}
rm -rf "$out"
mkdir -p "$out"
printf 'L/D  D/d_v  steps  seconds  max_pair/D  solid_fraction\n'
for ld in 0 0.25 0.45 0.7 1 1.5 2; do
    d=$(python3 -c "print(repr((1 + 1.5 * $ld) ** (-1 / 3)))")
    l=$(python3 -c "print(repr($ld * $d))")
    $exe generate --shape "spherocylinder:$d,$l" --container "periodic:$w,$w" -n "$n" -s "$seed" \
        --band-clearance "$c" -q -o "$out/$ld"
    python3 - "$out/$ld/summary.json" "$ld" "$d" <<'PY'
import json, sys
s = json.load(open(sys.argv[1]))
d = float(sys.argv[3])
print(f"{sys.argv[2]:4}  {d:.4f}  {s['steps']:6d}  {s['seconds']:7.1f}  "
      f"{s['max_penetration_pair'] / d:.2e}  {1 - s['void_fraction']:.4f}")
PY
done
