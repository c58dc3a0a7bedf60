"""The ParaView recipe of examples/render_bed.py, run headless: a bed seen side-on in a
parallel projection must show as a column of touching spheres exactly 2 Rt wide and as tall
as the bed, filled with spheres (an empty view, or spheres drawn at the wrong size, fails).
Usage: xvfb-run -a pvbatch tests/check_paraview.py PACKBED SOURCE_DIR
Exit 77 (reported as skipped by ctest) when pvbatch's Python has no paraview module."""
import json
import os
import shutil
import subprocess
import sys
import tempfile

try:
    from paraview.simple import OpenDataFile, SaveScreenshot
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

reader = vtkPNGReader()
reader.SetFileName(f"{out}/side.png")
reader.Update()
image = reader.GetOutput()
scalars = image.GetPointData().GetScalars()
nx, ny, _ = image.GetDimensions()
columns, rows, filled = set(), set(), 0
for j in range(ny):
    for i in range(nx):
        if scalars.GetTuple(j * nx + i)[:3] != (255.0, 255.0, 255.0):
            columns.add(i)
            rows.add(j)
            filled += 1
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
shutil.rmtree(out)  # kept only when a check failed, for a look
