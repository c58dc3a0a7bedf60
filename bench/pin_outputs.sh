#!/usr/bin/env bash
# The bytes a refactor must keep: 69 commands (beds in every container, with sizes, lattices,
# surfaces, OpenFOAM cases, data files, LAMMPS jobs, analyses, voxel images, hydraulics, help
# texts and refusals) run by PACKBED into OUT, and the md5 of every output
# (summary.json and other JSON without their timings and version). Run it with the binary
# before a change and after, and compare: `diff before.md5 after.md5`.
#
# Usage: bench/pin_outputs.sh PACKBED OUT > FILE.md5    (OUT is replaced)
set -euo pipefail
exe=$(realpath "$1")
out=$2
rm -rf "$out"
mkdir -p "$out"
cd "$out"
printf 'diameter,cumulative_fraction\n0.8,0\n1.0,0.5\n1.2,1\n' > sizes.csv
$exe generate -a 5 -n 500 -s 1 -q -o a5
$exe generate --container box:6,6 -n 600 -s 1 --sizes lognormal:1,1.2 -q -o box
$exe generate --container annulus:10,2 -n 800 -s 2 --sizes discrete:1:0.5,1.5:0.5 -q -o ann
$exe generate -a 6 -n 400 -s 3 --sizes file:sizes.csv -q -o file
$exe generate --container periodic:6,6 -n 300 -s 2 -q -o per
$exe lattice --type diamond --region cylinder:8,6 --rotate z:30,x:10 --origin 0.1,0,0.5 -q -o lat
$exe export a5/particles.csv --format stl --contacts caps:0.01 -q -o a5.stl
$exe export a5/particles.csv --format stl --contacts shrink:0.02 --box -2,2,-2,2,0,5 -q -o a5box.stl
$exe analyze a5/particles.csv --band 1,5 -q -o an
$exe voxelize a5/particles.csv --voxel-size 0.1 -q -o a5.npy
$exe analyze box/particles.csv -q -o anbox
$exe analyze ann/particles.csv -q -o anann
$exe analyze per/particles.csv -q -o anper
$exe export a5/particles.csv --format openfoam -q -o a5foam
$exe export ann/particles.csv --format openfoam -q -o annfoam
$exe export per/particles.csv --format openfoam -q -o perfoam
$exe export box/particles.csv --format openfoam -q -o boxfoam
$exe export box/particles.csv --format stl --contacts caps:0.01 -q -o box.stl
$exe export ann/particles.csv --format stl --contacts caps:0.01 -q -o ann.stl
{ $exe export per/particles.csv --format stl -q -o per.stl || echo "exit $?"; } > per.stl.refused 2>&1
for c in cylinder:0.5 box:0.5,3 annulus:4,3.5 periodic:1.5,3; do
  { $exe generate --container $c -n 50 -q -o small || echo "exit $?"; } > "fit_${c%%:*}.refused" 2>&1
done
$exe export a5/particles.csv --format liggghts-data -q -o a5.data
$exe export box/particles.csv -q -o box.data
$exe export ann/particles.csv -q -o ann.data
$exe export per/particles.csv -q -o per.data
$exe generate -a 5 -n 200 -s 1 --engine lammps --write-only lmp_cyl -q
$exe generate --container box:5,5 -n 200 -s 1 --engine lammps --write-only lmp_box -q
$exe generate --container annulus:8,2 -n 200 -s 1 --engine lammps --write-only lmp_ann -q
$exe generate --container periodic:5,5 -n 200 -s 1 --engine lammps --write-only lmp_per -q
$exe lattice --type fcc --region box:6,6,6 -q -o latbox
$exe lattice --type sc --region annulus:8,2,4 --keep centres -q -o latann
$exe lattice --type sc --region periodic:4,4,3 -q -o latper
{ $exe lattice --type fcc --region periodic:4,4,3 || echo "exit $?"; } > latper.refused 2>&1
{ $exe lattice --region cylinder:4 || echo "exit $?"; } > latcyl.refused 2>&1
$exe voxelize per/particles.csv --voxel-size 0.2 -q -o per.npy
$exe voxelize ann/particles.csv --voxel-size 0.2 -q -o ann.npy
for c in generate lattice hydraulics export analyze correlations voxelize cfd-report import-lammps; do
  $exe $c --help
done > help.txt
{ $exe generate --container cone:1,2 || echo "exit $?"; } > unknown_shape.refused 2>&1
# The cone: both solvers, its analysis, a lattice, its surfaces, case, data file and LAMMPS job.
$exe generate --container cone:6,10,30 -n 400 -s 1 -q -o cone
$exe generate --container cone:10,6,30 -n 300 -s 1 --solver paper -q -o conep
$exe analyze cone/particles.csv --band 1,6 -q -o ancone
$exe lattice --type diamond --region cone:8,12,20,6 -q -o latcone
$exe export cone/particles.csv --format stl --contacts caps:0.01 -q -o cone.stl
$exe export cone/particles.csv --format openfoam -q -o conefoam
$exe export cone/particles.csv -q -o cone.data
$exe generate --container cone:6,10,30 -n 200 -s 1 --engine lammps --write-only lmp_cone -q
{ $exe generate --container cone:4,8,10 -n 400 || echo "exit $?"; } > cone_top.refused 2>&1
for c in cylinder:0.05 box:0.05,0.04 annulus:0.05,0.01 periodic:0.05,0.05; do
  { $exe hydraulics --container $c -d 0.003 --porosity 0.4 || echo "exit $?"; } > "hyd_${c%%:*}.txt" 2>&1
done
# Pellets: cylinder beds in a tube and a periodic cell, their analysis, surfaces, case, data file.
$exe generate --shape cylinder:1,1 -a 4 -n 12 -s 1 -q -o pel
$exe generate --shape cylinder:1,1.5 --container periodic:4,4 -n 10 -s 2 -q -o pelper
$exe analyze pel/particles.csv --band 0.2,0.6 -q -o anpel
$exe analyze pelper/particles.csv --band 0.2,0.6 -q -o anpelper
$exe export pel/particles.csv --format stl -q -o pel.stl
$exe export pel/particles.csv --format openfoam --contacts shrink:0.02 -q -o pelfoam
$exe export pel/particles.csv --format lammps-data -q -o pel.data
find . -type f ! -name '*.json' -print0 | sort -z | xargs -0 md5sum
find . -name '*.json' -print0 | sort -z | while IFS= read -r -d '' f; do
  python3 - "$f" <<'PY' | md5sum | sed "s|-|$f|"
import json, sys
timing = ("seconds", "version", "command_seconds", "wall_seconds", "created")
def strip(o):
    if isinstance(o, dict):
        return {k: strip(v) for k, v in o.items() if k not in timing}
    if isinstance(o, list):
        return [strip(v) for v in o]
    return o
print(json.dumps(strip(json.load(open(sys.argv[1]))), sort_keys=True))
PY
done
