#!/usr/bin/env python3
"""The STL files of `packbed export` checked by real checkers from Debian: admesh (closed, every
edge shared by two facets, consistent normals, one part per body) and OpenFOAM's surfaceCheck
(closed, not self-intersecting), for a generated bed and a lattice, with caps and with shrink.
The untreated generated bed (spheres overlapping by up to 1e-4 Dp) must be reported as
self-intersecting: the checker is alive.
Usage: check_stl.py PACKBED. Exit 77 (reported as skipped by ctest) when admesh or surfaceCheck
is missing (scripts/install-deps.sh --test installs both)."""
import os
import re
import shutil
import subprocess
import sys
import tempfile

exe = sys.argv[1]
if not shutil.which("admesh") or not shutil.which("surfaceCheck"):
    print("admesh or surfaceCheck (Debian packages admesh, openfoam) is not installed: skipped")
    sys.exit(77)
env = dict(os.environ)
if "WM_PROJECT_DIR" not in env and os.path.isdir("/usr/share/openfoam"):
    env["WM_PROJECT_DIR"] = "/usr/share/openfoam"  # Debian's OpenFOAM finds its etc/ there
work = tempfile.mkdtemp(prefix="packbed-stl-")


def run(*args):
    return subprocess.run(args, cwd=work, env=env, check=True, capture_output=True,
                          text=True).stdout


def admesh(stl, parts):
    out = run("admesh", stl)
    stats = {k: v for k, v in re.findall(r"^(Number of parts|Backwards edges|Normals fixed|"
                                         r"Total disconnected facets)\s*:\s*(\d+)", out, re.M)}
    expected = {"Number of parts": str(parts), "Backwards edges": "0", "Normals fixed": "0",
                "Total disconnected facets": "0"}
    assert stats == expected, (stl, stats, expected)


def surface_check(stl):
    out = run("surfaceCheck", "-checkSelfIntersection", "-outputThreshold", "0", stl)
    closed = "Surface is closed. All edges connected to two faces." in out
    return closed, "Surface is not self-intersecting" in out


run(exe, "generate", "--solver", "fire", "--aspect-ratio", "3", "--particles", "30", "--seed",
    "1", "--quiet", "--out", "bed")
run(exe, "lattice", "--type", "fcc", "--region", "cylinder:3,3", "--quiet", "--out", "lattice")
n_lattice = sum(1 for _ in open(os.path.join(work, "lattice", "particles.csv"))) - 1
for bed, spheres in (("bed", 30), ("lattice", n_lattice)):
    for contacts in ("caps:0.02", "shrink:0.01"):
        stl = f"{bed}-{contacts.split(':')[0]}.stl"
        run(exe, "export", f"{bed}/particles.csv", "--format", "stl", "--contacts", contacts,
            "--out", stl, "--quiet")
        admesh(stl, spheres + 1)  # the bodies and the container
        assert surface_check(stl) == (True, True), (stl, "closed, not self-intersecting")
        print(f"{stl}: {spheres} bodies + container, closed, oriented, not self-intersecting")
run(exe, "export", "bed/particles.csv", "--format", "stl", "--out", "none.stl", "--quiet")
assert surface_check("none.stl") == (True, False), "the overlapping spheres must intersect"
print("none.stl: self-intersecting, as the untreated overlapping spheres are")
shutil.rmtree(work)
