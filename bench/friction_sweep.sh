#!/usr/bin/env bash
# Frictional beds against published packings (docs/validation.md, "Friction"): the bulk sweep
# (a periodic cell of 12 x 12 Dp, 4 000 spheres, seed 1, mu = 0 to 10 at the spheres; solid
# fraction and coordination over the band 4 Dp clear of floor and top) and the tube sweep
# (a = 5, 10, 20, 30 with 1 500, 4 000, 10 000 and 20 000 spheres, seeds 1-10, mu = 0, 0.02, 0.03
# and 0.05 at the spheres and the walls; summary.json's void fraction). One line per bed, with
# its steps and seconds, then per a and mu the mean e over the seeds and its range), and the
# loose beds (a = 5, 10, 20, 30, seeds 1-10, --target-void-fraction at Zou & Yu's loose curve as
# `packbed correlations` gives it: the friction that follows it). The tubes take about 25
# minutes on 2 cores, the loose beds about 10, the bulk 15 s.
#
# Usage: bench/friction_sweep.sh PACKBED OUT [bulk|tubes|loose]    (OUT is replaced; all three
# by default)
set -euo pipefail
exe=$(realpath "$1")
out=$2
part=${3:-all}
rm -rf "$out"
mkdir -p "$out"
# The spheres of a tube bed at aspect ratio $1: 1 500, 4 000, 10 000, 20 000 at a = 5, 10, 20, 30.
spheres() { case $1 in 5) echo 1500 ;; 10) echo 4000 ;; 20) echo 10000 ;; *) echo 20000 ;; esac; }
# Generate into $1 with the other arguments, timed into $1.time; keep its summary only.
bed() {
  local d=$1
  shift
  /usr/bin/time -f "%e" -o "$d.time" "$exe" generate "$@" -o "$d" -q --no-analysis
}
if [[ $part == all || $part == bulk ]]; then
# Z without rattlers by analyze's rule for the bed's friction (a rattler: fewer than 2 contacts
# with friction, 4 without), and by the frictionless rule (fewer than 4) beside it.
echo "# bulk: mu phi Z_all Z_without_rattlers rattlers Z_4_or_more rattlers_4 spheres steps seconds"
for mu in 0 0.01 0.1 0.3 1 10; do
  d=$out/bulk-mu$mu
  bed "$d" --container periodic:12,12 -n 4000 -s 1 --friction "$mu"
  "$exe" analyze "$d/particles.csv" --band-clearance 4 -q -o "$d.analysis"
  "$exe" analyze "$d/particles.csv" --band-clearance 4 --friction 0 -q -o "$d.analysis4"
  python3 - "$mu" "$d" <<'PY'
import json, sys
mu, d = sys.argv[1], sys.argv[2]
s = json.load(open(d + "/summary.json"))
a = json.load(open(d + ".analysis/summary.json"))
c = a["coordination"]
c4 = json.load(open(d + ".analysis4/summary.json"))["coordination"]
print(mu, round(1 - a["void_fraction"], 4), round(c["mean"], 3), round(c["mean_without_rattlers"], 3),
      c["rattlers"], round(c4["mean_without_rattlers"], 3), c4["rattlers"], c["spheres"],
      s["iterations"], open(d + ".time").read().strip(), flush=True)
PY
done
fi
if [[ $part == all || $part == tubes ]]; then
echo "# tubes: a mu seed e steps seconds"
tubes=$out/tubes.txt
for a in 5 10 20 30; do
  for mu in 0 0.02 0.03 0.05; do
    for s in 1 2 3 4 5 6 7 8 9 10; do
      d=$out/a$a-mu$mu-s$s
      bed "$d" -a $a -n "$(spheres $a)" -s $s --friction $mu --wall-friction $mu
      python3 -c "import json; s = json.load(open('$d/summary.json')); print($a, $mu, $s, round(s['void_fraction'], 4), s['iterations'], open('$d.time').read().strip(), flush=True)" |
        tee -a "$tubes"
      rm -f "$d/particles.csv" "$d/particles.vtu" # 160 beds: keep their summaries
    done
  done
done
echo "# tubes: a mu mean_e min_e max_e seeds"
python3 - "$tubes" <<'PY'
import collections, sys
e = collections.defaultdict(list)
for line in open(sys.argv[1]):
    a, mu, _, v = line.split()[:4]
    e[(int(a), float(mu))].append(float(v))
for (a, mu), v in sorted(e.items()):
    print(a, mu, round(sum(v) / len(v), 4), min(v), max(v), len(v))
PY
fi
[[ $part == all || $part == loose ]] || exit 0
echo "# loose: a seed target e friction seconds"
loose=$out/loose.txt
for a in 5 10 20 30; do
  target=$("$exe" correlations --aspect-ratio $a --json |
    python3 -c "import json, sys; print(round(json.load(sys.stdin)['mean_void_fraction']['zou-yu-1995-loose']['value'], 4))")
  for s in 1 2 3 4 5 6 7 8 9 10; do
    d=$out/loose-a$a-s$s
    bed "$d" -a $a -n "$(spheres $a)" -s $s --target-void-fraction "$target"
    python3 -c "import json; s = json.load(open('$d/summary.json')); print($a, $s, $target, round(s['void_fraction'], 4), round(s['target_void_fraction']['friction'], 4), open('$d.time').read().strip(), flush=True)" |
      tee -a "$loose"
    rm -f "$d/particles.csv" "$d/particles.vtu"
  done
done
echo "# loose: a target mean_e mean_friction min_friction max_friction seeds"
python3 - "$loose" <<'PY'
import collections, sys
rows = collections.defaultdict(list)
for line in open(sys.argv[1]):
    a, _, target, e, mu = line.split()[:5]
    rows[(int(a), float(target))].append((float(e), float(mu)))
for (a, target), v in sorted(rows.items()):
    mus = [mu for _, mu in v]
    print(a, target, round(sum(e for e, _ in v) / len(v), 4), round(sum(mus) / len(mus), 4),
          min(mus), max(mus), len(v))
PY
