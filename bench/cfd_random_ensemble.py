#!/usr/bin/env python3
"""The drag of an ensemble of random periodic arrays against van der Hoef et al. (2005)
(docs/validation.md, "CFD: periodic arrays"): `bench/cfd_periodic_series.py` at one mesh level
for each seed, then the ensemble's mean, its standard deviation between arrays and the standard
error of the mean. With SERIES (a series.json of one array over several levels, whose Celik
extrapolation carries the ensemble from this level to the mesh's limit) the mean is also given
extrapolated: mean F x extrapolated F / F at this level, of that array.

Usage: bench/cfd_random_ensemble.py PACKBED OUT N FRACTION GAP CPD FIRST_SEED LAST_SEED [SERIES]
    Each seed's case goes to OUT/seedS (replaced; a seed whose OUT/seedS/series.json exists
    at level CPD is read, not run again). Prints a line per array and the summary, writes
    OUT/ensemble.json.
"""
import json
import math
import os
import statistics
import subprocess
import sys


def level_row(series, cpd):
    with open(series) as f:
        rows = json.load(f)["levels"]
    return next(r for r in rows if r["cells_per_diameter"] == cpd)


def main():
    exe, out, n, fraction, gap, cpd, first, last, *series = sys.argv[1:]
    cpd, here = int(cpd), os.path.dirname(os.path.abspath(__file__))
    rows = []
    for seed in range(int(first), int(last) + 1):
        case = f"{out}/seed{seed}"
        done = f"{case}/series.json"
        try:
            row = level_row(done, cpd)
        except (OSError, StopIteration, ValueError):
            subprocess.run([f"{here}/cfd_periodic_series.py", exe, case,
                            f"random:{n}:{fraction}:{gap}:{seed}", str(cpd)],
                           check=True, stdout=subprocess.DEVNULL)
            row = level_row(done, cpd)
        row["seed"] = seed
        rows.append(row)
        print(json.dumps({k: row[k] for k in ("seed", "cells", "mesh_void_fraction", "F",
                                              "van_der_hoef_F", "iterations", "failed")
                          if k in row}), flush=True)
    passed = [r for r in rows if "failed" not in r]  # meshes that failed checkMesh stay out
    f = [r["F"] for r in passed]
    law = passed[0]["van_der_hoef_F"]
    mean, sd = statistics.fmean(f), statistics.stdev(f) if len(f) > 1 else 0.0
    result = {"count": len(f), "failed_meshes": [r["seed"] for r in rows if "failed" in r],
              "cells_per_diameter": cpd, "mean_F": mean, "sd_F": sd,
              "standard_error_F": sd / math.sqrt(len(f)), "van_der_hoef_F": law,
              "mean_over_law": mean / law, "arrays": rows}
    if series:
        with open(series[0]) as s:
            whole = json.load(s)
        factor = whole["celik"]["extrapolated_F"] / level_row(series[0], cpd)["F"]
        result["extrapolation_factor"] = factor
        result["extrapolated_mean_over_law"] = mean * factor / law
    print(json.dumps({k: v for k, v in result.items() if k != "arrays"}))
    with open(f"{out}/ensemble.json", "w") as o:
        json.dump(result, o, indent=1)


if __name__ == "__main__":
    main()
