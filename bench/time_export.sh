#!/usr/bin/env bash
# Time `packbed export` of a generated bed to surfaces (target: 10 000 spheres to STL
# with caps under 30 s). The bed: `packbed generate --solver fire --aspect-ratio 20 --particles
# 10000 --seed 1` (about a minute), made once into BED_DIR and reused.
# Usage: bench/time_export.sh [PACKBED] [BED_DIR] [LEVELS]   (LEVELS default "2 3 4")
set -euo pipefail
exe=${1:-build/packbed}
bed=${2:-results/bench-export-bed}
levels=${3:-2 3 4}
if [[ ! -f $bed/particles.csv ]]; then
  "$exe" generate --solver fire --aspect-ratio 20 --particles 10000 --seed 1 --quiet --out "$bed"
fi
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT
echo "| contacts | icosphere level | triangles | file (MB) | wall time (s) | peak memory (MB) |"
echo "|---|---|---|---|---|---|"
for level in $levels; do
  for contacts in none shrink:0.01 caps:0.01; do
    /usr/bin/time -f "%e %M" -o "$out/time" \
      "$exe" export "$bed/particles.csv" --format stl --refine "$level" --contacts "$contacts" \
      --out "$out/bed.stl" --quiet
    read -r seconds kb < "$out/time"
    triangles=$(python3 -c "import json,sys; print(sum(s['triangles'] for s in json.load(open(sys.argv[1]))['solids']))" "$out/bed.stl.json")
    mb=$(($(stat -c %s "$out/bed.stl") / 1000000))
    echo "| $contacts | $level | $triangles | $mb | $seconds | $((kb / 1000)) |"
  done
done
