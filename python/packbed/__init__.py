"""packbed: packed beds of spheres, generated, read, measured and written.

The library of the `packbed` command line, for Python, with numpy arrays:

    import packbed
    bed = packbed.generate(aspect_ratio=5, particles=500, seed=1)
    bed.centers, bed.radii            # numpy views of the bed (no copy)
    a = packbed.analyze(bed)          # profiles as numpy arrays, a.summary the numbers
    bed.write("my-bed")               # what `packbed generate` writes
    im = packbed.voxelize(bed, voxel_size=0.05)   # True = pore space, as PoreSpy
    packbed.export(bed, "bed.data")                # a LAMMPS data file (or STL, OpenFOAM, ...)
    packbed.hydraulics(porosity=0.4)               # eq. (1) of Tsayger (2013), Ergun, ... (dict)
    packbed.correlations(aspect_ratio=5)           # the void-fraction correlations (dict)
    packbed.cfd_report("case")        # a run OpenFOAM case's pressure drop against Ergun's (dict)
    packbed.cfd_series(["c8", "c12", "c16"])   # a mesh series: order, extrapolation, GCI (dict)

Bad values raise ValueError with the command line's message, a run that does not converge
raises packbed.ConvergenceError, and Ctrl-C raises KeyboardInterrupt. See help(packbed.generate).
"""

from ._core import (
    Analysis,
    Bed,
    ConvergenceError,
    PelletAnalysis,
    Profile,
    __version__,
    analyze,
    analyze_frames,
    cfd_report,
    cfd_series,
    correlations,
    export,
    generate,
    hydraulics,
    lattice,
    mesh_preset,
    random_array,
    read,
    voxelize,
)

__all__ = [
    "Analysis",
    "Bed",
    "ConvergenceError",
    "PelletAnalysis",
    "Profile",
    "__version__",
    "analyze",
    "analyze_frames",
    "cfd_report",
    "cfd_series",
    "correlations",
    "export",
    "generate",
    "hydraulics",
    "lattice",
    "mesh_preset",
    "random_array",
    "read",
    "voxelize",
]
