#!/usr/bin/env python3
"""packbed against LAMMPS and LIGGGHTS pour-and-settle of the same bed.

Places Np spheres at random, not touching, in a cylinder of aspect ratio a (random sequential
addition, a solid fraction of 0.2, fixed seed), lets LAMMPS (Debian's `lmp`, GRANULAR
package, bench/peers/lammps_pour.in) drop them frictionlessly until the kinetic energy per
sphere is below 1e-6 m g D, and does the same with LIGGGHTS (Debian's `liggghts`,
bench/peers/liggghts_pour.in: the same model and stopping rule) where it is installed, and
runs `packbed generate` on the same cylinder and Np with each solver, and with fire and
`--no-analysis` (the spheres and the summary only, as the peers write only a dump). Prints,
for each: wall time, void fraction (`packbed analyze`, 1 Dp clear of the ends) and the largest
sphere-sphere and sphere-wall overlaps in Dp, then the time ratios of each peer to each
solver.
Installs nothing: run bench/peers/install.sh first (Debian's lammps, liggghts, openmpi-bin).

Usage: bench/peers/pour.py [--packbed build/packbed] [--aspect-ratio 5] [--particles 500]
                           [--seed 1] [--ranks 2] [--work DIR]
"""
import argparse
import csv
import json
import math
import os
import random
import shutil
import subprocess
import sys
import time

HERE = os.path.dirname(os.path.abspath(__file__))
D = 1e-3  # sphere diameter, m (as the peers' reference runs, docs/sources.md#peers)


def random_start(n, a, seed, fraction=0.2):
    """Random sequential addition of n spheres of diameter 1 in a cylinder of radius a/2; the
    solid fraction refers to the cylinder the centres can reach (radius a/2 - 1/2)."""
    rng = random.Random(seed)
    reach = a / 2 - 0.5
    height = n * (math.pi / 6) / (math.pi * reach * reach * fraction)
    cells = {}
    centres = []
    while len(centres) < n:
        r = reach * math.sqrt(rng.random())
        t = 2 * math.pi * rng.random()
        p = (r * math.cos(t), r * math.sin(t), 0.5 + height * rng.random())
        key = tuple(math.floor(c) for c in p)
        if any(sum((p[k] - q[k]) ** 2 for k in range(3)) < 1.0
               for dx in (-1, 0, 1) for dy in (-1, 0, 1) for dz in (-1, 0, 1)
               for q in cells.get((key[0] + dx, key[1] + dy, key[2] + dz), ())):
            continue
        cells.setdefault(key, []).append(p)
        centres.append(p)
    return centres, height + 1.0


def write_data(path, centres, a, top):
    R = a / 2 * D
    with open(path, "w") as f:
        f.write("spheres at rest, not touching (bench/peers/pour.py)\n\n")
        f.write(f"{len(centres)} atoms\n1 atom types\n\n")
        f.write(f"{-R} {R} xlo xhi\n{-R} {R} ylo yhi\n0 {top * D} zlo zhi\n\nAtoms # sphere\n\n")
        for i, (x, y, z) in enumerate(centres, 1):
            f.write(f"{i} 1 {D} 2500 {x * D:.9g} {y * D:.9g} {z * D:.9g}\n")


def largest_overlaps(path, radius):
    """Largest pair and wall overlaps of a CSV or dump file, in units of the diameter (the
    floor is not counted: packbed's is rigid, LAMMPS's is a soft wall like the side)."""
    with open(path) as f:
        lines = f.read().splitlines()
    if lines[0].startswith("ITEM:"):
        start = next(i for i, line in enumerate(lines) if line.startswith("ITEM: ATOMS"))
        cols = lines[start].split()[2:]
        rows = [dict(zip(cols, line.split())) for line in lines[start + 1:] if line.strip()]
    else:
        rows = list(csv.DictReader(lines))
    spheres = []
    for row in rows:
        r = float(row["r"]) if "r" in row else float(row.get("radius", 0) or 0) or \
            float(row["diameter"] if "diameter" in row else row["d"]) / 2
        spheres.append((float(row["x"]), float(row["y"]), float(row["z"]), r))
    d = 2 * spheres[0][3]
    cells = {}
    for s in spheres:
        cells.setdefault(tuple(math.floor(c / d) for c in s[:3]), []).append(s)
    pair = wall = 0.0
    for s in spheres:
        key = tuple(math.floor(c / d) for c in s[:3])
        for dx in (-1, 0, 1):
            for dy in (-1, 0, 1):
                for dz in (-1, 0, 1):
                    for q in cells.get((key[0] + dx, key[1] + dy, key[2] + dz), ()):
                        if q is not s:
                            dist = math.dist(s[:3], q[:3])
                            pair = max(pair, s[3] + q[3] - dist)
        wall = max(wall, math.hypot(s[0], s[1]) + s[3] - radius)
    return pair / d, wall / d


def analyze(packbed, path, radius, out):
    subprocess.run([packbed, "analyze", path, "--container-radius", repr(radius), "--out", out,
                    "--force", "--quiet"], check=True, stdout=subprocess.DEVNULL)
    with open(os.path.join(out, "summary.json")) as f:
        return json.load(f)["void_fraction"]


def main():
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawTextHelpFormatter)
    p.add_argument("--packbed", default="build/packbed")
    p.add_argument("--aspect-ratio", type=float, default=5.0)
    p.add_argument("--particles", type=int, default=500)
    p.add_argument("--seed", type=int, default=1)
    p.add_argument("--ranks", type=int, default=2)
    p.add_argument("--work", default="results/peers")
    args = p.parse_args()
    lmp = shutil.which("lmp")
    if lmp is None:
        sys.exit("bench/peers/pour.py: lmp not found; run bench/peers/install.sh")
    a, n = args.aspect_ratio, args.particles
    if not (a > 1.0 and n >= 1):
        sys.exit(f"bench/peers/pour.py: --aspect-ratio {a:g} and --particles {n}: need a > 1 "
                 "and at least one sphere")
    work = os.path.abspath(os.path.join(args.work, f"a{a:g}-n{n}-seed{args.seed}"))
    os.makedirs(work, exist_ok=True)
    centres, top = random_start(n, a, args.seed)
    data = os.path.join(work, "start.data")
    write_data(data, centres, a, top)
    rows = []

    dump = os.path.join(work, "lammps.dump")
    cmd = ["mpirun", "--allow-run-as-root", "-np", str(args.ranks), lmp] if args.ranks > 1 \
        else [lmp]
    start = time.perf_counter()
    subprocess.run(cmd + ["-in", os.path.join(HERE, "lammps_pour.in"), "-var", "DATA", data,
                          "-var", "R", repr(a / 2 * D), "-var", "D", repr(D), "-var", "H",
                          repr(top * D), "-var", "OUT", dump, "-log",
                          os.path.join(work, "log.lammps"), "-screen", "none"], check=True)
    seconds = time.perf_counter() - start
    e = analyze(args.packbed, dump, a / 2 * D, os.path.join(work, "lammps-analysis"))
    rows.append((f"LAMMPS pour-and-settle ({args.ranks} ranks)", seconds, e,
                 *largest_overlaps(dump, a / 2 * D)))

    liggghts = shutil.which("liggghts")
    if liggghts is None:
        print("liggghts not found: LIGGGHTS not run (bench/peers/install.sh)", file=sys.stderr)
    else:
        dump = os.path.join(work, "liggghts.dump")
        cmd = ["mpirun", "--allow-run-as-root", "-np", str(args.ranks), liggghts] \
            if args.ranks > 1 else [liggghts]
        start = time.perf_counter()
        subprocess.run(cmd + ["-in", os.path.join(HERE, "liggghts_pour.in"), "-var", "DATA",
                              data, "-var", "R", repr(a / 2 * D), "-var", "D", repr(D),
                              "-var", "OUT", dump, "-log", os.path.join(work, "log.liggghts"),
                              "-screen", "none"], check=True, cwd=work)  # its default log
        seconds = time.perf_counter() - start
        e = analyze(args.packbed, dump, a / 2 * D, os.path.join(work, "liggghts-analysis"))
        rows.append((f"LIGGGHTS pour-and-settle ({args.ranks} ranks)", seconds, e,
                     *largest_overlaps(dump, a / 2 * D)))

    # The last: the spheres and their summary only, as the peers write only their dump.
    for solver, extra in (("paper", []), ("fire", []), ("fire", ["--no-analysis"])):
        out = os.path.join(work, f"packbed-{solver}{'-bare' if extra else ''}")
        start = time.perf_counter()
        subprocess.run([args.packbed, "generate", "--solver", solver, "--aspect-ratio", f"{a:g}",
                        "--particles", str(n), "--seed", str(args.seed), "--quiet", "--force",
                        "--out", out] + extra,
                       check=True)
        seconds = time.perf_counter() - start
        with open(os.path.join(out, "summary.json")) as f:
            s = json.load(f)
        rows.append((" ".join([f"packbed --solver {solver}"] + extra), seconds,
                     s["void_fraction"], s["max_overlap_pair"], s["max_overlap_wall"]))

    print(f"a = {a:g}, Np = {n}, seed {args.seed}")
    print("| program | wall time (s) | void fraction | largest overlap pair (Dp) "
          "| largest overlap wall (Dp) |")
    print("|---|---|---|---|---|")
    for name, seconds, e, pair, wall in rows:
        print(f"| {name} | {seconds:.2f} | {e:.4f} | {pair:.2e} | {wall:.2e} |")
    peers = [r for r in rows if not r[0].startswith("packbed")]
    for name, seconds, *_ in rows:
        if name.startswith("packbed"):
            for peer, peer_seconds, *_ in peers:
                print(f"time ratio {peer.split()[0]} / {name}: {peer_seconds / seconds:.1f}")


if __name__ == "__main__":
    main()
