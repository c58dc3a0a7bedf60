"""The Python module against the command line, geometry and its promises (issue 19).

Run by ctest (python_module): PYTHONPATH holds build/python, PACKBED the command line.
"""

import json
import math
import os
import signal
import subprocess
import sys
import time
from pathlib import Path

import numpy as np
import pytest

import packbed

PACKBED = os.environ.get("PACKBED", "packbed")


def cli(*arguments):
    """Run the command line; return (status, stdout, stderr)."""
    done = subprocess.run([PACKBED, *map(str, arguments)], capture_output=True, text=True)
    return done.returncode, done.stdout, done.stderr


def read_csv(path):
    return np.loadtxt(path, delimiter=",", skiprows=1, ndmin=2)


# A small bed both front ends make: fire, a = 4, 150 spheres, seed 7.
BED = dict(aspect_ratio=4, particles=150, seed=7)


@pytest.fixture(scope="module")
def cli_bed(tmp_path_factory):
    out = tmp_path_factory.mktemp("cli") / "bed"
    status, _, err = cli("generate", "-a", 4, "-n", 150, "-s", 7, "-q", "--out", out)
    assert status == 0, err
    return out


@pytest.fixture(scope="module")
def bed():
    return packbed.generate(**BED)


def test_generated_bed_has_the_command_lines_bits(bed, cli_bed, tmp_path):
    # particles.csv writes shortest round-trip doubles: reading it back gives the same bits.
    table = read_csv(cli_bed / "particles.csv")
    assert table.shape == (150, 4)
    assert np.array_equal(bed.centers, table[:, :3])
    assert np.array_equal(2 * bed.radii, table[:, 3]) or np.array_equal(bed.radii, table[:, 3])
    # and the files written from Python are the command line's, byte for byte
    bed.write(tmp_path / "py")
    for name in ["particles.csv", "particles.vtu", "radial_void_fraction.csv"]:
        assert (tmp_path / "py" / name).read_bytes() == (cli_bed / name).read_bytes(), name
    summary = json.loads((cli_bed / "summary.json").read_text())
    assert bed.summary["iterations"] == summary["iterations"]
    assert bed.summary["void_fraction"] == summary["void_fraction"]


def test_same_seed_same_bits_whatever_the_threads(bed):
    again = packbed.generate(**BED, threads=1)
    assert np.array_equal(again.centers, bed.centers)


def test_arrays_are_views_of_the_bed_without_a_copy(bed):
    centers, radii = bed.centers, bed.radii
    assert centers.shape == (150, 3) and centers.dtype == np.float64
    assert not centers.flags["OWNDATA"] and not radii.flags["OWNDATA"]
    assert centers.base is bed and radii.base is bed
    # two reads of the property see the same memory: nothing was copied
    assert np.shares_memory(centers, bed.centers)
    assert np.shares_memory(radii, bed.radii)
    assert np.all(radii == 0.5)


def test_analyze_gives_the_command_lines_numbers(bed, cli_bed, tmp_path):
    status, _, err = cli("analyze", cli_bed / "particles.csv", "--out", tmp_path / "a", "-q")
    assert status == 0, err
    summary = json.loads((tmp_path / "a" / "summary.json").read_text())
    # the bed read back from the command line's files, and the one generated in Python
    for b in [packbed.read(str(cli_bed / "particles.csv")), bed]:
        a = packbed.analyze(b)
        assert a.void_fraction == summary["void_fraction"]
        assert a.summary["coordination"] == summary["coordination"]
        assert a.summary["void_fraction_band"] == summary["void_fraction_band"]
        table = read_csv(tmp_path / "a" / "radial_void_fraction.csv")
        assert np.array_equal(a.radial_void_fraction.value, table[:, -1])
    assert b.container == "cylinder:4"


def test_a_lattice_in_a_box_has_its_exact_porosity():
    # 4 x 4 x 4 simple cubic cells of unit balls: 64 balls, porosity 1 - pi/6, 6 contacts each
    lattice = packbed.lattice(type="sc", region="box:4,4,4")
    assert len(lattice) == 64
    assert lattice.summary["lattice"]["porosity"] == pytest.approx(1 - math.pi / 6, abs=1e-15)
    # the same balls from numpy arrays in a box: the band z = 1 to 3 holds exactly the two
    # middle layers, so its void fraction is the lattice's to rounding
    built = packbed.Bed(np.array(lattice.centers), diameter=1.0, container="box:4,4")
    a = packbed.analyze(built, band=(1.0, 3.0))
    assert a.void_fraction == pytest.approx(1 - math.pi / 6, abs=1e-12)
    # every ball in the band has its 6 neighbours... except those on the box's faces
    assert a.coordination_histogram.sum() == 32


@pytest.mark.parametrize(
    "call, words",
    [
        (lambda: packbed.generate(e0=1.5), ["e0", "1.5", "allowed"]),
        (lambda: packbed.generate(particles=0), ["particles", "0", "allowed"]),
        (lambda: packbed.generate(solver="newton"), ["solver", "newton", "paper, fire"]),
        (lambda: packbed.generate(container="box:1"), ["container", "box:1", "allowed"]),
        (lambda: packbed.generate(sizes="foo"), ["sizes", "foo", "allowed"]),
        (lambda: packbed.generate(aspect_ratio=0.5), ["aspect-ratio", "0.5", "allowed"]),
        (lambda: packbed.generate(threads=0), ["threads", "0", "allowed"]),
        (lambda: packbed.read("/nonexistent/bed.csv"), ["/nonexistent/bed.csv"]),
        (lambda: packbed.read("x.csv", frame=0), ["frame", "0", "allowed"]),
        (lambda: packbed.read("x.csv", format="pdf"), ["format", "pdf", "allowed"]),
        (lambda: packbed.Bed(np.zeros((3, 2)), diameter=1.0), ["centers", "allowed"]),
        (lambda: packbed.Bed(np.zeros((3, 3)), np.ones(2)), ["radii", "allowed"]),
        (lambda: packbed.Bed([[0, 0, math.nan]], diameter=1.0), ["nan", "allowed"]),
        (lambda: packbed.Bed([[0, 0, 0.5]], diameter=1.0, container="cylinder:0.5"),
         ["sticks out", "allowed"]),
        (lambda: packbed.analyze(packbed.Bed([[0, 0, 0.5]], diameter=1.0)), ["container"]),
        (lambda: packbed.lattice(region="sphere:3"), ["region", "sphere:3", "allowed"]),
        (lambda: packbed.lattice(type="quasi"), ["type", "quasi", "allowed"]),
    ],
)
def test_bad_values_raise_value_error_with_one_line(call, words):
    with pytest.raises(ValueError) as raised:
        call()
    message = str(raised.value)
    assert "\n" not in message
    for word in words:
        assert word in message


def test_bad_output_directory_raises_and_writes_nothing(tmp_path):
    full = tmp_path / "full"
    full.mkdir()
    (full / "mine.txt").write_text("keep")
    with pytest.raises(ValueError, match="--out"):
        packbed.generate(particles=10, out=str(full))
    assert sorted(os.listdir(full)) == ["mine.txt"]


def test_a_run_that_does_not_converge_raises_convergence_error(tmp_path):
    with pytest.raises(packbed.ConvergenceError):
        packbed.generate(particles=100, max_iterations=50, out=str(tmp_path / "bed"))
    assert not (tmp_path / "bed").exists()
    assert issubclass(packbed.ConvergenceError, RuntimeError)


def test_progress_is_reported_and_its_exceptions_go_through():
    reports = []
    packbed.generate(particles=50, progress=reports.append)
    assert reports and reports[-1]["stage"] in {"initial", "intermediate", "final"}
    assert all(b["iteration"] - a["iteration"] == 100 for a, b in zip(reports, reports[1:])
               if a["stage"] == b["stage"] and b["layer"] == a["layer"])

    def fail(report):
        raise ZeroDivisionError("from the callback")

    with pytest.raises(ZeroDivisionError, match="from the callback"):
        packbed.generate(particles=50, progress=fail)


CHILD = """
import sys, time, packbed
def started(report, said=[]):
    if not said:
        said.append(1)
        print("started", flush=True)
try:
    packbed.generate(aspect_ratio=20, particles=20000, progress=started, out=sys.argv[1])
except KeyboardInterrupt:
    print("KeyboardInterrupt", flush=True)
    sys.exit(3)
print("finished", flush=True)
"""


def test_ctrl_c_raises_keyboard_interrupt_within_a_second(tmp_path):
    child = subprocess.Popen([sys.executable, "-c", CHILD, str(tmp_path / "bed")],
                             stdout=subprocess.PIPE, text=True, env=os.environ)
    assert child.stdout.readline().strip() == "started"
    time.sleep(0.5)  # well inside the run (tens of seconds)
    sent = time.monotonic()
    child.send_signal(signal.SIGINT)
    rest = child.stdout.read()
    child.wait(timeout=30)
    elapsed = time.monotonic() - sent
    assert "KeyboardInterrupt" in rest and child.returncode == 3
    assert elapsed < 1.0
    assert list(tmp_path.iterdir()) == []  # nothing written, nothing staged left


def test_help_shows_the_docstrings():
    assert "Salvat" in packbed.generate.__doc__ and "ValueError" in packbed.generate.__doc__
    for f in [packbed.read, packbed.analyze, packbed.lattice, packbed.Bed.write]:
        assert len(f.__doc__) > 100
    stubs = Path(packbed.__file__).with_name("__init__.pyi").read_text()
    for name in packbed.__all__:
        if not name.startswith("__"):
            assert name in stubs
