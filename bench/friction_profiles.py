#!/usr/bin/env python3
"""Radial void fraction of frictionless and poured beds at a = 7.99 against de Klerk's and
Mueller's profiles (docs/validation.md, "Friction"): 10 beds of 1 436 spheres (seeds 1-10) for
each friction (spheres and walls alike), shells of 0.02 Dp, the band 2 Dp clear of the ends as
examples/validate.py's Figs. 2-3; the mean profile's RMS difference to each correlation over
x <= a/2, and its first minimum.

Usage: bench/friction_profiles.py PACKBED OUT [FRICTION ...]    (default frictions 0 0.03)
"""
import json
import math
import os
import shutil
import subprocess
import sys

exe, out = os.path.realpath(sys.argv[1]), sys.argv[2]
frictions = sys.argv[3:] or ["0", "0.03"]
a = 7.99
shutil.rmtree(out, ignore_errors=True)
os.makedirs(out)
corr = json.loads(subprocess.run([exe, "correlations", "-a", str(a), "--json"], check=True,
                                 capture_output=True, text=True).stdout)["radial_void_fraction"]
print("| friction | e (mean of 10) | RMS to de Klerk | RMS to Mueller | first minimum | at x |")
print("|---|---|---|---|---|---|")
for mu in frictions:
    profiles, voids = [], []
    for seed in range(1, 11):
        d = os.path.join(out, f"mu{mu}-s{seed}")
        subprocess.run([exe, "generate", "-a", str(a), "-n", "1436", "-s", str(seed), "--friction",
                        mu, "--wall-friction", mu, "--band-clearance", "2", "-q", "-o", d],
                       check=True)
        rows = open(os.path.join(d, "radial_void_fraction.csv")).read().split("\n")
        head = rows[0].split(",")
        xi, vi = head.index("x_from_wall_d"), head.index("void_fraction")
        table = [[float(v) for v in r.split(",")] for r in rows[1:] if r]
        profiles.append([(r[xi], r[vi]) for r in table])
        voids.append(json.load(open(os.path.join(d, "summary.json")))["void_fraction"])
    x = [p[0] for p in profiles[0] if p[0] <= a / 2]
    mean = [sum(p[i][1] for p in profiles) / len(profiles) for i in range(len(x))]
    rms = {}
    for name in ("de-klerk-2003", "mueller-1992"):
        c = corr[name]["void_fraction"]
        values = [c[min(round(xv / 0.01), len(c) - 1)] for xv in x]
        rms[name] = math.sqrt(sum((v - m) ** 2 for v, m in zip(values, mean)) / len(x))
    j = min(range(len(x) // 4), key=lambda i: mean[i])
    print(f"| {mu} | {sum(voids) / len(voids):.4f} | {rms['de-klerk-2003']:.3f} | "
          f"{rms['mueller-1992']:.3f} | {mean[j]:.3f} | {x[j]:.2f} |", flush=True)
