#!/usr/bin/env python3
"""particles.vtu read by VTK's own XML reader (the one ParaView uses for .vtu; from
python3-paraview or python3-vtk9, whichever is installed): as many
points and vertex cells as spheres, a `radius` array, and the same numbers as particles.csv;
for a bed of pellets also each one's `orientation` and `axis`.
Usage: check_vtu.py PACKBED. Exit 77 (reported as skipped by ctest) when VTK is missing."""
import csv
import shutil
import subprocess
import sys
import tempfile

try:
    from vtkmodules.vtkIOXML import vtkXMLUnstructuredGridReader
except ImportError:
    print("neither python3-paraview nor python3-vtk9 is installed: skipped")
    sys.exit(77)

exe = sys.argv[1]
out = tempfile.mkdtemp(prefix="packbed-vtu-")
subprocess.run([exe, "generate", "--aspect-ratio", "3", "--particles", "40", "--seed", "5",
                "--diameter", "0.002", "--quiet", "--out", out], check=True)

reader = vtkXMLUnstructuredGridReader()
reader.SetFileName(f"{out}/particles.vtu")
reader.Update()
grid = reader.GetOutput()
rows = list(csv.DictReader(open(f"{out}/particles.csv")))
assert len(rows) == 40, len(rows)
assert grid.GetNumberOfPoints() == 40, grid.GetNumberOfPoints()
assert grid.GetNumberOfCells() == 40, grid.GetNumberOfCells()
assert all(grid.GetCellType(i) == 1 for i in range(40)), "cells must be VTK_VERTEX"
radius = grid.GetPointData().GetArray("radius")
assert radius is not None and radius.GetNumberOfTuples() == 40
for i, row in enumerate(rows):
    point = grid.GetPoint(i)
    assert point == (float(row["x"]), float(row["y"]), float(row["z"])), (i, point, row)
    assert radius.GetValue(i) == float(row["r"]) == 0.001, (i, radius.GetValue(i), row["r"])
print("particles.vtu: 40 vertices, radius array, positions identical to particles.csv")

# Pellets (generate --shape): the quaternion of particles.csv and the axis it turns the body
# z axis into, the third column of its rotation matrix.
pellets = f"{out}/pellets"
subprocess.run([exe, "generate", "--shape", "cylinder:3,3", "--aspect-ratio", "4",
                "--particles", "12", "--seed", "3", "--quiet", "--out", pellets], check=True)
reader = vtkXMLUnstructuredGridReader()
reader.SetFileName(f"{pellets}/particles.vtu")
reader.Update()
grid = reader.GetOutput()
rows = list(csv.DictReader(open(f"{pellets}/particles.csv")))
assert grid.GetNumberOfPoints() == len(rows) == 12, (grid.GetNumberOfPoints(), len(rows))
orientation = grid.GetPointData().GetArray("orientation")
axis = grid.GetPointData().GetArray("axis")
assert orientation.GetNumberOfComponents() == 4 and axis.GetNumberOfComponents() == 3
for i, row in enumerate(rows):
    w, x, y, z = (float(row[k]) for k in ("qw", "qx", "qy", "qz"))
    assert orientation.GetTuple(i) == (w, x, y, z), (i, orientation.GetTuple(i), row)
    expected = (2 * (x * z + w * y), 2 * (y * z - w * x), 1 - 2 * (x * x + y * y))
    assert all(abs(a - b) <= 1e-15 for a, b in zip(axis.GetTuple(i), expected)), (i, expected)
    assert grid.GetPoint(i) == (float(row["x"]), float(row["y"]), float(row["z"])), i
print("particles.vtu of 12 pellets: their quaternions and axes, as particles.csv says")
shutil.rmtree(out)  # kept only when a check failed, for a look
