// Surfaces of a bed for meshers (particle-resolved CFD): each sphere tessellated, the contacts
// treated so that no two bodies touch, the container as its own solids, and the exact change of
// void fraction each treatment makes. The treatments are those of the CFD literature
// (docs/surfaces.md).
#pragma once

#include <array>
#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "packbed/container.hpp"
#include "packbed/mesh.hpp"
#include "packbed/packing.hpp"
#include "packbed/particle_shape.hpp"
#include "packbed/registry.hpp"
#include "packbed/vec3.hpp"

namespace packbed {

/// The unit sphere as a subdivided icosahedron: `level` times each triangle split in four, new
/// vertices pushed onto the sphere; 20 * 4^level triangles, every vertex on the sphere (so the
/// polyhedron lies inside it). \param level 0 to 7
TriangleMesh icosphere(int level);

/// The edge of the unit icosphere of a level: the icosahedron's edge 1.0515 halved per level
/// (projecting onto the sphere lengthens the edges a little: a bound from below).
double icosphere_edge(int level);

/// The icosphere level whose mean edge on a sphere of radius `radius` is at most `edge`
/// (capped at 7). \param radius,edge lengths (> 0)
int icosphere_level_for_edge(double radius, double edge);

/// A half-space: the points x with dot(normal, x) <= offset are kept (normal of unit length).
struct HalfSpace {
    Vec3 normal;
    double offset = 0.0;
};

/// Cut a closed convex mesh by a half-space and close the cut with a flat face (fanned from
/// its centroid). Edges crossing the plane get one new vertex each, shared by the two
/// triangles: the result is closed and outward when the input is. Vertices within `snap` of
/// the plane are not cut near: those outside are moved onto it (along the normal, which for a
/// polyhedron inscribed in a ball keeps them in the ball), those inside stay, so that the cut
/// makes no sliver triangles; the cut face is then flat to within `snap`, never beyond the
/// plane. \param snap >= 0, a small fraction of the mesh's edge length
/// \return the kept part (empty when nothing is kept).
TriangleMesh clip_convex(const TriangleMesh& mesh, const HalfSpace& half_space, double snap = 0.0);

/// How contacts (and near contacts) are treated so that a mesher can resolve the gaps,
/// parameters in units of the sphere diameter Dp (docs/surfaces.md has the usual values).
enum class ContactTreatment {
    none,    ///< spheres as they are (touching at points: for viewing, not for meshing)
    shrink,  ///< every radius times (1 - F): gaps of F Dp at contacts, F Dp / 2 at the walls
    enlarge, ///< every radius times (1 + F), the union of the bodies; wall and floor contacts
             ///< capped F Dp from them
    caps,    ///< each pair closer than H Dp cut by two planes H Dp apart (a cap from each
             ///< sphere), each sphere closer than H Dp to the wall or floor cut by a plane
             ///< H Dp from it: flat faces with a gap of H Dp
    bridges, ///< a cylinder of diameter D Dp along the line of centres of each pair closer than
             ///< bridge_gap Dp, the union of spheres and bridges; wall and floor contacts capped
             ///< bridge_gap Dp from them
};

/// Pairs closer than this (Dp) get a bridge, and spheres closer than this to the wall or floor
/// a cap, under ContactTreatment::bridges.
constexpr double bridge_gap = 0.01;

/// A treatment and its parameter (F, H or D, fraction of Dp).
struct Contacts {
    ContactTreatment treatment = ContactTreatment::none;
    double parameter = 0.0;
};

/// The names users pick a treatment by ("none", "shrink", "enlarge", "caps", "bridges"): the
/// one registry.
const Registry<ContactTreatment>& contact_treatments();

/// Parse "none", "shrink:F", "enlarge:F", "caps:H" or "bridges:D" (parameter in (0, 0.5)).
/// \throws InvalidInput naming the text and what is allowed
Contacts parse_contacts(std::string_view text);

/// The container a surface is cut against: a cylinder or a box from the floor z = 0 to
/// `height`.
struct SurfaceContainer {
    Container container = Container::tube(2.0);
    double height = 1.0;
    /// A periodic cell that repeats along z too, with `height` as its period (export --flow
    /// periodic): its bottom and top are no floor and no lid but sides like the others, which a
    /// sphere may cross (its copy comes in across the other), and two spheres touch across
    /// them by the minimum image.
    bool periodic_z = false;

    /// \return the container's periods (Container::periods), along z too (`height`) with
    /// periodic_z; nothing for a container with walls.
    std::optional<Periods> periods() const {
        const std::optional<Periods> sides = container.periods();
        if (sides && periodic_z)
            return Periods(sides->lx(), sides->ly(), height);
        return sides;
    }
};

/// Where a sphere's polyhedron lies: `inscribed`, its vertices on the sphere (inside it, short
/// of its volume by 0.86 % at icosphere level 3, 0.054 % at 5); `volume`, scaled about the
/// centre to hold the sphere's volume (volume_facets_scale), its vertices a little outside;
/// `automatic`, volume where every gap leaves the facets room to grow, else inscribed
/// (facets_for).
enum class Facets { inscribed, volume, automatic };

/// The names users pick facets by ("inscribed", "volume", "auto"): the one registry.
const Registry<Facets>& facet_modes();

/// The factor that gives the icosphere of `level` the unit sphere's volume,
/// \f$s = (4 \pi / 3 / V_{level})^{1/3}\f$ (1.00289 at level 3, 1.00018 at level 5).
double volume_facets_scale(int level);

/// What bed_surface builds.
struct SurfaceOptions {
    int level = 3;                             ///< icosphere level of each sphere (see icosphere)
    Facets facets = Facets::inscribed;         ///< where its polyhedron lies
    std::optional<SurfaceContainer> container; ///< the container whose solids are written
    bool write_container = true; ///< add the container's solids ("wall", "bottom", "top")
};

/// Each sphere's body after the treatment, as exact geometry: the sphere (radius after
/// shrinking or enlarging) and the half-spaces that cut it (caps). Body i belongs to sphere i.
struct TreatedBody {
    Vec3 center;
    double radius = 0.0;
    std::vector<HalfSpace> cuts;
};

/// A bridge: the cylinder of `radius` along the segment between the centres of bodies `first`
/// and `second`.
struct Bridge {
    std::uint32_t first = 0, second = 0;
    double radius = 0.0;
};

/// A treated bed: the bodies, the bridges, and whether the surface is their union (enlarge,
/// bridges) or the bodies one by one (disjoint by construction).
struct TreatedBed {
    std::vector<TreatedBody> bodies;
    std::vector<Bridge> bridges;
    bool unite = false;
};

/// Apply a treatment. The reference diameter Dp is the packing's mean diameter.
/// \throws InvalidInput when the treated geometry would not be what the treatment promises,
/// naming the spheres and what is allowed: shrink leaving bodies overlapping (F Dp not above
/// the largest overlap); two caps, lenses or bridge ends of one sphere meeting (the parameter
/// too large); a bridge thinner than the lens of its overlapping pair; enlarge or bridges in a
/// periodic cell (there, pairs are found by the minimum image and the centres moved into the
/// cell); a periodic cell narrower than twice the largest diameter
TreatedBed treat_contacts(const Packing& packing, const Contacts& contacts,
                          const std::optional<SurfaceContainer>& container);

/// Exact solid volumes and void fractions of a bed inside its container, before and after a
/// treatment. Untouched: sum of the spheres' volumes inside the container
/// (Container::sphere_volume: closed forms for a cylinder, converged quadrature where a box's
/// edge cuts a sphere) minus the lenses of
/// overlapping pairs; treated: the bodies (inside by construction) minus their caps,
/// \f$V_{cap} = \pi c^2 (3 r - c) / 3\f$, minus the lenses of overlapping bodies (enlarge,
/// bridges), plus each bridge's part outside its two spheres,
/// \f$\pi \rho^2 d - H(r_i) - H(r_j) + V_{lens}\f$ with H the part of a sphere within \f$\rho\f$
/// of the axis on the bridge's side of its centre (half_ball_in_cylinder). All closed forms.
struct TreatmentVolumes {
    double container_volume = 0.0; ///< cross-section x height (pi Rt^2 height, LX LY height)
    double untouched_solid = 0.0;  ///< solid volume of the bed as it is
    double treated_solid = 0.0;    ///< solid volume of the treated bodies
    double untouched_void_fraction = 0.0;
    double treated_void_fraction = 0.0;
};

/// \return the volumes for `bed` = treat_contacts(packing, ...) in `container`.
TreatmentVolumes treatment_volumes(const Packing& packing, const TreatedBed& bed,
                                   const SurfaceContainer& container);

/// Volume of the part of a ball (radius r) on one side of a plane through its centre and
/// within distance rho of the axis normal to that plane:
/// \f$\pi \rho^2 t + \pi (r^2 (r - t) - (r^3 - t^3) / 3)\f$, \f$t = \sqrt{r^2 - \rho^2}\f$
/// (the half ball when rho >= r).
double half_ball_in_cylinder(double radius, double rho);

/// Volume of the part of a ball of radius r beyond a plane at distance s from its centre (a
/// spherical cap of height c = r - s): \f$\pi c^2 (3 r - c) / 3\f$, 0 for s >= r.
double spherical_cap_volume(double radius, double distance);

/// Volume of the lens two balls share (radii r1, r2, centres d apart): 0 when they do not
/// overlap, the smaller ball when one holds the other.
double lens_volume(double r1, double r2, double distance);

/// A periodic cell's bed with the copies its surfaces need: every body whose sphere crosses a
/// side of the cell [0, LX] x [0, LY] is copied across it (shifted by +LX where it crosses
/// x = 0, -LX where it crosses x = LX, likewise in y, and by both at a corner), its cuts moved
/// with it, so that the bodies and copies cut by the cell are periodic. The bodies come first,
/// as given (their centres in the cell, as treat_contacts leaves them), then the copies.
/// \throws std::logic_error for bridges or a union (treat_contacts refuses them in a cell).
TreatedBed periodic_images(const TreatedBed& bed, const Periods& cell);

/// The surface: solid "particles" (every treated body tessellated: the icosphere scaled and
/// clipped by its cuts, vertices on the sphere, so each polyhedron lies inside its body, or
/// with Facets::volume a factor volume_facets_scale beyond it; each
/// bridge a prism inscribed in its cylinder; for a bed to unite, the union of all of them by
/// CGAL's corefinement), and
/// where the options ask for it the container as "wall" (a prism circumscribed about the
/// cylinder, so that no sphere inside the cylinder meets it; a box's four faces are "x_low",
/// "x_high", "y_low", "y_high" instead), "bottom" and "top" (Container::solids). In a periodic
/// cell the particles include the copies of periodic_images.
/// With Facets::automatic, the facets facets_for picks.
/// \throws InvalidInput when Facets::volume is asked for where volume_facets_conflict finds a
/// conflict
std::vector<Solid> bed_surface(const TreatedBed& bed, const SurfaceOptions& options);

/// Why facets grown to hold the volume (Facets::volume at icosphere `level`) would meet
/// something: two bodies not cut against each other (nor united) closer than their growth, or
/// a body not cut at the wall, floor or top closer to it than its own. The message names the
/// first such sphere and its gap; none where every gap leaves room.
std::optional<std::string> volume_facets_conflict(const TreatedBed& bed,
                                                  const std::optional<SurfaceContainer>& container,
                                                  int level);

/// The facets bed_surface lays for `options`: options.facets, and for Facets::automatic volume
/// where volume_facets_conflict finds no conflict, else inscribed.
Facets facets_for(const TreatedBed& bed, const SurfaceOptions& options);

/// Every particle of a bed of one shape class as one surface: its type's unit_surface(level)
/// scaled about its position by `scale` (1 - F for shrink:F, 1 as it is), turned and moved
/// (place_surface). Each polyhedron's vertices lie on its particle's surface (scaled), so a
/// convex particle's polyhedron lies inside it.
template <ParticleShape S>
TriangleMesh particle_surfaces(const ShapedBed<S>& bed, int level, double scale = 1.0) {
    std::vector<TriangleMesh> units;
    for (const S& shape : bed.shapes())
        units.push_back(shape.unit_surface(level));
    const Packing& particles = bed.particles();
    TriangleMesh all;
    for (std::size_t i = 0; i < bed.size(); ++i) {
        TriangleMesh mesh = units[particles.types.empty() ? 0 : particles.types[i]];
        Placement p = bed.placement(i);
        p.size *= scale;
        place_surface<S>(mesh, p);
        all.append(mesh);
    }
    return all;
}

/// The three formats.
enum class SurfaceFormat { stl_binary, stl_ascii, obj };

/// Write the solids to `path` (the caller provides the temporary name of an all-or-nothing
/// output). STL binary: one solid, the names in the 80-byte header; STL ASCII: `solid NAME`
/// per solid; OBJ: `g NAME` per solid, shared vertices. Numbers in single precision for STL
/// (the format's), shortest round-trip doubles for OBJ.
/// \throws std::runtime_error naming the file when writing fails
void write_surface(const std::vector<Solid>& solids, SurfaceFormat format,
                   const std::filesystem::path& path);

} // namespace packbed
