#!/usr/bin/env bash
# Time `packbed analyze` on a bed of N spheres (default 100 000): a face-centred cubic bed
# that fills a cylinder of radius 10 Dp (a = 20), written by make_lattice_bed.py.
# Usage: bench/time_analyze.sh [PACKBED] [SPHERES] [THREADS]
set -euo pipefail
exe=${1:-build/packbed}
n=${2:-100000}
threads=${3:-2}
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT
python3 "$(dirname "$0")/make_lattice_bed.py" "$out/bed.csv" 10 "$n"
start=$EPOCHREALTIME
"$exe" analyze "$out/bed.csv" --container-radius 10 --threads "$threads" --quiet --out "$out/a"
end=$EPOCHREALTIME
awk -v n="$n" -v t="$threads" -v s="$start" -v e="$end" \
  'BEGIN { printf "packbed analyze, %d spheres, %d threads: %.2f s wall\n", n, t, e - s }'
