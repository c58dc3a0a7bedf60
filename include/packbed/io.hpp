// Beds and their analysis as file contents: CSV, VTK XML (ParaView), LAMMPS data. Where the
// files go, whole or not at all: output.hpp.
#pragma once

#include <filesystem>
#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "packbed/container.hpp"
#include "packbed/packing.hpp"

namespace packbed {

/// The spheres as CSV: header `x,y,z,r`, one row per sphere, each number in the shortest form
/// that reads back to the same double (round-trip precision). A packing with orientations (a
/// bed of pellets) adds each one's unit quaternion, `qw,qx,qy,qz`, which turns the body z axis
/// into the pellet's; r is then its size (d_v / 2).
/// \return the file's text.
std::string particles_csv(const Packing& packing);

/// The spheres as a VTK XML unstructured grid (.vtu): one vertex cell per sphere, point data
/// `radius` and `diameter`. ParaView shows it with the Point Gaussian representation or glyphs.
/// Oriented particles (pellets: r their size d_v / 2) add `orientation`, the unit quaternion
/// (w, x, y, z), and `axis`, the body z axis it turns into the particle's.
/// \return the file's text.
std::string particles_vtu(const Packing& packing);

/// An axis-aligned box (lengths in the packing's units), lo < hi on every axis.
struct AxisBox {
    Vec3 lo, hi;
};

/// \return the smallest box holding every sphere whole (centre -/+ radius): the default box of
/// a DEM data file. An empty packing gives the unit cube.
AxisBox bounding_box(const Packing& packing);

/// The spheres as a LAMMPS data file for `atom_style sphere` (LIGGGHTS: `atom_style
/// granular`, the same columns): header with the atom count, one atom type and the box
/// bounds, then `Atoms # sphere` rows `id type diameter density x y z` (ids from 1 in packing
/// order, type 1), each particle's DEM spheres (ParticleShape::dem_spheres: a sphere is one
/// atom). Numbers in shortest round-trip form.
/// \param density particle density (mass per volume, in the units the DEM run uses; > 0)
/// \param box must hold every centre (LAMMPS drops atoms outside a fixed box)
/// \param comment first line of the file (no newline)
/// \param notes header comments written after it, each as a line `# NOTE`
/// \param types each sphere's atom type, from 1 (the LAMMPS engine's sizes); empty: type 1
/// \param clump_spheres 0: every sphere free; N > 0: each N consecutive spheres one rigid
/// clump (a pellet), written as a `Molecules` section (`atom-ID molecule-ID`, the clump's
/// number from 1) for `fix property/atom mol` (lammps_settle_input)
/// \throws InvalidInput when the density is not > 0, a centre is outside the box, or a header
/// line (the comment, a note) is longer than max_data_header_line (or holds a newline)
std::string lammps_data(const Packing& packing, double density, const AxisBox& box,
                        std::string_view comment, const std::vector<std::string>& notes = {},
                        const std::vector<std::uint32_t>& types = {}, std::size_t clump_spheres = 0,
                        std::uint32_t atom_types = 1);

/// The longest header line LAMMPS (2022) and LIGGGHTS (3.8) read whole: both read the data
/// file's lines into 256-byte buffers, and go on reading the rest of a longer title as a header
/// line, which they refuse ("Unknown identifier in data file").
constexpr std::size_t max_data_header_line = 250;

/// The margin the default DEM box leaves around a known container: max(Dp / 2, Rt / 100).
/// Rt / 100 is more than the prism packbed writes about the cylinder reaches beyond it (its
/// corners lie at Rt / cos(pi / sides) with at least 48 sides: Rt times 1.0022 at most), so
/// its STL lies wholly inside the box. For a box, Rt is its depth (half the narrower width):
/// its STL lies on its faces. \param diameter Dp, \param container_radius Rt (> 0)
double container_box_margin(double diameter, double container_radius);

/// The default box of a DEM data file for a bed in a known container (a cylinder of radius Rt
/// about the z axis, floor z = 0, top at `height`): x, y in [-Rt - m, Rt + m], z in
/// [-m, height + m] with m = container_box_margin(diameter, Rt). It holds the container, its
/// STL (Container::solids) and the fluid region above the bed up to `height`.
/// \throws InvalidInput when a value is not finite and > 0
AxisBox container_box(double container_radius, double height, double diameter);

/// The margin of the default DEM box of any container: container_box_margin(Dp, Rt) with Rt
/// a cylinder's radius, a box's depth, an annulus' tube radius (its STL is the cylinder's
/// prism about the tube); Dp / 2 for a periodic cell (only along z: x and y are its periods).
double container_box_margin(const Container& container, double diameter);

/// The same for any container: its bounds (Container::bounds) and [0, height], widened by
/// m = container_box_margin(container, diameter) on every side (for a box: x in
/// [x_low - m, x_high + m], y in [y_low - m, y_high + m], z in [-m, height + m]; for a cylinder
/// the box above, to the bit; for an annulus the box of its tube); for a periodic cell x in
/// [0, LX] and y in [0, LY] exactly (the data file's periodic box), z in [-m, height + m].
/// \throws InvalidInput when a bound is not finite, the depth (a periodic cell's area), the
/// height or the diameter not > 0
AxisBox container_box(const Container& container, double height, double diameter);

/// The Rayleigh time of a sphere, the time a Rayleigh surface wave takes to cross it (Li, Xu
/// & Thornton 2005, Powder Technol. 160: 219-228; LIGGGHTS' fix check/timestep/gran):
/// \f$t_R = \pi R \sqrt{\rho / G} / (0.1631 \nu + 0.8766)\f$, \f$G = E / (2 (1 + \nu))\f$.
/// DEM time steps are taken as a fraction of it for the smallest sphere.
/// \throws InvalidInput when a value is out of range (R, rho, E > 0; nu in [0, 0.5))
double rayleigh_time(double radius, double density, double youngs_modulus, double poisson_ratio);

/// Contact properties of the example DEM settle: a soft glass-like material (E far below
/// glass's 63 GPa, as usual in DEM, so that the time step is not tiny), Hertz contacts with
/// damping from the restitution coefficient and Coulomb friction. docs/dem.md.
struct DemMaterial {
    double youngs_modulus = 1e7;  ///< E (Pa with SI lengths)
    double poisson_ratio = 0.25;  ///< nu
    double restitution = 0.5;     ///< coefficient of restitution
    double friction = 0.5;        ///< sliding friction coefficient, sphere-sphere and wall
    bool friction_of_bed = false; ///< `friction` is the bed's own (generate --friction)
    /// The walls' and the floor's, where the bed's differs from `friction` (generate
    /// --wall-friction); none: `friction`. LAMMPS gives them their own `wall/gran`
    /// coefficients, LIGGGHTS their own atom type (2, the data file declaring two types).
    std::optional<double> wall_friction;
};

/// What the example DEM inputs (LAMMPS, LIGGGHTS) need: a short settle of the bed under
/// gravity in its container. File names are relative to the folder of the data file (the
/// inputs are run there).
struct DemSettle {
    std::string data_file;  ///< the data file's name (lammps_data)
    std::string wall_stl;   ///< LIGGGHTS: the container's side, STL (Container::solids)
    std::string bottom_stl; ///< LIGGGHTS: the container's floor, STL
    std::string dump;       ///< the dump the run writes (first and last step)
    /// The container (LAMMPS: the region, a cylinder or a block); a cylinder of radius 0, the
    /// default, is refused.
    Container container = Container::tube(0.0);
    double container_height = 0.0; ///< H (LAMMPS: the region's top)
    double smallest_radius = 0.0;  ///< sets the time step
    double diameter = 0.0;         ///< mean Dp: the neighbour skin (0.1 Dp)
    double density = 0.0;          ///< as in the data file
    DemMaterial material;
    int steps = 2000;                ///< the settle's length
    double time_step_fraction = 0.2; ///< dt = fraction x Rayleigh time of the smallest sphere
    /// 0: each atom a free sphere; N > 0: each N consecutive atoms one rigid pellet, its
    /// molecule (lammps_data's clump_spheres; LAMMPS only)
    std::size_t clump_spheres = 0;
    /// With clumps: the farthest a clump's sphere reaches from its pellet's centroid (m). The
    /// ghost atoms reach that far and the neighbour skin beyond (`comm_modify cutoff`), so that
    /// every atom of a rigid body near a processor's side has its ghost.
    double clump_reach = 0.0;
};

/// A LAMMPS (2022, GRANULAR package) input that reads the data file and settles the bed:
/// `units si`, `atom_style sphere`, `pair_style granular` (hertz/material, Mindlin tangential,
/// Tsuji damping), the side wall as `fix wall/gran/region` on a region (LAMMPS 2022 has no
/// STL walls for granular fixes): a cylinder, or for a box a block whose floor and top are
/// open (its four sides the wall), for an annulus two regions and two fixes (the tube `side
/// in`, the rod `side out`), for a periodic cell none (`boundary p p f`, else `f f f`), the
/// floor as `fix wall/gran ... zplane`, gravity,
/// `fix nve/sphere`, the time step from rayleigh_time computed in the script from its
/// variables (and written as a number in a comment), a dump at the first and last step. With
/// clump_spheres, each clump a rigid body: the molecule IDs read by `fix property/atom mol`
/// from the data file's `Molecules` section, `neigh_modify exclude molecule/intra`, and
/// `fix rigid/small molecule` instead of `fix nve/sphere`.
/// \throws InvalidInput when a value is out of range
std::string lammps_settle_input(const DemSettle& settle);

/// The same settle for LIGGGHTS 3.8: `atom_style granular`, `pair_style gran model hertz
/// tangential history`, the material as `fix property/global`, the container's side and
/// floor from packbed's STL files (`fix mesh/surface`, `fix wall/gran ... mesh`): a prism
/// about a cylinder, a box's four faces, an annulus' tube and rod in one file; a periodic cell
/// (`boundary p p f`) has no STL, its floor is `fix wall/gran ... primitive ... zplane 0.0`.
/// \throws InvalidInput when a value is out of range, or for clumps (LIGGGHTS builds its
/// multisphere clumps from its own templates as it inserts them, not from a data file)
std::string liggghts_settle_input(const DemSettle& settle);

} // namespace packbed
