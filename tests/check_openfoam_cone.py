#!/usr/bin/env python3
"""`packbed export --format openfoam` of a cone meshed by Debian's OpenFOAM.

A simple cubic lattice of Dp = 1 in a hopper whose floor of diameter 6 widens to 10 at z = 4,
one layer tall (`lattice --region cone:6,10,4,1`): the 21 points of z = 0.5 at least 0.5 from
the slanted wall (cos (3.25 - rho) >= 0.5, cos = 4 / sqrt(20): i^2 + j^2 <= 5), each on the
floor, none touching the wall; with caps:0.05, the container from z = 0 to the bed's top +
1 Dp = 2. The exact fluid volume by hand: the frustum pi 2 (3^2 + 3 x 4 + 4^2) / 3 less the
balls, their 21 floor caps of height 0.05 and two caps of height 0.025 per touching pair (32);
packbed.json and the README must state it. blockMesh + snappyHexMesh + checkMesh: asserts "Mesh OK.", the
patches inlet, outlet, wall (the slanted wall) and particles with faces and none left on
`outside`, and the mesh's total volume within 1 % of the exact fluid volume (-0.12 % measured
with the case's default facets, volume here: 66.5572 against 66.6385; the whole script 19 s on the 2-core machine).

Usage: check_openfoam_cone.py PACKBED. Exit 77 (skipped) when OpenFOAM is missing."""
import json
import math
import os
import re
import shutil
import sys
import tempfile

from openfoam_env import cap, check_patches, check_volume, mesh_case, openfoam_or_skip, runner

exe = sys.argv[1]
env = openfoam_or_skip()
work = tempfile.mkdtemp(prefix="packbed-foam-cone-")
run = runner(env, work)

case = os.path.join(work, "case")
run(exe, "lattice", "--type", "sc", "--region", "cone:6,10,4,1", "--diameter", "1", "--quiet",
    "--out", "hopper")
points = [(i, j) for i in range(-3, 4) for j in range(-3, 4) if i * i + j * j <= 5]
assert len(points) == 21
rows = open(os.path.join(work, "hopper", "particles.csv")).read().splitlines()
assert len(rows) == 22, len(rows)
pairs = sum(1 for a in points for b in points if a < b and abs(a[0] - b[0]) + abs(a[1] - b[1]) == 1)
assert pairs == 32, pairs
run(exe, "export", "hopper/particles.csv", "--format", "openfoam", "--contacts", "caps:0.05",
    "--out", case, "--quiet")
frustum = math.pi * 2 * (9 + 3 * 4 + 4 * 4) / 3
exact = frustum - (21 * math.pi / 6 - 2 * pairs * cap(0.5, 0.475) - 21 * cap(0.5, 0.45))
report = json.load(open(os.path.join(case, "packbed.json")))
assert report["container"] == {"shape": "cone", "floor_diameter": 6.0, "top_diameter": 10.0,
                               "cone_height": 4.0, "height": 2.0}, report["container"]
assert abs(report["volumes"]["fluid"] / exact - 1) < 1e-12, (report["volumes"], exact)
readme = open(os.path.join(case, "README.md")).read()
stated = float(re.search(r"; fluid ([0-9.eE+-]+?)\. ", readme).group(1))
assert abs(stated / exact - 1) < 1e-12, (stated, exact)
for stl in ("particles.stl", "wall.stl"):
    assert os.path.exists(os.path.join(case, "constant", "triSurface", stl)), stl
x, y, z = report["openfoam"]["location_in_mesh"]
assert math.hypot(x, y) < 3.0 and 0 < z < 2, (x, y, z)

out, patches, volume = mesh_case(run, case)
check_patches(patches, ("inlet", "outlet", "wall", "particles"))
check_volume("cone", volume, exact, 0.01, patches)
shutil.rmtree(work)
