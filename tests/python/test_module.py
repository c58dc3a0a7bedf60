"""The Python module against the command line, geometry and its promises.

Run by ctest (python_module): PYTHONPATH holds build/python, PACKBED the command line.
"""

import ast
import errno
import json
import math
import os
import re
import shutil
import signal
import subprocess
import sys
import tempfile
import time
import warnings
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


def test_friction_and_target_void_fraction_as_the_command_line(tmp_path):
    # a = 8, 1 000 spheres: friction loosens the bed; the target is reached within 0.005 by a
    # friction the summary records, with the command line's bytes.
    dense = packbed.generate(aspect_ratio=8, particles=1000, seed=2)
    loose = packbed.generate(aspect_ratio=8, particles=1000, seed=2, friction=0.3,
                             wall_friction=0.3)
    assert loose.summary["void_fraction"] > dense.summary["void_fraction"] + 0.02
    assert loose.summary["parameters"]["friction"] == 0.3
    reports = []
    target = packbed.generate(aspect_ratio=8, particles=1000, seed=2, target_void_fraction=0.43,
                              progress=reports.append)
    assert abs(target.summary["void_fraction"] - 0.43) <= 0.005
    # Each run of the search names itself: the frictionless calibration bed first, a whole bed
    # last, at the friction found.
    assert reports[0]["run"] == "calibration bed 1, friction 0"
    found = target.summary["target_void_fraction"]["friction"]
    assert reports[-1]["run"] == f"whole bed {len(target.summary['target_void_fraction']['runs'])}, friction {found:.3g}"
    mu = target.summary["target_void_fraction"]["friction"]
    assert target.summary["parameters"]["friction"] == mu > 0
    cli = subprocess.run([PACKBED, "generate", "-a", "8", "-n", "1000", "-s", "2",
                          "--target-void-fraction", "0.43", "-q", "--no-analysis", "-o",
                          str(tmp_path / "cli")], check=True)
    table = read_csv(tmp_path / "cli" / "particles.csv")
    assert np.array_equal(target.centers, table[:, :3])
    with pytest.raises(ValueError, match="--target-void-fraction 0.42 with --friction 0.1"):
        packbed.generate(particles=100, friction=0.1, target_void_fraction=0.42)


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
    # read-only: the bed was checked when it was made, and every call trusts it
    assert not centers.flags["WRITEABLE"] and not radii.flags["WRITEABLE"]
    with pytest.raises(ValueError, match="read-only"):
        bed.radii[:] = 5.0
    with pytest.raises(ValueError, match="read-only"):
        bed.centers[0, 0] = np.nan
    # a changed bed is a new one, from copies
    moved = packbed.Bed(bed.centers + [0.0, 0.0, 1.0], bed.radii, container=bed.container)
    assert moved.centers[0, 2] == bed.centers[0, 2] + 1.0


def test_a_bed_pickles_and_copies_exactly(bed, tmp_path):
    # multiprocessing returns beds by pickling them: every number, the container and the
    # record come back, and the copy measures as the bed does
    import copy
    import pickle

    for back in [pickle.loads(pickle.dumps(bed)), copy.copy(bed), copy.deepcopy(bed)]:
        assert np.array_equal(back.centers, bed.centers) and np.array_equal(back.radii, bed.radii)
        assert back.container == bed.container and back.summary == bed.summary
        assert back.orientations is None
        assert packbed.analyze(back).void_fraction == packbed.analyze(bed).void_fraction
    array = packbed.random_array(count=20, seed=2)
    assert pickle.loads(pickle.dumps(array)).summary["period_z"] == array.summary["period_z"]
    pellets = packbed.generate(shape="spherocylinder:1,1", aspect_ratio=3, particles=6, seed=1)
    back = pickle.loads(pickle.dumps(pellets))
    assert np.array_equal(back.orientations, pellets.orientations)
    assert packbed.analyze(back, band_clearance=0.2).void_fraction == \
        packbed.analyze(pellets, band_clearance=0.2).void_fraction


def test_analyze_refuses_a_container_the_bed_does_not_fit(bed):
    # the command line's check (packbed analyze --container): a sphere beyond the wall given
    for spec in ["cylinder:3", "box:1,1", "cylinder:0.5"]:
        with pytest.raises(ValueError, match="sticks out of the container"):
            packbed.analyze(bed, container=spec)
        with pytest.raises(ValueError, match="sticks out of the container"):
            packbed.voxelize(bed, voxel_size=0.5, container=spec)
    # a container that holds it is taken: the same tube, wider
    assert 0.0 < packbed.analyze(bed, container="cylinder:5").void_fraction < 1.0


def test_numpy_integers_are_whole_numbers(bed):
    # a parameter study over np.arange: numpy's integers are taken where Python's are
    again = packbed.generate(**{**BED, "seed": np.int64(BED["seed"]), "particles": np.int32(150)})
    assert np.array_equal(again.centers, bed.centers)
    array = packbed.random_array(count=np.int64(20), sweeps=np.uint16(10), seed=np.int8(3))
    assert len(array) == 20


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


def test_a_cone_gives_the_command_lines_bed_and_analysis(tmp_path):
    # A hopper, cone:4,7,30: the module's bed is the command line's, byte for byte, and the
    # bed read back from its files is measured in the same cone (summary.json's spec).
    out = tmp_path / "cli"
    status, _, err = cli("generate", "--container", "cone:4,7,30", "-n", 200, "-s", 3, "-q",
                         "--out", out)
    assert status == 0, err
    bed = packbed.generate(container="cone:4,7,30", particles=200, seed=3)
    assert bed.container == "cone:4,7,30"
    bed.write(tmp_path / "py")
    for name in ["particles.csv", "radial_void_fraction.csv"]:
        assert (tmp_path / "py" / name).read_bytes() == (out / name).read_bytes(), name
    back = packbed.read(str(out / "particles.csv"))
    assert back.container == "cone:4,7,30"
    a = packbed.analyze(back)
    assert a.void_fraction == json.loads((out / "summary.json").read_text())["void_fraction"]
    assert 0.34 < a.void_fraction < 0.47


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


def test_a_lattice_too_short_for_its_band_says_so(tmp_path):
    # 3 d tall against a band 2 d clear of floor and top: no analysis, and the summary says why
    packbed.lattice(type="sc", region="box:4,4,3", band_clearance=2.0, out=tmp_path / "l")
    summary = json.loads((tmp_path / "l" / "summary.json").read_text())
    assert "analysis" not in summary
    assert summary["analysis_note"].startswith("not analysed: the region is 3 d tall")
    assert not (tmp_path / "l" / "radial_void_fraction.csv").exists()


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
        (lambda: packbed.generate(update="in-place"), ["update", "in-place", "fire", "allowed"]),
        (
            lambda: packbed.generate(sizes="uniform:0.8,1.2", diameter=2.0),
            ["diameter", "uniform:0.8,1.2", "allowed"],
        ),
        (lambda: packbed.read("x.csv", frame=0), ["frame", "0", "allowed"]),
        (lambda: packbed.read("x.csv", format="pdf"), ["format", "pdf", "allowed"]),
        (lambda: packbed.Bed(np.zeros((3, 2)), diameter=1.0), ["centers", "(3, 2)", "allowed"]),
        (lambda: packbed.Bed(np.zeros((3, 3)), np.ones(2)), ["radii", "(2,)", "allowed"]),
        (lambda: packbed.Bed(np.zeros((3, 3)), np.ones((3, 1))), ["radii", "(3, 1)", "(3,)"]),
        (lambda: packbed.generate(particles=True), ["particles", "True", "allowed"]),
        (lambda: packbed.generate(progress=5), ["progress", "5", "allowed", "function"]),
        (lambda: packbed.generate(seed=np.True_), ["seed", "True", "allowed"]),
        (lambda: packbed.Bed([[0, 0, math.nan]], diameter=1.0), ["nan", "allowed"]),
        (lambda: packbed.Bed([[0, 0, 0.5]], diameter=1.0, container="cylinder:0.5"),
         ["sticks out", "allowed"]),
        (lambda: packbed.analyze(packbed.Bed([[0, 0, 0.5]], diameter=1.0)), ["container"]),
        (lambda: packbed.lattice(region="sphere:3"), ["region", "sphere:3", "allowed"]),
        (lambda: packbed.lattice(type="quasi"), ["type", "quasi", "allowed"]),
        (lambda: packbed.voxelize(packbed.lattice(), voxel_size=0), ["voxel-size", "allowed"]),
        (lambda: packbed.voxelize(packbed.lattice(), voxel_size=1e-9), ["voxel-size", "GiB"]),
        (lambda: packbed.voxelize(packbed.lattice(), voxel_size=0.1, kind="grey"),
         ["kind", "grey", "allowed"]),
        (lambda: packbed.voxelize(packbed.lattice(), voxel_size=0.1, out="im.jpg"),
         ["im.jpg", "allowed"]),
        (lambda: packbed.export(packbed.Bed(np.zeros((0, 3)), diameter=1.0), "x.data"),
         ["no spheres", "allowed"]),
        (lambda: packbed.export(packbed.lattice(), "x.data", format="vrml"),
         ["format", "vrml", "allowed"]),
        (lambda: packbed.hydraulics(), ["porosity", "allowed"]),
        (lambda: packbed.generate(engine="gromacs"), ["engine", "gromacs", "allowed"]),
        (lambda: packbed.generate(ranks=2), ["ranks", "engine", "allowed"]),
        (lambda: packbed.hydraulics(porosity=0.4, aspect_ratio=5, container="cylinder:0.01"),
         ["aspect-ratio", "container", "allowed"]),
        (lambda: packbed.generate(shape="cylinder:1,1", target_void_fraction=0.4),
         ["target_void_fraction", "cylinder:1,1", "allowed"]),
        (lambda: packbed.generate(shape="cylinder:1,1", friction=-0.1),
         ["friction", "-0.1", "allowed"]),
        (lambda: packbed.generate(shape="cylinder:1"), ["shape", "cylinder:1", "allowed"]),
        (lambda: packbed.generate(shape="cube:1"), ["shape", "cube:1", "allowed"]),
        (lambda: packbed.analyze(packbed.lattice(), band=(1, 2), band_clearance=0.5),
         ["band_clearance", "0.5", "band (1, 2)", "both given", "allowed"]),
    ],
)
def test_bad_values_raise_value_error_with_one_line(call, words):
    with pytest.raises(ValueError) as raised:
        call()
    message = str(raised.value)
    assert "\n" not in message
    for word in words:
        assert word in message


def pellets_from_both(tmp_path, shape, particles, seed, aspect_ratio=4, friction=0.0,
                      sizes="mono"):
    """A pellet bed in a tube (a = 4 unless given; friction between pellets and at the walls;
    sizes on D) from the command line (tmp_path/cli) and from Python (tmp_path/py): asserts
    their particles.csv and particles.vtu are the same bytes, returns the Python bed."""
    status, _, err = cli("generate", "--shape", shape, "-a", aspect_ratio, "-n", particles,
                         "-s", seed, "--friction", friction, "--wall-friction", friction,
                         "--sizes", sizes, "-q", "--out", tmp_path / "cli")
    assert status == 0, err
    bed = packbed.generate(shape=shape, aspect_ratio=aspect_ratio, particles=particles,
                           seed=seed, friction=friction, wall_friction=friction, sizes=sizes,
                           out=str(tmp_path / "py"))
    for name in ["particles.csv", "particles.vtu"]:
        assert (tmp_path / "py" / name).read_bytes() == (tmp_path / "cli" / name).read_bytes()
    return bed


def test_a_pellet_bed_has_the_command_lines_bytes(tmp_path):
    # 12 cylinders L = D in a tube of a = 4 (seed 3): the files written from Python are the
    # command line's byte for byte; the orientations are the table's unit quaternions; the
    # exact depths are below the tolerance; voxelize draws its pellets as the command line
    # does (read back, measured, written and exported: the next test).
    bed = pellets_from_both(tmp_path, "cylinder:1,1", 12, 3)
    table = np.loadtxt(tmp_path / "cli" / "particles.csv", delimiter=",", skiprows=1, ndmin=2)
    assert table.shape == (12, 8)
    assert np.array_equal(bed.centers, table[:, :3])
    assert np.array_equal(bed.orientations, table[:, 4:8])
    assert np.allclose(np.linalg.norm(bed.orientations, axis=1), 1.0, atol=1e-12)
    assert 0 < bed.summary["max_penetration_pair"] <= bed.summary["tolerance"]
    assert bed.summary["shape"]["spec"] == "cylinder:1,1"
    # The image from just below the floor (the pellets press into it by up to the tolerance)
    # holds the twelve cylinders, pi / 4 each.
    region = (-2.3, -2.3, -0.1, 2.3, 2.3, 4.9)
    image = packbed.voxelize(bed, voxel_size=0.1, kind="fraction", region=region)
    status, _, err = cli("voxelize", tmp_path / "cli" / "particles.csv", "--voxel-size", 0.1,
                         "--kind", "fraction", "--region", ",".join(map(str, region)), "-q",
                         "-o", tmp_path / "cli.npy")
    assert status == 0, err
    # The same image to rounding: the table's quaternions are read back divided by their norms
    # (docs/notes/voxels.md).
    assert np.allclose(image, np.load(tmp_path / "cli.npy"), rtol=0, atol=1e-12)
    assert image.sum() * 1e-3 == pytest.approx(12 * np.pi / 4, abs=1e-9)
    assert packbed.voxelize(bed, voxel_size=0.1).dtype == np.bool_
    assert packbed.generate(aspect_ratio=4, particles=10).orientations is None


def test_a_frictional_pellet_bed_has_the_command_lines_bytes_and_stands_looser(tmp_path):
    # 40 spherocylinders L = D in a tube of a = 4 (seed 1) with friction 0.5 at pellets and
    # walls: Python's files are the command line's bytes, the summary records the friction,
    # and the bed stands taller than the frictionless one (a poured bed against the dense
    # limit: its void fraction in the band 0.5-2.5 d_v is 0.530 against 0.367, the C++
    # test FrictionalPelletBed's).
    loose = pellets_from_both(tmp_path / "mu", "spherocylinder:1,1", 40, 1, friction=0.5)
    dense = pellets_from_both(tmp_path / "zero", "spherocylinder:1,1", 40, 1)
    assert loose.summary["friction"] == 0.5 and loose.summary["wall_friction"] == 0.5
    assert "friction_let_go" in loose.summary and "friction_let_go" not in dense.summary
    assert dense.summary["friction"] == 0.0
    assert loose.centers[:, 2].mean() > dense.centers[:, 2].mean() + 0.1
    # Its LAMMPS data file's example input settles with the bed's friction.
    packbed.export(loose, str(tmp_path / "rods.data"))
    text = (tmp_path / "rods.data.lammps.in").read_text()
    assert "variable        friction equal 0.5\n" in text


def test_a_sized_pellet_bed_has_the_command_lines_bytes_and_each_pellets_own_size(tmp_path):
    # 20 rods of D = 0.8 and 1.2 (half of the volume each: 15 and 5 of them, the command line's
    # test Cli.ASizedPelletBed...): Python's files are the command line's bytes, each r is
    # 0.5 D d_v / D with d_v = 2.5^(1/3) at D = 1, and the bed, read back, exports its STL as
    # the command line does (each rod at its own size).
    bed = pellets_from_both(tmp_path, "spherocylinder:1,1", 20, 1,
                            sizes="discrete:0.8:0.5,1.2:0.5")
    dv = 2.5 ** (1 / 3)
    radii = np.sort(bed.radii)
    assert np.allclose(radii[:15], 0.4 * dv, rtol=1e-12)
    assert np.allclose(radii[15:], 0.6 * dv, rtol=1e-12)
    assert bed.summary["sizes"]["statistics"]["largest"] == 1.2
    packbed.export(packbed.read(str(tmp_path / "cli" / "particles.csv")), str(tmp_path / "py.stl"),
                   format="stl")
    status, _, err = cli("export", tmp_path / "cli" / "particles.csv", "-f", "stl", "-q", "-o",
                         tmp_path / "cli.stl")
    assert status == 0, err
    assert (tmp_path / "py.stl").read_bytes() == (tmp_path / "cli.stl").read_bytes()
    packbed.export(bed, str(tmp_path / "generated.stl"), format="stl")
    assert (tmp_path / "generated.stl").read_bytes() == (tmp_path / "cli.stl").read_bytes()
    # The image's fractions add up to the rods' volumes, each pi d_v^3 / 6 at its own size.
    region = (-2.8, -2.8, -0.1, 2.8, 2.8, 8.0)
    image = packbed.voxelize(bed, voxel_size=0.1, kind="fraction", region=region)
    assert image.sum() * 1e-3 == pytest.approx(np.sum(np.pi / 6 * (2 * bed.radii) ** 3),
                                               rel=0, abs=1e-9)


def test_a_tall_pellet_bed_in_layers_has_the_command_lines_bytes_and_resumes(tmp_path):
    # 100 rods in a tube of a = 3 in layers of 10 d_v (the command line's test
    # Cli.ATallPelletBedInLayers...): five layers, the same files from Python.
    status, _, err = cli("generate", "--shape", "spherocylinder:1,1", "-a", 3, "-n", 100, "-s", 1,
                         "--layer-height", 10, "-q", "--out", tmp_path / "cli")
    assert status == 0, err
    bed = packbed.generate(shape="spherocylinder:1,1", aspect_ratio=3, particles=100, seed=1,
                           layer_height=10, out=str(tmp_path / "py"))
    assert bed.summary["layers"] == 5
    for name in ["particles.csv", "particles.vtu"]:
        assert (tmp_path / "py" / name).read_bytes() == (tmp_path / "cli" / name).read_bytes()
    # Stopped after 40 000 of its 66 318 steps (in the fourth layer), the run leaves the
    # checkpoint of the third; resumed from it, it writes the same bytes.
    checkpoint = tmp_path / "bed.ckpt"
    with pytest.raises(packbed.ConvergenceError):
        packbed.generate(shape="spherocylinder:1,1", aspect_ratio=3, particles=100, seed=1,
                         layer_height=10, checkpoint=str(checkpoint), max_iterations=40000)
    assert checkpoint.read_bytes().startswith(b"packbed-pellet-checkpoint 1\n")
    packbed.generate(shape="spherocylinder:1,1", aspect_ratio=3, particles=100, seed=1,
                     layer_height=10, checkpoint=str(checkpoint), out=str(tmp_path / "resumed"))
    for name in ["particles.csv", "particles.vtu"]:
        assert ((tmp_path / "resumed" / name).read_bytes() ==
                (tmp_path / "cli" / name).read_bytes())


def test_a_pellet_bed_is_read_measured_written_and_exported_as_the_command_line_does(tmp_path):
    # 12 cylinders L = D in a tube of a = 3 (seed 3), written by the command line: read() keeps
    # their orientations and shape; analyze() measures them as `packbed analyze` does (the same
    # numbers and tables; in generate's band, generate's void fraction), and the orientation
    # is the quaternions' (a pellet's axis along z is 1 - 2 (qx^2 + qy^2), along the radius the
    # rotation's third column's part along it); write() gives back
    # the table's bytes, export() the command line's STL.
    status, _, err = cli("generate", "--shape", "cylinder:1,1", "-a", 3, "-n", 12, "-s", 3, "-q",
                         "--out", tmp_path / "cli")
    assert status == 0, err
    particles = tmp_path / "cli" / "particles.csv"
    generated = json.loads((tmp_path / "cli" / "summary.json").read_text())
    bed = packbed.read(str(particles))
    table = read_csv(particles)
    assert np.array_equal(bed.centers, table[:, :3])
    assert np.allclose(bed.orientations, table[:, 4:8], rtol=0, atol=1e-15)
    assert bed.summary["shape"]["spec"] == "cylinder:1,1"
    assert bed.summary["shape"]["volume_equivalent_diameter"] == pytest.approx(
        (1.5 * 1.0 * 1.0) ** (1 / 3), abs=1e-12)  # (6 V / pi)^(1/3), V = pi D^2 L / 4

    # Measured in generate's band: the void fraction is generate's own.
    band = generated["void_fraction_band"]
    status, _, err = cli("analyze", particles, "--band", f"{band[0]!r},{band[1]!r}", "-q", "-o",
                         tmp_path / "cli_an")
    assert status == 0, err
    analysis = packbed.analyze(bed, band=tuple(band), out=str(tmp_path / "py_an"))
    assert type(analysis).__name__ == "PelletAnalysis"
    expected = json.loads((tmp_path / "cli_an" / "summary.json").read_text())
    del expected["particles_file"]
    assert analysis.summary == expected
    for name in expected["files"]:
        assert (tmp_path / "py_an" / name).read_bytes() == (tmp_path / "cli_an" / name).read_bytes()
    assert analysis.void_fraction == pytest.approx(generated["void_fraction"], abs=1e-12)
    z = bed.centers[:, 2]
    inside = (z >= analysis.band[0]) & (z < analysis.band[1])
    q = bed.orientations[inside]
    cos_theta = 1.0 - 2.0 * (q[:, 1] ** 2 + q[:, 2] ** 2)  # columns qw, qx, qy, qz
    assert analysis.mean_cos2 == pytest.approx(np.mean(cos_theta**2), abs=1e-12)
    assert analysis.order == pytest.approx(1.5 * np.mean(cos_theta**2) - 0.5, abs=1e-12)
    assert analysis.orientation["pellets"].sum() == inside.sum()
    # cos psi: the axis (the rotation matrix's third column) along the radius at the centroid.
    w, x, y, zq = q[:, 0], q[:, 1], q[:, 2], q[:, 3]
    axis_x, axis_y = 2.0 * (x * zq + w * y), 2.0 * (y * zq - w * x)
    c = bed.centers[inside]
    cos_psi = (axis_x * c[:, 0] + axis_y * c[:, 1]) / np.hypot(c[:, 0], c[:, 1])
    assert analysis.mean_cos2_wall == pytest.approx(np.mean(cos_psi**2), abs=1e-6)
    counts = analysis.orientation["pellets"]
    assert np.sum(analysis.orientation["mean_cos2_wall"] * counts) == \
        pytest.approx(np.sum(cos_psi**2), abs=1e-5)
    assert analysis.coordination_histogram.sum() == inside.sum()
    # Lengths in d_v: shells of 0.02 d_v from the wall.
    radial = analysis.radial_void_fraction
    assert radial.high[0] - radial.low[0] == pytest.approx(0.02 * analysis.diameter, abs=1e-12)
    with pytest.raises(ValueError, match="rdf_bin"):
        packbed.analyze(bed, rdf_bin=0.1)

    bed.write(str(tmp_path / "written"))
    assert (tmp_path / "written" / "particles.csv").read_bytes() == particles.read_bytes()
    assert packbed.read(str(tmp_path / "written" / "particles.csv")).summary["shape"] == \
        bed.summary["shape"]
    status, _, err = cli("export", particles, "--format", "stl", "-q", "-o", tmp_path / "cli.stl")
    assert status == 0, err
    report = packbed.export(bed, str(tmp_path / "py.stl"), format="stl")
    assert "12 cylinder:1,1 pellets" in report
    assert (tmp_path / "py.stl").read_bytes() == (tmp_path / "cli.stl").read_bytes()


def test_a_pellet_bed_from_arrays_is_measured_and_exported_as_the_file_it_came_from(tmp_path):
    # 12 cylinders L = D at a = 3 (seed 3) from the command line, rebuilt from their arrays as a
    # bed from another tool would be: the same void fraction in the same band, the same STL.
    status, _, err = cli("generate", "--shape", "cylinder:1,1", "-a", 3, "-n", 12, "-s", 3, "-q",
                         "--out", tmp_path / "cli")
    assert status == 0, err
    read = packbed.read(str(tmp_path / "cli" / "particles.csv"))
    # bed.container: the tube's diameter to the last digit (a = 3 times d_v)
    assert read.container == f"cylinder:{2 * read.summary['container']['radius']!r}"
    assert read.container != f"cylinder:{2 * read.summary['container']['radius']:.9g}"
    made = packbed.Bed(read.centers, orientations=read.orientations, shape="cylinder:1,1",
                       container=read.container)
    assert np.array_equal(made.radii, read.radii)  # d_v / 2 = (3/2)^(1/3) / 2 each
    assert made.radii[0] == pytest.approx(0.5 * 1.5 ** (1 / 3), abs=1e-15)
    assert made.summary["shape"] == read.summary["shape"]
    band = (0.5, 2.5)
    assert packbed.analyze(made, band=band).void_fraction == \
        packbed.analyze(read, band=band).void_fraction
    packbed.export(made, str(tmp_path / "made.stl"), format="stl")
    packbed.export(read, str(tmp_path / "read.stl"), format="stl")
    assert (tmp_path / "made.stl").read_bytes() == (tmp_path / "read.stl").read_bytes()
    # One cylinder 0.58 off the axis of a tube of radius 1.1: upright its rim reaches 1.08 and it
    # fits (a ball of d_v / 2 = 0.572 would not); turned a quarter about x, its corners reach
    # hypot(1.08, 0.5) = 1.19: refused by the exact shape, as read() refuses such a file.
    centre = [[0.58, 0.0, 0.6]]
    upright = packbed.Bed(centre, orientations=[[1.0, 0.0, 0.0, 0.0]], shape="cylinder:1,1",
                          container="cylinder:2.2")
    assert upright.container == "cylinder:2.2"
    with pytest.raises(ValueError, match="reaches out of the container"):
        packbed.Bed(centre, orientations=[[np.cos(np.pi / 4), np.sin(np.pi / 4), 0.0, 0.0]],
                    shape="cylinder:1,1", container="cylinder:2.2")
    for keywords, words in [
            (dict(orientations=read.orientations), "not allowed for a bed of spheres"),
            (dict(shape="cylinder:1,1"), "orientations: none for a bed of cylinder pellets"),
            (dict(shape="cylinder:1,1", orientations=read.orientations, diameter=1.0),
             "diameter: not allowed with a pellet shape"),
            (dict(shape="cylinder:1,1", orientations=2 * read.orientations),
             r"orientations\[0\]: .* has norm 2"),
            (dict(shape="cylinder:1,1", orientations=read.orientations[:, :3]),
             r"shape \(12, 3\) for 12 centres is not allowed; allowed: shape \(12, 4\)"),
            (dict(shape="cube:1", orientations=read.orientations), "--shape: 'cube:1'")]:
        with pytest.raises(ValueError, match=words):
            packbed.Bed(read.centers, **keywords)


def test_a_trilobe_bed_has_the_command_lines_bytes(tmp_path):
    # 8 trilobes (lobes 1 on a circle of 0.8, 1.5 long) in a tube of a = 4: the same bytes from
    # Python as from the command line, the shape's lobes in the summary.
    bed = pellets_from_both(tmp_path, "trilobe:1,0.8,1.5", 8, 1)
    assert bed.orientations.shape == (8, 4)
    assert bed.summary["shape"]["kind"] == "trilobe"
    assert bed.summary["shape"]["lobes"] == 3
    assert 0 < bed.summary["max_penetration_pair"] <= bed.summary["tolerance"]


def test_a_ring_bed_has_the_command_lines_bytes(tmp_path):
    # 3 rings (D = L = 1, bore 0.5) in a tube of a = 3: the same bytes from Python as from the
    # command line, the bore in the summary, the tolerance 1e-3 of the wall (D - DI) / 2.
    bed = pellets_from_both(tmp_path, "ring:1,0.5,1", 3, 1, aspect_ratio=3)
    assert bed.orientations.shape == (3, 4)
    assert bed.summary["shape"]["kind"] == "ring"
    assert bed.summary["shape"]["inner_diameter"] == 0.5
    assert bed.summary["tolerance"] == pytest.approx(2.5e-4, abs=1e-15)
    assert bed.summary["max_penetration_wall"] <= bed.summary["tolerance"]


def test_a_spherocylinder_bed_has_the_command_lines_bytes(tmp_path):
    # 10 spherocylinders (D = L = 1) in a tube of a = 4: the same bytes from Python as from the
    # command line, the tolerance 1e-3 of D, no nodes (the contact in closed form).
    bed = pellets_from_both(tmp_path, "spherocylinder:1,1", 10, 2)
    assert bed.orientations.shape == (10, 4)
    assert bed.summary["shape"]["kind"] == "spherocylinder"
    assert bed.summary["tolerance"] == pytest.approx(1e-3, abs=1e-15)
    assert bed.summary["nodes_per_pellet"] == 0
    assert bed.summary["max_penetration_pair"] <= bed.summary["tolerance"]
    assert 0 < bed.summary["max_penetration_wall"] <= bed.summary["tolerance"]


def test_bad_output_directory_raises_and_writes_nothing(tmp_path):
    full = tmp_path / "full"
    full.mkdir()
    (full / "mine.txt").write_text("keep")
    with pytest.raises(ValueError, match="--out"):
        packbed.generate(particles=10, out=str(full))
    assert sorted(os.listdir(full)) == ["mine.txt"]


def test_a_file_that_cannot_be_opened_raises_the_oserror_open_raises(tmp_path):
    # As open() and numpy.loadtxt: FileNotFoundError (an OSError) naming the file, errno ENOENT.
    missing = tmp_path / "no such" / "particles.csv"
    for call in (packbed.read, packbed.analyze_frames):
        with pytest.raises(FileNotFoundError) as raised:
            call(missing, container="cylinder:5")
        assert raised.value.errno == errno.ENOENT
        assert raised.value.filename == str(missing)
    # A directory opens but is not a file: a bad value, ValueError.
    with pytest.raises(ValueError, match="a directory"):
        packbed.read(tmp_path)


@pytest.mark.skipif(shutil.which("lmp") is None, reason="lmp (Debian package lammps) missing")
def test_the_lammps_engine_gives_the_command_lines_bed(tmp_path):
    # LAMMPS on one rank: the same bed from both front ends, bit for bit, and the temporary
    # folder LAMMPS ran in removed.
    before = set(Path(tempfile.gettempdir()).glob("packbed-lammps-*"))
    bed = packbed.generate(engine="lammps", **BED)
    assert set(Path(tempfile.gettempdir()).glob("packbed-lammps-*")) == before
    status, _, err = cli("generate", "--engine", "lammps", "-a", 4, "-n", 150, "-s", 7, "-q",
                         "--out", tmp_path / "cli")
    assert status == 0, err
    table = read_csv(tmp_path / "cli" / "particles.csv")
    assert np.array_equal(bed.centers, table[:, :3])
    assert bed.summary["engine"]["name"] == "lammps"
    assert bed.summary["max_overlap_pair"] < 1e-4 and bed.summary["max_overlap_wall"] < 1e-4


def test_a_run_that_does_not_converge_raises_convergence_error(tmp_path):
    with pytest.raises(packbed.ConvergenceError):
        packbed.generate(particles=100, max_iterations=50, out=str(tmp_path / "bed"))
    assert not (tmp_path / "bed").exists()
    assert issubclass(packbed.ConvergenceError, RuntimeError)


def test_a_pellet_bed_that_does_not_settle_raises_convergence_error(tmp_path):
    with pytest.raises(packbed.ConvergenceError, match="within 100 steps"):
        packbed.generate(shape="spherocylinder:1,1", aspect_ratio=3, particles=12, seed=3,
                         max_iterations=100, out=str(tmp_path / "rods"))
    assert not (tmp_path / "rods").exists()


def test_progress_is_reported_and_its_exceptions_go_through():
    reports = []
    packbed.generate(particles=50, progress=reports.append)
    assert reports and reports[-1]["stage"] in {"initial", "intermediate", "final"}
    # Every field of a report, in Progress's order, whole numbers as int and the rest as float.
    assert list(reports[0]) == ["stage", "iteration", "cg", "max_overlap_pair",
                                "max_overlap_wall", "mass_centre_z", "layer", "layers"]
    assert all(type(r["iteration"]) is int and type(r["cg"]) is float for r in reports)
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
    packbed.generate(aspect_ratio=10, particles=5000, progress=started, out=sys.argv[1])
except KeyboardInterrupt:
    print("KeyboardInterrupt", flush=True)
    sys.exit(3)
print("finished", flush=True)
"""


def test_ctrl_c_raises_keyboard_interrupt_within_a_second(tmp_path):
    child = subprocess.Popen([sys.executable, "-c", CHILD, str(tmp_path / "bed")],
                             stdout=subprocess.PIPE, text=True, env=os.environ)
    assert child.stdout.readline().strip() == "started"
    time.sleep(0.5)  # well inside the run (2 s here; checks every 100 steps, 20 ms)
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


def test_the_stubs_name_every_keyword_the_functions_take():
    # The type stubs (__init__.pyi) against the signatures pybind11 writes into each
    # function's docstring: an editor completes every keyword the module takes, and only those.
    tree = ast.parse(Path(packbed.__file__).with_name("__init__.pyi").read_text())
    declared = {}
    for node in ast.walk(tree):
        if isinstance(node, ast.FunctionDef):
            a = node.args
            declared.setdefault(node.name, set()).update(
                x.arg for x in a.posonlyargs + a.args + a.kwonlyargs if x.arg != "self")
    checked = 0
    for name in packbed.__all__:
        f = getattr(packbed, name)
        if not callable(f) or isinstance(f, type):
            continue
        signature = re.match(r"\w+\((.*)\) ->", f.__doc__.splitlines()[0])
        assert signature, name
        taken = set(re.findall(r"(?:^|, )(\w+)(?=:|,|$)", signature.group(1)))
        assert taken == declared.get(name), name
        checked += 1
    assert checked >= 12


def test_voxelize_a_sphere_on_a_voxel_corner():
    # a ball of radius 0.8 on the corner shared by 8 voxels of edge 1: each holds an eighth of
    # it exactly, and no voxel centre (0.866 away) is inside it: all pore
    bed = packbed.Bed([[1.0, 1.0, 1.0]], [0.8], container="box:2,2")
    fraction = packbed.voxelize(bed, voxel_size=1.0, kind="fraction", region=(0, 0, 0, 2, 2, 2))
    assert fraction.shape == (2, 2, 2) and fraction.dtype == np.float64
    assert np.allclose(fraction, 4 / 3 * math.pi * 0.8**3 / 8 / 1.0, rtol=0, atol=1e-14)
    pores = packbed.voxelize(bed, voxel_size=1.0, region=(0, 0, 0, 2, 2, 2))
    assert pores.dtype == np.bool_ and pores.all()
    assert pores.flags["OWNDATA"] is False and pores.base is not None  # the library's memory


def test_voxelize_a_sphere_cut_by_the_region():
    # centre on the face x = 0 of the region: half the ball in the image
    bed = packbed.Bed([[1.5, 1.5, 1.5]], [1.0], container="box:3,3")
    h = 0.1
    image = packbed.voxelize(bed, voxel_size=h, kind="fraction", region=(1.5, 0, 0, 3.5, 3, 3))
    assert image.shape == (20, 30, 30)
    assert image.sum() * h**3 == pytest.approx(2 / 3 * math.pi, rel=1e-12)


def test_voxel_images_sum_to_the_solid_volume_and_match_the_binary(bed):
    h = 0.05
    fraction = packbed.voxelize(bed, voxel_size=h, kind="fraction")
    # the default region holds every sphere whole: the sum is the spheres' volume
    assert fraction.sum() * h**3 == pytest.approx(150 * math.pi / 6, rel=1e-9)
    binary = packbed.voxelize(bed, voxel_size=h)
    assert binary.shape == fraction.shape == (80, 80, math.ceil(bed_top(bed) / h - 1e-9))
    # a voxel wholly in a sphere is solid in both, one touching none pore-or-outside in both
    assert not binary[fraction >= 1 - 1e-12].any()
    solid = ~binary
    # the binary image's solid inside the tube is the solid fraction to the sampling's error
    x = (np.arange(80) + 0.5) * h - 2.0
    inside = (x[:, None] ** 2 + x[None, :] ** 2 <= 4.0)[:, :, None]
    solid_in_tube = (solid & inside).sum() / (inside.sum() * binary.shape[2])
    assert solid_in_tube == pytest.approx(fraction.sum() / (inside.sum() * binary.shape[2]),
                                          abs=3e-3)


def test_single_precision_fractions_keep_the_sum(bed, cli_bed, tmp_path):
    h = 0.05
    double = packbed.voxelize(bed, voxel_size=h, kind="fraction")
    single = packbed.voxelize(bed, voxel_size=h, kind="fraction", dtype="float32")
    assert single.dtype == np.float32 and single.shape == double.shape
    # numpy's type and dtype name it as well as the string
    for given in (np.float32, np.dtype("<f4")):
        assert np.array_equal(packbed.voxelize(bed, voxel_size=h, kind="fraction", dtype=given),
                              single)
    with pytest.raises(ValueError, match="--dtype 'int32' is not allowed"):
        packbed.voxelize(bed, voxel_size=h, kind="fraction", dtype=np.int32)
    with pytest.raises(ValueError, match="--dtype 'no type' is not allowed"):
        packbed.voxelize(bed, voxel_size=h, kind="fraction", dtype="no type")
    with pytest.raises(ValueError, match="--dtype <object object at"):
        packbed.voxelize(bed, voxel_size=h, kind="fraction", dtype=object())
    # each voxel the double one rounded (a few roundings where spheres share it)
    assert np.abs(single - double).max() < 3e-7
    assert single.sum(dtype=np.float64) * h**3 == pytest.approx(150 * math.pi / 6, rel=1e-9)
    # the command line writes the same array, as a '<f4' .npy
    status, _, err = cli("voxelize", cli_bed / "particles.csv", "--voxel-size", h, "--kind",
                         "fraction", "--dtype", "float32", "-o", tmp_path / "im.npy")
    assert status == 0, err
    assert np.array_equal(np.load(tmp_path / "im.npy"), single)
    assert np.load(tmp_path / "im.npy").dtype == np.float32
    # a bool image has no float type: refused by both, with the same line
    with pytest.raises(ValueError) as raised:
        packbed.voxelize(bed, voxel_size=h, dtype="float32")
    status, _, err = cli("voxelize", cli_bed / "particles.csv", "--voxel-size", h, "--dtype",
                         "float32", "-o", tmp_path / "b.npy")
    assert status == 2 and err.strip().endswith(str(raised.value))
    assert "--dtype float32 is not allowed with --kind binary" in err


def bed_top(bed):
    return float((bed.centers[:, 2] + bed.radii).max())


def test_voxel_files_read_back_in_numpy_and_tifffile(bed, tmp_path):
    import tifffile  # Debian python3-tifffile (install-deps.sh --test): required, never skipped
    for kind, dtype in [("binary", "float64"), ("fraction", "float64"), ("fraction", "float32")]:
        image = packbed.voxelize(bed, voxel_size=0.1, kind=kind, dtype=dtype,
                                 out=tmp_path / f"{kind}.npy")
        assert np.array_equal(np.load(tmp_path / f"{kind}.npy"), image)
        packbed.voxelize(bed, voxel_size=0.1, kind=kind, dtype=dtype,
                         out=tmp_path / f"{kind}.tif")
        tif = tifffile.imread(tmp_path / f"{kind}.tif")
        assert tif.shape == image.shape
        assert kind == "binary" or tif.dtype == image.dtype == np.dtype(dtype)
        assert np.array_equal(tif.astype(image.dtype), image)
        packbed.voxelize(bed, voxel_size=0.1, kind=kind, dtype=dtype,
                         out=tmp_path / f"{kind}.raw")
        header = json.loads((tmp_path / f"{kind}.raw.json").read_text())
        assert header["dtype"] == ("uint8" if kind == "binary" else dtype)
        raw = np.fromfile(tmp_path / f"{kind}.raw", dtype=header["dtype"])
        assert np.array_equal(raw.reshape(header["shape"]).astype(image.dtype), image)
        assert header["voxel_size"] == 0.1 and header["origin"] == [-2.0, -2.0, 0.0]


def test_the_command_lines_voxelize_writes_the_modules_image(bed, cli_bed, tmp_path):
    status, out, err = cli("voxelize", cli_bed / "particles.csv", "--voxel-size", 0.1, "--kind",
                           "fraction", "-o", tmp_path / "im.npy")
    assert status == 0, err
    assert np.array_equal(np.load(tmp_path / "im.npy"),
                          packbed.voxelize(bed, voxel_size=0.1, kind="fraction"))
    status, _, err = cli("voxelize", cli_bed / "particles.csv", "--voxel-size", 0.1, "-o",
                         tmp_path / "im.png")
    assert status == 2 and err.count("\n") == 1 and "im.png" in err and "allowed" in err


# The same one-line message from both front ends: the Python call and the command line that
# gives the same value (option_ranges.hpp, one table for both).
@pytest.mark.parametrize(
    "call, arguments",
    [
        (lambda: packbed.generate(e0=1.5), ["generate", "--e0", "1.5"]),
        (lambda: packbed.generate(particles=0), ["generate", "-n", "0"]),
        (lambda: packbed.generate(aspect_ratio=0.5), ["generate", "-a", "0.5"]),
        (lambda: packbed.generate(ck=2), ["generate", "--ck", "2"]),
        (lambda: packbed.generate(mc_window=1), ["generate", "--mc-window", "1"]),
        (lambda: packbed.generate(threads=0), ["generate", "-j", "0"]),
        (lambda: packbed.analyze(packbed.lattice(), shell_width=20),
         ["analyze", "x.csv", "--shell-width", "20"]),
        (lambda: packbed.voxelize(packbed.lattice(), voxel_size=0),
         ["voxelize", "x.csv", "--voxel-size", "0", "-o", "im.npy"]),
        (lambda: packbed.hydraulics(porosity=1.5), ["hydraulics", "--porosity", "1.5"]),
        (lambda: packbed.hydraulics(porosity=0.4, gravity=0),
         ["hydraulics", "--porosity", "0.4", "--gravity", "0"]),
        (lambda: packbed.correlations(profile_step=2), ["correlations", "--profile-step", "2"]),
        (lambda: packbed.export(packbed.lattice(), "x.data", refine=9),
         ["export", "x.csv", "--refine", "9"]),
        (lambda: packbed.export(packbed.lattice(), "x.data", facets="round"),
         ["export", "x.csv", "--facets", "round"]),
    ],
)
def test_a_bad_value_gets_the_command_lines_message(call, arguments):
    with pytest.raises(ValueError) as raised:
        call()
    status, _, err = cli(*arguments)
    assert status == 2
    assert err == f"packbed: {raised.value}\n"


def test_cfd_report_gives_the_command_lines_numbers(tmp_path):
    # a run case's files, made without OpenFOAM by the command line's own test
    sys.path.insert(0, str(Path(__file__).resolve().parents[1]))
    from check_cfd_report import GRADIENT, make_case

    case = make_case(str(tmp_path), "case")
    status, out, err = cli("cfd-report", case, "--json", "--out", str(tmp_path / "cli"))
    assert status == 0, err
    got = packbed.cfd_report(case, out=str(tmp_path / "module"))
    assert got == json.loads(out)
    assert got["pressure_gradient_Pa_m"]["cfd"] == pytest.approx(GRADIENT, rel=1e-9)
    for name in ("pressure.csv", "cfd_report.json"):
        assert (tmp_path / "module" / name).read_bytes() == (tmp_path / "cli" / name).read_bytes()
    with pytest.raises(ValueError, match="^CASE .*none is not a directory"):
        packbed.cfd_report(str(tmp_path / "none"))


def test_cfd_series_gives_the_command_lines_numbers(tmp_path):
    # three periodic cases on K = 7.4 + 30 (h/d)^2, made by the command line's own test
    sys.path.insert(0, str(Path(__file__).resolve().parents[1]))
    from check_cfd_report import CELL, RADIUS, make_periodic_case

    cases = []
    for cells in (1000, 8000, 27000):
        h = (0.79 * CELL / cells) ** (1 / 3) / (2 * RADIUS)
        cases.append(make_periodic_case(str(tmp_path), f"c{cells}", 7.4 + 30 * h * h, cells))
    status, out, err = cli("cfd-report", *cases, "--json", "--out", str(tmp_path / "cli"))
    assert status == 0, err
    got = packbed.cfd_series(cases, out=str(tmp_path / "module"))
    assert got == json.loads(out)
    assert got["celik"]["extrapolated"] == pytest.approx(7.4, rel=1e-9)
    for name in ("series.csv", "series.json"):
        assert (tmp_path / "module" / name).read_bytes() == (tmp_path / "cli" / name).read_bytes()
    with pytest.raises(ValueError, match="2 case\\(s\\) given for a mesh series"):
        packbed.cfd_series(cases[:2], out=str(tmp_path / "two"))


def test_hydraulics_and_correlations_give_the_command_lines_numbers():
    status, out, _ = cli("hydraulics", "--porosity", "0.4", "-a", "5", "--json")
    assert status == 0
    got = packbed.hydraulics(porosity=0.4, aspect_ratio=5)
    assert got == json.loads(out)
    # Ergun at the critical velocity of eq. (1) (Tsayger 2013): 150 (1-e)^2/e^3 mu u/d^2
    # + 1.75 (1-e)/e^3 rho u^2/d, for glass (1 mm) in water
    e, d, mu, rho = 0.4, 1e-3, 1.002e-3, 998.2
    u = got["pressure_gradient"]["velocity_m_s"]
    ergun = 150 * (1 - e) ** 2 / e**3 * mu * u / d**2 + 1.75 * (1 - e) / e**3 * rho * u**2 / d
    assert got["pressure_gradient"]["ergun_Pa_m"] == pytest.approx(ergun, rel=1e-12)
    status, out, _ = cli("correlations", "-a", "5", "--json")
    assert status == 0
    assert packbed.correlations(aspect_ratio=5) == json.loads(out)


def test_a_correlation_out_of_its_range_warns_as_the_command_line():
    status, _, err = cli("correlations", "-a", "1.2")
    assert status == 0 and "warning" in err
    with pytest.warns(UserWarning) as warned:
        packbed.correlations(aspect_ratio=1.2)
    assert [f"packbed correlations: warning: {w.message}" for w in warned] == err.splitlines()


@pytest.mark.parametrize(
    "format, name, extra",
    [
        ("lammps-data", "bed.data", []),
        ("liggghts-data", "bed.data", []),
        ("stl", "bed.stl", ["--contacts", "caps:0.02", "--refine", "2"]),
        ("stl", "bed.stl", ["--contacts", "caps:0.02", "--refine", "2", "--facets", "volume"]),
        ("stl", "bed.stl", ["--contacts", "none", "--refine", "2", "--facets", "auto"]),
    ],
)
def test_export_writes_the_command_lines_files(cli_bed, tmp_path, format, name, extra):
    particles = str(cli_bed / "particles.csv")
    (tmp_path / "cli").mkdir()
    (tmp_path / "py").mkdir()
    status, _, err = cli("export", particles, "-f", format, "-q", "-o", tmp_path / "cli" / name,
                         *extra)
    assert status == 0, err
    keywords = {flag[2:]: int(value) if value.isdigit() else value
                for flag, value in zip(extra[::2], extra[1::2])}
    report = packbed.export(packbed.read(particles), str(tmp_path / "py" / name), format=format,
                            **keywords)
    assert str(tmp_path / "py" / name) in report
    written = sorted(os.listdir(tmp_path / "cli"))
    assert sorted(os.listdir(tmp_path / "py")) == written and len(written) >= 2
    for f in written:
        assert (tmp_path / "py" / f).read_bytes() == (tmp_path / "cli" / f).read_bytes(), f


def test_export_of_a_generated_bed_keeps_its_own_wall_friction(tmp_path):
    # A Bed made with walls of 0.1 and spheres of 0.3: its LIGGGHTS input gives the walls their
    # own atom type and coefficient, as the command line's export of its files does.
    bed = packbed.generate(aspect_ratio=4, particles=60, seed=1, diameter=0.003, friction=0.3,
                           wall_friction=0.1, out=str(tmp_path / "bed"))
    packbed.export(bed, str(tmp_path / "py.data"), format="liggghts-data")
    text = (tmp_path / "py.data.liggghts.in").read_text()
    assert "variable        wall_friction equal 0.1\n" in text
    assert ("peratomtypepair 2 ${friction} ${wall_friction} ${wall_friction} ${wall_friction}"
            in text)
    assert "\n2 atom types\n" in (tmp_path / "py.data").read_text()
    status, _, err = cli("export", tmp_path / "bed" / "particles.csv", "-f", "liggghts-data",
                         "-q", "-o", tmp_path / "cli.data")
    assert status == 0, err
    assert (tmp_path / "cli.data.liggghts.in").read_text().replace("cli.data", "py.data") == text


def test_export_writes_the_command_lines_openfoam_case(cli_bed, tmp_path):
    # the flow's options by keyword: the same case, file by file, Allrun executable
    particles = str(cli_bed / "particles.csv")
    status, _, err = cli("export", particles, "-f", "openfoam", "-q", "-o", tmp_path / "cli",
                         "--contacts", "caps:0.02", "--ranks", "3", "--reynolds", "2",
                         "--fluid-density", "1.2", "--viscosity", "1.8e-5", "--scale", "0.002",
                         "--layers", "2")
    assert status == 0, err
    packbed.export(packbed.read(particles), str(tmp_path / "py"), format="openfoam",
                   contacts="caps:0.02", ranks=3, reynolds=2, fluid_density=1.2,
                   viscosity=1.8e-5, scale=0.002, layers=2)
    written = sorted(str(f.relative_to(tmp_path / "cli")) for f in (tmp_path / "cli").rglob("*"))
    assert written == sorted(str(f.relative_to(tmp_path / "py"))
                             for f in (tmp_path / "py").rglob("*"))
    for f in written:
        if (tmp_path / "cli" / f).is_file():
            assert (tmp_path / "py" / f).read_bytes() == (tmp_path / "cli" / f).read_bytes(), f
    assert os.access(tmp_path / "py" / "Allrun", os.X_OK)
    decompose = (tmp_path / "py" / "system" / "decomposeParDict").read_text()
    assert "numberOfSubdomains 3;" in decompose and "n (1 1 3);" in decompose
    assert "particles { nSurfaceLayers 2; }" in (tmp_path / "py" / "system" /
                                                 "snappyHexMeshDict").read_text()
    # nu = mu / rho, and the velocity of Re_p = 2 at d = 2 mm: u = Re nu / d
    nu = 1.8e-5 / 1.2
    assert f"nu {nu:g};" in (tmp_path / "py" / "constant" / "transportProperties").read_text()
    flow = json.loads((tmp_path / "py" / "packbed.json").read_text())["openfoam"]["flow"]
    assert flow["velocity"] == pytest.approx(2 * nu / 0.002, rel=1e-12)
    with pytest.raises(ValueError, match="--ranks: 0 is not allowed"):
        packbed.export(packbed.read(particles), str(tmp_path / "bad"), format="openfoam", ranks=0)
    with pytest.raises(ValueError, match="--layers: 11 is not allowed"):
        packbed.export(packbed.read(particles), str(tmp_path / "bad"), format="openfoam", layers=11)


def test_the_accurate_mesh_is_the_command_lines_and_its_options_replace_its_values(cli_bed,
                                                                                  tmp_path):
    # --mesh accurate: d/32 at the particles (8 cells a diameter, level 2) and three layers, the
    # mesh within 2 % of the converged gradient (docs/validation.md)
    assert packbed.mesh_preset("accurate") == {"cells_per_diameter": 8, "particle_level": 2,
                                               "wall_level": 1, "layers": 3}
    assert packbed.mesh_preset("quick") == {"cells_per_diameter": 4, "particle_level": 2,
                                            "wall_level": 1, "layers": 0}
    particles = str(cli_bed / "particles.csv")
    status, _, err = cli("export", particles, "-f", "openfoam", "-q", "-o", tmp_path / "cli",
                         "--contacts", "caps:0.02", "--mesh", "accurate")
    assert status == 0, err
    packbed.export(packbed.read(particles), str(tmp_path / "py"), format="openfoam",
                   contacts="caps:0.02", **packbed.mesh_preset("accurate"))
    for f in (tmp_path / "cli").rglob("*"):
        if f.is_file():
            assert (tmp_path / "py" / f.relative_to(tmp_path / "cli")).read_bytes() == \
                f.read_bytes(), f
    mesh = json.loads((tmp_path / "py" / "packbed.json").read_text())["openfoam"]
    assert mesh["cell_size"] == pytest.approx(1 / 8, rel=1e-12)
    assert (mesh["particle_level"], mesh["layers"]) == (2, 3)
    # an option beside the preset replaces its value, whatever the order
    status, _, err = cli("export", particles, "-f", "openfoam", "-q", "-o", tmp_path / "two",
                         "--layers", "2", "--contacts", "caps:0.02", "--mesh", "accurate")
    assert status == 0, err
    mesh = json.loads((tmp_path / "two" / "packbed.json").read_text())["openfoam"]
    assert mesh["cell_size"] == pytest.approx(1 / 8, rel=1e-12) and mesh["layers"] == 2
    with pytest.raises(ValueError, match="--mesh: 'fine' is not allowed; allowed: quick, "
                                         "accurate"):
        packbed.mesh_preset("fine")


def test_export_of_a_cell_periodic_along_z_is_the_command_lines(tmp_path):
    # flow='periodic' is --flow periodic: the same case; the cell's numbers for cfd-report
    status, _, err = cli("lattice", "--type", "sc", "--region", "periodic:3,3,3", "--origin",
                         "0.5,0.5,0.5", "-q", "--no-analysis", "-o", tmp_path / "cell")
    assert status == 0, err
    particles = str(tmp_path / "cell" / "particles.csv")
    options = ["--contacts", "caps:0.02", "--container-height", "3", "--refine", "2"]
    status, _, err = cli("export", particles, "-f", "openfoam", "-q", "-o", tmp_path / "cli",
                         "--flow", "periodic", *options)
    assert status == 0, err
    packbed.export(packbed.read(particles), str(tmp_path / "py"), format="openfoam",
                   flow="periodic", contacts="caps:0.02", container_height=3, refine=2)
    for f in (tmp_path / "cli").rglob("*"):
        if f.is_file():
            assert (tmp_path / "py" / f.relative_to(tmp_path / "cli")).read_bytes() == \
                f.read_bytes(), f
    cell = json.loads((tmp_path / "py" / "packbed.json").read_text())["openfoam"]["flow"]["periodic"]
    # 27 touching balls, each with 6 caps 0.01 from its contacts (two of them across the
    # bottom and the top): pi/6 - 6 caps of height 0.01 per unit of volume
    caps = 6 * math.pi * 0.01**2 * (3 * 0.5 - 0.01) / 3
    assert cell["spheres"] == 27 and cell["sphere_radius"] == pytest.approx(0.5, rel=1e-14)
    assert cell["solid_fraction"] == pytest.approx(math.pi / 6 - caps, rel=1e-12)
    with pytest.raises(ValueError, match="flow 'sideways' is not allowed"):
        packbed.export(packbed.read(particles), str(tmp_path / "bad"), format="openfoam",
                       flow="sideways", container_height=2)


def test_random_array_is_the_command_lines_and_its_case_repeats_along_z(tmp_path):
    # the same seed: the command line's bytes; the spheres no closer than (1 + gap) d across
    # every face (the 27 copies of each, by brute force); the case's cell the array's own
    status, _, err = cli("random-array", "-n", "40", "--solid-fraction", "0.3", "--gap", "0.05",
                         "--sweeps", "200", "--seed", "3", "-q", "-o", tmp_path / "cli")
    assert status == 0, err
    array = packbed.random_array(count=40, solid_fraction=0.3, gap=0.05, sweeps=200, seed=3,
                                 out=str(tmp_path / "py"))
    assert (tmp_path / "py" / "particles.csv").read_bytes() == \
        (tmp_path / "cli" / "particles.csv").read_bytes()
    summary = json.loads((tmp_path / "cli" / "summary.json").read_text())
    edge = summary["period_z"]
    assert summary["container"]["spec"] == f"periodic:{edge:.9g},{edge:.9g}"
    assert summary["solid_fraction"] == pytest.approx(40 * math.pi / 6 / edge**3, rel=1e-15)
    assert summary["solid_fraction"] == pytest.approx(0.3, abs=2e-9)
    c = np.array(array.centers)
    assert ((c >= 0) & (c < edge)).all()
    shifts = np.array([[i, j, k] for i in (-1, 0, 1) for j in (-1, 0, 1) for k in (-1, 0, 1)])
    closest = min(np.linalg.norm(c[b] + shifts * edge - c[a], axis=1).min()
                  for a in range(40) for b in range(a + 1, 40))
    assert closest >= 1.05 and closest == pytest.approx(summary["closest_distance_d"], rel=1e-12)
    with pytest.raises(ValueError, match="--count: 1 is not allowed"):
        packbed.random_array(count=1)
    # export flow='periodic' takes the array's period, as the command line does
    status, _, err = cli("export", tmp_path / "cli" / "particles.csv", "-f", "openfoam", "-q",
                         "--flow", "periodic", "--refine", "2", "-o", tmp_path / "cli-case")
    assert status == 0, err
    packbed.export(array, str(tmp_path / "py-case"), format="openfoam", flow="periodic", refine=2)
    for name in ("system/blockMeshDict", "system/snappyHexMeshDict", "constant/fvOptions"):
        assert (tmp_path / "py-case" / name).read_bytes() == \
            (tmp_path / "cli-case" / name).read_bytes(), name
    cell = json.loads((tmp_path / "py-case" / "packbed.json").read_text())["openfoam"]["flow"]
    assert cell["periodic"]["period_z"] == edge
    assert cell["periodic"]["solid_fraction"] == pytest.approx(0.3, abs=2e-9)


def test_the_voxel_image_of_a_random_array_wraps_on_all_six_faces(tmp_path):
    # the cube's image, by default the cube itself: its exact solid fractions add up to the
    # array's solid fraction (the spheres crossing the floor and the top drawn a period away,
    # as those crossing the sides), and the command line's file is the same image
    array = packbed.random_array(count=100, solid_fraction=0.3, seed=2, out=str(tmp_path / "a"))
    edge = array.summary["period_z"]
    image = packbed.voxelize(array, voxel_size=edge / 40, kind="fraction")
    assert image.shape == (40, 40, 40)
    assert image.mean() == pytest.approx(array.summary["solid_fraction"], abs=1e-12)
    # the faces meet as the inside does: opposite faces' layers are neighbours
    assert np.corrcoef(image[:, :, 0].ravel(), image[:, :, -1].ravel())[0, 1] > 0.5
    status, _, err = cli("voxelize", tmp_path / "a" / "particles.csv", "--voxel-size",
                         repr(edge / 40), "--kind", "fraction", "-q", "-o", tmp_path / "a.npy")
    assert status == 0, err
    assert np.array_equal(np.load(tmp_path / "a.npy"), image)
    # read back from its files (the period from summary.json beside them): the same image
    back = packbed.read(str(tmp_path / "a" / "particles.csv"))
    assert back.summary["period_z"] == edge
    assert np.array_equal(packbed.voxelize(back, voxel_size=edge / 40, kind="fraction"), image)
    # and the command line's analyze takes the cube whose spheres cross its floor and top
    status, _, err = cli("analyze", tmp_path / "a" / "particles.csv", "-q", "-o", tmp_path / "an")
    assert status == 0, err


def test_export_takes_its_format_from_the_name_when_none_is_given(bed, cli_bed, tmp_path):
    # x.stl is an STL and y.OBJ an OBJ, not LAMMPS data files named so; the command line's the
    # same bytes
    packbed.export(bed, str(tmp_path / "x.stl"))
    packbed.export(bed, str(tmp_path / "y.OBJ"))
    assert not (tmp_path / "x.stl.lammps.in").exists()
    stl = (tmp_path / "x.stl").read_bytes()
    assert len(stl) == 84 + 50 * int.from_bytes(stl[80:84], "little")  # binary STL's layout
    assert (tmp_path / "y.OBJ").read_text().startswith(("#", "v ", "o ", "g "))
    status, _, err = cli("export", cli_bed / "particles.csv", "-q", "-o", tmp_path / "c.stl")
    assert status == 0, err
    read = packbed.read(str(cli_bed / "particles.csv"))
    packbed.export(read, str(tmp_path / "p.stl"))
    assert (tmp_path / "p.stl").read_bytes() == (tmp_path / "c.stl").read_bytes()
    # a format given wins over the name
    packbed.export(bed, str(tmp_path / "z.stl"), format="lammps-data")
    assert (tmp_path / "z.stl").read_text().split("\n")[0].endswith("atom_style sphere)")


def test_export_of_a_bed_made_in_python_holds_every_sphere(bed, tmp_path):
    packbed.export(bed, str(tmp_path / "bed.data"))
    lines = (tmp_path / "bed.data").read_text().splitlines()
    assert "150 spheres from Python" in lines[0]
    assert "150 atoms" in lines
    # the example settle beside it: the container (a = 4) is the bed's own
    assert (tmp_path / "bed.data.lammps.in").exists()


def test_analyze_frames_gives_the_command_lines_series(tmp_path):
    # A trajectory of a simple cubic lattice of unit balls filling a 4 x 4 box layer by layer:
    # 1, 3 and 4 layers. With a band 1 Dp clear of the ends, the first frame has none; the
    # others have whole middle layers in it, void fraction 1 - pi/6 exactly.
    lattice = packbed.lattice(type="sc", region="box:4,4,4")
    centers = np.array(lattice.centers)
    dump = tmp_path / "fill.dump"
    with open(dump, "w") as f:
        for step, layers in [(0, 1), (1000, 3), (2000, 4)]:
            frame = centers[centers[:, 2] < layers]
            f.write(f"ITEM: TIMESTEP\n{step}\nITEM: NUMBER OF ATOMS\n{len(frame)}\n"
                    "ITEM: BOX BOUNDS pp pp ff\n0 4\n0 4\n0 4\nITEM: ATOMS id type x y z radius\n")
            for i, (x, y, z) in enumerate(frame):
                f.write(f"{i + 1} 1 {x!r} {y!r} {z!r} 0.5\n")
    series = packbed.analyze_frames(str(dump), container="box:4,4")
    assert list(series["frame"]) == [1, 2, 3]
    assert list(series["timestep"]) == [0, 1000, 2000]
    assert list(series["particles"]) == [16, 48, 64]
    assert math.isnan(series["void_fraction"][0])
    assert series["void_fraction"][1:] == pytest.approx([1 - math.pi / 6] * 2, abs=1e-12)
    assert len(series["last"]) == 64
    status, _, err = cli("analyze", dump, "--container", "box:4,4", "--frames", "all", "-q",
                         "--out", tmp_path / "cli")
    assert status == 0, err
    rows = (tmp_path / "cli" / "void_fraction_series.csv").read_text().splitlines()
    assert rows[0] == "frame,timestep,void_fraction,particles"
    for row, e in zip(rows[1:], series["void_fraction"]):
        value = row.split(",")[2]
        assert (value == "" and math.isnan(e)) or float(value) == e


@pytest.mark.parametrize(
    "keywords, options",
    [
        ({"solver": "foo"}, ["--solver", "foo"]),
        ({"update": "foo"}, ["--update", "foo"]),
        ({"engine": "gromacs"}, ["--engine", "gromacs"]),
        ({"fractions": "mass"}, ["--fractions", "mass"]),
        ({"container": "cylinder:-1"}, ["--container", "cylinder:-1"]),
        ({"container": "sphere:3"}, ["--container", "sphere:3"]),
    ],
)
def test_bad_values_are_worded_as_the_command_line_words_them(keywords, options, tmp_path):
    # ValueError carries the command line's one-line message, word for word (the
    # command line prefixes "packbed: "; --solver, --update, --container and the other
    # named choices included)
    run = subprocess.run([PACKBED, "generate", *options, "--out", str(tmp_path / "out")],
                         capture_output=True, text=True)
    assert run.returncode == 2
    with pytest.raises(ValueError) as raised:
        packbed.generate(**keywords)
    assert run.stderr == "packbed: " + str(raised.value) + "\n"


# The module refuses what the command line refuses, with the same words (the
# command line's line is "packbed: MESSAGE" for a value CLI11 checks, "packbed COMMAND: MESSAGE"
# for one the library checks).
@pytest.mark.parametrize(
    "keywords, options",
    [
        ({"seed": -1}, ["--seed", "-1"]),
        ({"seed": 2**64}, ["--seed", str(2**64)]),
        ({"seed": 1.5}, ["--seed", "1.5"]),
        ({"aspect_ratio": 5, "container": "cylinder:8"}, ["-a", "5", "--container", "cylinder:8"]),
        ({"band_clearance": 1e300, "particles": 30}, ["--band-clearance", "1e300", "-n", "30"]),
    ],
)
def test_the_module_refuses_what_the_command_line_refuses(keywords, options, tmp_path):
    run = subprocess.run([PACKBED, "generate", *options, "--out", str(tmp_path / "out")],
                         capture_output=True, text=True)
    assert run.returncode == 2
    with pytest.raises(ValueError) as raised:
        packbed.generate(**keywords)
    assert run.stderr in (f"packbed: {raised.value}\n", f"packbed generate: {raised.value}\n")
    assert not (tmp_path / "out").exists()


def test_a_seed_up_to_2_to_the_64_gives_the_command_lines_bed(tmp_path):
    seed = 2**64 - 1
    status, _, err = cli("generate", "-a", 3, "-n", 30, "-s", seed, "-q", "--no-analysis",
                         "--out", tmp_path / "cli")
    assert status == 0, err
    bed = packbed.generate(aspect_ratio=3, particles=30, seed=seed)
    assert np.array_equal(bed.centers, read_csv(tmp_path / "cli" / "particles.csv")[:, :3])


@pytest.mark.parametrize(
    "make, words",
    [
        (lambda c: np.ma.masked_array(c, mask=np.eye(2, 3, dtype=bool)), "a masked array"),
        (lambda c: c + 0j, "dtype complex128"),
        (lambda c: c.astype(str), "dtype <U"),
        (lambda c: c.astype(bool), "dtype bool"),
        (lambda c: c.astype(object), "dtype object"),
    ],
)
def test_arrays_numpy_would_change_are_refused(make, words):
    centers = np.array([[0.0, 0.0, 0.5], [0.0, 0.0, 1.5]])
    with pytest.raises(ValueError, match=words):
        packbed.Bed(make(centers), diameter=1.0)
    with pytest.raises(ValueError, match=words):
        packbed.Bed(centers, make(np.array([[0.5, 0.5, 0.5], [0.5, 0.5, 0.5]]))[:, 0])
    assert len(packbed.Bed(centers.astype(np.float32), diameter=1.0)) == 2  # real numbers


def test_no_output_replaces_an_input_of_the_call(cli_bed, tmp_path):
    # The bed's own file, its summary.json as a sidecar, a case written over itself: refused,
    # nothing changed.
    shutil.copytree(cli_bed, tmp_path / "bed")
    before = {p: p.read_bytes() for p in (tmp_path / "bed").iterdir()}
    bed = packbed.read(tmp_path / "bed" / "particles.csv")
    with pytest.raises(ValueError, match="would overwrite it"):
        packbed.export(bed, tmp_path / "bed" / "particles.csv", format="stl")
    with pytest.raises(ValueError, match="summary.json would overwrite it"):
        packbed.export(packbed.read(tmp_path / "bed" / "particles.csv"),
                       tmp_path / "bed" / "summary", format="stl")
    assert {p: p.read_bytes() for p in (tmp_path / "bed").iterdir()} == before


def test_deep_nesting_raises_value_error_not_a_crash(cli_bed, tmp_path):
    # 1e5 nested brackets in the summary.json read beside a bed: the interpreter survives.
    (tmp_path / "deep").mkdir()
    shutil.copy(cli_bed / "particles.csv", tmp_path / "deep")
    (tmp_path / "deep" / "summary.json").write_text(
        '{"diameter": ' + "[" * 100000 + "]" * 100000 + "}")
    with pytest.raises(ValueError, match="nested deeper than 64 levels"):
        packbed.read(tmp_path / "deep" / "particles.csv")
    with pytest.raises(ValueError, match="nested deeper than 64 levels"):
        packbed.hydraulics(bed=str(tmp_path / "deep"))


def test_a_periodic_cell_narrower_than_three_diameters_is_analysed():
    # 30 spheres in periodic:2.5,2.5: g(r) to the smaller period by default, as the command
    # line's generate analyses the bed; asked for, 3 d is refused (one line).
    bed = packbed.generate(container="periodic:2.5,2.5", particles=30, seed=1)
    analysis = packbed.analyze(bed)
    assert analysis.summary["options"]["rdf_range"] == 2.5
    assert analysis.pair_correlation.high[-1] == pytest.approx(2.5, abs=1e-12)
    assert 0.3 < analysis.void_fraction < 0.7
    with pytest.raises(ValueError, match=r"--rdf-range 3 Dp \(3\) is not allowed"):
        packbed.analyze(bed, rdf_range=3)


def test_a_random_array_rebuilt_from_its_arrays_is_the_same_cell():
    # The cube is periodic along z too: with period_z the rebuilt bed has the same void
    # fraction and the same voxel image; without it, a sphere across the floor is refused.
    b = packbed.random_array(count=32, solid_fraction=0.3, gap=0.02, seed=1)
    assert b.period_z == pytest.approx((32 * math.pi / 6 / 0.3) ** (1 / 3), rel=1e-8)
    c = packbed.Bed(b.centers, b.radii, container=b.container, period_z=b.period_z)
    assert c.period_z == b.period_z
    assert packbed.analyze(c).void_fraction == packbed.analyze(b).void_fraction
    assert np.array_equal(packbed.voxelize(c, voxel_size=0.2, kind="fraction"),
                          packbed.voxelize(b, voxel_size=0.2, kind="fraction"))
    with pytest.raises(ValueError, match="sticks out of the container"):
        packbed.Bed(b.centers, b.radii, container=b.container)
    with pytest.raises(ValueError, match="period_z 3: not allowed without a periodic container"):
        packbed.Bed(b.centers, b.radii, container="cylinder:5", period_z=3)
    assert packbed.lattice().period_z is None


def test_a_read_bed_written_again_is_a_bed_hydraulics_takes(tmp_path):
    # A bed read from a file and written: its summary names the file it came from as its source
    # (the written particles.csv is its own), and hydraulics takes the void fraction of its
    # analysis, as it takes a generated bed's.
    status, _, err = cli("generate", "-a", 4, "-n", 100, "-s", 1, "-q", "--out", tmp_path / "g")
    assert status == 0, err
    read = packbed.read(str(tmp_path / "g" / "particles.csv"))
    read.write(str(tmp_path / "w"))
    summary = json.loads((tmp_path / "w" / "summary.json").read_text())
    assert summary["source"] == str(tmp_path / "g" / "particles.csv")
    assert "particles_file" not in summary
    porosity = packbed.hydraulics(bed=str(tmp_path / "w"), diameter=0.003)["porosity"]
    assert porosity["value"] == summary["analysis"]["void_fraction"]
    assert porosity["from"].startswith("the overall void fraction of its analysis")


def test_an_image_of_a_cell_that_does_not_tile_is_warned_of():
    # 0.1 does not divide the cube's edge (3.822... = 38.2 voxels): 39 voxels reach past the
    # cell, and the image's solid fraction is not the array's. Edge / 39 tiles it: no warning,
    # and the exact fractions average to the array's solid fraction.
    b = packbed.random_array(count=32, solid_fraction=0.3, seed=1)
    with pytest.warns(UserWarning, match=r"does not tile: its period along x, 3\.82245559, is "
                                         r"38\.2246 voxels of 0\.1"):
        untiled = packbed.voxelize(b, voxel_size=0.1, kind="fraction")
    assert abs(untiled.mean() - b.summary["solid_fraction"]) > 1e-3
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        tiled = packbed.voxelize(b, voxel_size=b.period_z / 39, kind="fraction")
    assert tiled.shape == (39, 39, 39)
    assert tiled.mean() == pytest.approx(b.summary["solid_fraction"], abs=1e-9)
