#!/usr/bin/env python3
"""`packbed export --format openfoam` meshed by Debian's OpenFOAM: blockMesh, snappyHexMesh,
checkMesh on two tiny beds.

1. A generated bed in a cylinder (a = 3, 30 spheres) with caps:0.02. Asserts checkMesh's
   "Mesh OK.", the patches inlet, outlet, wall and particles with faces, no face left on
   `outside`, and the mesh's total volume within 5 % of the bed's exact fluid volume
   (packbed.json). At the default levels (cells of Dp/16 at the particles) the mesh loses
   3.3 % of the fluid (21.9613 against 22.7211): the 0.02 Dp gaps of the caps and the thin
   wedges near contacts are narrower than a cell.
2. A simple cubic lattice in a box: 3 x 3 x 2 balls of Dp = 1 in [0, 3] x [0, 3],
   touching their neighbours, 16 of them one or two faces, the lower 9 the floor, with
   caps:0.05; the container from z = 0 to the bed's top + 1 Dp = 3. The exact fluid volume is
   computed here by hand and must be the one packbed.json and the case's README state: 27 -
   (18 pi / 6 - 66 caps of height 0.025 - 33 caps of height 0.05). The background mesh is the
   box (12 x 12 x 12 cells, bounding box (0 0 0) (3 3 3) to 1e-4), its sides the patch `wall`:
   no wall.stl. Asserts
   "Mesh OK.", the patches inlet, outlet, wall and particles (and no other), and the mesh's
   total volume within 1 % of the exact fluid volume (-0.47 % measured: 17.6814 against
   17.7642; snappyHexMesh about 12 s).

Both cases have the default facets of a case (auto: volume here, each sphere's polyhedron
holding its volume), so the mesh's volume is compared with the exact one without the 0.86 %
of the solid that inscribed facets leave out.

Usage: check_openfoam.py PACKBED. Exit 77 (skipped) when OpenFOAM is missing
(scripts/install-deps.sh --test installs it)."""
import json
import math
import os
import re
import shutil
import sys
import tempfile

from openfoam_env import check_patches, check_volume, mesh_case, openfoam_or_skip, runner

exe = sys.argv[1]
env = openfoam_or_skip()
work = tempfile.mkdtemp(prefix="packbed-foam-")
run = runner(env, work)


def mesh(case):
    """blockMesh, snappyHexMesh, checkMesh in `case` (mesh_case)."""
    return mesh_case(run, case)


# 1. The cylinder.
case = os.path.join(work, "case")
run(exe, "generate", "--solver", "fire", "--aspect-ratio", "3", "--particles", "30", "--seed",
    "1", "--quiet", "--out", "bed")
run(exe, "export", "bed/particles.csv", "--format", "openfoam", "--contacts", "caps:0.02",
    "--out", case, "--quiet")
fluid = json.load(open(os.path.join(case, "packbed.json")))["volumes"]["fluid"]
out, patches, volume = mesh(case)
check_patches(patches, ("inlet", "outlet", "wall", "particles"))
check_volume("cylinder", volume, fluid, 0.05, patches)

# 2. The box.
box_case = os.path.join(work, "box_case")
run(exe, "lattice", "--type", "sc", "--region", "box:3,3,2", "--diameter", "1", "--quiet",
    "--out", "boxed")
run(exe, "export", "boxed/particles.csv", "--format", "openfoam", "--contacts", "caps:0.05",
    "--out", box_case, "--quiet")


def cap(r, s):  # a ball's cap beyond a plane s from its centre
    c = r - s
    return math.pi * c * c * (3 * r - c) / 3


# 33 contacts (12 along x, 12 along y, 9 along z) capped on both sides, 24 face and 9 floor
# contacts capped 0.05 from the face.
exact = 27.0 - (18 * math.pi / 6 - 66 * cap(0.5, 0.475) - 33 * cap(0.5, 0.45))
report = json.load(open(os.path.join(box_case, "packbed.json")))
assert report["container"] == {"shape": "box", "size": [3.0, 3.0], "corner": [0.0, 0.0],
                               "height": 3.0}, report["container"]
assert abs(report["volumes"]["container"] - 27.0) < 1e-12, report["volumes"]
assert abs(report["volumes"]["fluid"] / exact - 1) < 1e-12, (report["volumes"], exact)
readme = open(os.path.join(box_case, "README.md")).read()
stated = float(re.search(r"; fluid ([0-9.eE+-]+?)\. ", readme).group(1))
assert abs(stated / exact - 1) < 1e-12, (stated, exact)
assert "No `wall.stl`" in readme, readme
assert not os.path.exists(os.path.join(box_case, "constant", "triSurface", "wall.stl"))
block = open(os.path.join(box_case, "system", "blockMeshDict")).read()
assert "(12 12 12) simpleGrading" in block, block
out, patches, volume = mesh(box_case)
for name in ("inlet", "outlet", "wall", "particles"):
    assert patches.get(name, 0) > 0, (name, patches)
assert set(patches) == {"inlet", "outlet", "wall", "particles"}, patches
# The box, to the snapping's small moves of the wall's points (3e-5 measured).
low_high = re.search(r"Overall domain bounding box \(([^)]*)\) \(([^)]*)\)", out)
bounds = [float(x) for x in low_high.group(1).split() + low_high.group(2).split()]
assert all(abs(b - e) < 1e-4 for b, e in zip(bounds, (0, 0, 0, 3, 3, 3))), bounds
check_volume("box", volume, exact, 0.01, patches)
shutil.rmtree(work)
