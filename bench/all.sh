#!/usr/bin/env bash
# Every figure of docs/performance.md, in one run, as a user runs the commands (packbed's
# default threads: every core; no OpenMP variables set). Writes one Markdown file per
# section into OUT and prints each as it ends. Noisy machines: compare the ratios of one run.
#
# Usage: bench/all.sh [OUT] [SECTIONS]
#   OUT       a new folder (default results/bench-all); runs found there are reused by the
#             scripts that reuse runs (scaling.py, lammps_scaling.py)
#   SECTIONS  a space-separated subset of: threads peers iteration scaling analyze lattice
#             export voxels seams timeleft lammps (default: all, in that order; about 45
#             minutes on 2 cores, 12 of them the million-sphere bed)
# Needs: a Release build with the benchmarks (cmake -S . -B build -DCMAKE_BUILD_TYPE=Release
# -DPACKBED_BUILD_BENCH=ON; cmake --build build -j2), the Python module in build/python, and for
# `peers` and `lammps` bench/peers/install.sh (Debian's lammps, liggghts, openmpi-bin).
set -euo pipefail
cd "$(dirname "$0")/.."
out=${1:-results/bench-all}
sections=${2:-threads peers iteration scaling analyze lattice export voxels seams timeleft lammps friction}
packbed=build/packbed
mkdir -p "$out"
out=$(cd "$out" && pwd)
export PYTHONPATH=$PWD/build/python${PYTHONPATH:+:$PYTHONPATH}
timed() { # FILE COMMAND...: run it, append "wall s, peak MB" of the command to FILE
  local file=$1
  shift
  /usr/bin/time -f "%e %M" -o "$out/.time" "$@" > /dev/null
  read -r s kb < "$out/.time"
  echo "| \`${*}\` | $s | $((kb / 1000)) |" >> "$file"
}

for section in $sections; do
  file=$out/$section.md
  {
    echo "## $section ($(date -u +%Y-%m-%dT%H:%MZ), $(nproc) cores, $(git rev-parse --short HEAD))"
    echo
  } > "$file"
  case $section in
  threads)
    bench/threads_back_to_back.sh "$packbed" 3 >> "$file"
    ;;
  peers) # the paper's case against LAMMPS's fast script, alternating, then pour.py's scripts
    lmp_dir=$(mktemp -d)
    mpi=(mpirun -np 2)
    [[ $(id -u) != 0 ]] || mpi+=(--allow-run-as-root)
    {
      echo "| command | wall s | peak MB |"
      echo "|---|---|---|"
    } >> "$file"
    for _ in 1 2 3; do
      (cd "$lmp_dir" && timed "$file" "${mpi[@]}" lmp -in \
        "$OLDPWD/../shared/reference/lammps_pour.in" -var N 500 -var a 5 -var out bed.dump \
        -var seed 12345 -log none -screen none)
      timed "$file" "$packbed" generate -a 5 -n 500 -s 1 -q --force -o "$out/peers-a5"
      timed "$file" "$packbed" generate -a 5 -n 500 -s 1 -q --no-analysis --force \
        -o "$out/peers-a5-bed"
    done
    timed "$file" "$packbed" generate --solver paper -a 5 -n 500 -s 1 -q --force \
      -o "$out/peers-a5-paper"
    rm -rf "$lmp_dir"
    python3 -c 'import json, sys
for d in sys.argv[1:]:
    s = json.load(open(d + "/summary.json"))
    n, t, e, j = s["iterations"], s["seconds"], s["void_fraction"], s["parameters"]["threads"]
    print(f"\n{d}: {n} steps, relaxation {t:.3f} s, e = {e:.4f}, {j} threads")' \
      "$out/peers-a5" "$out/peers-a5-paper" >> "$file"
    echo >> "$file"
    bench/peers/pour.py --packbed "$packbed" --work "$out/pour" >> "$file"
    ;;
  iteration)
    build/bench/bench_iteration --benchmark_min_time=1 --benchmark_repetitions=3 \
      --benchmark_report_aggregates_only=true 2>&1 | grep -E "_median|Run on" >> "$file"
    ;;
  scaling) # the paper's solver to 1e4 (3e4 passes 200 s), fire to 1e6
    bench/scaling.py --packbed "$packbed" --solvers paper,fire --limit paper:200,fire:3000 \
      --out "$out/scaling" >> "$file"
    ;;
  analyze)
    bench/time_analyze.sh "$packbed" 100000 "$(nproc)" >> "$file"
    bench/time_analyze.sh "$packbed" 100000 1 >> "$file"
    ;;
  lattice)
    build/bench/bench_lattice 2>&1 | grep -vE "^\*\*\*|DEBUG" >> "$file"
    {
      echo "| command | wall s | peak MB |"
      echo "|---|---|---|"
    } >> "$file"
    timed "$file" "$packbed" lattice --type diamond --region box:117,117,117 --no-analysis -q \
      --force -o "$out/lattice-bed"
    timed "$file" "$packbed" lattice --type diamond --region box:117,117,117 -q --force \
      -o "$out/lattice"
    ;;
  export)
    "$packbed" generate -a 20 -n 10000 -s 1 -q --force -o "$out/export-bed"
    bench/time_export.sh "$packbed" "$out/export-bed" "2 3" >> "$file"
    {
      echo
      echo "| command | wall s | peak MB |"
      echo "|---|---|---|"
    } >> "$file"
    "$packbed" generate -a 5 -n 500 -s 1 -q --force -o "$out/export-a5"
    for c in enlarge:0.01 bridges:0.2; do
      timed "$file" "$packbed" export "$out/export-a5/particles.csv" --format stl --contacts "$c" \
        -q -o "$out/union.stl"
    done
    ;;
  voxels) # the 1e5 bed of the scaling section, or a new one
    bed=$out/scaling/fire/n100000
    [[ -f $bed/particles.csv ]] || "$packbed" generate -a 20 -n 100000 -s 1 -q --force -o "$bed"
    PACKBED=$packbed /usr/bin/python3 bench/voxelize.py "$bed" 0.05 2 >> "$file"
    ;;
  seams)
    build/bench/bench_seams 20 60000 1,2,3,4 >> "$file"
    ;;
  friction) # frictional beds and targets against the frictionless bed, side by side
    bench/time_friction.sh "$packbed" "$out/friction" >> "$file"
    ;;
  timeleft) # the progress line's estimate on a terminal: in layers, and in one piece
    bench/time_left.py --packbed "$packbed" -a 20 -n 60000 -s 1 >> "$file"
    echo >> "$file"
    bench/time_left.py --packbed "$packbed" -a 20 -n 10000 -s 1 >> "$file"
    ;;
  lammps)
    bench/lammps_scaling.py --packbed "$packbed" --particles 1000,3000,10000,30000 \
      --out "$out/lammps-scaling" >> "$file"
    ;;
  *)
    echo "bench/all.sh: unknown section '$section'" >&2
    exit 2
    ;;
  esac
  cat "$file"
done
rm -f "$out/.time"
