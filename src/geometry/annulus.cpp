#include "packbed/annulus.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "geometry/around_axis.hpp"
#include "geometry/shape_text.hpp"
#include "packbed/limits.hpp"
#include "packbed/volume.hpp"

namespace packbed {

double Annulus::cross_section_area() const {
    return std::numbers::pi * (m_outer * m_outer - m_inner * m_inner);
}

Annulus Annulus::shrunk(double d) const {
    const double mid = 0.5 * (m_outer + m_inner);
    return Annulus(std::max(m_outer - d, mid), std::min(m_inner + d, mid));
}

double Annulus::shell_area(double d_low, double d_high) const {
    return shrunk(d_low).cross_section_area() - shrunk(d_high).cross_section_area();
}

double Annulus::sphere_volume(const Vec3& c, double r, double z_low, double z_high) const {
    if (!(m_outer > m_inner))
        return 0.0;
    const double rod =
        m_inner > 0.0 ? sphere_volume_in_cylinder_slab(c, r, m_inner, z_low, z_high) : 0.0;
    return sphere_volume_in_cylinder_slab(c, r, m_outer, z_low, z_high) - rod;
}

double Annulus::ball_volume(const Vec3& c, double r, double z_low, double z_high) const {
    if (!(r > 0.0 && m_outer > m_inner))
        return 0.0;
    if (!(r <= c.z - z_low && r <= z_high - c.z))
        return sphere_volume(c, r, z_low, z_high);
    const double rho = std::hypot(c.x, c.y);
    const double rod = m_inner > 0.0 ? ball_volume_in_cylinder(rho, r, m_inner) : 0.0;
    return ball_volume_in_cylinder(rho, r, m_outer) - rod;
}

std::vector<WallPlane> Annulus::walls_within(const Vec3& c, double r, double gap) const {
    const double rho = std::hypot(c.x, c.y);
    std::vector<WallPlane> planes;
    if (!(rho > 0.0))
        return planes;
    const Vec3 out{c.x / rho, c.y / rho, 0.0};
    if (m_outer - rho - r < gap)
        planes.push_back({out, m_outer});
    if (rho - r - m_inner < gap)
        planes.push_back({out * -1.0, -m_inner});
    return planes;
}

Annulus Annulus::shrunk_from(std::size_t wall, double d) const {
    const double mid = 0.5 * (m_outer + m_inner);
    if (wall == 0)
        return Annulus(std::max(m_outer - d, mid), m_inner);
    return Annulus(m_outer, std::min(m_inner + d, mid));
}

double Annulus::shell_area_from(std::size_t wall, double d_low, double d_high, double,
                                double) const {
    return shrunk_from(wall, d_low).cross_section_area() -
           shrunk_from(wall, d_high).cross_section_area();
}

std::string Annulus::spec(bool exact) const {
    return fmt::format("annulus:{},{}", detail::spec_length(2.0 * m_outer, exact),
                       detail::spec_length(2.0 * m_inner, exact));
}

std::string Annulus::describe() const {
    return spec();
}

std::optional<double> Annulus::tube_diameter() const {
    return std::nullopt;
}

std::optional<Periods> Annulus::periods() const {
    return std::nullopt;
}

/// 4 pi (R^2 - Ri^2) / (2 pi (R + Ri)) = 2 (R - Ri).
HydraulicDiameter Annulus::hydraulic_diameter() const {
    return {2.0 * (m_outer - m_inner), hydraulic_formula};
}

BoxMargin Annulus::box_margin() const {
    return {m_outer, "the tube's radius/100", spec()};
}

std::string Annulus::fit_problem(double largest, const FitWords& words) const {
    const double outer = 2.0 * m_outer, inner = 2.0 * m_inner;
    if (!(outer <= detail::widest && inner >= 0.0 && outer - inner >= 2.0 * largest)) {
        const double s = words.scale;
        const std::string_view u = words.unit;
        return fmt::format("D up to {:g}{} and DI <= D - {:.6g}{}: the gap between rod and "
                           "tube, (D - DI) / 2, at least {} ({:.6g}{})",
                           detail::widest * s, u, 2.0 * largest * s, u, words.particle, largest * s,
                           u);
    }
    return {};
}

double Annulus::fill_height(double solid, double e0) const {
    return detail::prism_fill_height(cross_section_area(), solid, e0);
}

/// rho^2 uniform between (Ri + r_i)^2 and (R - r_i)^2.
Vec3 Annulus::uniform_point(double radius, double u, double v, double z) const {
    return detail::ring_point(m_inner + radius, m_outer - radius, u, v, z);
}

std::optional<double> Annulus::top() const {
    return std::nullopt;
}

/// The middle of the bounds is in the rod: lines across the gap instead, at fractions of it
/// from the rod and generic angles (radians).
std::vector<std::pair<double, double>> Annulus::search_lines() const {
    constexpr double across[8][2] = {{0.5123, 0.1371}, {0.3137, 1.2291}, {0.6719, 2.0213},
                                     {0.4409, 2.9129}, {0.5731, 3.7917}, {0.3843, 4.4753},
                                     {0.6233, 5.2571}, {0.4621, 5.9309}};
    const double gap = m_outer - m_inner;
    std::vector<std::pair<double, double>> lines;
    for (const auto& f : across) {
        const double rho = m_inner + f[0] * gap;
        lines.emplace_back(rho * std::cos(f[1]), rho * std::sin(f[1]));
    }
    return lines;
}

nlohmann::json Annulus::summary_json() const {
    return {{"shape", "annulus"}, {"radius", m_outer}, {"inner_radius", m_inner}, {"spec", spec()}};
}

nlohmann::ordered_json Annulus::export_json(double height) const {
    return {
        {"shape", "annulus"}, {"radius", m_outer}, {"inner_radius", m_inner}, {"height", height}};
}

/// The tube as the cylinder's region, the rod (side out) set back by less than its radius.
LammpsSide Annulus::lammps_side(std::span<const double> diameters, double setback) const {
    const double r = m_outer, ri = m_inner, m = 2.0 * setback;
    LammpsSide s;
    s.box = {-r - m, r + m, -r - m, r + m};
    const double rod_setback = std::min(setback, 0.5 * ri);
    s.walls = fmt::format("region tube cylinder z 0 0 {} INF INF side in units box\n",
                          detail::num(r + setback));
    if (ri > 0.0)
        s.walls += fmt::format("region rod cylinder z 0 0 {} INF INF side out units box\n",
                               detail::num(ri - rod_setback));
    for (std::size_t t = 0; t < diameters.size(); ++t) {
        const double radius = 0.5 * diameters[t];
        s.walls += fmt::format("fix side{0} size{0} wall/region tube harmonic 0.5 1.0 {1}\n"
                               "fix_modify side{0} energy yes\n",
                               t + 1, detail::num(radius + setback));
        if (ri > 0.0)
            s.walls += fmt::format("fix rod{0} size{0} wall/region rod harmonic 0.5 1.0 {1}\n"
                                   "fix_modify rod{0} energy yes\n",
                                   t + 1, detail::num(radius + rod_setback));
    }
    s.overlaps.push_back(fmt::format("v_r+sqrt(x*x+y*y)-{}", detail::num(r)));
    if (ri > 0.0)
        s.overlaps.push_back(fmt::format("v_r+{}-sqrt(x*x+y*y)", detail::num(ri)));
    return s;
}

/// {radius, inner_radius} (summary.json) or {diameter, inner_diameter} (a lattice's region),
/// 0 < inner_radius < radius <= max_length.
std::optional<Annulus> Annulus::from_record(const nlohmann::json& record) {
    const double r = detail::record_radius(record, "radius", "diameter");
    const double ri = detail::record_radius(record, "inner_radius", "inner_diameter");
    if (!(ri > 0.0 && ri < r && r <= limits::max_length))
        return std::nullopt;
    return Annulus(r, ri);
}

std::string Annulus::record_allowed() {
    return fmt::format("radius and inner_radius with 0 < inner_radius < radius <= {:g}",
                       limits::max_length);
}

/// 0 < DI < D <= 2 max_length.
std::optional<Annulus> Annulus::from_numbers(std::span<const double> v) {
    if (v.size() != 2 || !detail::lengths_in(v, 2.0 * limits::max_length) || !(v[1] < v[0]))
        return std::nullopt;
    return Annulus(0.5 * v[0], 0.5 * v[1]);
}

std::string Annulus::allowed() {
    return fmt::format("annulus:D,DI, between a tube of diameter D and a coaxial rod of "
                       "diameter DI, 0 < DI < D <= {:g}",
                       2.0 * limits::max_length);
}

Annulus Annulus::scaled(double factor) const {
    return Annulus(m_outer * factor, m_inner * factor);
}

std::vector<Solid> Annulus::solids(double z_low, double z_high, double edge) const {
    // The tube as a cylinder's wall (a prism circumscribed about it, outside it), the rod as
    // a prism inscribed in it (its corners on the rod, its faces inside it: no sphere outside
    // the rod meets it), with the tube's sides and rows, so that the rings of the two share
    // their angles and the bottom and the top are strips of quads between them.
    const double ri = m_inner;
    const detail::PrismGrid grid(m_outer, z_low, z_high, edge);
    const int rows = grid.rows;
    const double corner = grid.corner;
    const auto s = static_cast<std::uint32_t>(grid.sides);
    auto ring_point = [&](double radius, int row, std::uint32_t k) {
        return grid.point(radius, row, k);
    };
    // The tube's normals point away from the axis, the rod's towards it: out of the fluid, as
    // the bottom's (-z) and the top's (+z).
    Solid wall{"wall", detail::ring_wall(
                           grid, [&](int) { return corner; }, true)};
    Solid rod{"rod", detail::ring_wall(
                         grid, [&](int) { return ri; }, false)};
    Solid bottom{"bottom", {}}, top{"top", {}};
    // Bottom and top: vertices 0..s-1 on the tube's ring, s..2s-1 on the rod's.
    for (Solid* face : {&bottom, &top}) {
        const int row = face == &bottom ? 0 : rows;
        for (std::uint32_t k = 0; k < s; ++k)
            face->mesh.vertices.push_back(ring_point(corner, row, k));
        for (std::uint32_t k = 0; k < s; ++k)
            face->mesh.vertices.push_back(ring_point(ri, row, k));
        for (std::uint32_t k = 0; k < s; ++k) {
            const std::uint32_t k1 = (k + 1) % s;
            if (face == &top) { // counter-clockwise seen from above: normal +z
                face->mesh.triangles.push_back({k, k1, s + k1});
                face->mesh.triangles.push_back({k, s + k1, s + k});
            } else {
                face->mesh.triangles.push_back({k, s + k1, k1});
                face->mesh.triangles.push_back({k, s + k, s + k1});
            }
        }
    }
    std::vector<Solid> solids;
    solids.push_back(std::move(wall));
    solids.push_back(std::move(rod));
    solids.push_back(std::move(bottom));
    solids.push_back(std::move(top));
    return solids;
}

DemSettleWall Annulus::settle_wall(double height, std::string_view contact) const {
    // Two regions, two wall fixes: the tube's inside and the rod's outside (side out), each
    // open at the floor and the top (cylinder faces 1 and 2).
    return {fmt::format("annulus between a tube\n# of radius {:.9g} and a coaxial rod of radius "
                        "{:.9g} about the z axis, from the floor z = 0 to\n# z = {:.9g}, and the "
                        "data file's box holds it",
                        outer_radius(), inner_radius(), height),
            fmt::format("# The container: the tube as a cylinder region (side in) and the rod as "
                        "another\n# (side out), each its own wall (LAMMPS 2022 has no STL walls "
                        "for granular fixes;\n# the LIGGGHTS input uses packbed's STL), the floor "
                        "as the plane z = 0.\n"
                        "region          tube cylinder z 0 0 {} 0 {} side in open 1 open 2 "
                        "units box\n"
                        "region          rod cylinder z 0 0 {} 0 {} side out open 1 open 2 "
                        "units box\n",
                        outer_radius(), height, inner_radius(), height) +
                detail::region_wall("side", contact, "tube") +
                detail::region_wall("side_rod", contact, "rod"),
            "the tube's prism and the rod's"};
}

/// An annulus: the cylinder's background about its tube (a box one cell beyond the tube
/// sideways, 0 to height in z); snappyHexMesh cuts the tube (wall.stl) and the rod (rod.stl,
/// patch `rod`) out of it, both refined to the wall level.
OpenFoamBackground Annulus::openfoam_background(double height, double cell,
                                                const OpenFoamMeshOptions& options) const {
    OpenFoamBackground b;
    b.block_mesh = detail::box_about_tube(
        outer_radius(),
        fmt::format("the annulus (tube radius {}, rod radius {}", outer_radius(), inner_radius()),
        height, cell, options);
    b.wall_surface = true;
    b.rod_surface = true;
    b.where = fmt::format("the annulus between a tube of radius {} and a coaxial rod of radius {}",
                          outer_radius(), inner_radius());
    b.surfaces = "; `wall.stl`: the tube, open, reaching half a cell beyond both ends (patch "
                 "`wall`); `rod.stl`: the rod, likewise (patch `rod`)";
    b.patches = ", `wall`, `rod`; `outside` keeps no faces";
    b.cells = detail::tube_cells(cell, options, "the tube and the rod");
    return b;
}

std::vector<double> Annulus::spec_numbers() const {
    return {2.0 * m_outer, 2.0 * m_inner};
}

/// pi (D^2 - DI^2) H / 4.
double Annulus::prism_volume(double height) const {
    const double d = 2.0 * m_outer, di = 2.0 * m_inner;
    return std::numbers::pi / 4.0 * (d * d - di * di) * height;
}

/// {shape, diameter, inner_diameter, height}.
nlohmann::json Annulus::region_json(double height) const {
    return {{"shape", "annulus"},
            {"diameter", 2.0 * m_outer},
            {"inner_diameter", 2.0 * m_inner},
            {"height", height}};
}

std::string Annulus::region_allowed() {
    return fmt::format("diameters 0 < DI < D and a height > 0, each at most {:g}",
                       limits::max_length);
}

/// The centres between Ri + margin and R - margin from the axis (none when the gap is
/// thinner than twice the margin).
FillWindow Annulus::fill_window(double margin, double) const {
    const double reach = m_outer - margin, inner = m_inner + margin;
    FillWindow w{{-reach, reach, -reach, reach}, reach * reach, inner * inner};
    if (!(inner <= reach))
        w.box.x_high = w.box.x_low - 1.0;
    return w;
}

/// The line inside the tube less its part inside the rod: up to two intervals.
Chord Annulus::side_chord(const Vec3& p, const Vec3& u) const {
    const Chord tube = detail::inside_circle(p, u, m_outer);
    const Chord rod = detail::inside_circle(p, u, m_inner);
    if (tube.count == 0 || rod.count == 0)
        return tube;
    const Chord::Interval t = tube.parts[0], r = rod.parts[0];
    Chord out;
    if (const Chord before = Chord::between(t.low, std::min(t.high, r.low)); before.count)
        out.parts[out.count++] = before.parts[0];
    if (const Chord after = Chord::between(std::max(t.low, r.high), t.high); after.count)
        out.parts[out.count++] = after.parts[0];
    return out;
}

/// The tube as a cylinder's wall (the farthest point from the axis beyond the tube's radius),
/// the rod as the least horizontal shift that clears it: the rod's radius less the largest,
/// over the horizontal directions u, of the body's nearest extent along u, u . support(-u)
/// (the penetration depth of the body's projection into the rod's circle), pushed along u.
void Annulus::convex_wall_contacts(const SupportFunction& support, const Vec3& centre,
                                   const ConvexWallFunction& f) const {
    f(detail::beyond_tube(support, centre, m_outer));
    const detail::AroundAxis clear = detail::maximum_around_axis(
        [&](double phi) {
            const Vec3 u = detail::around_axis(phi);
            return dot(u, support(-1.0 * u));
        },
        std::atan2(centre.y, centre.x));
    const Vec3 u = detail::around_axis(clear.phi);
    f({m_inner - clear.value, u, support(-1.0 * u)});
}

} // namespace packbed
