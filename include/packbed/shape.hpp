// What a container answers, the types of its answers: each shape (cylinder.hpp, box.hpp,
// annulus.hpp, periodic.hpp, cone.hpp) is a small class answering every question generation,
// analysis and export ask of a container (the ContainerShape concept and the class comments);
// `Container` (container.hpp) holds one and hands each question to it. voro++'s vocabulary:
// contains(), the overlap of a sphere with the wall and the wall normal. Every container has a
// rigid flat floor at z = 0 and an open top.
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <concepts>
#include <cstddef>
#include <functional>
#include <limits>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <utility>
#include <variant>
#include <vector>

#include <nlohmann/json_fwd.hpp>

#include "packbed/mesh.hpp"
#include "packbed/vec3.hpp"

namespace packbed {

/// How deep a sphere presses into a deformable wall and which way the wall pushes back.
struct WallContact {
    double overlap = 0.0; ///< penetration depth (length); <= 0 means no contact
    Vec3 push; ///< unit vector along which the wall pushes the sphere (into the container)
};

/// The rectangle [x_low, x_high] x [y_low, y_high] a container's cross-section lies in.
/// How a container's fit problem (Container::fit_problem) names sizes: a size of 1 is `scale`
/// of the text's unit, written after each number as `unit`, and the particle whose size is
/// checked is `particle`. Spheres': Dp and the largest sphere; a pellet's: the length units of
/// its --shape and its bounding sphere.
struct FitWords {
    double scale = 1.0;
    std::string_view unit = " Dp";
    std::string_view particle = "the largest sphere";
};

struct Rectangle {
    double x_low = 0.0;
    double x_high = 0.0;
    double y_low = 0.0;
    double y_high = 0.0;
};

/// A plane tangent to a container's lateral wall from inside: the points x with
/// dot(normal, x) <= offset are on the container's side of it (normal of unit length, pointing
/// out of the container; horizontal but for a cone's slanted wall).
struct WallPlane {
    Vec3 normal;
    double offset = 0.0;
};

/// The part of a line p + s u inside a container's side (its walls continued above and below:
/// neither the floor nor a top cuts it), as at most two intervals of s in increasing order
/// (two where an annulus' rod cuts the line); an end may be infinite (a vertical line inside a
/// tube, any line in a periodic cell). What the exact volumes of an oriented particle
/// integrate over (cylinder_shape.hpp).
struct Chord {
    struct Interval {
        double low = 0.0;
        double high = 0.0;
    };
    std::array<Interval, 2> parts{};
    std::size_t count = 0;

    /// The whole line.
    static Chord whole() {
        constexpr double inf = std::numeric_limits<double>::infinity();
        return {{{{-inf, inf}, {}}}, 1};
    }
    /// The interval [low, high], or nothing where it is empty.
    static Chord between(double low, double high) {
        if (!(low < high))
            return {};
        return {{{{low, high}, {}}}, 1};
    }
};

/// A convex body's support function: its point farthest along a direction v (not necessarily
/// unit). What a container asks of a particle to find how far it reaches into the walls.
using SupportFunction = std::function<Vec3(const Vec3&)>;

/// How far a convex body reaches beyond one wall (depth <= 0: it does not), the wall's push
/// (its inward unit normal there) and the body's point that reaches deepest.
struct ConvexWallContact {
    double depth = 0.0;
    Vec3 push;
    Vec3 point;
};
/// Called once per wall with its ConvexWallContact.
using ConvexWallFunction = std::function<void(const ConvexWallContact&)>;

/// Periodicity in x and y, a boundary of the cell [0, LX) x [0, LY) rather than a wall: a
/// sphere leaving one side comes back through the opposite one, and two spheres touch through
/// the sides by the minimum image (their nearest copies). What the searches, the solvers and
/// the exports ask of a periodic container (Container::periods). Along z too when LZ > 0 (a
/// random array, a cell the CFD case repeats along z: [0, LX) x [0, LY) x [0, LZ)); LZ = 0
/// leaves z alone, to the bit. Immutable.
class Periods {
public:
    /// \param lx,ly the periods (length, > 0) \param lz the period along z, 0 for none
    Periods(double lx, double ly, double lz = 0.0)
        : m_lx(lx)
        , m_ly(ly)
        , m_lz(lz) {}

    double lx() const { return m_lx; }
    double ly() const { return m_ly; }
    /// \return the period along z, 0 when z does not repeat.
    double lz() const { return m_lz; }

    /// \return p moved by whole periods into [0, LX) x [0, LY) (and [0, LZ) when z repeats).
    Vec3 wrapped(const Vec3& p) const {
        return {p.x - m_lx * std::floor(p.x / m_lx), p.y - m_ly * std::floor(p.y / m_ly),
                m_lz > 0.0 ? p.z - m_lz * std::floor(p.z / m_lz) : p.z};
    }
    /// \return the separation b - a between the nearest copies of a and b (minimum image),
    /// for |b - a| within one period and a half on each side: whole periods are taken off
    /// each of x and y (and z when it repeats) while it exceeds half a period.
    /// -separation(a, b) == separation(b, a) to the bit.
    Vec3 separation(const Vec3& a, const Vec3& b) const {
        Vec3 d = b - a;
        const double hx = 0.5 * m_lx, hy = 0.5 * m_ly;
        if (d.x > hx)
            d.x -= m_lx;
        else if (d.x < -hx)
            d.x += m_lx;
        if (d.y > hy)
            d.y -= m_ly;
        else if (d.y < -hy)
            d.y += m_ly;
        if (m_lz > 0.0) {
            if (d.z > 0.5 * m_lz)
                d.z -= m_lz;
            else if (d.z < -0.5 * m_lz)
                d.z += m_lz;
        }
        return d;
    }

private:
    double m_lx, m_ly, m_lz;
};

/// The hydraulic diameter 4 A / P of a container's cross-section (A its area, P its wetted
/// perimeter), with the formula in its spec's letters ("D - DI"); none for a container with
/// no wall, `formula` then says why ("is a periodic cell, it has no wall").
struct HydraulicDiameter {
    std::optional<double> value;
    std::string_view formula;
};

/// The length whose hundredth is the least margin of a data file's box beyond the container's
/// side (io.hpp's container_box_margin: max(Dp / 2, length / 100)), how the box's note words
/// that hundredth ("Rt/100") and names the container ("radius 5", or the spec); a length of 0
/// where the box is the container itself (a periodic cell).
struct BoxMargin {
    double length = 0.0;
    std::string_view words;
    std::string container;
};

/// A container's side as the LAMMPS engine's input writes it (docs/lammps.md): the x and y
/// boundary ("f f", or "p p" for a periodic cell), the data file's box in x and y (the side
/// and a margin of twice the set-back), the regions and harmonic wall fixes of each size
/// (type t + 1 of diameter diameters[t], each wall set back by `setback` and reaching the
/// radius and the set-back) and atom-style formulas of each wall's overlap (v_r the radius).
struct LammpsSide {
    std::string boundary = "f f";
    Rectangle box;
    std::string walls;
    std::vector<std::string> overlaps;
};

/// What an export's DEM settle inputs (LAMMPS and LIGGGHTS, docs/dem.md) say of the
/// container's side: the words of their head, the LAMMPS regions and wall fixes, the side's STL.
struct DemSettleWall {
    std::string words;        // the head's "the container is the ..., and the data file's box
                              // holds it" (two comment lines)
    std::string lammps;       // LAMMPS: the comment, the region(s) and the fix(es) of the side
    std::string liggghts_stl; // LIGGGHTS: what the side's STL is ("": none, periodic)
    std::string boundary = "f f f";
};

/// Mesh resolution, tied to the mean particle diameter Dp.
struct OpenFoamMeshOptions {
    int cells_per_diameter = 4; ///< background (blockMesh) cells per Dp, >= 1
    int particle_level = 2;     ///< snappyHexMesh refinement level at the particles, 0 to 8
    int wall_level = 1;         ///< ... at a cylinder's wall, 0 to 8 (a box's is not refined)
    /// snappyHexMesh's prism layers (nSurfaceLayers) on the particles and on a cut wall or
    /// rod, 0 (none) to 10: the cells against the walls, which carry the drag, made thin
    int layers = 0;
    /// A periodic cell's bottom and top a cyclic pair too (export --flow periodic): the cell
    /// repeats along z with the container's height as its period. Other containers refuse it.
    bool periodic_z = false;
};

/// The background mesh of an OpenFOAM case (export --format openfoam, docs/surfaces.md) about
/// a container and what the case's README says of it.
struct OpenFoamBackground {
    std::string block_mesh;     // blockMeshDict after its header
    bool wall_surface = false;  // the wall is cut out of the background by snappyHexMesh
    bool rod_surface = false;   // an annulus' rod too (rod.stl, patch rod)
    std::string where;          // README: "a cylinder of radius R"
    std::string surfaces;       // README: the wall's surface, after particles.stl's line
    std::string patches;        // README: after the patches' list
    std::string cells;          // README: the background cells and the levels
    int boundary_skewness = 20; // snappyHexMesh's maxBoundarySkewness
};

/// Where a lattice's kept centres lie in the cross-section (lattice.hpp's fill): the
/// rectangle, and for a round container the largest and smallest squared distance from the
/// axis (none: -1); where these only bound them (a cone, whose cross-section changes with
/// height), `by_distance`: a centre is kept where its distance from the wall is at least the
/// margin.
struct FillWindow {
    Rectangle box;
    double reach2 = -1.0;
    double inner2 = -1.0;
    bool by_distance = false;
};

/// The answers every shape gives beyond the questions above, declared once (`Container`
/// documents each, and each shape's source file defines them) so that the shapes' headers do
/// not repeat the list: the SPEC's numbers read (`from_numbers`: the shape, or nothing when the
/// numbers are not one) and given back (`spec_numbers`), read back from summary.json
/// (`from_record`: the shape's summary_json or region_json, nothing when its lengths are not
/// one; `record_allowed`: what they must be), what --container and --region allow,
/// scaling, and what generation, analysis and export ask. `S` is the shape's class.
#define PACKBED_SHAPE_ANSWERS(S)                                                                   \
    static std::optional<S> from_numbers(std::span<const double> numbers);                         \
    static std::optional<S> from_record(const nlohmann::json& record);                             \
    static std::string record_allowed();                                                           \
    static std::string allowed();                                                                  \
    static std::string region_allowed();                                                           \
    std::vector<double> spec_numbers() const;                                                      \
    S scaled(double factor) const;                                                                 \
    std::optional<double> tube_diameter() const;                                                   \
    std::optional<Periods> periods() const;                                                        \
    HydraulicDiameter hydraulic_diameter() const;                                                  \
    BoxMargin box_margin() const;                                                                  \
    std::string fit_problem(double largest, const FitWords& words = {}) const;                     \
    double fill_height(double solid, double e0) const;                                             \
    Vec3 uniform_point(double radius, double u, double v, double z) const;                         \
    std::optional<double> top() const;                                                             \
    std::vector<std::pair<double, double>> search_lines() const;                                   \
    nlohmann::json summary_json() const;                                                           \
    nlohmann::ordered_json export_json(double height) const;                                       \
    LammpsSide lammps_side(std::span<const double> diameters, double setback) const;               \
    std::vector<Solid> solids(double z_low, double z_high, double edge) const;                     \
    DemSettleWall settle_wall(double height, std::string_view contact) const;                      \
    OpenFoamBackground openfoam_background(double height, double cell,                             \
                                           const OpenFoamMeshOptions& options) const;              \
    double prism_volume(double height) const;                                                      \
    nlohmann::json region_json(double height) const;                                               \
    FillWindow fill_window(double margin, double height) const;                                    \
    Chord side_chord(const Vec3& p, const Vec3& u) const;                                          \
    void convex_wall_contacts(const SupportFunction& support, const Vec3& centre,                  \
                              const ConvexWallFunction& f) const

/// The answers at a height of a prism (a cross-section the same at every height): its area,
/// the area between two distances from the wall and its depth, over the heights z_low to
/// z_high as everywhere (a cone's change with height, cone.hpp).
#define PACKBED_PRISM_HEIGHTS                                                                      \
    double cross_section_area(double, double) const {                                              \
        return cross_section_area();                                                               \
    }                                                                                              \
    double shell_area(double d_low, double d_high, double, double) const {                         \
        return shell_area(d_low, d_high);                                                          \
    }                                                                                              \
    double depth(double, double) const {                                                           \
        return depth();                                                                            \
    }

/// What every shape of `Container` answers (a part of it: the rest is in the class comments).
/// The wall law calls back f(overlap, push) once per wall a sphere presses into.
template <class C>
concept ContainerShape = requires(const C& c, const Vec3& p, double radius) {
    c.wall_contacts(p, radius, [](double, const Vec3&) {});
    { c.contains(p) } -> std::same_as<bool>;
    { c.wall_distance(p) } -> std::same_as<double>;
    { c.sphere_volume(p, radius, 0.0, 1.0) } -> std::same_as<double>;
    { c.cross_section_area(0.0, 1.0) } -> std::same_as<double>;
    { c.shell_area(0.0, 1.0, 0.0, 1.0) } -> std::same_as<double>;
    { c.depth(0.0, 1.0) } -> std::same_as<double>;
    { c.spec() } -> std::same_as<std::string>;
    { C::kind } -> std::convertible_to<std::string_view>;
    { C::form } -> std::convertible_to<std::string_view>;
    { C::hydraulic_formula } -> std::convertible_to<std::string_view>;
    { C::allowed() } -> std::same_as<std::string>;
    { c.scaled(1.0) } -> std::same_as<C>;
};

/// The per-wall questions of the analysis (Container::profile_walls) for a shape whose
/// profiles are measured from one wall, "wall": its nearest-wall questions as they are (a box's
/// four faces count as one wall, the nearest; a corner counts with the nearer face).
template <class Shape> class OneProfileWall {
public:
    std::span<const std::string_view> profile_walls() const { return one_wall; }
    double wall_distance_from(std::size_t, const Vec3& p) const { return self().wall_distance(p); }
    std::pair<double, double> wall_distances_from(std::size_t, const Vec3& c, double r) const {
        return self().wall_distances(c, r);
    }
    Shape shrunk_from(std::size_t, double d) const { return self().shrunk(d); }
    double shell_area_from(std::size_t, double d_low, double d_high, double z_low,
                           double z_high) const {
        return self().shell_area(d_low, d_high, z_low, z_high);
    }
    std::size_t nearest_wall(const Vec3&) const { return 0; }
    std::string_view profile_position_name_from(std::size_t) const {
        return self().profile_position_name();
    }
    double profile_position_from(std::size_t, double d) const { return self().profile_position(d); }

private:
    static constexpr std::array<std::string_view, 1> one_wall{"wall"};
    const Shape& self() const { return static_cast<const Shape&>(*this); }
};

} // namespace packbed
