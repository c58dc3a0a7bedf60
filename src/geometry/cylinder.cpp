#include "packbed/cylinder.hpp"

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

double Cylinder::cross_section_area() const {
    return std::numbers::pi * m_radius * m_radius;
}

double Cylinder::shell_area(double d_low, double d_high) const {
    const double a = std::max(m_radius - d_low, 0.0), b = std::max(m_radius - d_high, 0.0);
    return std::numbers::pi * (a * a - b * b);
}

double Cylinder::sphere_volume(const Vec3& c, double r, double z_low, double z_high) const {
    return m_radius > 0.0 ? sphere_volume_in_cylinder_slab(c, r, m_radius, z_low, z_high) : 0.0;
}

double Cylinder::ball_volume(const Vec3& c, double r, double z_low, double z_high) const {
    if (!(r > 0.0 && m_radius > 0.0))
        return 0.0;
    if (r <= c.z - z_low && r <= z_high - c.z)
        return ball_volume_in_cylinder(std::hypot(c.x, c.y), r, m_radius);
    return sphere_volume_in_cylinder_slab(c, r, m_radius, z_low, z_high);
}

std::vector<WallPlane> Cylinder::walls_within(const Vec3& c, double r, double gap) const {
    const double rho = std::hypot(c.x, c.y);
    if (m_radius - rho - r < gap && rho > 0.0)
        return {WallPlane{{c.x / rho, c.y / rho, 0.0}, m_radius}};
    return {};
}

std::string Cylinder::spec(bool exact) const {
    return "cylinder:" + detail::spec_length(2.0 * m_radius, exact);
}

std::string Cylinder::describe() const {
    return fmt::format("a cylinder of radius {}", radius());
}

std::optional<double> Cylinder::tube_diameter() const {
    return 2.0 * m_radius;
}

std::optional<Periods> Cylinder::periods() const {
    return std::nullopt;
}

HydraulicDiameter Cylinder::hydraulic_diameter() const {
    return {2.0 * m_radius, hydraulic_formula};
}

BoxMargin Cylinder::box_margin() const {
    return {m_radius, "Rt/100", fmt::format("radius {:.9g}", m_radius)};
}

std::string Cylinder::fit_problem(double largest, const FitWords& words) const {
    const double a = 2.0 * m_radius;
    if (!(a >= largest && a <= detail::widest))
        return fmt::format("a tube diameter from {:.6g}{} ({}) to {:g}{}", largest * words.scale,
                           words.unit, words.particle, detail::widest * words.scale, words.unit);
    return {};
}

/// The paper's eq. (6), L0 = (2 / 3) N / (a^2 (1 - e0)), with sum (d_i / Dp)^3 for N.
double Cylinder::fill_height(double solid, double e0) const {
    const double a = 2.0 * m_radius;
    return 2.0 / 3.0 * solid / (a * a * (1.0 - e0));
}

/// Section 3.1: r = (Rt - r_i) u^(1/2), theta = 2 pi v.
Vec3 Cylinder::uniform_point(double radius, double u, double v, double z) const {
    return detail::disk_point(m_radius - radius, u, v, z);
}

std::optional<double> Cylinder::top() const {
    return std::nullopt;
}

std::vector<std::pair<double, double>> Cylinder::search_lines() const {
    return detail::lines_in(bounds());
}

nlohmann::json Cylinder::summary_json() const {
    return {{"shape", "cylinder"}, {"radius", m_radius}};
}

nlohmann::ordered_json Cylinder::export_json(double height) const {
    return {{"shape", "cylinder"}, {"radius", m_radius}, {"height", height}};
}

/// A cylinder region set back beyond the wall, pushing towards the axis.
LammpsSide Cylinder::lammps_side(std::span<const double> diameters, double setback) const {
    const double r = m_radius, m = 2.0 * setback;
    LammpsSide s;
    s.box = {-r - m, r + m, -r - m, r + m};
    s.walls = fmt::format("region tube cylinder z 0 0 {} INF INF side in units box\n",
                          detail::num(r + setback));
    s.walls += detail::per_type(diameters, setback, [](std::size_t t, double reach) {
        return fmt::format("fix side{0} size{0} wall/region tube harmonic 0.5 1.0 {1}\n"
                           "fix_modify side{0} energy yes\n",
                           t, detail::num(reach));
    });
    s.overlaps.push_back(fmt::format("v_r+sqrt(x*x+y*y)-{}", detail::num(r)));
    return s;
}

/// D in (0, 2 max_length].
std::optional<Cylinder> Cylinder::from_numbers(std::span<const double> v) {
    if (v.size() != 1 || !(v[0] > 0.0 && v[0] <= 2.0 * limits::max_length))
        return std::nullopt;
    return Cylinder(0.5 * v[0]);
}

/// {radius} (summary.json), {diameter} (a lattice's region): the radius in (0, max_length].
std::optional<Cylinder> Cylinder::from_record(const nlohmann::json& record) {
    const double r = detail::record_radius(record, "radius", "diameter");
    if (!(r > 0.0 && r <= limits::max_length))
        return std::nullopt;
    return Cylinder(r);
}

std::string Cylinder::record_allowed() {
    return fmt::format("radius, a number in (0, {:g}]", limits::max_length);
}

std::string Cylinder::allowed() {
    return fmt::format("cylinder:D, a tube of inner diameter D, a number in (0, {:g}]",
                       2.0 * limits::max_length);
}

Cylinder Cylinder::scaled(double factor) const {
    return Cylinder(m_radius * factor);
}

std::vector<Solid> Cylinder::solids(double z_low, double z_high, double edge) const {
    const detail::PrismGrid grid(m_radius, z_low, z_high, edge);
    return detail::tube_solids(grid, [&](int) { return grid.corner; });
}

DemSettleWall Cylinder::settle_wall(double height, std::string_view contact) const {
    return {fmt::format("cylinder of radius\n# {:.9g} about the z axis from the floor z = 0 to "
                        "z = {:.9g}, and the data file's\n# box holds it",
                        radius(), height),
            fmt::format("# The container: its side as a cylinder region (LAMMPS 2022 has no STL "
                        "walls for\n# granular fixes; the LIGGGHTS input uses packbed's STL), its "
                        "floor as the plane z = 0.\n"
                        "region          container cylinder z 0 0 {} 0 {} side in open 1 open 2 "
                        "units box\n",
                        radius(), height) +
                detail::region_wall("side", contact, "container"),
            "a prism about the cylinder"};
}

/// A cylinder: a box one cell beyond it sideways, exactly 0 to height in z; snappyHexMesh
/// cuts the wall (wall.stl) out of it, and the box's sides (`outside`) keep no faces.
OpenFoamBackground Cylinder::openfoam_background(double height, double cell,
                                                 const OpenFoamMeshOptions& options) const {
    const double rt = radius();
    OpenFoamBackground b;
    b.block_mesh = detail::box_about_tube(rt, fmt::format("the cylinder (radius {}", rt), height,
                                          cell, options);
    b.wall_surface = true;
    b.where = fmt::format("a cylinder of radius {}", rt);
    b.surfaces = "; `wall.stl`: the cylinder wall, open, reaching half a cell beyond both ends "
                 "(patch `wall`)";
    b.patches = ", `wall`; `outside` keeps no faces";
    b.cells = detail::tube_cells(cell, options, "the wall");
    return b;
}

std::vector<double> Cylinder::spec_numbers() const {
    return {2.0 * m_radius};
}

/// pi D^2 H / 4.
double Cylinder::prism_volume(double height) const {
    const double d = 2.0 * m_radius;
    return std::numbers::pi / 4.0 * d * d * height;
}

/// {shape, diameter, height}.
nlohmann::json Cylinder::region_json(double height) const {
    return {{"shape", "cylinder"}, {"diameter", 2.0 * m_radius}, {"height", height}};
}

std::string Cylinder::region_allowed() {
    return fmt::format("diameter and height > 0 and at most {:g}", limits::max_length);
}

/// The centres within Rt - margin of the axis.
FillWindow Cylinder::fill_window(double margin, double) const {
    const double reach = m_radius - margin;
    return {{-reach, reach, -reach, reach}, reach * reach, -1.0};
}

/// The line inside the circle of radius Rt (detail::inside_circle).
Chord Cylinder::side_chord(const Vec3& p, const Vec3& u) const {
    return detail::inside_circle(p, u, m_radius);
}

/// The body's farthest point from the axis, beyond Rt (a point's wall overlap).
void Cylinder::convex_wall_contacts(const SupportFunction& support, const Vec3& centre,
                                    const ConvexWallFunction& f) const {
    f(detail::beyond_tube(support, centre, m_radius));
}

} // namespace packbed
