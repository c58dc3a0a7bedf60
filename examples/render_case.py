"""Render a vertical slice of a meshed packbed OpenFOAM case (headless, ParaView's pvbatch).

Usage: xvfb-run -a pvbatch examples/render_case.py CASE_DIR OUT.png
(Debian: packages paraview, python3-paraview and xvfb; Debian's ParaView renders through X, so
xvfb-run provides the display.) CASE_DIR holds a case written by `packbed export --format
openfoam` after blockMesh and snappyHexMesh -overwrite.
"""
import os
import sys

from paraview.simple import (CreateView, OpenFOAMReader, SaveScreenshot, Show, Slice)

case, out = sys.argv[1], sys.argv[2]
foam = os.path.join(case, "case.foam")
if not os.path.exists(foam):
    open(foam, "w").close()  # the reader opens the case through an empty .foam file
reader = OpenFOAMReader(FileName=foam)
reader.MeshRegions = ["internalMesh"]
reader.UpdatePipeline()
bounds = reader.GetDataInformation().GetBounds()
middle = [(bounds[0] + bounds[1]) / 2, (bounds[2] + bounds[3]) / 2, (bounds[4] + bounds[5]) / 2]
cut = Slice(Input=reader)
cut.SliceType = "Plane"
cut.SliceType.Origin = middle
cut.SliceType.Normal = [0, 1, 0]
cut.Triangulatetheslice = 0  # show the hexahedra and their split faces as they are
view = CreateView("RenderView")
view.ViewSize = [900, 1400]
view.UseColorPaletteForBackground = 0
view.Background = [1, 1, 1]
view.OrientationAxesVisibility = 0
shown = Show(cut, view)
shown.SetRepresentationType("Surface With Edges")
shown.ColorArrayName = [None, ""]
shown.DiffuseColor = [0.74, 0.84, 0.96]
shown.EdgeColor = [0.12, 0.16, 0.35]
view.CameraPosition = [middle[0], middle[1] - 10 * (bounds[5] - bounds[4]), middle[2]]
view.CameraFocalPoint = middle
view.CameraViewUp = [0, 0, 1]
view.ResetCamera()
SaveScreenshot(out, view, ImageResolution=[900, 1400])
