#!/usr/bin/env python3
"""packbed generate --engine lammps, run by the real LAMMPS.

The paper's bed (a = 5, Np = 500, seed 1) relaxed by LAMMPS on 2 MPI ranks, then checked here
with code of its own (no packbed): every sphere inside the tube and above the floor within the
tolerance, no pair overlapping by more than the tolerance, the void fraction in the range
Salvat et al. (2005) report for a = 5 ([0.43, 0.44], section 4.1); run again, the same bytes. Then the failures: a run that
does not converge (too few iterations) and a LAMMPS error each exit 1 with LAMMPS's or the
schedule's own message and write nothing; --write-only's job run as its README says and
brought back by import-lammps; a folder without the run refused (exit 2); a bed that jams in
the final stage stopped by the stage's budget (exit 1).

Usage: check_lammps_engine.py PACKBED. Exits 77 (skipped) without lmp (Debian package lammps) or
mpirun (openmpi-bin); scripts/install-deps.sh --test installs both.
"""
import csv
import json
import math
import os
import shutil
import stat
import subprocess
import sys
import tempfile

packbed = os.path.abspath(sys.argv[1])
missing = [tool for tool in ("lmp", "mpirun") if shutil.which(tool) is None]
if missing:
    print(f"{' and '.join(missing)} not installed (Debian packages lammps, openmpi-bin): skipped")
    sys.exit(77)

failures = []


def check(condition, what):
    print(("ok   " if condition else "FAIL ") + what)
    if not condition:
        failures.append(what)


def run(args, **kwargs):
    return subprocess.run([packbed] + args, capture_output=True, text=True, **kwargs)


def spheres(path):
    with open(path) as f:
        return [(float(r["x"]), float(r["y"]), float(r["z"]), float(r["r"]))
                for r in csv.DictReader(f)]


def largest_overlaps(balls, radius_tube):
    """Largest pair overlap (all pairs), wall overlap and floor overlap, by brute force."""
    pair = wall = floor = 0.0
    for i, (x, y, z, r) in enumerate(balls):
        wall = max(wall, math.hypot(x, y) + r - radius_tube)
        floor = max(floor, r - z)
        for (u, v, w, s) in balls[i + 1:]:
            if abs(w - z) < r + s:
                pair = max(pair, r + s - math.sqrt((x - u) ** 2 + (y - v) ** 2 + (z - w) ** 2))
    return pair, wall, floor


tmp = tempfile.mkdtemp(prefix="packbed-lammps-")
try:
    # 1. The paper's bed on 2 ranks.
    out = os.path.join(tmp, "bed")
    p = run(["generate", "--engine", "lammps", "--ranks", "2", "-a", "5", "-n", "500", "-s", "1",
             "-q", "-o", out])
    check(p.returncode == 0, f"generate --engine lammps --ranks 2 exits 0 ({p.returncode}: "
                             f"{p.stderr.strip()[:300]})")
    if p.returncode == 0:
        balls = spheres(os.path.join(out, "particles.csv"))
        check(len(balls) == 500, f"500 spheres come back ({len(balls)})")
        pair, wall, floor = largest_overlaps(balls, 2.5)
        check(pair < 1e-4, f"largest pair overlap {pair:.3g} < 1e-4 Dp")
        check(wall < 1e-4, f"every sphere inside the tube: largest wall overlap {wall:.3g}")
        check(floor < 1e-4, f"every sphere above the floor: largest floor overlap {floor:.3g}")
        with open(os.path.join(out, "summary.json")) as f:
            s = json.load(f)
        e = s["void_fraction"]
        check(0.43 <= e <= 0.44, f"void fraction {e:.4f} in the paper's [0.43, 0.44]")
        check(s["engine"]["name"] == "lammps" and s["engine"]["ranks"] == 2,
              "summary.json records the engine and its 2 ranks")
        band = (s["parameters"]["overlap_low"], s["parameters"]["overlap_high"])
        check(band == (0.01, 0.02),
              f"summary.json records the band LAMMPS ran, its own 1-2 % of Dp ({band})")
        check([st["name"] for st in s["stages"]] == ["initial", "intermediate", "final"]
              and s["iterations"] == sum(st["iterations"] for st in s["stages"]) > 0,
              f"the three stages recorded, their steps summing to {s['iterations']}")
        check(all(os.path.isfile(os.path.join(out, "lammps", f)) for f in
                  ("in.packbed", "start.data", "log.lammps", "bed.dump", "job.json")),
              "the job and LAMMPS's log are kept in lammps/")
        again = os.path.join(tmp, "again")
        p = run(["generate", "--engine", "lammps", "--ranks", "2", "-a", "5", "-n", "500", "-s",
                 "1", "-q", "-o", again])
        same = p.returncode == 0 and (open(os.path.join(out, "particles.csv")).read() ==
                                      open(os.path.join(again, "particles.csv")).read())
        check(same, "the same seed on the same ranks gives the same bytes")

    # 1b. The other containers map onto LAMMPS: a box's four walls, a periodic cell's
    # boundaries (the floor its one wall), an annulus's rod, a cone's slanted wall (LAMMPS's
    # region cone); and two sizes as two types.
    for spec, inside in (
            ("box:6,5", lambda x, y, r: min(x - r, 6 - x - r, y - r, 5 - y - r)),
            ("periodic:6,6", lambda x, y, r: min(x, 6 - x, y, 6 - y) + r),
            ("annulus:8,2", lambda x, y, r: min(4 - math.hypot(x, y) - r,
                                                math.hypot(x, y) - r - 1)),
            # a hopper, Rb = 2.5 widening to 4.5 at z = 20: (R(z) - rho) cos - r with
            # cos = 20 / sqrt(404)
            ("cone:5,9,20", None)):
        out = os.path.join(tmp, spec.split(":")[0])
        p = run(["generate", "--engine", "lammps", "--container", spec, "-n", "300", "-s", "2",
                 "-q", "-o", out])
        ok = p.returncode == 0
        if ok:
            balls = spheres(os.path.join(out, "particles.csv"))
            gap = min(inside(x, y, r) if inside else
                      (2.5 + 0.1 * z - math.hypot(x, y)) * 20 / math.sqrt(404) - r
                      for x, y, z, r in balls)
            floor = max(r - z for x, y, z, r in balls)
            s = json.load(open(os.path.join(out, "summary.json")))
            ok = (len(balls) == 300 and gap > -1e-4 and floor < 1e-4
                  and s["max_overlap_pair"] < 1e-4)
        check(ok, f"--container {spec}: relaxed by LAMMPS, every sphere inside, overlaps within "
                  f"the tolerance ({p.returncode}: {p.stderr.strip()[:160]})")
    out = os.path.join(tmp, "sizes")
    p = run(["generate", "--engine", "lammps", "--sizes", "discrete:1:0.5,1.5:0.5", "-a", "6",
             "-n", "300", "-s", "2", "-q", "-o", out])
    ok = p.returncode == 0
    if ok:
        balls = spheres(os.path.join(out, "particles.csv"))
        worst = 0.0
        for i, (x, y, z, r) in enumerate(balls):
            for (u, v, w, q) in balls[i + 1:]:
                worst = max(worst, (r + q - math.dist((x, y, z), (u, v, w))) / (2 * min(r, q)))
        ok = len({r for *_, r in balls}) == 2 and worst < 1e-4
    check(ok, f"two sizes: every pair within 1e-4 of its smaller diameter ({p.returncode}: "
              f"{p.stderr.strip()[:160]})")

    # 2. A schedule that does not end: the initial stage's overlaps not gone in 50 iterations.
    out = os.path.join(tmp, "short")
    p = run(["generate", "--engine", "lammps", "-a", "5", "-n", "500", "--max-iterations", "50",
             "-q", "-o", out])
    check(p.returncode == 1 and "not removed within 50 iterations" in p.stderr
          and len(p.stderr.strip().splitlines()) == 1 and not os.path.exists(out),
          f"a run that does not converge: exit 1, one line, nothing written ({p.returncode}: "
          f"{p.stderr.strip()[:200]})")

    # 2b. A bed that jams in the final stage (its overlaps do not fall with gravity): with a
    # skin of 0.2 this periodic bed took 1 956 680 steps (78 s); the stage's budget (10 times
    # the 6 883 steps before it) stops it after 75 713 with the schedule's line.
    out = os.path.join(tmp, "jammed")
    p = run(["generate", "--engine", "lammps", "--container", "periodic:6,6", "-n", "300", "-s",
             "2", "--skin", "0.2", "-q", "-o", out])
    check(p.returncode == 1 and "the bed is jammed" in p.stderr
          and "after 68830 steps of the final stage" in p.stderr
          and len(p.stderr.strip().splitlines()) == 1 and not os.path.exists(out),
          f"a jammed bed: exit 1 within the final stage's budget, one line, nothing written "
          f"({p.returncode}: {p.stderr.strip()[:200]})")

    # 3. A LAMMPS error (a variable given twice, of two styles): LAMMPS's own message.
    wrapper = os.path.join(tmp, "lmp-bad")
    with open(wrapper, "w") as f:
        f.write('#!/bin/sh\nif [ "$1" = -h ]; then exec lmp -h; fi\n'
                'exec lmp "$@" -var g 1\n')
    os.chmod(wrapper, os.stat(wrapper).st_mode | stat.S_IXUSR)
    out = os.path.join(tmp, "error")
    p = run(["generate", "--engine", "lammps", "--lmp", wrapper, "-a", "5", "-n", "100", "-q",
             "-o", out])
    check(p.returncode == 1 and "LAMMPS: ERROR" in p.stderr and "variable" in p.stderr
          and not os.path.exists(out),
          f"a LAMMPS error: exit 1 with LAMMPS's message, nothing written ({p.returncode}: "
          f"{p.stderr.strip()[:200]})")

    # 4. No LAMMPS by that name: bad input.
    p = run(["generate", "--engine", "lammps", "--lmp", "no-such-lmp", "-o",
             os.path.join(tmp, "none")])
    check(p.returncode == 2 and "--lmp no-such-lmp" in p.stderr,
          f"--lmp naming no program: exit 2 naming it ({p.stderr.strip()[:120]})")

    # 5. --write-only, run as the README says, brought back by import-lammps.
    job = os.path.join(tmp, "job")
    p = run(["generate", "--engine", "lammps", "--write-only", job, "-a", "4", "-n", "150",
             "-s", "3", "-q"])
    check(p.returncode == 0 and os.path.isfile(os.path.join(job, "README.md")),
          f"--write-only writes the job ({p.returncode}: {p.stderr.strip()[:200]})")
    p = run(["import-lammps", job, "-o", os.path.join(tmp, "early")])
    check(p.returncode == 2 and "log.lammps is missing" in p.stderr,
          f"import-lammps before the run: exit 2 ({p.stderr.strip()[:160]})")
    readme = open(os.path.join(job, "README.md")).read()
    check("srun lmp -in in.packbed" in readme and "#SBATCH" in readme,
          "the README has a Slurm script")
    lmp = subprocess.run(["lmp", "-in", "in.packbed", "-log", "log.lammps"], cwd=job,
                         capture_output=True, text=True)
    check(lmp.returncode == 0, f"LAMMPS runs the job ({lmp.returncode})")
    back = os.path.join(tmp, "back")
    p = run(["import-lammps", job, "-o", back, "-q"])
    check(p.returncode == 0, f"import-lammps brings it back ({p.returncode}: "
                             f"{p.stderr.strip()[:200]})")
    if p.returncode == 0:
        balls = spheres(os.path.join(back, "particles.csv"))
        pair, wall, floor = largest_overlaps(balls, 2.0)
        check(len(balls) == 150 and max(pair, wall, floor) < 1e-4,
              f"the imported bed: 150 spheres, largest overlap {max(pair, wall, floor):.3g}")
    # 6. What import-lammps keeps stays in proportion to the log: 6e7 empty lines appended
    # (60 MB) are read within an address space of 1 GB (a list of the lines took 1.1 GB).
    with open(os.path.join(job, "log.lammps"), "a") as f:
        f.write("\n" * 60_000_000)
    import resource
    p = subprocess.run([packbed, "import-lammps", job, "-o", os.path.join(tmp, "long-log"), "-q"],
                       capture_output=True, text=True,
                       preexec_fn=lambda: resource.setrlimit(resource.RLIMIT_AS, (1 << 30,) * 2))
    check(p.returncode == 0, f"a log of 60 MB read within 1 GB of address space ({p.returncode}: "
                             f"{p.stderr.strip()[:200]})")
finally:
    shutil.rmtree(tmp, ignore_errors=True)

if failures:
    print(f"{len(failures)} check(s) failed")
    sys.exit(1)
print("all checks passed")
