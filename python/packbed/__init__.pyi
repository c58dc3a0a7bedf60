# Type stubs of the packbed module (python/module.cpp): names and types for editors.
from typing import Any, Callable, Dict, List, Optional, Tuple, Union

import numpy as np
import numpy.typing as npt

__version__: str

class ConvergenceError(RuntimeError): ...

class Bed:
    def __init__(
        self,
        centers: npt.ArrayLike,
        radii: Optional[npt.ArrayLike] = None,
        *,
        diameter: Optional[float] = None,
        container: Optional[str] = None,
        orientations: Optional[npt.ArrayLike] = None,
        shape: str = "sphere",
    ) -> None: ...
    @property
    def centers(self) -> npt.NDArray[np.float64]: ...
    @property
    def radii(self) -> npt.NDArray[np.float64]: ...
    @property
    def container(self) -> Optional[str]: ...
    @property
    def summary(self) -> Dict[str, Any]: ...
    def __len__(self) -> int: ...
    def write(
        self, out: str, *, force: bool = False, analysis: bool = True, band_clearance: float = 1.0
    ) -> None: ...

class Profile:
    @property
    def low(self) -> npt.NDArray[np.float64]: ...
    @property
    def high(self) -> npt.NDArray[np.float64]: ...
    @property
    def value(self) -> npt.NDArray[np.float64]: ...
    @property
    def middle(self) -> npt.NDArray[np.float64]: ...

class Analysis:
    @property
    def void_fraction(self) -> float: ...
    @property
    def band(self) -> Tuple[float, float]: ...
    @property
    def diameter(self) -> float: ...
    @property
    def radial_void_fraction(self) -> Profile: ...
    @property
    def centre_distribution(self) -> Profile: ...
    @property
    def axial_void_fraction(self) -> Profile: ...
    @property
    def pair_correlation(self) -> Profile: ...
    @property
    def walls(self) -> Dict[str, Dict[str, Any]]: ...
    @property
    def coordination_histogram(self) -> npt.NDArray[np.int64]: ...
    @property
    def summary(self) -> Dict[str, Any]: ...

class PelletAnalysis:
    @property
    def void_fraction(self) -> float: ...
    @property
    def band(self) -> Tuple[float, float]: ...
    @property
    def diameter(self) -> float: ...
    @property
    def radial_void_fraction(self) -> Profile: ...
    @property
    def axial_void_fraction(self) -> Profile: ...
    @property
    def orientation(self) -> Dict[str, npt.NDArray[Any]]: ...
    @property
    def order(self) -> float: ...
    @property
    def mean_cos2(self) -> float: ...
    @property
    def mean_cos2_wall(self) -> float: ...
    @property
    def coordination_histogram(self) -> npt.NDArray[np.int64]: ...
    @property
    def summary(self) -> Dict[str, Any]: ...

def generate(
    *,
    aspect_ratio: Optional[float] = None,
    container: Optional[str] = None,
    particles: int = 500,
    seed: int = 1,
    diameter: float = 1.0,
    sizes: str = "mono",
    fractions: str = "volume",
    e0: float = 0.47,
    ck: float = 0.3,
    cg_step: float = 1.25e-7,
    overlap_low: Optional[float] = None,
    overlap_high: Optional[float] = None,
    tolerance: float = 1e-4,
    mc_period: int = 100,
    mc_window: int = 10,
    mc_tolerance: Optional[float] = None,
    update: str = "simultaneous",
    solver: str = "fire",
    skin: Optional[float] = None,
    layer_height: Optional[float] = None,
    friction: float = 0.0,
    wall_friction: float = 0.0,
    target_void_fraction: Optional[float] = None,
    checkpoint: Optional[str] = None,
    max_iterations: Optional[int] = None,
    band_clearance: float = 1.0,
    threads: Optional[int] = None,
    progress: Optional[Callable[[Dict[str, Any]], None]] = None,
    out: Optional[str] = None,
    force: bool = False,
    engine: str = "packbed",
    ranks: int = 1,
    mpi_command: Optional[str] = None,
    lmp: str = "lmp",
    shape: str = "sphere",
) -> Bed: ...
def read(
    path: str,
    *,
    format: str = "auto",
    frame: int = -1,
    axis: Optional[Tuple[float, float]] = None,
    floor: float = 0.0,
    diameter: Optional[float] = None,
    container: Optional[str] = None,
    outside_tolerance: float = 0.01,
) -> Bed: ...
def analyze(
    bed: Bed,
    *,
    container: Optional[str] = None,
    band: Optional[Tuple[float, float]] = None,
    band_clearance: float = 1.0,
    diameter: Optional[float] = None,
    shell_width: float = 0.02,
    slab_height: float = 0.05,
    centre_bin: Optional[float] = None,
    contact_tolerance: float = 1e-3,
    rdf_range: Optional[float] = None,
    rdf_bin: Optional[float] = None,
    friction: Optional[float] = None,
    threads: Optional[int] = None,
    out: Optional[str] = None,
    force: bool = False,
) -> Union[Analysis, PelletAnalysis]: ...
def lattice(
    *,
    type: str = "diamond",
    region: str = "box:10,10,10",
    diameter: float = 1.0,
    origin: Optional[str] = None,
    keep: str = "whole",
    rotate: str = "",
    band_clearance: float = 1.0,
    analysis: bool = True,
    out: Optional[str] = None,
    force: bool = False,
) -> Bed: ...
def random_array(
    *,
    count: int,
    solid_fraction: float = 0.3,
    diameter: float = 1.0,
    gap: float = 0.0,
    sweeps: int = 1000,
    seed: int = 1,
    out: Optional[str] = None,
    force: bool = False,
) -> Bed: ...
def voxelize(
    bed: Bed,
    *,
    voxel_size: float,
    region: Optional[Tuple[float, float, float, float, float, float]] = None,
    kind: str = "binary",
    dtype: npt.DTypeLike = "float64",
    container: Optional[str] = None,
    threads: Optional[int] = None,
    out: Optional[str] = None,
) -> npt.NDArray[Any]: ...
def export(
    bed: Bed,
    out: str,
    *,
    format: Optional[str] = None,
    container: Optional[str] = None,
    container_height: Optional[float] = None,
    no_container: bool = False,
    density: float = 2500.0,
    box: Optional[str] = None,
    fluid_velocity: Optional[float] = None,
    contacts: str = "none",
    refine: int = 3,
    edge: Optional[float] = None,
    facets: Optional[str] = None,
    cells_per_diameter: int = 4,
    particle_level: int = 2,
    wall_level: int = 1,
    ranks: int = 2,
    reynolds: float = 1.0,
    turbulence: str = "laminar",
    fluid_density: float = 998.2,
    viscosity: float = 0.001002,
    scale: Optional[float] = None,
    flow: str = "inlet",
    force: bool = False,
    layers: int = 0,
) -> str: ...
def cfd_report(
    case: str,
    *,
    out: Optional[str] = None,
    force: bool = False,
) -> Dict[str, Any]: ...
def cfd_series(
    cases: List[str],
    *,
    out: Optional[str] = None,
    force: bool = False,
) -> Dict[str, Any]: ...
def hydraulics(
    *,
    porosity: Optional[float] = None,
    bed: Optional[str] = None,
    diameter: Optional[float] = None,
    particle_density: float = 2500.0,
    fluid_density: float = 998.2,
    viscosity: float = 0.001002,
    gravity: float = 9.80665,
    velocity: Optional[float] = None,
    aspect_ratio: Optional[float] = None,
    container: Optional[str] = None,
) -> Dict[str, Any]: ...
def mesh_preset(name: str) -> Dict[str, int]: ...
def correlations(
    *, aspect_ratio: float = 5.0, profile_step: float = 0.01, profile_to: float = 5.0
) -> Dict[str, Any]: ...
def analyze_frames(
    path: str,
    *,
    format: str = "auto",
    axis: Optional[Tuple[float, float]] = None,
    floor: float = 0.0,
    diameter: Optional[float] = None,
    container: Optional[str] = None,
    outside_tolerance: float = 0.01,
    band: Optional[Tuple[float, float]] = None,
    band_clearance: float = 1.0,
    threads: Optional[int] = None,
) -> Dict[str, Any]: ...
