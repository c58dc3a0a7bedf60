#!/usr/bin/env python3
"""`packbed export --format openfoam` meshed by Debian's OpenFOAM: a tiny bed (a = 3, 30 spheres)
with caps, blockMesh, snappyHexMesh, checkMesh. Asserts checkMesh's "Mesh OK.", the patches
inlet, outlet, wall and particles with faces, no face left on `outside`, and the mesh's total
volume within 5 % of the bed's exact fluid volume (packbed.json). At the default levels
(cells of Dp/16 at the particles) the mesh loses about 3 % of the fluid: the 0.02 Dp gaps
of the caps and the thin wedges near contacts are narrower than a cell.
Usage: check_openfoam.py PACKBED. Exit 77 (skipped) when OpenFOAM is missing
(scripts/install-deps.sh --test installs it)."""
import json
import os
import re
import shutil
import subprocess
import sys
import tempfile

from openfoam_env import openfoam_env

exe = sys.argv[1]
if not all(shutil.which(p) for p in ("blockMesh", "snappyHexMesh", "checkMesh")):
    print("blockMesh, snappyHexMesh or checkMesh (Debian package openfoam) is missing: skipped")
    sys.exit(77)
env = openfoam_env()
work = tempfile.mkdtemp(prefix="packbed-foam-")
case = os.path.join(work, "case")


def run(*args, cwd=work):
    r = subprocess.run(args, cwd=cwd, env=env, capture_output=True, text=True)
    assert r.returncode == 0, (args, r.stdout[-3000:], r.stderr[-3000:])
    return r.stdout


run(exe, "generate", "--solver", "fire", "--aspect-ratio", "3", "--particles", "30", "--seed",
    "1", "--quiet", "--out", "bed")
run(exe, "export", "bed/particles.csv", "--format", "openfoam", "--contacts", "caps:0.02",
    "--out", case, "--quiet")
fluid = json.load(open(os.path.join(case, "packbed.json")))["volumes"]["fluid"]
run("blockMesh", cwd=case)
run("snappyHexMesh", "-overwrite", cwd=case)
out = run("checkMesh", cwd=case)
assert "Mesh OK." in out, out[-3000:]
patches = dict(re.findall(r"^\s+(\w+)\s+(\d+)\s+\d+\s+(?:ok|multiply)", out, re.M))
for name in ("inlet", "outlet", "wall", "particles"):
    assert int(patches.get(name, 0)) > 0, (name, patches)
assert int(patches.get("outside", 0)) == 0, patches
volume = float(re.search(r"Total volume = ([0-9.eE+-]+?)\.?\s", out).group(1))
error = volume / fluid - 1.0
print(f"mesh volume {volume:.6g} against the exact fluid volume {fluid:.6g}: {error:+.2%}; "
      f"patches {patches}")
assert abs(error) < 0.05, error
shutil.rmtree(work)
