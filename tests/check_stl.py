#!/usr/bin/env python3
"""The STL files of `packbed export` checked by real checkers from Debian: admesh (closed, every
edge shared by two facets, consistent orientation, no degenerate facet, one part per body) and
OpenFOAM's surfaceCheck (closed, not self-intersecting), for a generated bed, a lattice in a
cylinder, a simple cubic lattice in a box (3 x 3 x 2 balls, 16 of them touching
one or two faces of the box, the lower 9 the floor) and a bed in a cone, with every treatment,
and beds of 12 cylinder pellets, of 8 trilobes, of 3 rings and of 10 spherocylinders, each
shrunk by 2 %. For caps and shrink admesh must also leave every stored normal as it is; the
unions of enlarge and bridges (CGAL's corefinement) keep small triangles whose single-precision
normal admesh recomputes differently, so there only orientation is checked.
Two untreated spheres overlapping by 0.045 Dp must be reported as self-intersecting: the
checker is alive.
Usage: check_stl.py PACKBED. Exit 77 (reported as skipped by ctest) when admesh or surfaceCheck
is missing (scripts/install-deps.sh --test installs both)."""
import os
import re
import shutil
import subprocess
import sys
import tempfile

from openfoam_env import openfoam_env

exe = sys.argv[1]
if not shutil.which("admesh") or not shutil.which("surfaceCheck"):
    print("admesh or surfaceCheck (Debian packages admesh, openfoam) is not installed: skipped")
    sys.exit(77)
env = openfoam_env()
work = tempfile.mkdtemp(prefix="packbed-stl-")


def run(*args):
    # admesh 0.98 prints the 80-byte STL header past its end (into the facet count): bytes
    # that need not be UTF-8.
    return subprocess.run(args, cwd=work, env=env, check=True, capture_output=True,
                          text=True, errors="replace").stdout


def admesh(stl, parts, normals_kept):
    out = run("admesh", stl)
    stats = {k: v for k, v in re.findall(r"^(Number of parts|Backwards edges|Normals fixed|"
                                         r"Facets reversed|Degenerate facets|"
                                         r"Total disconnected facets)\s*:\s*(\d+)", out, re.M)}
    expected = {"Number of parts": str(parts), "Backwards edges": "0", "Facets reversed": "0",
                "Degenerate facets": "0", "Total disconnected facets": "0",
                "Normals fixed": "0" if normals_kept else stats.get("Normals fixed")}
    assert stats == expected, (stl, stats, expected)


def surface_check(stl):
    out = run("surfaceCheck", "-checkSelfIntersection", "-outputThreshold", "0", stl)
    closed = "Surface is closed. All edges connected to two faces." in out
    return closed, "Surface is not self-intersecting" in out


run(exe, "generate", "--solver", "fire", "--aspect-ratio", "3", "--particles", "30", "--seed",
    "1", "--quiet", "--out", "bed")
run(exe, "lattice", "--type", "fcc", "--region", "cylinder:3,3", "--quiet", "--out", "lattice")
n_lattice = sum(1 for _ in open(os.path.join(work, "lattice", "particles.csv"))) - 1
run(exe, "lattice", "--type", "sc", "--region", "box:3,3,2", "--quiet", "--out", "boxed")
n_boxed = sum(1 for _ in open(os.path.join(work, "boxed", "particles.csv"))) - 1
assert n_boxed == 18, n_boxed  # 3 x 3 x 2 balls of diameter 1
# A hopper: the prism about its slanted wall closes with the floor and the top.
run(exe, "generate", "--solver", "fire", "--container", "cone:2.5,4.5,12", "--particles", "30",
    "--seed", "1", "--quiet", "--out", "coned")
for bed, spheres in (("bed", 30), ("lattice", n_lattice), ("boxed", n_boxed), ("coned", 30)):
    for contacts in ("caps:0.02", "shrink:0.01", "enlarge:0.01", "bridges:0.2"):
        stl = f"{bed}-{contacts.split(':')[0]}.stl"
        run(exe, "export", f"{bed}/particles.csv", "--format", "stl", "--contacts", contacts,
            "--out", stl, "--quiet")
        united = contacts.split(":")[0] in ("enlarge", "bridges")
        # The bodies and the container; a union of touching bodies is one part.
        admesh(stl, (1 if united else spheres) + 1, normals_kept=not united)
        assert surface_check(stl) == (True, True), (stl, "closed, not self-intersecting")
        print(f"{stl}: {'one union' if united else f'{spheres} bodies'} + container, closed, "
              f"oriented, not self-intersecting")
# Pellets: 12 cylinders poured into a tube (generate --shape), each shrunk by 2 % about its
# centroid: 12 bodies and the container.
run(exe, "generate", "--shape", "cylinder:3,3", "--aspect-ratio", "4", "--particles", "12",
    "--seed", "3", "--quiet", "--out", "pellets")
run(exe, "export", "pellets/particles.csv", "--format", "stl", "--contacts", "shrink:0.02",
    "--out", "pellets.stl", "--quiet")
admesh("pellets.stl", 12 + 1, normals_kept=True)
assert surface_check("pellets.stl") == (True, True), ("pellets.stl", "closed, not self-intersecting")
print("pellets.stl: 12 cylinders + container, closed, oriented, not self-intersecting")
# Trilobes: 8 poured into a tube, each one closed surface of its three lobes' arcs meeting in
# the grooves, shrunk by 2 %.
run(exe, "generate", "--shape", "trilobe:1,0.8,1.5", "--aspect-ratio", "4", "--particles",
    "8", "--seed", "1", "--quiet", "--out", "trilobes")
run(exe, "export", "trilobes/particles.csv", "--format", "stl", "--contacts", "shrink:0.02",
    "--out", "trilobes.stl", "--quiet")
admesh("trilobes.stl", 8 + 1, normals_kept=True)
assert surface_check("trilobes.stl") == (True, True), ("trilobes.stl",
                                                        "closed, not self-intersecting")
print("trilobes.stl: 8 trilobes + container, closed, oriented, not self-intersecting")
# Rings: 3 poured into a tube of a = 3, each one closed surface of its side, its bore and its
# two annular ends (genus one), shrunk by 2 %.
run(exe, "generate", "--shape", "ring:1,0.5,1", "--aspect-ratio", "3", "--particles", "3",
    "--seed", "1", "--quiet", "--out", "rings")
run(exe, "export", "rings/particles.csv", "--format", "stl", "--contacts", "shrink:0.02",
    "--out", "rings.stl", "--quiet")
admesh("rings.stl", 3 + 1, normals_kept=True)
assert surface_check("rings.stl") == (True, True), ("rings.stl", "closed, not self-intersecting")
print("rings.stl: 3 rings + container, closed, oriented, not self-intersecting")
# Spherocylinders: 10 poured into a tube of a = 4, each its side and two caps of latitude bands
# closed by fans at the tips, shrunk by 2 %.
run(exe, "generate", "--shape", "spherocylinder:1,1", "--aspect-ratio", "4", "--particles",
    "10", "--seed", "2", "--quiet", "--out", "rods")
run(exe, "export", "rods/particles.csv", "--format", "stl", "--contacts", "shrink:0.02",
    "--out", "rods.stl", "--quiet")
admesh("rods.stl", 10 + 1, normals_kept=True)
assert surface_check("rods.stl") == (True, True), ("rods.stl", "closed, not self-intersecting")
print("rods.stl: 10 spherocylinders + container, closed, oriented, not self-intersecting")
with open(os.path.join(work, "overlap.csv"), "w") as f:
    f.write("x,y,z,r\n0,0,1,0.5\n0.95,0.1,1.02,0.5\n")  # 0.045 Dp of overlap
run(exe, "export", "overlap.csv", "--format", "stl", "--container-radius", "3", "--out",
    "none.stl", "--quiet")
assert surface_check("none.stl") == (True, False), "the overlapping spheres must intersect"
print("none.stl: self-intersecting, as two untreated overlapping spheres are")
shutil.rmtree(work)
