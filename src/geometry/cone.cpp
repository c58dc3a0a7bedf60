#include "packbed/cone.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <numbers>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "geometry/around_axis.hpp"
#include "geometry/shape_text.hpp"
#include "geometry/volume_pieces.hpp"
#include "packbed/limits.hpp"
#include "packbed/volume.hpp"

namespace packbed {

/// The wall's angle theta from the vertical from the slant height L = hypot(H, Rt - Rb):
/// cos theta = H / L, sin theta = (Rt - Rb) / L (exactly 1 and 0 when Rb = Rt).
Cone::Cone(double floor_radius, double top_radius, double height)
    : Cone(floor_radius, top_radius, height, (top_radius - floor_radius) / height,
           height / std::hypot(height, top_radius - floor_radius),
           (top_radius - floor_radius) / std::hypot(height, top_radius - floor_radius)) {}

Cone::Cone(double floor_radius, double top_radius, double height, double slope, double cos_theta,
           double sin_theta)
    : m_rb(floor_radius)
    , m_rt(top_radius)
    , m_h(height)
    , m_slope(slope)
    , m_cos(cos_theta)
    , m_sin(sin_theta)
    , m_inv_cos(1.0 / cos_theta)
    , m_reach(std::max(floor_radius, top_radius)) {}

std::vector<WallPlane> Cone::walls_within(const Vec3& c, double r, double gap) const {
    const double rho = std::hypot(c.x, c.y);
    if (wall_distance(c) - r < gap && rho > 0.0)
        return {WallPlane{{m_cos * c.x / rho, m_cos * c.y / rho, -m_sin}, m_cos * m_rb}};
    return {};
}

double Cone::cross_section_area(double z_low, double z_high) const {
    if (!(z_high > z_low)) {
        const double r = std::max(radius_at(z_low), 0.0);
        return std::numbers::pi * r * r;
    }
    return frustum_volume(m_rb, m_slope, z_low, z_high) / (z_high - z_low);
}

double Cone::shell_area(double d_low, double d_high, double z_low, double z_high) const {
    return shrunk(d_low).cross_section_area(z_low, z_high) -
           shrunk(d_high).cross_section_area(z_low, z_high);
}

/// The wall moved d along its normal: every radius d / cos theta smaller, the same slope.
Cone Cone::shrunk(double d) const {
    const double in = d / m_cos;
    return Cone(m_rb - in, m_rt - in, m_h, m_slope, m_cos, m_sin);
}

double Cone::sphere_volume(const Vec3& c, double r, double z_low, double z_high) const {
    return r > 0.0 ? sphere_volume_in_cone_slab(c, r, m_rb, m_slope, z_low, z_high) : 0.0;
}

std::string Cone::spec(bool /*exact*/) const {
    return fmt::format("cone:{},{},{}", 2.0 * m_rb, 2.0 * m_rt, m_h);
}

std::string Cone::describe() const {
    return fmt::format("a cone ({})", spec());
}

std::optional<double> Cone::tube_diameter() const {
    return std::nullopt;
}

std::optional<Periods> Cone::periods() const {
    return std::nullopt;
}

HydraulicDiameter Cone::hydraulic_diameter() const {
    return {std::nullopt, "is a cone, its cross-section changes with height"};
}

BoxMargin Cone::box_margin() const {
    return {m_reach, "a hundredth of its widest radius", spec()};
}

std::string Cone::fit_problem(double largest, const FitWords& words) const {
    const double low = 2.0 * std::min(m_rb, m_rt), high = 2.0 * m_reach;
    if (!(low >= largest && high <= detail::widest))
        return fmt::format("floor and top diameters from {:.6g}{} ({}) to {:g}{}",
                           largest * words.scale, words.unit, words.particle,
                           detail::widest * words.scale, words.unit);
    return {};
}

/// The height L where the frustum holds (pi / 6) solid / (1 - e0): the paper's eq. (6) when
/// Rb = Rt (to the bit), else the root of V(L) = pi L (Rb^2 + Rb R(L) + R(L)^2) / 3 by
/// bisection (V grows with L up to the apex; +infinity when even the cone up to its apex
/// holds less).
double Cone::fill_height(double solid, double e0) const {
    if (m_slope == 0.0) {
        const double a = 2.0 * m_rb;
        return 2.0 / 3.0 * solid / (a * a * (1.0 - e0));
    }
    const double volume = std::numbers::pi / 6.0 * solid / (1.0 - e0);
    double low = 0.0;
    double high = m_slope > 0.0 ? volume / (std::numbers::pi * m_rb * m_rb) : -m_rb / m_slope;
    if (frustum_volume(m_rb, m_slope, 0.0, high) < volume)
        return std::numeric_limits<double>::infinity();
    for (int k = 0; k < 200 && high - low > 1e-12 * high; ++k) {
        const double mid = 0.5 * (low + high);
        (frustum_volume(m_rb, m_slope, 0.0, mid) < volume ? low : high) = mid;
    }
    return high;
}

/// Section 3.1 of the paper over the disk at height z that a centre reaches: r = (R(z) - r_i /
/// cos theta) u^(1/2), theta = 2 pi v.
Vec3 Cone::uniform_point(double radius, double u, double v, double z) const {
    return detail::disk_point(std::max(radius_at(z) - radius / m_cos, 0.0), u, v, z);
}

std::optional<double> Cone::top() const {
    return m_h;
}

/// In the square of the narrower end: inside the cone at every height from the floor to H.
std::vector<std::pair<double, double>> Cone::search_lines() const {
    const double r = std::min(m_rb, m_rt);
    return detail::lines_in({-r, r, -r, r});
}

nlohmann::json Cone::summary_json() const {
    return {{"shape", "cone"},
            {"floor_diameter", 2.0 * m_rb},
            {"top_diameter", 2.0 * m_rt},
            {"cone_height", m_h},
            {"spec", spec()}};
}

nlohmann::ordered_json Cone::export_json(double height) const {
    return {{"shape", "cone"},
            {"floor_diameter", 2.0 * m_rb},
            {"top_diameter", 2.0 * m_rt},
            {"cone_height", m_h},
            {"height", height}};
}

/// A cone region (LAMMPS `region cone`, its ends open) set back beyond the wall along its
/// normal (every radius setback / cos theta larger), from 2 set-backs below the floor to
/// twice H (or the set-back cone's apex, for a cone that narrows): LAMMPS stops a run where a
/// sphere leaves the region, so it reaches beyond every sphere. The overlap of a sphere of
/// radius v_r: v_r + cos theta (rho - R(z)).
LammpsSide Cone::lammps_side(std::span<const double> diameters, double setback) const {
    const double m = 2.0 * setback, out = setback / m_cos;
    const double lo = -m;
    const double hi = m_slope < 0.0 ? std::min(2.0 * m_h, -(m_rb + out) / m_slope) : 2.0 * m_h;
    const double r_lo = m_rb + out + m_slope * lo, r_hi = std::max(m_rb + out + m_slope * hi, 0.0);
    LammpsSide s;
    const double r = m_reach + out + m;
    s.box = {-r, r, -r, r};
    s.walls = fmt::format("region tube cone z 0 0 {} {} {} {} side in open 1 open 2 units box\n",
                          detail::num(r_lo), detail::num(r_hi), detail::num(lo), detail::num(hi));
    s.walls += detail::per_type(diameters, setback, [](std::size_t t, double reach) {
        return fmt::format("fix side{0} size{0} wall/region tube harmonic 0.5 1.0 {1}\n"
                           "fix_modify side{0} energy yes\n",
                           t, detail::num(reach));
    });
    s.overlaps.push_back(fmt::format("v_r+{}*(sqrt(x*x+y*y)-({}+({})*z))", detail::num(m_cos),
                                     detail::num(m_rb), detail::num(m_slope)));
    return s;
}

/// DB and DT in (0, 2 max_length], H in (0, max_length].
std::optional<Cone> Cone::from_numbers(std::span<const double> v) {
    if (v.size() != 3 || !detail::lengths_in(v.first(2), 2.0 * limits::max_length) ||
        !detail::lengths_in(v.last(1), limits::max_length))
        return std::nullopt;
    return Cone(0.5 * v[0], 0.5 * v[1], v[2]);
}

/// {floor_diameter, top_diameter, cone_height} (summary.json and a lattice's region), as
/// from_numbers takes them.
std::optional<Cone> Cone::from_record(const nlohmann::json& record) {
    const std::array<double, 3> numbers{detail::record_number(record, "floor_diameter"),
                                        detail::record_number(record, "top_diameter"),
                                        detail::record_number(record, "cone_height")};
    return from_numbers(numbers);
}

std::string Cone::record_allowed() {
    return "floor_diameter, top_diameter and cone_height as " + allowed();
}

std::string Cone::allowed() {
    return fmt::format("cone:DB,DT,H, a frustum of floor diameter DB at z = 0 and diameter DT at "
                       "z = H, DB and DT in (0, {:g}], H in (0, {:g}]",
                       2.0 * limits::max_length, limits::max_length);
}

Cone Cone::scaled(double factor) const {
    return Cone(m_rb * factor, m_rt * factor, m_h * factor);
}

/// The wall: a prism circumscribed about the cone, each ring about the circle at its height.
std::vector<Solid> Cone::solids(double z_low, double z_high, double edge) const {
    const double widest = std::max({radius_at(z_low), radius_at(z_high), 0.0});
    const detail::PrismGrid grid(widest, z_low, z_high, edge);
    const double outside = 1.0 / std::cos(std::numbers::pi / grid.sides);
    return detail::tube_solids(
        grid, [&](int row) { return std::max(radius_at(grid.height(row)), 0.0) * outside; });
}

DemSettleWall Cone::settle_wall(double height, std::string_view contact) const {
    return {fmt::format("cone of floor radius\n# {:.9g} and radius {:.9g} at z = {:.9g} about "
                        "the z axis, from the floor z = 0 to z = {:.9g},\n# and the data file's "
                        "box holds it",
                        m_rb, m_rt, m_h, height),
            fmt::format("# The container: its side as a cone region (LAMMPS 2022 has no STL walls "
                        "for\n# granular fixes; the LIGGGHTS input uses packbed's STL), its floor "
                        "as the plane z = 0.\n"
                        "region          container cone z 0 0 {} {} 0 {} side in open 1 open 2 "
                        "units box\n",
                        m_rb, std::max(radius_at(height), 0.0), height) +
                detail::region_wall("side", contact, "container"),
            "a prism about the cone"};
}

/// A box one cell beyond the cone's widest circle sideways, 0 to height in z; snappyHexMesh
/// cuts the wall (wall.stl) out of it, as for a cylinder.
OpenFoamBackground Cone::openfoam_background(double height, double cell,
                                             const OpenFoamMeshOptions& options) const {
    const double widest = std::max({radius_at(0.0), radius_at(height), 0.0});
    OpenFoamBackground b;
    b.block_mesh =
        detail::box_about_tube(widest, fmt::format("the cone ({}", spec()), height, cell, options);
    b.wall_surface = true;
    b.where = describe();
    b.surfaces = "; `wall.stl`: the cone's wall, open, reaching half a cell beyond both ends "
                 "(patch `wall`)";
    b.patches = ", `wall`; `outside` keeps no faces";
    b.cells = detail::tube_cells(cell, options, "the wall");
    return b;
}

std::vector<double> Cone::spec_numbers() const {
    return {2.0 * m_rb, 2.0 * m_rt, m_h};
}

/// The frustum from the floor up to `height`.
double Cone::prism_volume(double height) const {
    return frustum_volume(m_rb, m_slope, 0.0, height);
}

nlohmann::json Cone::region_json(double height) const {
    return {{"shape", "cone"},
            {"floor_diameter", 2.0 * m_rb},
            {"top_diameter", 2.0 * m_rt},
            {"cone_height", m_h},
            {"height", height}};
}

std::string Cone::region_allowed() {
    return fmt::format("diameters and heights > 0 and at most {:g}", limits::max_length);
}

/// The square of the widest circle up to `height`, each centre kept by its distance from the
/// wall.
FillWindow Cone::fill_window(double, double height) const {
    const double reach = std::max({radius_at(0.0), radius_at(height), 0.0});
    return {{-reach, reach, -reach, reach}, reach * reach, -1.0, true};
}

// The cone's exact volumes: the frustum in closed form, a sphere's part by the pieces of
// volume_pieces.hpp (shared with the cylinder's sphere_volume_in_cylinder_slab).

using detail::pi;
using detail::volume_over_pieces;

double frustum_volume(double rb, double slope, double z_low, double z_high) {
    if (!(z_high > z_low))
        return 0.0;
    // Only the heights where R(z) >= 0: cut at the apex z = -Rb / k.
    if (slope != 0.0) {
        const double apex = -rb / slope;
        if (slope > 0.0)
            z_low = std::max(z_low, apex);
        else
            z_high = std::min(z_high, apex);
    } else if (rb < 0.0) {
        return 0.0;
    }
    if (!(z_high > z_low))
        return 0.0;
    const double r1 = std::max(rb + slope * z_low, 0.0), r2 = std::max(rb + slope * z_high, 0.0);
    return pi / 3.0 * (z_high - z_low) * (r1 * r1 + r1 * r2 + r2 * r2);
}

double sphere_volume_in_cone_slab(const Vec3& center, double radius, double rb, double slope,
                                  double z_low, double z_high) {
    // Work in t = z - center.z, as for the cylinder; the wall's radius at t is
    // R(t) = Rc + k t, Rc = R(center.z), and none (0) beyond the apex.
    const double t_low = std::max(z_low - center.z, -radius);
    const double t_high = std::min(z_high - center.z, radius);
    if (!(t_low < t_high))
        return 0.0;
    const double rho = std::hypot(center.x, center.y);
    const double rc = rb + slope * center.z;
    auto wall_radius = [&](double t) { return std::max(rc + slope * t, 0.0); };
    auto slice_radius = [&](double t) { return std::sqrt(std::max(radius * radius - t * t, 0.0)); };

    // Break [t_low, t_high] where the slice changes regime, s(t) = |rho - R(t)| and
    // s(t) = rho + R(t): with s^2 = r^2 - t^2 and R linear, each is the quadratic
    // (1 + B^2) t^2 + 2 A B t + A^2 - r^2 = 0 (A = rho -+ Rc, B = -+k). Also at the equator
    // (the densest nodes where the slice is largest) and at the apex, where R(t) has its kink.
    std::array<double, 8> cuts{};
    std::size_t ncuts = 0;
    cuts[ncuts++] = t_low;
    auto cut = [&](double t) {
        if (t > t_low && t < t_high)
            cuts[ncuts++] = t;
    };
    cut(0.0);
    if (slope != 0.0)
        cut(-rc / slope);
    for (const auto& [a, b] : {std::pair{rho - rc, -slope}, std::pair{rho + rc, slope}}) {
        const double q = 1.0 + b * b;
        const double disc = radius * radius * q - a * a;
        if (disc <= 0.0)
            continue;
        const double root = std::sqrt(disc);
        cut((-a * b - root) / q);
        cut((-a * b + root) / q);
    }
    cuts[ncuts++] = t_high;
    return volume_over_pieces(std::span(cuts.data(), ncuts), radius, rho, slice_radius, wall_radius,
                              [&](double t1, double t2) {
                                  // the wall's disk inside the slice: the frustum itself
                                  return frustum_volume(rc, slope, t1, t2);
                              });
}

/// The line inside the nappe of the cone that holds the frustum: rho^2 <= R(z)^2 with
/// R(z) >= 0, a quadratic inequality in s cut by a half-line (one interval: the nappe's inside
/// is convex).
Chord Cone::side_chord(const Vec3& p, const Vec3& u) const {
    const double r0 = radius_at(p.z), ku = m_slope * u.z;
    const double a = u.x * u.x + u.y * u.y - ku * ku;
    const double b = p.x * u.x + p.y * u.y - ku * r0;
    const double c = p.x * p.x + p.y * p.y - r0 * r0;
    constexpr double inf = std::numeric_limits<double>::infinity();
    // Where a s^2 + 2 b s + c <= 0: up to two intervals.
    std::array<Chord::Interval, 2> parts{};
    std::size_t count = 0;
    if (a == 0.0) {
        if (b > 0.0)
            parts[count++] = {-inf, -c / (2.0 * b)};
        else if (b < 0.0)
            parts[count++] = {-c / (2.0 * b), inf};
        else if (c <= 0.0)
            parts[count++] = {-inf, inf};
    } else {
        const double disc = b * b - a * c;
        if (disc > 0.0) {
            const double q = -(b + std::copysign(std::sqrt(disc), b));
            const double s1 = std::min(q / a, c / q), s2 = std::max(q / a, c / q);
            if (a > 0.0) {
                parts[count++] = {s1, s2};
            } else {
                parts[count++] = {-inf, s1};
                parts[count++] = {s2, inf};
            }
        } else if (a < 0.0) {
            parts[count++] = {-inf, inf};
        }
    }
    // R(z(s)) = r0 + k u_z s >= 0.
    double low = -inf, high = inf;
    if (ku > 0.0)
        low = -r0 / ku;
    else if (ku < 0.0)
        high = -r0 / ku;
    else if (r0 < 0.0)
        return {};
    Chord out;
    for (std::size_t i = 0; i < count; ++i)
        if (const Chord part =
                Chord::between(std::max(parts[i].low, low), std::min(parts[i].high, high));
            part.count)
            out.parts[out.count++] = part.parts[0];
    return out;
}

/// How far the body reaches beyond the slanted wall along its normal: cos(theta) times the
/// largest rho - R(z) over its points, max over the horizontal u of (u, -k) . support((u, -k))
/// less Rb; pushed along the inward normal (-cos u, sin theta).
void Cone::convex_wall_contacts(const SupportFunction& support, const Vec3& centre,
                                const ConvexWallFunction& f) const {
    auto outward = [&](double phi) { return Vec3{std::cos(phi), std::sin(phi), -m_slope}; };
    const detail::AroundAxis far = detail::maximum_around_axis(
        [&](double phi) {
            const Vec3 v = outward(phi);
            return dot(v, support(v));
        },
        std::atan2(centre.y, centre.x));
    const Vec3 u = detail::around_axis(far.phi);
    f({m_cos * (far.value - m_rb), {-m_cos * u.x, -m_cos * u.y, m_sin}, support(outward(far.phi))});
}

} // namespace packbed
