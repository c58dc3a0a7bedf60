#!/usr/bin/env bash
# Stability and iteration count of both update orders against Ck: for each Ck and seed, run
# `packbed generate` and report the iterations, or how it failed.
# Usage: bench/stability.sh [PACKBED] [ASPECT_RATIO] [PARTICLES] [SEEDS] [CKS] [MAX_ITERATIONS]
# Example: bench/stability.sh build/packbed 4 150 "1 2 3" "0.3 0.45 0.6 0.75 0.9" 2000000
set -uo pipefail
exe=${1:-build/packbed}
a=${2:-4}
n=${3:-150}
seeds=${4:-"1 2 3"}
cks=${5:-"0.3 0.45 0.6 0.75 0.9"}
max=${6:-2000000}
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT
echo "| Ck | seed | in-place | simultaneous |"
echo "|---|---|---|---|"
for ck in $cks; do
  for seed in $seeds; do
    row="| $ck | $seed |"
    for update in in-place simultaneous; do
      if "$exe" generate -a "$a" -n "$n" -s "$seed" --ck "$ck" --update "$update" \
          --max-iterations "$max" --quiet --threads 1 --force --out "$out/run" 2>"$out/err"; then
        cell=$(python3 -c "import json,sys; s=json.load(open(sys.argv[1])); print(f\"{s['iterations']} it, e = {s['void_fraction']:.4f}\")" "$out/run/summary.json")
      else
        cell="fails: $(sed -E 's/^packbed generate: //; s/ \(.*//; s/;.*//' "$out/err")"
      fi
      row="$row $cell |"
    done
    echo "$row"
  done
done
