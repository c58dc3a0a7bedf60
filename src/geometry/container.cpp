#include "packbed/container.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <type_traits>

#include <fmt/format.h>
#include <fmt/ranges.h>
#include <nlohmann/json.hpp>

#include "packbed/files.hpp"
#include "packbed/limits.hpp"
#include "packbed/text.hpp"
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

std::string Cylinder::spec() const {
    return fmt::format("cylinder:{:.9g}", 2.0 * m_radius);
}

std::string Cylinder::describe() const {
    return fmt::format("a cylinder of radius {}", radius());
}

double Box::cross_section_area() const {
    return (m_x_high - m_x_low) * (m_y_high - m_y_low);
}

double Box::shell_area(double d_low, double d_high) const {
    const Box outer = shrunk(d_low), inner = shrunk(d_high);
    return outer.cross_section_area() - inner.cross_section_area();
}

Box Box::shrunk(double d) const {
    const double x_mid = 0.5 * (m_x_low + m_x_high), y_mid = 0.5 * (m_y_low + m_y_high);
    return Box(std::min(m_x_low + d, x_mid), std::max(m_x_high - d, x_mid),
               std::min(m_y_low + d, y_mid), std::max(m_y_high - d, y_mid));
}

double Box::sphere_volume(const Vec3& c, double r, double z_low, double z_high) const {
    if (!(m_x_high > m_x_low && m_y_high > m_y_low && z_high > z_low))
        return 0.0;
    return sphere_volume_in_box(c, r, {m_x_low, m_y_low, z_low}, {m_x_high, m_y_high, z_high});
}

std::vector<WallPlane> Box::walls_within(const Vec3& c, double r, double gap) const {
    std::vector<WallPlane> planes;
    if (c.x - m_x_low - r < gap)
        planes.push_back({{-1.0, 0.0, 0.0}, -m_x_low});
    if (m_x_high - c.x - r < gap)
        planes.push_back({{1.0, 0.0, 0.0}, m_x_high});
    if (c.y - m_y_low - r < gap)
        planes.push_back({{0.0, -1.0, 0.0}, -m_y_low});
    if (m_y_high - c.y - r < gap)
        planes.push_back({{0.0, 1.0, 0.0}, m_y_high});
    return planes;
}

std::string Box::spec() const {
    std::string out = fmt::format("box:{:.9g},{:.9g}", m_x_high - m_x_low, m_y_high - m_y_low);
    if (m_x_low != 0.0 || m_y_low != 0.0)
        out += fmt::format("@{:.9g},{:.9g}", m_x_low, m_y_low);
    return out;
}

std::string Box::describe() const {
    return fmt::format("a box ({})", spec());
}

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

double Annulus::shell_area_from(std::size_t wall, double d_low, double d_high) const {
    return shrunk_from(wall, d_low).cross_section_area() -
           shrunk_from(wall, d_high).cross_section_area();
}

std::string Annulus::spec() const {
    return fmt::format("annulus:{:.9g},{:.9g}", 2.0 * m_outer, 2.0 * m_inner);
}

std::string Annulus::describe() const {
    return spec();
}

double Periodic::sphere_volume(const Vec3& c, double r, double z_low, double z_high) const {
    return sphere_slab_volume(c.z, r, z_low, z_high);
}

std::string Periodic::spec() const {
    return fmt::format("periodic:{:.9g},{:.9g}", lx(), ly());
}

std::string Periodic::describe() const {
    return spec();
}

// What the other stages ask, shape by shape.
namespace {

/// Widest allowed container, in Dp: as the cylinder's largest aspect ratio.
constexpr double widest = 1e4;

/// The height of `solid` (diameters cubed, Dp^3) over a cross-section of `area` at void
/// fraction e0: (pi / 6) solid / (A (1 - e0)).
double prism_fill_height(double area, double solid, double e0) {
    return std::numbers::pi / 6.0 * solid / (area * (1.0 - e0));
}

/// A box's or a periodic cell's fit: widths from `least` to `widest` Dp.
std::string widths_problem(const Rectangle& b, double least, std::string_view why) {
    const double lx = b.x_high - b.x_low, ly = b.y_high - b.y_low;
    if (!(lx >= least && ly >= least && lx <= widest && ly <= widest))
        return fmt::format("widths from {:.6g} Dp ({}) to {:g} Dp", least, why, widest);
    return {};
}

/// The search lines at irrational fractions of the half widths of `b` from its middle, so
/// that no line lies on a cell face of a background mesh.
std::vector<std::pair<double, double>> lines_in(const Rectangle& b) {
    const double x_mid = 0.5 * (b.x_low + b.x_high), y_mid = 0.5 * (b.y_low + b.y_high);
    const double x_half = 0.5 * (b.x_high - b.x_low), y_half = 0.5 * (b.y_high - b.y_low);
    constexpr double fractions[8][2] = {{0.0123, 0.0371},  {0.3137, 0.1291},   {-0.2719, 0.2213},
                                        {0.1409, -0.4129}, {-0.5231, -0.0917}, {0.6143, 0.2753},
                                        {-0.1733, 0.6571}, {0.4421, -0.5309}};
    std::vector<std::pair<double, double>> lines;
    for (const auto& f : fractions)
        lines.emplace_back(x_mid + f[0] * x_half, y_mid + f[1] * y_half);
    return lines;
}

/// A point at distance sqrt(a^2 + (b^2 - a^2) u) from the axis and angle 2 pi v: uniform
/// over the ring between the radii a and b (section 3.1 of the paper for a = 0).
Vec3 ring_point(double a, double b, double u, double v) {
    const double r = std::sqrt(a * a + (b * b - a * a) * u);
    const double theta = 2.0 * std::numbers::pi * v;
    return {r * std::cos(theta), r * std::sin(theta), 0.0};
}

/// A prism's summary: {shape, size [LX, LY], spec}.
nlohmann::json prism_json(std::string_view shape, const Rectangle& b, const std::string& spec) {
    return {{"shape", shape}, {"size", {b.x_high - b.x_low, b.y_high - b.y_low}}, {"spec", spec}};
}

nlohmann::ordered_json prism_export_json(std::string_view shape, const Rectangle& b,
                                         double height) {
    return {{"shape", shape},
            {"size", {b.x_high - b.x_low, b.y_high - b.y_low}},
            {"corner", {b.x_low, b.y_low}},
            {"height", height}};
}

/// Shortest round-trip text of a number, as the LAMMPS data file's.
std::string num(double value) {
    return fmt::format("{}", value);
}

/// line(t + 1, d / 2 + setback) for each size t: a wall fix per type.
template <class F>
std::string per_type(std::span<const double> diameters, double setback, F&& line) {
    std::string out;
    for (std::size_t t = 0; t < diameters.size(); ++t)
        out += line(t + 1, 0.5 * diameters[t] + setback);
    return out;
}

} // namespace

std::optional<double> Cylinder::tube_diameter() const {
    return 2.0 * m_radius;
}
std::optional<Periods> Cylinder::periods() const {
    return std::nullopt;
}
HydraulicDiameter Cylinder::hydraulic_diameter() const {
    return {2.0 * m_radius, "D"};
}
BoxMargin Cylinder::box_margin() const {
    return {m_radius, "Rt/100", fmt::format("radius {:.9g}", m_radius)};
}
std::string Cylinder::fit_problem(double largest) const {
    const double a = 2.0 * m_radius;
    if (!(a >= largest && a <= widest))
        return fmt::format("a tube diameter from {:.6g} Dp (the largest sphere) to {:g} Dp",
                           largest, widest);
    return {};
}
/// The paper's eq. (6), L0 = (2 / 3) N / (a^2 (1 - e0)), with sum (d_i / Dp)^3 for N.
double Cylinder::fill_height(double solid, double e0) const {
    const double a = 2.0 * m_radius;
    return 2.0 / 3.0 * solid / (a * a * (1.0 - e0));
}
/// Section 3.1: r = (Rt - r_i) u^(1/2), theta = 2 pi v.
Vec3 Cylinder::uniform_point(double radius, double u, double v) const {
    const double r = (m_radius - radius) * std::sqrt(u);
    const double theta = 2.0 * std::numbers::pi * v;
    return {r * std::cos(theta), r * std::sin(theta), 0.0};
}
std::vector<std::pair<double, double>> Cylinder::search_lines() const {
    return lines_in(bounds());
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
    s.walls =
        fmt::format("region tube cylinder z 0 0 {} INF INF side in units box\n", num(r + setback));
    s.walls += per_type(diameters, setback, [](std::size_t t, double reach) {
        return fmt::format("fix side{0} size{0} wall/region tube harmonic 0.5 1.0 {1}\n"
                           "fix_modify side{0} energy yes\n",
                           t, num(reach));
    });
    s.overlaps.push_back(fmt::format("v_r+sqrt(x*x+y*y)-{}", num(r)));
    return s;
}

std::optional<double> Box::tube_diameter() const {
    return std::nullopt;
}
std::optional<Periods> Box::periods() const {
    return std::nullopt;
}
HydraulicDiameter Box::hydraulic_diameter() const {
    const double lx = m_x_high - m_x_low, ly = m_y_high - m_y_low;
    return {4.0 * lx * ly / (2.0 * (lx + ly)), "2 LX LY / (LX + LY)"};
}
BoxMargin Box::box_margin() const {
    return {depth(), "a hundredth of half the narrower width", spec()};
}
std::string Box::fit_problem(double largest) const {
    return widths_problem(bounds(), largest, "the largest sphere");
}
double Box::fill_height(double solid, double e0) const {
    return prism_fill_height(cross_section_area(), solid, e0);
}
/// Each coordinate uniform between the faces less r_i.
Vec3 Box::uniform_point(double radius, double u, double v) const {
    return {m_x_low + radius + (m_x_high - m_x_low - 2.0 * radius) * u,
            m_y_low + radius + (m_y_high - m_y_low - 2.0 * radius) * v, 0.0};
}
std::vector<std::pair<double, double>> Box::search_lines() const {
    return lines_in(bounds());
}
nlohmann::json Box::summary_json() const {
    return prism_json(name(), bounds(), spec());
}
nlohmann::ordered_json Box::export_json(double height) const {
    return prism_export_json(name(), bounds(), height);
}

/// Four harmonic walls at the faces, each set back.
LammpsSide Box::lammps_side(std::span<const double> diameters, double setback) const {
    const double m = 2.0 * setback;
    LammpsSide s;
    s.box = {m_x_low - m, m_x_high + m, m_y_low - m, m_y_high + m};
    s.walls = per_type(diameters, setback, [&](std::size_t t, double reach) {
        return fmt::format(
            "fix side{0} size{0} wall/harmonic xlo {1} 0.5 1.0 {5} xhi {2} 0.5 1.0 {5} ylo "
            "{3} 0.5 1.0 {5} yhi {4} 0.5 1.0 {5} units box\nfix_modify side{0} energy yes\n",
            t, num(m_x_low - setback), num(m_x_high + setback), num(m_y_low - setback),
            num(m_y_high + setback), num(reach));
    });
    s.overlaps.push_back(fmt::format("v_r+{}-x", num(m_x_low)));
    s.overlaps.push_back(fmt::format("v_r+x-{}", num(m_x_high)));
    s.overlaps.push_back(fmt::format("v_r+{}-y", num(m_y_low)));
    s.overlaps.push_back(fmt::format("v_r+y-{}", num(m_y_high)));
    return s;
}

std::optional<double> Annulus::tube_diameter() const {
    return std::nullopt;
}
std::optional<Periods> Annulus::periods() const {
    return std::nullopt;
}
/// 4 pi (R^2 - Ri^2) / (2 pi (R + Ri)) = 2 (R - Ri).
HydraulicDiameter Annulus::hydraulic_diameter() const {
    return {2.0 * (m_outer - m_inner), "D - DI"};
}
BoxMargin Annulus::box_margin() const {
    return {m_outer, "the tube's radius/100", spec()};
}
std::string Annulus::fit_problem(double largest) const {
    const double outer = 2.0 * m_outer, inner = 2.0 * m_inner;
    if (!(outer <= widest && inner >= 0.0 && outer - inner >= 2.0 * largest))
        return fmt::format("D up to {:g} Dp and DI <= D - {:.6g} Dp: the gap between rod and "
                           "tube, (D - DI) / 2, at least the largest sphere ({:.6g} Dp)",
                           widest, 2.0 * largest, largest);
    return {};
}
double Annulus::fill_height(double solid, double e0) const {
    return prism_fill_height(cross_section_area(), solid, e0);
}
/// rho^2 uniform between (Ri + r_i)^2 and (R - r_i)^2.
Vec3 Annulus::uniform_point(double radius, double u, double v) const {
    return ring_point(m_inner + radius, m_outer - radius, u, v);
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
    s.walls =
        fmt::format("region tube cylinder z 0 0 {} INF INF side in units box\n", num(r + setback));
    if (ri > 0.0)
        s.walls += fmt::format("region rod cylinder z 0 0 {} INF INF side out units box\n",
                               num(ri - rod_setback));
    for (std::size_t t = 0; t < diameters.size(); ++t) {
        const double radius = 0.5 * diameters[t];
        s.walls += fmt::format("fix side{0} size{0} wall/region tube harmonic 0.5 1.0 {1}\n"
                               "fix_modify side{0} energy yes\n",
                               t + 1, num(radius + setback));
        if (ri > 0.0)
            s.walls += fmt::format("fix rod{0} size{0} wall/region rod harmonic 0.5 1.0 {1}\n"
                                   "fix_modify rod{0} energy yes\n",
                                   t + 1, num(radius + rod_setback));
    }
    s.overlaps.push_back(fmt::format("v_r+sqrt(x*x+y*y)-{}", num(r)));
    if (ri > 0.0)
        s.overlaps.push_back(fmt::format("v_r+{}-sqrt(x*x+y*y)", num(ri)));
    return s;
}

std::optional<double> Periodic::tube_diameter() const {
    return std::nullopt;
}
HydraulicDiameter Periodic::hydraulic_diameter() const {
    return {std::nullopt, "is a periodic cell, it has no wall"};
}
BoxMargin Periodic::box_margin() const {
    return {0.0, "", spec()};
}
/// Two spheres across, so that two spheres in contact have one nearest copy (the minimum
/// image).
std::string Periodic::fit_problem(double largest) const {
    return widths_problem(bounds(), 2.0 * largest,
                          "twice the largest sphere, for the minimum image");
}
double Periodic::fill_height(double solid, double e0) const {
    return prism_fill_height(cross_section_area(), solid, e0);
}
/// Anywhere in the cell.
Vec3 Periodic::uniform_point(double, double u, double v) const {
    return {lx() * u, ly() * v, 0.0};
}
std::vector<std::pair<double, double>> Periodic::search_lines() const {
    return lines_in(bounds());
}
nlohmann::json Periodic::summary_json() const {
    nlohmann::json j = prism_json(name(), bounds(), spec());
    j["periodic"] = "x and y";
    return j;
}
nlohmann::ordered_json Periodic::export_json(double height) const {
    return prism_export_json(name(), bounds(), height);
}

/// No wall: boundary p p, the box the cell.
LammpsSide Periodic::lammps_side(std::span<const double>, double) const {
    return {"p p", bounds(), "", {}};
}

// Every question to the shape: the one place a container's kind is looked at.
namespace {
template <class F> decltype(auto) ask(const Container::Shape& shape, F&& f) {
    return std::visit(std::forward<F>(f), shape);
}
} // namespace

std::optional<double> Container::tube_diameter() const {
    return ask(m_shape, [](const auto& s) { return s.tube_diameter(); });
}
std::string_view Container::axis() const {
    return ask(m_shape, [](const auto& s) { return s.axis(); });
}
std::optional<Periods> Container::periods() const {
    return ask(m_shape, [](const auto& s) { return s.periods(); });
}
HydraulicDiameter Container::hydraulic_diameter() const {
    return ask(m_shape, [](const auto& s) { return s.hydraulic_diameter(); });
}
BoxMargin Container::box_margin() const {
    return ask(m_shape, [](const auto& s) { return s.box_margin(); });
}
std::string Container::fit_problem(double largest) const {
    return ask(m_shape, [&](const auto& s) { return s.fit_problem(largest); });
}
double Container::fill_height(double solid, double e0) const {
    return ask(m_shape, [&](const auto& s) { return s.fill_height(solid, e0); });
}
Vec3 Container::uniform_point(double radius, double u, double v) const {
    return ask(m_shape, [&](const auto& s) { return s.uniform_point(radius, u, v); });
}
std::vector<std::pair<double, double>> Container::search_lines() const {
    return ask(m_shape, [](const auto& s) { return s.search_lines(); });
}
nlohmann::json Container::summary_json() const {
    return ask(m_shape, [](const auto& s) { return s.summary_json(); });
}
nlohmann::ordered_json Container::export_json(double height) const {
    return ask(m_shape, [&](const auto& s) { return s.export_json(height); });
}
LammpsSide Container::lammps_side(std::span<const double> diameters, double setback) const {
    return ask(m_shape, [&](const auto& s) { return s.lammps_side(diameters, setback); });
}

std::string_view Container::name() const {
    return ask(m_shape, [](const auto& s) { return s.name(); });
}

std::string Container::spec() const {
    return ask(m_shape, [](const auto& s) { return s.spec(); });
}

std::string Container::describe() const {
    return ask(m_shape, [](const auto& s) { return s.describe(); });
}

Container Container::scaled(double factor) const {
    return ask(m_shape, [&](const auto& s) -> Container {
        using S = std::decay_t<decltype(s)>;
        if constexpr (std::is_same_v<S, Cylinder>)
            return Cylinder(s.radius() * factor);
        else if constexpr (std::is_same_v<S, Box>)
            return Box(s.x_low() * factor, s.x_high() * factor, s.y_low() * factor,
                       s.y_high() * factor);
        else if constexpr (std::is_same_v<S, Annulus>)
            return Annulus(s.outer_radius() * factor, s.inner_radius() * factor);
        else
            return Periodic(s.lx() * factor, s.ly() * factor);
    });
}

bool Container::contains(const Vec3& p) const {
    return ask(m_shape, [&](const auto& s) { return s.contains(p); });
}

double Container::wall_distance(const Vec3& p) const {
    return ask(m_shape, [&](const auto& s) { return s.wall_distance(p); });
}

std::pair<double, double> Container::wall_distances(const Vec3& c, double r) const {
    return ask(m_shape, [&](const auto& s) { return s.wall_distances(c, r); });
}

double Container::depth() const {
    return ask(m_shape, [](const auto& s) { return s.depth(); });
}

std::vector<WallPlane> Container::walls_within(const Vec3& c, double r, double gap) const {
    return ask(m_shape, [&](const auto& s) { return s.walls_within(c, r, gap); });
}

double Container::cross_section_area() const {
    return ask(m_shape, [](const auto& s) { return s.cross_section_area(); });
}

double Container::shell_area(double d_low, double d_high) const {
    return ask(m_shape, [&](const auto& s) { return s.shell_area(d_low, d_high); });
}

Container Container::shrunk(double d) const {
    return ask(m_shape, [&](const auto& s) { return Container(s.shrunk(d)); });
}

double Container::sphere_volume(const Vec3& c, double r, double z_low, double z_high) const {
    return ask(m_shape, [&](const auto& s) { return s.sphere_volume(c, r, z_low, z_high); });
}

double Container::ball_volume(const Vec3& c, double r, double z_low, double z_high) const {
    return ask(m_shape, [&](const auto& s) { return s.ball_volume(c, r, z_low, z_high); });
}

Rectangle Container::bounds() const {
    return ask(m_shape, [](const auto& s) { return s.bounds(); });
}

std::string_view Container::profile_position_name() const {
    return ask(m_shape, [](const auto& s) { return s.profile_position_name(); });
}

double Container::profile_position(double d) const {
    return ask(m_shape, [&](const auto& s) { return s.profile_position(d); });
}

std::span<const std::string_view> Container::profile_walls() const {
    return ask(m_shape, [](const auto& s) { return s.profile_walls(); });
}

double Container::wall_distance_from(std::size_t wall, const Vec3& p) const {
    return ask(m_shape, [&](const auto& s) { return s.wall_distance_from(wall, p); });
}

std::pair<double, double> Container::wall_distances_from(std::size_t wall, const Vec3& c,
                                                         double r) const {
    return ask(m_shape, [&](const auto& s) { return s.wall_distances_from(wall, c, r); });
}

Container Container::shrunk_from(std::size_t wall, double d) const {
    return ask(m_shape, [&](const auto& s) { return Container(s.shrunk_from(wall, d)); });
}

double Container::shell_area_from(std::size_t wall, double d_low, double d_high) const {
    return ask(m_shape, [&](const auto& s) { return s.shell_area_from(wall, d_low, d_high); });
}

std::size_t Container::nearest_wall(const Vec3& p) const {
    return ask(m_shape, [&](const auto& s) { return s.nearest_wall(p); });
}

std::string_view Container::profile_position_name_from(std::size_t wall) const {
    return ask(m_shape, [&](const auto& s) { return s.profile_position_name_from(wall); });
}

double Container::profile_position_from(std::size_t wall, double d) const {
    return ask(m_shape, [&](const auto& s) { return s.profile_position_from(wall, d); });
}

double Container::sticks_out(const Vec3& c, double r) const {
    return ask(m_shape, [&](const auto& s) { return s.sticks_out(c, r); });
}

Container ContainerSpec::container() const {
    if (shape == "box")
        return Box(lx, ly);
    if (shape == "annulus")
        return Annulus(0.5 * diameter, 0.5 * inner);
    if (shape == "periodic")
        return Periodic(lx, ly);
    return Cylinder(0.5 * diameter);
}

std::optional<ContainerSpec> parse_container(std::string_view text) {
    const KindSpec parts = split_kind(text);
    const std::string_view shape = parts.kind;
    if (!parts.parameters)
        return std::nullopt;
    const auto known = std::find(all_shapes.begin(), all_shapes.end(), shape);
    const auto v = parse_finite_list(*parts.parameters);
    if (known == all_shapes.end() || !v || v->size() != (shape == "cylinder" ? 1u : 2u))
        return std::nullopt;
    // Every side within max_length of the origin, as the analysis allows.
    const bool round = shape == "cylinder" || shape == "annulus";
    const double largest = round ? 2.0 * limits::max_length : limits::max_length;
    for (const double x : *v)
        if (!(x > 0.0 && x <= largest))
            return std::nullopt;
    ContainerSpec spec{std::string(shape)};
    if (shape == "annulus" && !((*v)[1] < (*v)[0]))
        return std::nullopt;
    if (round) {
        spec.diameter = (*v)[0];
        spec.inner = v->size() > 1 ? (*v)[1] : 0.0;
    } else {
        spec.lx = (*v)[0];
        spec.ly = (*v)[1];
    }
    return spec;
}

std::string describe(const Container& container) {
    if (const auto* c = std::get_if<Cylinder>(&container.shape()))
        return fmt::format("radius {}", c->radius());
    return container.spec();
}

std::string allowed_containers(std::span<const std::string_view> shapes) {
    const auto takes = [&](std::string_view s) {
        return std::find(shapes.begin(), shapes.end(), s) != shapes.end();
    };
    std::vector<std::string> forms;
    const double round = 2.0 * limits::max_length, flat = limits::max_length;
    if (takes("cylinder"))
        forms.push_back(
            fmt::format("cylinder:D, a tube of inner diameter D, a number in (0, {:g}]", round));
    if (takes("box"))
        forms.push_back(
            fmt::format("box:LX,LY, walls at x = 0, LX and y = 0, LY, each in (0, {:g}]", flat));
    if (takes("annulus"))
        forms.push_back(fmt::format("annulus:D,DI, between a tube of diameter D and a coaxial "
                                    "rod of diameter DI, 0 < DI < D <= {:g}",
                                    round));
    if (takes("periodic"))
        forms.push_back(
            fmt::format("periodic:LX,LY, a cell periodic in x and y, each in (0, {:g}]", flat));
    return fmt::format("{}", fmt::join(forms, "; or "));
}

std::string container_not_allowed(std::string_view option, std::string_view spec) {
    return fmt::format("{}: '{}' is not allowed; allowed: {}", option,
                       printable(spec.substr(0, 80)), allowed_containers(all_shapes));
}

} // namespace packbed
