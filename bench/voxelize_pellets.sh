#!/bin/bash
# Voxel images of pellet beds (docs/voxels.md, "Pellets"): the seconds of `packbed voxelize`,
# binary and fraction, for a bed of cylinders, of trilobes and of spherocylinders, 20 voxels
# per D. Usage: bench/voxelize_pellets.sh PACKBED OUT [THREADS]
set -euo pipefail
packbed=$1 out=$2 threads=${3:-2}
mkdir -p "$out"
run() { # name spec aspect particles seed
    "$packbed" generate --shape "$2" -a "$3" -n "$4" -s "$5" -q --force --out "$out/$1"
    for kind in binary fraction; do
        start=$(date +%s.%N)
        "$packbed" voxelize "$out/$1/particles.csv" --voxel-size 0.05 --kind $kind \
            --threads "$threads" -q -o "$out/$1-$kind.npy"
        end=$(date +%s.%N)
        printf '%s %s %s: %.2f s\n' "$1" "$2" "$kind" "$(echo "$end - $start" | bc)"
    done
}
run cylinders cylinder:1,1 4 20 1
run trilobes trilobe:1,0.8,1.5 5 16 2
run rods spherocylinder:1,1 4 40 1
