#!/usr/bin/env python3
"""A mesh series of an array in a periodic cell against Zick & Homsy (1982) or van der Hoef et
al. (2005) (docs/validation.md, "CFD: periodic arrays"): the 2 x 2 x 2 array of `packbed
lattice --type sc`, its spheres shrunk to the solid fraction PHI (`export --contacts shrink:F`)
or, with PHI "touching", the 3 x 3 x 3 array left touching with their contacts flattened into
caps 0.02 d apart; with PHI "random:N:FRACTION:GAP:SEED", `packbed random-array` of N spheres
(no contact: the gap keeps them apart); each mesh
level exported with `--flow periodic` (icosphere level 5: 20 480 triangles a sphere, whose
inscribed polyhedron holds all but about 0.1 % of its volume), run by its Allrun and read by `cfd-report --json`; then
the observed order, the Richardson extrapolation and the grid convergence index of the three
finest levels (Celik et al. 2008, J. Fluids Eng. 130, 078001, the procedure of their section 2).

Usage: bench/cfd_periodic_series.py PACKBED OUT PHI CPD [CPD ...] [--refine N] [--facets MODE]
    PHI: a solid fraction (0.216), "touching" or "random:N:FRACTION:GAP:SEED"; CPD: --cells-per-diameter of each level
    (level 1 at the spheres), coarse to fine; --refine and --facets: export's (default 5 and
    inscribed). OUT is replaced. Prints a table and writes
    OUT/series.json. Each level also records Allrun's wall time, snappyHexMesh's "Finished
    meshing in", simpleFoam's last ExecutionTime and the largest resident set of a process; a
    level that cfd-report refuses (a mesh that failed checkMesh) records its reason as
    "failed" and stays out of the extrapolation.
"""
import json
import math
import shutil
import subprocess
import sys
import time


def celik(h, f):
    """Celik et al. (2008): h and f of three levels, finest first. Returns p, the
    extrapolated value, the approximate and extrapolated relative errors and GCI_fine (all of
    the two finest levels)."""
    (h1, h2, h3), (f1, f2, f3) = h, f
    r21, r32 = h2 / h1, h3 / h2
    e21, e32 = f2 - f1, f3 - f2
    s = math.copysign(1.0, e32 / e21)
    p = 2.0
    for _ in range(200):  # p = |ln|e32/e21| + q(p)| / ln r21, q(p) = ln((r21^p - s)/(r32^p - s))
        q = math.log((r21**p - s) / (r32**p - s))
        p = abs(math.log(abs(e32 / e21)) + q) / math.log(r21)
    ext = (r21**p * f1 - f2) / (r21**p - 1.0)
    ea = abs((f1 - f2) / f1)
    eext = abs((ext - f1) / ext)
    gci = 1.25 * ea / (r21**p - 1.0)
    return {"order": p, "extrapolated": ext, "approximate_error": ea,
            "extrapolated_error": eext, "gci_fine": gci, "oscillating": s < 0}


def main():
    args = sys.argv[1:]
    surface = {"--refine": "5", "--facets": "inscribed"}
    for flag in surface:
        if flag in args:
            k = args.index(flag)
            surface[flag] = args[k + 1]
            del args[k:k + 2]
    exe, out, phi_text, *levels = args
    shutil.rmtree(out, ignore_errors=True)
    # Touching spheres need a cell wider than 2 d each way (caps across a side and inside
    # both), so 3 x 3 x 3; a shrunk array fits in 2 x 2 x 2.
    if phi_text.startswith("random:"):
        n, fraction, gap, seed = phi_text.split(":")[1:]
        subprocess.run([exe, "random-array", "-n", n, "--solid-fraction", fraction, "--gap", gap,
                        "--seed", seed, "-q", "--out", f"{out}/lattice"], check=True)
        with open(f"{out}/lattice/summary.json") as f:
            array = json.load(f)
        contacts, phi, height = "none", array["solid_fraction"], repr(array["period_z"])
    else:
        region = "periodic:3,3,3" if phi_text == "touching" else "periodic:2,2,2"
        height = "3" if phi_text == "touching" else "2"
        subprocess.run([exe, "lattice", "--type", "sc", "--region", region,
                        "--origin", "0.5,0.5,0.5", "--no-analysis", "-q", "--out",
                        f"{out}/lattice"], check=True)
        if phi_text == "touching":
            contacts, phi = "caps:0.02", math.pi / 6
        else:
            phi = float(phi_text)
            contacts = f"shrink:{1.0 - (6.0 * phi / math.pi) ** (1.0 / 3.0)!r}"
    rows = []
    for cpd in levels:
        case = f"{out}/cpd{cpd}"
        subprocess.run([exe, "export", f"{out}/lattice/particles.csv", "--format", "openfoam",
                        "--flow", "periodic", "--container-height", height, "--contacts", contacts,
                        "--cells-per-diameter", cpd, "--particle-level", "1",
                        "--refine", surface["--refine"], "--facets", surface["--facets"],
                        "--reynolds", "0.01", "-q", "--out", case], check=True)
        start = time.time()
        # GNU time's %M: the largest resident set of the run's processes (one rank), kB
        subprocess.run(["/usr/bin/time", "-f", "%M", "-o", f"{case}/memory", f"{case}/Allrun"],
                       check=True, stdout=subprocess.DEVNULL)
        seconds = time.time() - start
        run = subprocess.run([exe, "cfd-report", case, "--json", "-q"], capture_output=True,
                             text=True)
        if run.returncode != 0:  # a mesh that failed checkMesh: recorded, left out of Celik's
            row = {"cells_per_diameter": int(cpd), "failed": run.stderr.strip(),
                   "seconds": time.time() - start}
            rows.append(row)
            print(json.dumps(row), flush=True)
            continue
        report = json.loads(run.stdout)
        cells = 0
        with open(f"{case}/log.checkMesh") as log:
            for line in log:
                if line.strip().startswith("cells:"):
                    cells = int(line.split()[1])
        with open(f"{case}/log.snappyHexMesh") as log:
            meshing = [float(line.split("=")[1].split()[0]) for line in log
                       if line.startswith("Finished meshing in")]
        with open(f"{case}/log.simpleFoam") as log:
            solving = [float(line.split("=")[1].split()[0]) for line in log
                       if line.startswith("ExecutionTime")]
        with open(f"{case}/memory") as f:
            memory = int(f.read().split()[-1]) / 1024.0
        p = report["periodic"]
        volume = p["cell_volume_m3"] * report["void_fraction"]["mesh"]
        row = {"cells_per_diameter": int(cpd), "cells": cells,
               "h_over_d": (volume / cells) ** (1 / 3) / report["flow"]["diameter_m"],
               "mesh_void_fraction": report["void_fraction"]["mesh"],
               "exact_void_fraction": report["void_fraction"]["exact"],
               "K": p["K"], "F": p["F"], "iterations": report["solver"]["iterations"],
               "converged": report["solver"]["converged"], "seconds": seconds,
               "snappy_seconds": meshing[-1], "simplefoam_seconds": solving[-1],
               "largest_process_MiB": memory,
               "reference": p["references"].get("zick_homsy_simple_cubic_K"),
               "van_der_hoef_F": p["references"].get("van_der_hoef_random_F")}
        rows.append(row)
        print(json.dumps(row), flush=True)
    result = {"phi": phi, "contacts": contacts, "refine": int(surface["--refine"]),
              "facets": surface["--facets"], "levels": rows}
    passed = [r for r in rows if "failed" not in r]
    if len(passed) >= 3:
        fine = passed[-3:][::-1]
        result["celik"] = celik([r["h_over_d"] for r in fine], [r["K"] for r in fine])
        result["celik"]["extrapolated_F"] = (1.0 - phi) * result["celik"]["extrapolated"]
        print(json.dumps(result["celik"]))
    with open(f"{out}/series.json", "w") as f:
        json.dump(result, f, indent=1)


if __name__ == "__main__":
    main()
