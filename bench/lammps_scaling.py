#!/usr/bin/env python3
"""Wall time against Np and against ranks: the LAMMPS engine next to packbed's fire.

Beds of Np spheres in a tube as wide as keeps the initial height L0 (eq. 6) at about 30 Dp
(a = sqrt(Np / 23.85): 6.5 at 1e3, 20.5 at 1e4, 64.8 at 1e5), so that both engines relax each
bed in one piece; seed 1. For every Np: `packbed generate` with --threads 1 and 2, then
`--engine lammps` with --ranks 1 and 2, one after the other. Prints a markdown table (wall
time of the relaxation as summary.json records it (the LAMMPS engine's: from writing the job
to the bed read back), of the whole command, steps, nanoseconds per sphere-step, void fraction
1 Dp clear of the ends) and writes the
rows to OUT/lammps_scaling.csv. Runs whose summary.json exists are reused.

Usage: bench/lammps_scaling.py [--packbed build/packbed] [--particles 1000,10000,100000]
                               [--out results/lammps-scaling]
"""
import argparse
import csv
import json
import math
import os
import subprocess
import time


def main():
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawTextHelpFormatter)
    p.add_argument("--packbed", default="build/packbed")
    p.add_argument("--particles", default="1000,10000,100000")
    p.add_argument("--out", default="results/lammps-scaling")
    args = p.parse_args()
    os.makedirs(args.out, exist_ok=True)
    rows = []
    print("| Np | a | engine | threads/ranks | relaxation (s) | whole command (s) | steps "
          "| ns per sphere-step | void fraction |")
    print("|---|---|---|---|---|---|---|---|---|")
    for n in [int(x) for x in args.particles.split(",")]:
        a = round(math.sqrt(n / 23.85), 1)
        for engine, count in (("packbed", 1), ("packbed", 2), ("lammps", 1), ("lammps", 2)):
            run = os.path.join(args.out, f"n{n}-{engine}-{count}")
            if not os.path.exists(os.path.join(run, "summary.json")):
                extra = (["--threads", str(count)] if engine == "packbed"
                         else ["--engine", "lammps", "--ranks", str(count)])
                t0 = time.monotonic()
                subprocess.run([args.packbed, "generate", "-a", f"{a:g}", "-n", str(n), "-s", "1",
                                "-q", "--force", "-o", run] + extra, check=True)
                with open(os.path.join(run, "command-seconds.txt"), "w") as f:
                    f.write(f"{time.monotonic() - t0:.2f}\n")
            with open(os.path.join(run, "summary.json")) as f:
                s = json.load(f)
            ns = 1e9 * s["seconds"] / (s["iterations"] * n)
            with open(os.path.join(run, "command-seconds.txt")) as f:
                command = float(f.read())
            row = {"particles": n, "aspect_ratio": a, "engine": engine, "workers": count,
                   "seconds": s["seconds"], "command_seconds": command, "steps": s["iterations"], "ns_per_sphere_step": ns,
                   "void_fraction": s.get("void_fraction")}
            rows.append(row)
            print(f"| {n} | {a:g} | {engine} | {count} | {s['seconds']:.1f} | {command:.1f} "
                  f"| {s['iterations']} "
                  f"| {ns:.0f} | {row['void_fraction']:.4f} |", flush=True)
    with open(os.path.join(args.out, "lammps_scaling.csv"), "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=list(rows[0]))
        w.writeheader()
        w.writerows(rows)


if __name__ == "__main__":
    main()
