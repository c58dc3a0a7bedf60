"""The environment Debian's OpenFOAM tools need, shared by the tests that run them."""
import os


def openfoam_env():
    """os.environ plus WM_PROJECT_DIR=/usr/share/openfoam where Debian's OpenFOAM keeps its
    etc/ (its tools stop with "Could not find mandatory etc entry" without it)."""
    env = dict(os.environ)
    if "WM_PROJECT_DIR" not in env and os.path.isdir("/usr/share/openfoam"):
        env["WM_PROJECT_DIR"] = "/usr/share/openfoam"
    return env


MESHING = ("blockMesh", "snappyHexMesh", "checkMesh")
RUNNING = ("blockMesh", "decomposePar", "snappyHexMesh", "simpleFoam", "reconstructPar", "mpirun")


def openfoam_or_skip(tools=MESHING):
    """openfoam_env(), or exit 77 (ctest: skipped) when one of `tools` is missing (OpenFOAM's
    meshers by default; RUNNING for a case run by ./Allrun on MPI ranks)."""
    import shutil
    import sys
    missing = [p for p in tools if not shutil.which(p)]
    if missing:
        print(f"{', '.join(missing)} (Debian packages openfoam, openmpi-bin) missing: skipped")
        sys.exit(77)
    return openfoam_env()


def runner(env, work):
    """run(*args, cwd=work): the command's stdout, asserting it exits 0 (its last output
    shown when it does not)."""
    import subprocess

    def run(*args, cwd=work):
        r = subprocess.run(args, cwd=cwd, env=env, capture_output=True, text=True)
        assert r.returncode == 0, (args, r.stdout[-3000:], r.stderr[-3000:])
        return r.stdout
    return run


def cap(r, s):
    """The volume of a ball of radius r beyond a plane s from its centre (0 <= s <= r):
    pi c^2 (3 r - c) / 3, c = r - s."""
    import math
    c = r - s
    return math.pi * c * c * (3 * r - c) / 3


def mesh_case(run, case):
    """blockMesh, snappyHexMesh, checkMesh in `case` by run (runner's): asserts "Mesh OK.";
    checkMesh's output, its patches (name -> faces) and the mesh's total volume."""
    import re
    run("blockMesh", cwd=case)
    run("snappyHexMesh", "-overwrite", cwd=case)
    out = run("checkMesh", cwd=case)
    assert "Mesh OK." in out, out[-3000:]
    volume = float(re.search(r"Total volume = ([0-9.eE+-]+?)\.?\s", out).group(1))
    return out, patch_faces(out), volume


def patch_faces(check):
    """The patches (name -> faces) in checkMesh's output `check`: a serial run's table of
    patches ("ok" or "multiply" after each), or a parallel run's, listed under "Checking basic
    patch addressing"."""
    import re
    addressing = check.find("Checking basic patch addressing")
    if addressing >= 0:
        table = check[addressing:]
        table = table[:table.find("\n\n")]
        patches = re.findall(r"^\s+(\w+)\s+(\d+)\s+\d+$", table, re.M)
    else:
        patches = re.findall(r"^\s+(\w+)\s+(\d+)\s+\d+\s+(?:ok|multiply)", check, re.M)
    return {k: int(v) for k, v in patches}


def check_patches(patches, names):
    """Every patch of `names` has faces, and none are left on snappyHexMesh's `outside`."""
    for name in names:
        assert patches.get(name, 0) > 0, (name, patches)
    assert patches.get("outside", 0) == 0, patches


def check_volume(label, volume, exact, tolerance, patches, what=""):
    """The mesh's total volume within `tolerance` (relative) of the exact fluid volume: printed
    as "LABEL: WHATmesh volume ... against the exact fluid volume ...", then asserted."""
    error = volume / exact - 1.0
    print(f"{label}: {what}mesh volume {volume:.6g} against the exact fluid volume {exact:.6g}: "
          f"{error:+.2%}; patches {patches}")
    assert abs(error) < tolerance, error
