"""Render a bed written by packbed (particles.vtu) with ParaView, headless.
Usage: xvfb-run -a pvbatch examples/render_bed.py results/a5-n500/particles.vtu bed.png
(Debian packages: paraview, python3-paraview, xvfb.)

show_spheres() is the recipe for ParaView's window, step for step (docs/paraview.md); the
tests run it headless (tests/check_paraview.py) and measure the picture."""
import sys

from paraview.simple import ColorBy, CreateView, GetActiveCamera, OpenDataFile, SaveScreenshot, Show

WIDTH, HEIGHT = 420, 900       # picture size in pixels
COLOUR = [0.8, 0.45, 0.2]      # sphere colour (RGB)


def show_spheres(bed, view):
    """Each point of particles.vtu drawn as a shaded sphere of its own `radius`, 1:1.
    In the window: Representation *Point Gaussian*; then, with the gear icon (advanced
    properties) on: Shader Preset *Sphere*, tick *Scale By Array*, Scale Array *radius*,
    untick *Use Scale Function*, Gaussian Radius *1*. (The scale function would map the
    radius range onto [0, 1]; for spheres of one size it maps every radius to 0.)"""
    spheres = Show(bed, view)
    spheres.SetRepresentationType("Point Gaussian")
    spheres.ShaderPreset = "Sphere"
    spheres.ScaleByArray = 1
    spheres.SetScaleArray = ["POINTS", "radius"]
    spheres.UseScaleFunction = 0
    spheres.GaussianRadius = 1.0   # the drawn radius is the array's value times this
    return spheres


def white_view(width, height):
    """A white render view without axes."""
    view = CreateView("RenderView")
    view.ViewSize = [width, height]
    view.Background = [1, 1, 1]
    if hasattr(view, "UseColorPaletteForBackground"):
        view.UseColorPaletteForBackground = 0
    view.OrientationAxesVisibility = 0
    return view


def main(vtu, png):
    bed = OpenDataFile(vtu)
    view = white_view(WIDTH, HEIGHT)
    spheres = show_spheres(bed, view)
    ColorBy(spheres, None)
    spheres.AmbientColor = spheres.DiffuseColor = COLOUR
    # Look at the bed from the side, slightly from above, and fill the picture.
    view.CameraPosition = [40, -40, 14]
    view.CameraViewUp = [0, 0, 1]
    view.ResetCamera()
    GetActiveCamera().Zoom(1.6)
    SaveScreenshot(png, view, ImageResolution=[WIDTH, HEIGHT])


if __name__ == "__main__":
    main(sys.argv[1], sys.argv[2])
