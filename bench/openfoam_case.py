#!/usr/bin/env python3
"""Cells, time and memory of an exported OpenFOAM case against the number of spheres.

For each Np: packbed generate (a, seed 1), packbed export --format openfoam --contacts caps:0.02
(the default mesh unless --cells-per-diameter / --particle-level), then either the case's own
./Allrun (mesh, solve, reconstruct) or, with --mesh-only, its meshing steps as Allrun runs them
(blockMesh, decomposePar, mpirun snappyHexMesh -parallel). Each run under /usr/bin/time -v: wall
time and the largest resident set of one process (snappyHexMesh and simpleFoam run one process
per rank: the whole run needs about RANKS times it). Prints a table; the cases stay in WORK.

Usage: bench/openfoam_case.py PACKBED WORK [--particles 30 500 2000] [--aspect-ratio 5]
       [--ranks 2] [--mesh-only] [--cells-per-diameter C] [--particle-level L]
       [--facets inscribed|volume|auto] (export's; default inscribed, as docs/performance.md's
       tables were measured)"""
import argparse
import os
import re
import subprocess
import sys

parser = argparse.ArgumentParser()
parser.add_argument("packbed")
parser.add_argument("work")
parser.add_argument("--particles", type=int, nargs="+", default=[30, 500, 2000])
parser.add_argument("--aspect-ratio", type=float, default=5.0)
parser.add_argument("--ranks", type=int, default=2)
parser.add_argument("--mesh-only", action="store_true")
parser.add_argument("--cells-per-diameter", type=int)
parser.add_argument("--particle-level", type=int)
parser.add_argument("--facets", default="inscribed")  # export checks the name
args = parser.parse_args()
env = dict(os.environ, WM_PROJECT_DIR=os.environ.get("WM_PROJECT_DIR", "/usr/share/openfoam"))
os.makedirs(args.work, exist_ok=True)


def timed(command, cwd, log):
    """Run `command` under /usr/bin/time -v: (wall seconds, max RSS in MiB)."""
    with open(os.path.join(cwd, log), "w") as out:
        done = subprocess.run(["/usr/bin/time", "-v", *command], cwd=cwd, env=env, stdout=out,
                              stderr=subprocess.PIPE, text=True)
    if done.returncode != 0:
        sys.exit(f"{' '.join(command)} failed in {cwd} (see {log}): {done.stderr[-2000:]}")
    wall = re.search(r"Elapsed \(wall clock\) time \(h:mm:ss or m:ss\): (\S+)", done.stderr).group(1)
    seconds = sum(float(p) * 60 ** k for k, p in enumerate(reversed(wall.split(":"))))
    rss = int(re.search(r"Maximum resident set size \(kbytes\): (\d+)", done.stderr).group(1))
    return seconds, rss / 1024


print(f"{'Np':>6} {'cells':>10} {'mesh s':>8} {'solve s':>8} {'iterations':>10} {'all s':>8} "
      f"{'max RSS MiB':>11}")
for n in args.particles:
    root = os.path.join(args.work, f"a{args.aspect_ratio:g}-n{n}")
    bed, case = os.path.join(root, "bed"), os.path.join(root, "case")
    if not os.path.exists(os.path.join(bed, "particles.csv")):
        subprocess.run([args.packbed, "generate", "--aspect-ratio", str(args.aspect_ratio),
                        "--particles", str(n), "--seed", "1", "--quiet", "--out", bed], check=True)
    mesh = []
    if args.cells_per_diameter:
        mesh += ["--cells-per-diameter", str(args.cells_per_diameter)]
    if args.particle_level is not None:
        mesh += ["--particle-level", str(args.particle_level)]
    subprocess.run([args.packbed, "export", os.path.join(bed, "particles.csv"), "--format",
                    "openfoam", "--contacts", "caps:0.02", "--facets", args.facets,
                    "--ranks", str(args.ranks), *mesh,
                    "--out", case, "--force", "--quiet"], check=True)
    mpi = ["mpirun", "-np", str(args.ranks)] + (["--allow-run-as-root"] if os.getuid() == 0
                                                 else [])
    if args.mesh_only:
        total, rss = timed(["blockMesh"], case, "log.blockMesh")
        if args.ranks > 1:
            total += timed(["decomposePar", "-force"], case, "log.decomposePar")[0]
        seconds, rss_snappy = timed(
            (mpi if args.ranks > 1 else []) + ["snappyHexMesh", "-overwrite"] +
            (["-parallel"] if args.ranks > 1 else []), case, "log.snappyHexMesh")
        total += seconds
        rss = max(rss, rss_snappy)
        mesh_s, solve_s, iterations = seconds, float("nan"), 0
    else:
        total, rss = timed(["./Allrun"], case, "log.Allrun")
        clock = lambda step: float(re.findall(r"ClockTime = (\S+) s",  # noqa: E731
                                              open(os.path.join(case, f"log.{step}")).read())[-1])
        mesh_s, solve_s = clock("snappyHexMesh"), clock("simpleFoam")
        iterations = int(re.findall(r"^Time = (\d+)", open(os.path.join(case, "log.simpleFoam"))
                                    .read(), re.M)[-1])
    log = open(os.path.join(case, "log.snappyHexMesh")).read()
    cells = int(re.findall(r"Snapped mesh : cells:(\d+)", log)[-1])
    print(f"{n:>6} {cells:>10} {mesh_s:>8.0f} {solve_s:>8.0f} {iterations:>10} {total:>8.0f} "
          f"{rss:>11.0f}", flush=True)
