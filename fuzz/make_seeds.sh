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

# Checkpoints of the parameters fuzz_checkpoint.cpp reads them with: after layer 1 (a run cut
# short by --max-iterations, which checkpoints may differ in) and after the last layer; and
# one of another seed, refused for its parameters.
fire=(generate -q --solver fire -a 3 -n 200 --layer-height 10 --threads 1)
"$packbed" "${fire[@]}" --checkpoint layer1.ckpt --max-iterations 9000 -o g1 2>/dev/null || true
"$packbed" "${fire[@]}" --checkpoint final.ckpt -o g
"$packbed" "${fire[@]}" --seed 2 --checkpoint seed2.ckpt --max-iterations 9000 -o g2 \
  2>/dev/null || true
test -s layer1.ckpt && test -s final.ckpt && test -s seed2.ckpt
cp layer1.ckpt "$corpus/fuzz_checkpoint/a3-n200-layer1.ckpt"
cp final.ckpt "$corpus/fuzz_checkpoint/a3-n200-final.ckpt"
cp seed2.ckpt "$corpus/fuzz_checkpoint/a3-n200-seed2-other-parameters.ckpt"
head -2 final.ckpt >"$corpus/fuzz_checkpoint/no-hash-line.ckpt"
head -c 300 final.ckpt >"$corpus/fuzz_checkpoint/cut-in-header.ckpt"
{ echo "packbed-checkpoint 2"; sed -n 2p final.ckpt; } >"$corpus/fuzz_checkpoint/format-2.ckpt"

# Pellet checkpoints of the parameters fuzz_pellet_checkpoint.cpp reads them with (five layers):
# after layer 1 and after the last; one of another seed (3: seed 2 jams in its first layer,
# docs/generate.md); a sphere bed's.
rods=(generate -q --shape spherocylinder:1,1 -a 3 -n 100 --layer-height 10 --threads 1)
mkdir -p "$corpus/fuzz_pellet_checkpoint"
"$packbed" "${rods[@]}" --checkpoint rods1.ckpt --max-iterations 15000 -o r1 2>/dev/null || true
"$packbed" "${rods[@]}" --checkpoint rods.ckpt -o r
"$packbed" "${rods[@]}" --seed 3 --checkpoint rods3.ckpt --max-iterations 30000 -o r3 \
  2>/dev/null || true
test -s rods1.ckpt && test -s rods.ckpt && test -s rods3.ckpt
cp rods1.ckpt "$corpus/fuzz_pellet_checkpoint/rods-a3-n100-layer1.ckpt"
cp rods.ckpt "$corpus/fuzz_pellet_checkpoint/rods-a3-n100-final.ckpt"
cp rods3.ckpt "$corpus/fuzz_pellet_checkpoint/rods-a3-n100-seed3-other-parameters.ckpt"
cp layer1.ckpt "$corpus/fuzz_pellet_checkpoint/a-sphere-bed.ckpt"
head -c 400 rods.ckpt >"$corpus/fuzz_pellet_checkpoint/cut-in-header.ckpt"

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
