#!/usr/bin/env python3
"""`packbed export --format openfoam` of an annulus meshed by Debian's OpenFOAM.

A simple cubic lattice of Dp = 1 in the annulus between a tube of diameter 6 and a rod of
diameter 2, one layer tall (`lattice --region annulus:6,2,1`): the 12 lattice points at
1.5 <= rho <= 2.5, z = 0.5, each on the floor, 8 touching pairs, none touching a wall; with
caps:0.05, the container from z = 0 to the bed's top + 1 Dp = 2. The exact fluid volume by
hand: pi (9 - 1) 2 - (12 pi / 6 - 16 caps of height 0.025 - 12 caps of height 0.05), which
packbed.json and the README must state. blockMesh + snappyHexMesh + checkMesh: asserts "Mesh
OK.", the patches inlet, outlet, wall (the tube), rod and particles with faces and none left on
`outside`, and the mesh's total volume within 1 % of the exact fluid volume (+0.03 % measured
with the case's default facets, volume here: 44.0563 against 44.0433; the whole script 26 s on the 2-core machine).

Usage: check_openfoam_annulus.py PACKBED. Exit 77 (skipped) when OpenFOAM is missing."""
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
work = tempfile.mkdtemp(prefix="packbed-foam-annulus-")
run = runner(env, work)


case = os.path.join(work, "case")
run(exe, "lattice", "--type", "sc", "--region", "annulus:6,2,1", "--diameter", "1", "--quiet",
    "--out", "ring")
assert len(open(os.path.join(work, "ring", "particles.csv")).read().splitlines()) == 13
run(exe, "export", "ring/particles.csv", "--format", "openfoam", "--contacts", "caps:0.05",
    "--out", case, "--quiet")
exact = 16 * math.pi - (12 * math.pi / 6 - 16 * cap(0.5, 0.475) - 12 * cap(0.5, 0.45))
report = json.load(open(os.path.join(case, "packbed.json")))
assert report["container"] == {"shape": "annulus", "radius": 3.0, "inner_radius": 1.0,
                               "height": 2.0}, report["container"]
assert abs(report["volumes"]["fluid"] / exact - 1) < 1e-12, (report["volumes"], exact)
readme = open(os.path.join(case, "README.md")).read()
stated = float(re.search(r"; fluid ([0-9.eE+-]+?)\. ", readme).group(1))
assert abs(stated / exact - 1) < 1e-12, (stated, exact)
for stl in ("particles.stl", "wall.stl", "rod.stl"):
    assert os.path.exists(os.path.join(case, "constant", "triSurface", stl)), stl
x, y, z = report["openfoam"]["location_in_mesh"]
assert 1.0 < math.hypot(x, y) < 3.0 and 0 < z < 2, (x, y, z)

out, patches, volume = mesh_case(run, case)
check_patches(patches, ("inlet", "outlet", "wall", "rod", "particles"))
check_volume("annulus", volume, exact, 0.01, patches)
shutil.rmtree(work)
