#!/usr/bin/env python3
"""Write a face-centred cubic bed of spheres (diameter 1, touching) that fills a cylinder,
as packbed CSV: a large, dense bed for timing `packbed analyze` without generating one.
Usage: make_lattice_bed.py OUT.csv CONTAINER_RADIUS SPHERES"""
import math
import sys

out, rt, wanted = sys.argv[1], float(sys.argv[2]), int(sys.argv[3])
a = math.sqrt(2.0)  # FCC cell edge for touching unit spheres
basis = [(0, 0, 0), (0.5, 0.5, 0), (0.5, 0, 0.5), (0, 0.5, 0.5)]
n = int(rt / a) + 2
rows = []
k = 0
while len(rows) < wanted:
    for j in range(-n, n + 1):
        for i in range(-n, n + 1):
            for bx, by, bz in basis:
                x, y, z = (i + bx) * a, (j + by) * a, 0.5 + (k + bz) * a
                if math.hypot(x, y) + 0.5 <= rt and len(rows) < wanted:
                    rows.append(f"{x!r},{y!r},{z!r},0.5")
    k += 1
with open(out, "w") as f:
    f.write("x,y,z,r\n" + "\n".join(rows) + "\n")
