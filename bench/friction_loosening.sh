#!/usr/bin/env bash
# The loosening curve behind --target-void-fraction's search (src/pipeline/generate.cpp,
# loosening(); docs/generate.md, "A target void fraction"): calibration beds (a = 5, 10, 20
# with 500, 1 193 and 4 777 spheres: the first spheres of 1 500, 4 000 and 10 000 up to 15 Dp of
# L0), seeds 1-3, at friction mu = 0 to 1 at the spheres and walls alike. Prints each bed, then
# per mu the mean over the seeds' share of e(1) - e(0), averaged over a, and each a's difference
# to that mean.
#
# Usage: bench/friction_loosening.sh PACKBED OUT    (OUT is replaced)
set -euo pipefail
exe=$(realpath "$1")
out=$2
rm -rf "$out"
mkdir -p "$out"
for a_n in "5 500" "10 1193" "20 4777"; do
  read -r a n <<<"$a_n"
  for mu in 0 0.005 0.01 0.02 0.03 0.05 0.1 0.3 1; do
    for s in 1 2 3; do
      d=$out/a$a-mu$mu-s$s
      "$exe" generate -a "$a" -n "$n" -s "$s" --friction "$mu" --wall-friction "$mu" -o "$d" -q \
        --no-analysis
      echo "$a $n $mu $s $(python3 -c "import json; print(json.load(open('$d/summary.json'))['void_fraction'])")"
    done
  done
done | tee "$out/beds.txt"
python3 - "$out/beds.txt" <<'PY'
import collections, sys
e = collections.defaultdict(list)
for line in open(sys.argv[1]):
    a, _, mu, _, v = line.split()
    e[(int(a), float(mu))].append(float(v))
mean = {k: sum(v) / len(v) for k, v in e.items()}
sizes = sorted({a for a, _ in mean})
mus = sorted({mu for _, mu in mean})
share = {(a, mu): (mean[(a, mu)] - mean[(a, 0.0)]) / (mean[(a, 1.0)] - mean[(a, 0.0)])
         for a, mu in mean}
print("# mu, mean share of e(1) - e(0), each a's difference (a =", sizes, ")")
for mu in mus:
    m = sum(share[(a, mu)] for a in sizes) / len(sizes)
    print(mu, round(m, 3), [round(share[(a, mu)] - m, 3) for a in sizes])
print("# e(1) - e(0):", {a: round(mean[(a, 1.0)] - mean[(a, 0.0)], 4) for a in sizes})
PY
