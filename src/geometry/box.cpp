#include "packbed/box.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "geometry/shape_text.hpp"
#include "packbed/limits.hpp"
#include "packbed/volume.hpp"

namespace packbed {

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
    return detail::widths_problem(bounds(), largest, "the largest sphere");
}

double Box::fill_height(double solid, double e0) const {
    return detail::prism_fill_height(cross_section_area(), solid, e0);
}

/// Each coordinate uniform between the faces less r_i.
Vec3 Box::uniform_point(double radius, double u, double v) const {
    return {m_x_low + radius + (m_x_high - m_x_low - 2.0 * radius) * u,
            m_y_low + radius + (m_y_high - m_y_low - 2.0 * radius) * v, 0.0};
}

std::vector<std::pair<double, double>> Box::search_lines() const {
    return detail::lines_in(bounds());
}

nlohmann::json Box::summary_json() const {
    return detail::prism_json(name(), bounds(), spec());
}

nlohmann::ordered_json Box::export_json(double height) const {
    return detail::prism_export_json(name(), bounds(), height);
}

/// Four harmonic walls at the faces, each set back.
LammpsSide Box::lammps_side(std::span<const double> diameters, double setback) const {
    const double m = 2.0 * setback;
    LammpsSide s;
    s.box = {m_x_low - m, m_x_high + m, m_y_low - m, m_y_high + m};
    s.walls = detail::per_type(diameters, setback, [&](std::size_t t, double reach) {
        return fmt::format(
            "fix side{0} size{0} wall/harmonic xlo {1} 0.5 1.0 {5} xhi {2} 0.5 1.0 {5} ylo "
            "{3} 0.5 1.0 {5} yhi {4} 0.5 1.0 {5} units box\nfix_modify side{0} energy yes\n",
            t, detail::num(m_x_low - setback), detail::num(m_x_high + setback),
            detail::num(m_y_low - setback), detail::num(m_y_high + setback), detail::num(reach));
    });
    s.overlaps.push_back(fmt::format("v_r+{}-x", detail::num(m_x_low)));
    s.overlaps.push_back(fmt::format("v_r+x-{}", detail::num(m_x_high)));
    s.overlaps.push_back(fmt::format("v_r+{}-y", detail::num(m_y_low)));
    s.overlaps.push_back(fmt::format("v_r+y-{}", detail::num(m_y_high)));
    return s;
}

std::optional<Box> Box::from_numbers(std::span<const double> v) {
    if (v.size() != 2 || !detail::lengths_in(v, limits::max_length))
        return std::nullopt;
    return Box(v[0], v[1]);
}

std::string Box::allowed() {
    return fmt::format("box:LX,LY, walls at x = 0, LX and y = 0, LY, each in (0, {:g}]",
                       limits::max_length);
}

Box Box::scaled(double factor) const {
    return Box(m_x_low * factor, m_x_high * factor, m_y_low * factor, m_y_high * factor);
}

} // namespace packbed
