"""The ParaView recipe of examples/render_bed.py, run headless: a bed seen side-on in a
parallel projection must show as a column of touching spheres exactly 2 Rt wide and as tall
as the bed, filled with spheres (an empty view, or spheres drawn at the wrong size, fails);
then a bed of cylinder pellets, its exact shapes' STL, as wide and tall as the pellets reach.
Usage: xvfb-run -a pvbatch tests/check_paraview.py PACKBED SOURCE_DIR
Exit 77 (reported as skipped by ctest) when pvbatch's Python has no paraview module."""
import json
import math
import os
import shutil
import subprocess
import sys
import tempfile

try:
    from paraview.simple import OpenDataFile, SaveScreenshot, Show
    from vtkmodules.vtkIOImage import vtkPNGReader
except ImportError:
    print("ParaView's Python is not installed: skipped")
    sys.exit(77)

exe, source = sys.argv[1], sys.argv[2]
sys.path.insert(0, os.path.join(source, "examples"))
from render_bed import show_spheres, white_view  # noqa: E402

out = tempfile.mkdtemp(prefix="packbed-paraview-")
subprocess.run([exe, "generate", "--aspect-ratio", "5", "--particles", "200", "--seed", "1",
                "--diameter", "0.003", "--quiet", "--out", f"{out}/bed"], check=True)
summary = json.load(open(f"{out}/bed/summary.json"))
rt, top = summary["container"]["radius"], summary["container"]["height"]

W, H = 400, 800
view = white_view(W, H)
show_spheres(OpenDataFile(f"{out}/bed/particles.vtu"), view)
# Side-on, parallel projection: a pixel is the same length everywhere.
view.CameraParallelProjection = 1
view.CameraPosition = [0, -1, top / 2]
view.CameraFocalPoint = [0, 0, top / 2]
view.CameraViewUp = [0, 0, 1]
view.CameraParallelScale = 0.6 * top  # half the picture's height, in metres
SaveScreenshot(f"{out}/side.png", view, ImageResolution=[W, H])


def silhouette(png):
    """The drawn (not white) pixels of a screenshot: their columns, their rows, how many."""
    reader = vtkPNGReader()
    reader.SetFileName(png)
    reader.Update()
    image = reader.GetOutput()
    scalars = image.GetPointData().GetScalars()
    nx, ny, _ = image.GetDimensions()
    cols, rs, count = set(), set(), 0
    for j in range(ny):
        for i in range(nx):
            if scalars.GetTuple(j * nx + i)[:3] != (255.0, 255.0, 255.0):
                cols.add(i)
                rs.add(j)
                count += 1
    return cols, rs, count


columns, rows, filled = silhouette(f"{out}/side.png")
assert filled > 0, "the view is empty"
metres_per_pixel = 2 * 0.6 * top / H
width = (max(columns) - min(columns) + 1) * metres_per_pixel
height = (max(rows) - min(rows) + 1) * metres_per_pixel
fill = filled / ((max(columns) - min(columns) + 1) * (max(rows) - min(rows) + 1))
print(f"silhouette {width * 1e3:.2f} x {height * 1e3:.2f} mm (bed: {2 * rt * 1e3:.2f} x "
      f"{top * 1e3:.2f} mm), {fill:.3f} of its box filled")
# The spheres touch the wall: the silhouette spans 2 Rt (within 2 pixels), the floor to the
# top (within 2 pixels); spheres drawn half size would leave it 4 Dp wide and full of holes.
assert abs(width - 2 * rt) <= 2 * metres_per_pixel, (width, 2 * rt)
assert abs(height - top) <= 2 * metres_per_pixel, (height, top)
assert fill > 0.9, fill
print("ParaView recipe: spheres of the right size, side-on silhouette matches the container")


# Pellets: 12 cylinders (generate --shape) as the exact shapes' STL, shrunk by 2 %, seen
# side-on: the silhouette spans, to 2 pixels, what the pellets' own support functions give
# from particles.csv (the axis is the body z axis turned by qw, qx, qy, qz; a cylinder reaches
# |a_x| L / 2 + R sqrt(1 - a_x^2) along x from its centre).
subprocess.run([exe, "generate", "--shape", "cylinder:3,3", "--aspect-ratio", "4",
                "--particles", "12", "--seed", "3", "--quiet", "--out", f"{out}/pellets"],
               check=True)
subprocess.run([exe, "export", f"{out}/pellets/particles.csv", "--format", "stl", "--contacts",
                "shrink:0.02", "--no-container", "--out", f"{out}/pellets.stl", "--quiet"],
               check=True)
lo, hi = [math.inf] * 3, [-math.inf] * 3
with open(f"{out}/pellets/particles.csv") as f:
    next(f)
    for line in f:
        x, y, z, r, qw, qx, qy, qz = map(float, line.split(","))
        axis = (2 * (qx * qz + qw * qy), 2 * (qy * qz - qw * qx), 1 - 2 * (qx * qx + qy * qy))
        for k, c in enumerate((x, y, z)):
            reach = 0.98 * (abs(axis[k]) * 1.5 + 1.5 * math.sqrt(max(0.0, 1 - axis[k] ** 2)))
            lo[k], hi[k] = min(lo[k], c - reach), max(hi[k], c + reach)
S = 600
view = white_view(S, S)
Show(OpenDataFile(f"{out}/pellets.stl"), view)
half = 0.6 * max(hi[0] - lo[0], hi[2] - lo[2])
view.CameraParallelProjection = 1
view.CameraPosition = [(lo[0] + hi[0]) / 2, -100, (lo[2] + hi[2]) / 2]
view.CameraFocalPoint = [(lo[0] + hi[0]) / 2, 0, (lo[2] + hi[2]) / 2]
view.CameraViewUp = [0, 0, 1]
view.CameraParallelScale = half
SaveScreenshot(f"{out}/pellets.png", view, ImageResolution=[S, S])
columns, rows, filled = silhouette(f"{out}/pellets.png")
assert filled > 0, "the pellets' view is empty"
per_pixel = 2 * half / S
width = (max(columns) - min(columns) + 1) * per_pixel
height = (max(rows) - min(rows) + 1) * per_pixel
print(f"pellets: silhouette {width:.3f} x {height:.3f} (their support functions: "
      f"{hi[0] - lo[0]:.3f} x {hi[2] - lo[2]:.3f})")
assert abs(width - (hi[0] - lo[0])) <= 2 * per_pixel, (width, hi[0] - lo[0])
assert abs(height - (hi[2] - lo[2])) <= 2 * per_pixel, (height, hi[2] - lo[2])
print("ParaView: the pellets' exact shapes drawn where and as large as the bed says")
shutil.rmtree(out)  # kept only when a check failed, for a look
