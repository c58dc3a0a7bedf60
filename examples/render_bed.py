"""Render a bed written by `packbed generate` with ParaView, headless.
Usage: xvfb-run -a pvbatch examples/render_bed.py results/a5-n500/particles.vtu bed.png
(Debian packages: paraview, xvfb.)"""
import sys

from paraview.simple import GetActiveCamera, OpenDataFile, CreateView, SaveScreenshot, Show, ColorBy

WIDTH, HEIGHT = 420, 900       # picture size in pixels
COLOUR = [0.8, 0.45, 0.2]      # sphere colour (RGB)

# Read particles.vtu: one vertex per sphere with a `radius` point array.
bed = OpenDataFile(sys.argv[1])

# A white view without axes.
view = CreateView("RenderView")
view.ViewSize = [WIDTH, HEIGHT]
view.Background = [1, 1, 1]
if hasattr(view, "UseColorPaletteForBackground"):
    view.UseColorPaletteForBackground = 0
view.OrientationAxesVisibility = 0

# Each point drawn as a shaded sphere whose radius is the `radius` array (scale 1:1).
spheres = Show(bed, view)
spheres.SetRepresentationType("Point Gaussian")
spheres.ShaderPreset = "Sphere"
spheres.ScaleByArray = 1
spheres.SetScaleArray = ["POINTS", "radius"]
spheres.ScaleTransferFunction.Points = [0.0, 0.0, 0.5, 0.0, 1.0, 1.0, 0.5, 0.0]
spheres.GaussianRadius = 1.0
ColorBy(spheres, None)
spheres.AmbientColor = spheres.DiffuseColor = COLOUR

# Look at the bed from the side, slightly from above, and fill the picture.
view.CameraPosition = [40, -40, 14]
view.CameraViewUp = [0, 0, 1]
view.ResetCamera()
GetActiveCamera().Zoom(1.6)
SaveScreenshot(sys.argv[2], view, ImageResolution=[WIDTH, HEIGHT])
