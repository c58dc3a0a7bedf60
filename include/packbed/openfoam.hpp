// A ready OpenFOAM case for blockMesh + snappyHexMesh around a treated bed: the
// background box sized to the container, refinement levels tied to the particle diameter, a
// locationInMesh certainly in the fluid. Written for OpenFOAM v1912 (Debian 12's package) and
// later; the dictionaries use no keyword that newer releases dropped.
#pragma once

#include <string>
#include <utility>
#include <vector>

#include "packbed/surface.hpp"

namespace packbed {

/// The flow model of the case: laminar, or a RANS model with wall functions.
enum class Turbulence { laminar, k_epsilon, k_omega_sst };

/// The names --turbulence takes, as OpenFOAM names the models: laminar, kEpsilon, kOmegaSST.
const Registry<Turbulence>& turbulence_models();

/// Named meshes of `export --mesh` (docs/validation.md, "Prism layers"): "quick", the
/// defaults (d/16 at the particles, no layers: the creeping-flow gradient of the a = 5 tube bed
/// 16 % low); "accurate", d/32 and three prism layers (the gradient within 2 % of the converged
/// one). Options given beside a preset replace its values.
const Registry<OpenFoamMeshOptions>& mesh_presets();

/// The flow of the runnable case (simpleFoam, steady, incompressible), in SI units: the case
/// is meshed in the bed's units and Allrun scales it to metres (transformPoints) before the
/// flow is solved. Defaults: water at 20 C and particles of 1 mm, as packbed hydraulics.
struct OpenFoamFlowOptions {
    int ranks = 2;                ///< MPI ranks of Allrun (decomposeParDict), 1 to 1024
    double fluid_density = 998.2; ///< kg/m^3
    double viscosity = 1.002e-3;  ///< dynamic, Pa s
    double velocity = 0.0;        ///< superficial velocity at the inlet, m/s; 0: from reynolds
    double reynolds = 1.0;        ///< particle Reynolds number rho u d / mu, u superficial
    double scale = 0.0;           ///< metres per unit of the bed's lengths; 0: d = 1 mm
    /// laminar, or RANS (0.orig/k, epsilon or omega, nut: 5 % turbulence intensity and a
    /// mixing length of 0.1 d at the inlet, wall functions on the walls and particles)
    Turbulence turbulence = Turbulence::laminar;
};

/// What openfoam_case builds: the text files by path inside the case directory, the two
/// surfaces to write under constant/triSurface, and the numbers its README and users need.
struct OpenFoamCase {
    std::vector<std::pair<std::string, std::string>> files; ///< (relative path, contents)
    std::vector<Solid> particles;                           ///< constant/triSurface/particles.stl
    std::vector<Solid> wall; ///< constant/triSurface/wall.stl (a cylinder's or an annulus'
                             ///< tube; empty for a box)
    std::vector<Solid> rod;  ///< constant/triSurface/rod.stl (an annulus' rod; else empty)
    Vec3 location_in_mesh;   ///< a point of the fluid, farthest from every surface we tried
    double clearance = 0.0;  ///< its distance to the nearest surface (length)
    double fluid_volume = 0; ///< exact void volume of the container with the treated bodies
    double cell_size = 0.0;  ///< background cell edge, Dp / cells_per_diameter (length; a
                             ///< box's cells are at most that long)
    double scale = 0.0;      ///< metres per bed unit (Allrun's transformPoints)
    double velocity = 0.0;   ///< the inlet's superficial velocity, m/s
    double interstitial_velocity = 0.0; ///< velocity / the exact void fraction, m/s (the mean
                                        ///< in the fluid a periodic cell's flow is held at)
    double reynolds = 0.0;              ///< the particle Reynolds number of that velocity
    std::vector<double> planes;         ///< heights of the pressure planes, m (after scaling)
    std::string allrun;                 ///< the script Allrun (to be written executable)
};

/// The case for `bed` (from treat_contacts) in `container`, surfaces tessellated with
/// `surface`. The box of blockMesh spans exactly the container's height, so its bottom and top
/// faces become the patches "inlet" (z = 0) and "outlet" (z = height). For a cylinder it spans
/// the cylinder with a margin of one background cell sideways, and snappyHexMesh cuts the wall
/// (patch "wall", wall.stl: a surface open at both ends reaching half a cell beyond them) out
/// of it; for a box it is the box itself, ceil(length / cell) cells along each axis, and its
/// four sides are the patch "wall" (type wall): no wall surface. snappyHexMesh cuts the
/// particles (patch "particles") out of either. For an annulus the background is the
/// cylinder's about its tube, and snappyHexMesh cuts the tube (wall.stl, patch "wall") and
/// the rod (rod.stl, patch "rod", refined as the wall); a periodic cell is the background
/// itself, its sides cyclic pairs. The location in the mesh is searched inside
/// the container's bounds, its clearance from the wall by Container::wall_distance. `volumes`
/// gives the exact fluid volume written in the README.
/// The flow files (`flow`): 0.orig/U and p (inlet velocity, outlet pressure 0, no slip on the
/// walls and particles), constant/transportProperties and turbulenceProperties (laminar),
/// fvSchemes and fvSolution for simpleFoam, decomposeParDict (hierarchical, `ranks` along z),
/// function objects writing the area-averaged pressure on planes across the bed clear of its
/// ends and the inlet's and outlet's fluxes, and Allrun (mesh, scale, run; docs/notes).
/// \throws InvalidInput when the options are out of range, the container is a periodic cell,
/// or no point of the fluid clears every surface by two cells of the finest level
OpenFoamCase openfoam_case(const TreatedBed& bed, const SurfaceContainer& container,
                           const TreatmentVolumes& volumes, const std::string& contacts,
                           double diameter, const SurfaceOptions& surface,
                           const OpenFoamMeshOptions& options = {},
                           const OpenFoamFlowOptions& flow = {});

/// The particles as a case sees them, whatever their shape: what openfoam_case builds from a
/// treated bed of spheres, and the pellets' export from their shapes.
struct CaseParticles {
    std::vector<Solid> surface; ///< constant/triSurface/particles.stl
    /// a ball holding each body (with a periodic cell's copies across its sides): the fluid
    /// point keeps its clearance from them
    std::vector<TreatedBody> bounds;
    double reach = 0.0;     ///< how far a surface may come beyond the balls (a bridge's)
    std::size_t count = 0;  ///< the particles of the bed (README)
    double top = 0.0;       ///< the bed's top: the last pressure plane stays below it
    double wall_edge = 0.0; ///< the wall's triangles, at most this long (and half a cell)
};

/// The same case for particles of any shape (the other overload's `level` is in their
/// surface and wall_edge).
OpenFoamCase openfoam_case(const CaseParticles& particles, const SurfaceContainer& container,
                           const TreatmentVolumes& volumes, const std::string& contacts,
                           double diameter, const OpenFoamMeshOptions& options = {},
                           const OpenFoamFlowOptions& flow = {});

} // namespace packbed
