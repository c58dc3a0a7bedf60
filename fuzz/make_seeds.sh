#!/usr/bin/env bash
# Regenerate the seeds of fuzz/corpus/ that are real outputs of packbed (after a format
# change: the checkpoints above all); the hand-made edge cases beside them are left as they are.
# Usage: fuzz/make_seeds.sh [PACKBED]   (default: build/packbed)
set -euo pipefail
cd "$(dirname "$0")/.."
packbed=$(realpath "${1:-build/packbed}")
corpus=$PWD/fuzz/corpus
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
cd "$tmp"

# Three checkpoints of one bed in layers: NAME-layer1 (a run cut short by --max-iterations
# FIRST, which checkpoints may differ in), NAME-final (after the last layer) and NAME-other (of
# seed OTHER, cut at OTHER_MAX, refused for its parameters); the bed's own outputs in NAME/.
# Usage: checkpoints NAME FIRST OTHER OTHER_MAX GENERATE-ARGS...
checkpoints() {
  local name=$1 first=$2 other=$3 other_max=$4
  shift 4
  "$packbed" "$@" --checkpoint "$name-layer1.ckpt" --max-iterations "$first" -o "$name-1" \
    2>/dev/null || true
  "$packbed" "$@" --checkpoint "$name-final.ckpt" -o "$name"
  "$packbed" "$@" --seed "$other" --checkpoint "$name-other.ckpt" --max-iterations "$other_max" \
    -o "$name-other" 2>/dev/null || true
  test -s "$name-layer1.ckpt" && test -s "$name-final.ckpt" && test -s "$name-other.ckpt"
}

# Checkpoints of the parameters fuzz_checkpoint.cpp reads them with.
checkpoints g 9000 2 9000 generate -q --solver fire -a 3 -n 200 --layer-height 10 --threads 1
cp g-layer1.ckpt "$corpus/fuzz_checkpoint/a3-n200-layer1.ckpt"
cp g-final.ckpt "$corpus/fuzz_checkpoint/a3-n200-final.ckpt"
cp g-other.ckpt "$corpus/fuzz_checkpoint/a3-n200-seed2-other-parameters.ckpt"
head -2 g-final.ckpt >"$corpus/fuzz_checkpoint/no-hash-line.ckpt"
head -c 300 g-final.ckpt >"$corpus/fuzz_checkpoint/cut-in-header.ckpt"
{ echo "packbed-checkpoint 2"; sed -n 2p g-final.ckpt; } >"$corpus/fuzz_checkpoint/format-2.ckpt"

# Pellet checkpoints of the parameters fuzz_pellet_checkpoint.cpp reads them with (five layers),
# the other of seed 3; and a sphere bed's.
mkdir -p "$corpus/fuzz_pellet_checkpoint"
checkpoints r 15000 3 30000 generate -q --shape spherocylinder:1,1 -a 3 -n 100 --layer-height 10 \
  --threads 1
cp r-layer1.ckpt "$corpus/fuzz_pellet_checkpoint/rods-a3-n100-layer1.ckpt"
cp r-final.ckpt "$corpus/fuzz_pellet_checkpoint/rods-a3-n100-final.ckpt"
cp r-other.ckpt "$corpus/fuzz_pellet_checkpoint/rods-a3-n100-seed3-other-parameters.ckpt"
cp g-layer1.ckpt "$corpus/fuzz_pellet_checkpoint/a-sphere-bed.ckpt"
head -c 400 r-final.ckpt >"$corpus/fuzz_pellet_checkpoint/cut-in-header.ckpt"

# summary.json of generate, lattice (a box and a cylinder) and analyze.
"$packbed" lattice -q -t fcc -r box:3,3,3 -o lat-box
"$packbed" lattice -q -t sc -r cylinder:6,4 -o lat-cyl
"$packbed" analyze -q g/particles.csv -o ana
cp g/summary.json "$corpus/fuzz_summary/generate.json"
cp lat-box/summary.json "$corpus/fuzz_summary/lattice-box.json"
cp lat-cyl/summary.json "$corpus/fuzz_summary/lattice-cylinder.json"
cp ana/summary.json "$corpus/fuzz_summary/analyze.json"

# A small bed as CSV, XYZ (with and without radii) and a LAMMPS dump; a lattice's CSV.
"$packbed" generate -q --solver fire -a 3 -n 12 -o small
cp small/particles.csv "$corpus/fuzz_csv/generate-a3-n12.csv"
cp lat-box/particles.csv "$corpus/fuzz_csv/lattice-fcc-box.csv"
n=$(($(wc -l <small/particles.csv) - 1))
{ echo "$n"; echo "packbed generate -a 3 -n 12 --solver fire"
  tail -n +2 small/particles.csv | awk -F, '{print "C", $1, $2, $3, $4}'; } \
  >"$corpus/fuzz_xyz/generate-a3-n12.xyz"
{ echo "$n"; echo
  tail -n +2 small/particles.csv | awk -F, '{print "C", $1, $2, $3}'; } \
  >"$corpus/fuzz_xyz/generate-a3-n12-no-radius.xyz"
{ printf 'ITEM: TIMESTEP\n1000\nITEM: NUMBER OF ATOMS\n%d\nITEM: BOX BOUNDS ff ff ff\n' "$n"
  printf -- '-1.5 1.5\n-1.5 1.5\n0 4\nITEM: ATOMS id type x y z diameter\n'
  tail -n +2 small/particles.csv | awk -F, '{print NR, 1, $1, $2, $3, 2 * $4}'; } \
  >"$corpus/fuzz_dump/generate-a3-n12.dump"
# The same bed as packbed export's LAMMPS data file (fuzz_data), and gzip-compressed copies.
"$packbed" export -q small/particles.csv --out small.data
cp small.data "$corpus/fuzz_data/generate-a3-n12.data"
gzip -9n <small.data >"$corpus/fuzz_data/generate-a3-n12.data.gz"
gzip -9n <small/particles.csv >"$corpus/fuzz_csv/generate-a3-n12.csv.gz"
gzip -9n <"$corpus/fuzz_dump/generate-a3-n12.dump" >"$corpus/fuzz_dump/generate-a3-n12.dump.gz"
# A real LAMMPS log of the engine (fuzz_lammps_log), where LAMMPS is installed.
if command -v lmp >/dev/null && command -v mpirun >/dev/null; then
  "$packbed" generate -q --engine lammps -a 3 -n 30 -o lmp
  cp lmp/lammps/log.lammps "$corpus/fuzz_lammps_log/real-a3-n30.log"
else
  echo "make_seeds: no lmp and mpirun, fuzz_lammps_log's real log left as it is" >&2
fi
echo "make_seeds: seeds regenerated with $packbed"
