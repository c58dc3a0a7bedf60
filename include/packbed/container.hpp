// Containers: the walls a bed is packed against. `Container` is the one place the rest of the
// library asks about a container; it holds one shape (cylinder.hpp, box.hpp, annulus.hpp,
// periodic.hpp, cone.hpp: shape.hpp says what each answers) and hands every question to it, one
// std::visit each, so that the compiler lists what a new shape must answer.
#pragma once

#include <cstddef>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <utility>
#include <variant>
#include <vector>

#include <nlohmann/json_fwd.hpp>

#include "packbed/annulus.hpp"
#include "packbed/box.hpp"
#include "packbed/cone.hpp"
#include "packbed/cylinder.hpp"
#include "packbed/periodic.hpp"
#include "packbed/shape.hpp"
#include "packbed/vec3.hpp"

namespace packbed {

/// A container of any shape: what generation, analysis and export ask. Each shape converts to
/// it implicitly. Every question goes to the shape (one std::visit each, in container.cpp, with
/// no catch-all: a new shape that misses an answer does not compile). Plain value type.
class Container {
public:
    /// Every shape, in the order --help lists them: the one line that registers a shape.
    using Shape = std::variant<Cylinder, Box, Annulus, Periodic, Cone>;

    template <class S>
    requires ContainerShape<S>
    Container(const S& shape) // NOLINT(google-explicit-constructor): a cylinder is a container
        : m_shape(shape) {}

    /// The front ends' shorthand of a tube (--aspect-ratio a in units of Dp,
    /// --container-radius R): the cylinder of inner diameter `diameter` about the z axis.
    static Container tube(double diameter);
    /// The same tube by its radius (--container-radius R: every radius, however large).
    static Container tube_of_radius(double radius);

    /// The shape itself, for the container's own files and for tests.
    const Shape& shape() const { return m_shape; }

    /// The shape's kind: "cylinder", "box", "annulus", "periodic" or "cone".
    std::string_view name() const;
    /// The --container form: "cylinder:D", "box:LX,LY", "annulus:D,DI", "periodic:LX,LY",
    /// "cone:DB,DT,H".
    std::string spec() const;
    /// The same with each length the shortest text that reads back as the same double:
    /// parse_container(exact_spec()) is this container (spec() rounds to 9 significant digits,
    /// for messages and titles).
    std::string exact_spec() const;
    /// How a message names it ("a cylinder of radius 10", "a box (box:6,6)", the spec).
    std::string describe() const;

    /// The wall law of every wall: f(overlap, push) for each wall the sphere (p, radius)
    /// presses into (none in a periodic cell).
    /// The first shape (the paper's cylinder) is asked without the visit, inlined: this is the
    /// solvers' innermost call (docs/notes/iteration-kernels.md, "The wall term").
    template <class F>
    [[gnu::always_inline]] void wall_contacts(const Vec3& p, double radius, F&& f) const {
        if (const auto* first = std::get_if<0>(&m_shape)) [[likely]]
            first->wall_contacts(p, radius, f);
        else
            other_wall_contacts(p, radius, f);
    }
    /// \return the largest overlap of the sphere (p, radius) with a wall, 0 when it touches none.
    double wall_overlap(const Vec3& p, double radius) const {
        double largest = 0.0;
        wall_contacts(p, radius, [&](double o, const Vec3&) { largest = std::max(largest, o); });
        return largest;
    }
    /// \return the same container with every length times `factor` (> 0).
    Container scaled(double factor) const;

    bool contains(const Vec3& p) const;
    /// Distance of p from the nearest lateral wall (negative outside): the coordinate of the
    /// wall profiles.
    double wall_distance(const Vec3& p) const;
    /// Nearest and farthest distance from the wall of the points of a sphere.
    std::pair<double, double> wall_distances(const Vec3& c, double r) const;
    /// The largest distance from the wall inside at the heights from z_low to z_high.
    double depth(double z_low, double z_high) const;
    /// The wall within `gap` of the sphere (c, r) as tangent planes (the cylinder's at the
    /// nearest point, each box face that near): where the contact treatments cut.
    std::vector<WallPlane> walls_within(const Vec3& c, double r, double gap) const;
    /// The area of the cross-section, its mean over the heights from z_low to z_high (the
    /// same at every height but in a cone; at z_low when z_high <= z_low).
    double cross_section_area(double z_low, double z_high) const;
    /// Area of the cross-section between two distances from the wall, its mean over the
    /// heights from z_low to z_high.
    double shell_area(double d_low, double d_high, double z_low, double z_high) const;
    /// The points at least d from the wall, as a container of the same shape.
    Container shrunk(double d) const;
    /// Exact volume of a sphere inside the container between two heights.
    double sphere_volume(const Vec3& c, double r, double z_low, double z_high) const;
    /// The same, by the faster routine where there is one (g(r); agrees to 3e-9 relative).
    double ball_volume(const Vec3& c, double r, double z_low, double z_high) const;
    /// The rectangle the cross-section lies in.
    Rectangle bounds() const;

    /// The first column of the wall profiles' tables: "radial_position" (the distance from
    /// the axis, Rt - d) for a cylinder, "wall_distance" (d) for a box.
    std::string_view profile_position_name() const;
    /// The position written in that column for the distance d from the wall.
    double profile_position(double d) const;

    /// The walls the wall profiles, centre distributions and wall contacts are measured from,
    /// each by name: {"wall"} for a cylinder and for a box (its four faces together: the
    /// distance from the nearest face), {"outer", "inner"} for an annulus (the tube and the
    /// rod, each to the middle of the gap), none for a periodic cell. A wall is named below by
    /// its index in this list.
    std::span<const std::string_view> profile_walls() const;
    /// \return the distance of p from wall `wall` (negative beyond it); for a container of
    /// one wall, wall_distance(p).
    double wall_distance_from(std::size_t wall, const Vec3& p) const;
    /// \return the nearest and farthest distance from wall `wall` of the points of the sphere
    /// (c, r); for a container of one wall, wall_distances(c, r).
    std::pair<double, double> wall_distances_from(std::size_t wall, const Vec3& c, double r) const;
    /// \return the points at least d from wall `wall` within that wall's part of the
    /// cross-section (up to the depth); for a container of one wall, shrunk(d).
    Container shrunk_from(std::size_t wall, double d) const;
    /// \return the area between the distances d_low <= d_high from wall `wall`, its mean over
    /// the heights from z_low to z_high; for a container of one wall, shell_area.
    double shell_area_from(std::size_t wall, double d_low, double d_high, double z_low,
                           double z_high) const;
    /// \return the wall whose part of the cross-section holds p (the nearer wall; the first
    /// on a tie).
    std::size_t nearest_wall(const Vec3& p) const;
    /// The first column of wall `wall`'s profile tables and its value at d from that wall.
    std::string_view profile_position_name_from(std::size_t wall) const;
    double profile_position_from(std::size_t wall, double d) const;
    /// \return how far the sphere (c, r) sticks out of the container sideways (<= 0: not at
    /// all): beyond the nearest wall (the cylinder, a box face, the tube or the rod), or, in a
    /// periodic cell, how far its centre lies outside [0, LX] x [0, LY].
    double sticks_out(const Vec3& c, double r) const;

    /// The diameter D of a tube, where the published correlations for tubes apply as written
    /// at the aspect ratio a = D / Dp (the paper's eq. (6), Dixon's and de Klerk's void
    /// fractions, the radial profiles, the wall correction of pressure drops); nothing for
    /// another shape, which a front end then names by its spec.
    std::optional<double> tube_diameter() const;
    /// The periods of a container periodic in x and y (a boundary, not a wall: pairs by the
    /// minimum image, centres wrapped into the cell); nothing for one with side walls.
    std::optional<Periods> periods() const;
    /// The hydraulic diameter 4 A / P and its formula (none without a wall).
    HydraulicDiameter hydraulic_diameter() const;
    /// The length that sets a data file's box margin beyond the side, and its words.
    BoxMargin box_margin() const;
    /// Why a bed of spheres of diameter up to `largest` (lengths in Dp) cannot be packed in
    /// the container, empty if it can: a tube or a box at least one sphere wide each way, a
    /// periodic cell two (the minimum image), an annulus whose gap (D - DI) / 2 holds one
    /// sphere; no width above 10^4 Dp. The answer is what is allowed, for a message naming
    /// the container.
    std::string fit_problem(double largest, const FitWords& words = {}) const;
    /// The height of a bed of spheres whose diameters cubed (in Dp) add to `solid`, at void
    /// fraction e0: (pi / 6) solid / (A (1 - e0)); the paper's eq. (6) for a tube.
    double fill_height(double solid, double e0) const;
    /// A point at height z uniform over the part of the cross-section there that a centre of
    /// radius `radius` reaches, from two uniform numbers u, v in [0, 1).
    Vec3 uniform_point(double radius, double u, double v, double z) const;
    /// The height where the container ends (a cone's H: a bed must stay below it); nothing
    /// for a prism, open at the top.
    std::optional<double> top() const;
    /// Eight vertical lines (x, y) inside the container, off its symmetries, along which to
    /// search for a point of the fluid far from every surface (the OpenFOAM case's
    /// locationInMesh).
    std::vector<std::pair<double, double>> search_lines() const;
    /// The axis of a container of revolution in summary.json's words ("z through x = y = 0"),
    /// empty for a prism.
    std::string_view axis() const;
    /// The container in summary.json: its shape, its lengths and spec.
    nlohmann::json summary_json() const;
    /// The container in an export's packbed.json: its shape, lengths and `height`.
    nlohmann::ordered_json export_json(double height) const;
    /// The side's walls in the LAMMPS engine's input, one fix per size.
    LammpsSide lammps_side(std::span<const double> diameters, double setback) const;
    /// The container between z_low and z_high as closed, outward solids of triangles about
    /// `edge` (> 0) wide: "wall" (a cylinder's or an annulus' tube: a prism circumscribed
    /// about it, so that no sphere inside meets it; an annulus adds "rod", a prism inscribed
    /// in the rod; a box's four faces are "x_low", "x_high", "y_low", "y_high" instead, each a
    /// grid of ceil(length / edge) cells, at most 4096, rims shared so the STL is watertight),
    /// "bottom" and "top"; a periodic cell only "bottom" and "top".
    std::vector<Solid> solids(double z_low, double z_high, double edge) const;
    /// \return true when the shape is one its spec allows (from_numbers of its numbers).
    bool well_formed() const;
    /// The numbers of the spec, in order (a cylinder's D; a box's LX, LY).
    std::vector<double> spec_numbers() const;
    /// The volume from the floor up to `height`.
    double prism_volume(double height) const;
    /// A lattice region of the container up to `height` in summary.json.
    nlohmann::json region_json(double height) const;
    /// What a lattice region of this shape allows (--region's refusal).
    std::string region_allowed() const;
    /// Where the centres at least `margin` inside the side lie, from the floor up to
    /// `height` (a lattice's fill).
    FillWindow fill_window(double margin, double height) const;
    /// The part of the line p + s u inside the side walls (their continuation above and below
    /// included; the floor does not cut it), at most two intervals of s (shape.hpp's Chord):
    /// what an oriented particle's exact volumes integrate over.
    Chord side_chord(const Vec3& p, const Vec3& u) const;
    /// f(contact) for each side wall the convex body of support function `support` reaches
    /// beyond (shape.hpp's ConvexWallContact: depth > 0, measured as a sphere's wall overlap
    /// is, along the wall's normal; the push; the deepest point). `centre` is a point of the
    /// body and `reach` the radius about it that holds the body: a body whose sphere (centre,
    /// reach) touches no wall is answered without a support call. A wall seen from inside (a
    /// tube, a box face, a cone) is asked for the body's farthest point: the maximum over the
    /// directions around the axis of the support function (a scan of 64 directions refined by
    /// golden-section search to 1e-12 rad); an annulus' rod, convex towards the body, for the
    /// least horizontal shift that clears it (the same search, on the body's projection).
    void convex_wall_contacts(const SupportFunction& support, const Vec3& centre, double reach,
                              const ConvexWallFunction& f) const;
    /// \return the deepest of convex_wall_contacts, 0 when it touches no wall.
    double convex_wall_overlap(const SupportFunction& support, const Vec3& centre,
                               double reach) const;
    /// The side in an export's DEM settle inputs, `contact` the LAMMPS wall's contact model.
    DemSettleWall settle_wall(double height, std::string_view contact) const;
    /// The background mesh of an OpenFOAM case in the container up to `height`, cells of
    /// `cell`: a box one cell beyond a tube sideways (snappyHexMesh cuts the wall out of it),
    /// or the box or cell itself with its sides as patches.
    OpenFoamBackground openfoam_background(double height, double cell,
                                           const OpenFoamMeshOptions& options) const;

private:
    /// wall_contacts of the shapes after the first, out of the solvers' loops.
    template <class F>
    [[gnu::noinline]] void other_wall_contacts(const Vec3& p, double radius, F& f) const {
        std::visit([&](const auto& s) { s.wall_contacts(p, radius, f); }, m_shape);
    }

    Shape m_shape;
};

/// \return the container of `text`, a container as users write it, in length units, the one
/// form every front end takes: "KIND:NUMBERS" with KIND a shape's `kind` and NUMBERS what its
/// `from_numbers` takes (`cylinder:D`, a tube of inner diameter D about the z axis; `box:LX,LY`,
/// four flat walls at x = 0, LX and y = 0, LY; `annulus:D,DI`, the space between the tube of
/// diameter D and a coaxial rod of diameter DI < D; `periodic:LX,LY`, a cell periodic in x and
/// y; `cone:DB,DT,H`, a frustum of floor diameter DB and diameter DT at z = H; every length in
/// (0, limits::max_length], diameters up to twice that), or nothing when it is not one.
std::optional<Container> parse_container(std::string_view text);

/// A container as summary.json records it (its `container`, or a lattice's `region`) read
/// back: the shape `record.shape` names reads its own lengths (from_record); a record with a
/// radius and no shape is a cylinder. When it is not one, `container` is empty and `allowed`
/// says what it must be.
struct ContainerRecord {
    std::optional<Container> container;
    std::string allowed;
};
ContainerRecord container_from_record(const nlohmann::json& record);

/// What --container allows, as both front ends word it (the command line's validator and
/// --help, the library's InvalidInput, so the Python module's ValueError): each of `shapes`
/// (kinds as all_shapes below has them) as its SPEC,
/// what it is and its ranges, joined by "; or ".
std::string allowed_containers(std::span<const std::string_view> shapes);
/// The message for a --container SPEC that parse_container refuses, the command line's words:
/// "--container: 'SPEC' is not allowed; allowed: " and allowed_containers of every shape.
std::string container_not_allowed(std::string_view option, std::string_view spec);

/// "radius R" for a cylinder, its spec (box:LX,LY, ...) for the others: a container in messages.
std::string describe(const Container& container);

namespace detail {
template <class... S> std::vector<std::string_view> kinds_of(const std::variant<S...>*) {
    return {S::kind...};
}
template <class... S> std::vector<std::string_view> forms_of(const std::variant<S...>*) {
    return {S::form...};
}
template <class... S>
std::vector<std::pair<std::string_view, std::string_view>>
hydraulic_formulas_of(const std::variant<S...>*) {
    return {{S::kind, S::hydraulic_formula}...};
}
} // namespace detail

/// The shapes parse_container takes, by kind, in Container::Shape's order.
inline const std::vector<std::string_view> all_shapes =
    detail::kinds_of(static_cast<const Container::Shape*>(nullptr));
/// Their SPECs in letters ("cylinder:D", "box:LX,LY", ...), in the same order.
inline const std::vector<std::string_view> all_forms =
    detail::forms_of(static_cast<const Container::Shape*>(nullptr));

/// The shapes' hydraulic diameters in words: "cylinder D, box 2 LX LY / (LX + LY), annulus D -
/// DI; none in periodic, cone" (each shape's hydraulic_formula).
std::string hydraulic_formulas();
/// The forms of all_forms but `kind`'s, joined by ", " and " or ".
std::string forms_but(std::string_view kind);

} // namespace packbed
