"""Render the flow of a run packbed OpenFOAM case: the velocity magnitude on the vertical slice
through the tube's axis, at the last time written (headless, ParaView's pvbatch).

Usage: xvfb-run -a pvbatch examples/render_flow.py CASE_DIR OUT.png [WIDTH HEIGHT]
(Debian: packages paraview, python3-paraview and xvfb.) CASE_DIR holds a case written by
`packbed export --format openfoam` and run by its ./Allrun (reconstructed: U in the last time
folder). The particles are the holes in the slice; the colour scale is |U| over the superficial
velocity (packbed.json), so 1 is the inlet's mean velocity.
"""
import json
import os
import sys

from paraview.simple import (Calculator, ColorBy, CreateView, GetColorTransferFunction,
                             GetScalarBar, OpenFOAMReader, SaveScreenshot, Show, Slice)

case, out = sys.argv[1], sys.argv[2]
size = [int(sys.argv[3]), int(sys.argv[4])] if len(sys.argv) > 4 else [480, 1400]
flow = json.load(open(os.path.join(case, "packbed.json")))["openfoam"]["flow"]
foam = os.path.join(case, "case.foam")
if not os.path.exists(foam):
    open(foam, "w").close()  # the reader opens the case through an empty .foam file
reader = OpenFOAMReader(FileName=foam)
reader.MeshRegions = ["internalMesh"]
reader.CellArrays = ["U"]
times = list(reader.TimestepValues)
last = times[-1] if times else 0
if not last:
    sys.exit(f"{case}: no time but 0 written; run ./Allrun first")
reader.UpdatePipeline(last)
bounds = reader.GetDataInformation().GetBounds()
middle = [(bounds[0] + bounds[1]) / 2, (bounds[2] + bounds[3]) / 2, (bounds[4] + bounds[5]) / 2]
cut = Slice(Input=reader)
cut.SliceType = "Plane"
cut.SliceType.Origin = middle
cut.SliceType.Normal = [0, 1, 0]
speed = Calculator(Input=cut)
speed.AttributeType = "Cell Data"
speed.ResultArrayName = "speed"
speed.Function = f"mag(U) / {flow['velocity']!r}"

view = CreateView("RenderView")
view.ViewSize = size
view.ViewTime = last
view.UseColorPaletteForBackground = 0
view.Background = [1, 1, 1]
view.OrientationAxesVisibility = 0
shown = Show(speed, view)
ColorBy(shown, ("CELLS", "speed"))
lut = GetColorTransferFunction("speed")
lut.ApplyPreset("Turbo", True)
lut.RescaleTransferFunction(0.0, 6.0)  # the pores' peaks are a few times the superficial speed
bar = GetScalarBar(lut, view)
bar.Title = "|U| / u_s"
bar.ComponentTitle = ""
bar.TitleColor = bar.LabelColor = [0, 0, 0]
bar.Visibility = 1
shown.SetScalarBarVisibility(view, True)
# Side-on, in parallel projection: the slice fills the picture's height, on its left, and the
# colour bar stands in the room on its right.
height = bounds[5] - bounds[4]
half_width = 0.52 * height * size[0] / size[1]  # half the picture's width, in lengths
shift = max(0.0, half_width - 0.5 * (bounds[1] - bounds[0])) * 0.55
focus = [middle[0] + shift, middle[1], middle[2]]
view.CameraPosition = [focus[0], focus[1] - 10 * height, focus[2]]
view.CameraFocalPoint = focus
view.CameraViewUp = [0, 0, 1]
view.CameraParallelProjection = 1
view.CameraParallelScale = 0.52 * height
bar.WindowLocation = "Any Location"
bar.Orientation = "Vertical"
bar.Position = [0.70, 0.05]
bar.ScalarBarLength = 0.35
SaveScreenshot(out, view, ImageResolution=size)
