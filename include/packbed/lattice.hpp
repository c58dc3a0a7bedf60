// Regular packings of touching balls: the tetrahedral (diamond) packing of Tsayger (2013),
// "Discrete elements method: a new kind of initial conditions - tetrahedral packing of balls",
// DEM6, Golden (Colorado), and the cubic, body-centred, face-centred and hexagonal close
// packings, filling a region (a box or a cylinder) as initial conditions for DEM.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <utility>
#include <variant>
#include <vector>

#include <nlohmann/json.hpp>

#include "packbed/container.hpp"
#include "packbed/packing.hpp"
#include "packbed/registry.hpp"
#include "packbed/vec3.hpp"

namespace packbed {

/// The regular packings `packbed lattice` builds.
enum class LatticeType {
    diamond, ///< tetrahedral packing (Tsayger 2013, Table 1): coordination 4
    sc,      ///< simple cubic (Slichter's cubic): coordination 6
    bcc,     ///< body-centred cubic: coordination 8
    fcc,     ///< face-centred cubic (Slichter's hexagonal, ABC stacking): coordination 12
    hcp,     ///< hexagonal close packing (ABAB stacking): coordination 12
};

/// The names users pick a lattice by ("diamond", "sc", "bcc", "fcc", "hcp"): the one registry.
const Registry<LatticeType>& lattice_types();
/// \return the name of a lattice type in lattice_types().
std::string to_string(LatticeType type);

/// The repeating cell of a lattice of touching balls of diameter 1: a rectangular box of edges
/// `edges` with the ball centres `balls` inside it (fractions in [0, 1) of the edges, times the
/// edges). Plain value type.
struct UnitCell {
    Vec3 edges;              ///< cell edge lengths, diameters
    std::vector<Vec3> balls; ///< ball centres in the cell, diameters
    int coordination = 0;    ///< touching neighbours of every ball of the infinite lattice
    double porosity = 0.0;   ///< exact void fraction of the infinite lattice
};

/// \return the unit cell of `type` for balls of diameter 1:
/// - diamond: Tsayger's Table 1, a cube of edge \f$4/\sqrt3\f$ with the balls A-H at
///   (0,0,0), (2,2,0), (2,0,2), (0,2,2), (1,3,3), (3,1,3), (1,1,1), (3,3,1) over \f$\sqrt3\f$;
///   porosity \f$1 - \pi\sqrt3/16\f$;
/// - sc: a cube of edge 1, one ball; \f$1 - \pi/6\f$;
/// - bcc: a cube of edge \f$2/\sqrt3\f$, corner and centre; \f$1 - \pi\sqrt3/8\f$;
/// - fcc: a cube of edge \f$\sqrt2\f$, corner and face centres; \f$1 - \pi/(3\sqrt2)\f$;
/// - hcp: the orthohexagonal cell \f$1 \times \sqrt3 \times 2\sqrt{2/3}\f$ with four balls at
///   fractions (0,0,0), (1/2,1/2,0), (1/2,1/6,1/2), (0,2/3,1/2); \f$1 - \pi/(3\sqrt2)\f$.
/// The porosity is \f$1 - n \frac{\pi}{6} / V_{cell}\f$, n balls per cell.
UnitCell unit_cell(LatticeType type);

/// A region a lattice fills: a container (its cross-section, the floor z = 0) up to `height`
/// (lengths in output units). In a periodic cell the lattice must repeat across it: LX and LY
/// whole multiples (to 1e-9 relative) of the unit cell's edges along x and y, at least 2 d (so
/// that each touching pair has one nearest copy), and no rotation; every ball of one period is
/// kept once, moved into the cell.
struct LatticeRegion {
    Container container = Box(10.0, 10.0);
    double height = 10.0;
};

/// \return the volume of a region (Container::prism_volume): LX LY H, pi D^2 H / 4,
/// pi (D^2 - DI^2) H / 4.
double region_volume(const LatticeRegion& region);

/// \return the region as --region writes it: the container's kind, its numbers and the height
/// ("box:10,10,10", "cylinder:8,6"), shortest round-trip numbers.
std::string region_text(const LatticeRegion& region);

/// Which balls fill a region.
enum class LatticeKeep {
    whole,   ///< only balls wholly inside the region (within 1e-9 d, so balls that touch a wall
             ///< exactly are kept)
    centres, ///< every ball whose centre is inside the region
};

/// The names users pick by ("whole", "centres"; `--keep`): the one registry.
const Registry<LatticeKeep>& lattice_keeps();

/// Everything `fill_lattice` needs. Plain value type; lengths in output units.
struct LatticeParameters {
    LatticeType type = LatticeType::diamond;
    double diameter = 1.0; ///< ball diameter d, 1e-12 to 1e12
    LatticeRegion region;
    /// Where the first ball of cell (0, 0, 0) lies (ball A of Table 1 for the diamond
    /// packing); by default d/2 from each wall at the low corner of a box or a periodic cell,
    /// on the axis d/2 above the floor of a cylinder or an annulus. At most 1e6 d from the region
    /// (limits::max_lattice_origin_offset): farther, the positions lose their precision.
    std::optional<Vec3> origin;
    LatticeKeep keep = LatticeKeep::whole;
    /// Rotations of the lattice about the origin, applied in this order: (axis 'x', 'y' or 'z',
    /// angle in degrees, counter-clockwise looking down the axis). Empty: the cell edges lie
    /// along x, y and z.
    std::vector<std::pair<char, double>> rotations;

    /// Check every value, and that the fill stays within its limits (limits.hpp: at most
    /// max_spheres balls and max_lattice_positions positions tried, an origin within
    /// max_lattice_origin_offset diameters of the region). \throws InvalidInput naming the
    /// parameter (the command line's option), its value and the range.
    void validate() const;
};

/// Fill the region with the lattice: every ball of every cell of the infinite lattice through
/// the origin, kept by `keep`, in the order cell layer (z), row (y), position (x), then the
/// cell's balls in unit_cell order. O(balls); the same output whatever the threads.
/// \throws InvalidInput for invalid parameters, a fill beyond its limits (see validate), or a
/// region that holds no ball
Packing fill_lattice(const LatticeParameters& parameters);

/// Contacts of a packing of equal balls of diameter d: pairs whose centres are d apart within
/// `tolerance` d. \return the number of contacts of each ball, and the smallest centre distance
/// over d (for "nobody closer than d").
struct LatticeContacts {
    std::vector<std::uint32_t> contacts; ///< per ball
    double closest = 0.0;                ///< smallest centre distance / d (inf for < 2 balls)
};
LatticeContacts lattice_contacts(const Packing& packing, double tolerance = 1e-9);
/// The same in a periodic cell: distances by the minimum image (Periodic::separation) and to
/// the copies one period either way (a cell exactly 2 d wide has a ball touch both copies of
/// its neighbour across it), the cell at least 2 d wide.
LatticeContacts lattice_contacts(const Packing& packing, const Periods& cell,
                                 double tolerance = 1e-9);

/// \return the region of `text`: a container's spec with the height after its numbers
/// (`box:LX,LY,LZ`, `cylinder:D,H`, `annulus:D,DI,H` (0 < DI < D) or `periodic:LX,LY,H`),
/// lengths in (0, limits::max_length].
/// \throws InvalidInput "--region '...' is not allowed; allowed: ..."
LatticeRegion parse_lattice_region(std::string_view text);

/// \return the origin of `text`, "x,y,z". \throws InvalidInput naming --origin
Vec3 parse_lattice_origin(std::string_view text);

/// \return the rotations of `text`, "AXIS:DEGREES" pairs separated by commas ("z:30,x:10"),
/// in order; none for "". \throws InvalidInput naming --rotate
std::vector<std::pair<char, double>> parse_rotations(std::string_view text);

/// The record of a lattice (`packbed lattice`): its parameters, the number of balls, the
/// lattice's exact porosity and coordination, the porosity measured in the region (the balls'
/// volume inside it over its volume, balls cut by the walls included: sphere_volume_in_box,
/// sphere_volume_in_cylinder_slab) and the contacts found (within 1e-9 d).
/// Lengths in output units.
nlohmann::json lattice_summary(const LatticeParameters& parameters, const Packing& packing);

} // namespace packbed
