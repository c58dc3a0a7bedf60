#!/usr/bin/env bash
# Frictional beds against published packings (docs/validation.md, "Friction"): the bulk sweep
# (a periodic cell of 12 x 12 Dp, 4 000 spheres, seed 1, mu = 0 to 10 at the spheres; solid
# fraction and coordination over the band 4 Dp clear of floor and top) and the tube sweep
# (a = 5, 10, 20 with 1 500, 4 000 and 10 000 spheres, seeds 1-3, mu = 0, 0.02 and 0.05 at the
# spheres and the walls; summary.json's void fraction). One line per bed, with its steps and
# seconds.
#
# Usage: bench/friction_sweep.sh PACKBED OUT    (OUT is replaced)
set -euo pipefail
exe=$(realpath "$1")
out=$2
rm -rf "$out"
mkdir -p "$out"
echo "# bulk: mu phi Z_all Z_4_or_more rattlers spheres steps seconds"
for mu in 0 0.01 0.1 0.3 1 10; do
  d=$out/bulk-mu$mu
  /usr/bin/time -f "%e" -o "$d.time" "$exe" generate --container periodic:12,12 -n 4000 -s 1 \
    --friction "$mu" -o "$d" -q --no-analysis
  "$exe" analyze "$d/particles.csv" --band-clearance 4 -q -o "$d.analysis"
  python3 - "$mu" "$d" <<'PY'
import json, sys
mu, d = sys.argv[1], sys.argv[2]
s = json.load(open(d + "/summary.json"))
a = json.load(open(d + ".analysis/summary.json"))
c = a["coordination"]
print(mu, round(1 - a["void_fraction"], 4), round(c["mean"], 3), round(c["mean_without_rattlers"], 3),
      c["rattlers"], c["spheres"], s["iterations"], open(d + ".time").read().strip(), flush=True)
PY
done
echo "# tubes: a mu seed e steps seconds"
for a in 5 10 20; do
  case $a in 5) n=1500 ;; 10) n=4000 ;; *) n=10000 ;; esac
  for mu in 0 0.02 0.05; do
    for s in 1 2 3; do
      d=$out/a$a-mu$mu-s$s
      /usr/bin/time -f "%e" -o "$d.time" "$exe" generate -a $a -n $n -s $s --friction $mu \
        --wall-friction $mu -o "$d" -q --no-analysis
      python3 -c "import json; s = json.load(open('$d/summary.json')); print($a, $mu, $s, round(s['void_fraction'], 4), s['iterations'], open('$d.time').read().strip(), flush=True)"
    done
  done
done
