"""The environment Debian's OpenFOAM tools need, shared by the tests that run them."""
import os


def openfoam_env():
    """os.environ plus WM_PROJECT_DIR=/usr/share/openfoam where Debian's OpenFOAM keeps its
    etc/ (its tools stop with "Could not find mandatory etc entry" without it)."""
    env = dict(os.environ)
    if "WM_PROJECT_DIR" not in env and os.path.isdir("/usr/share/openfoam"):
        env["WM_PROJECT_DIR"] = "/usr/share/openfoam"
    return env
