#include "packbed/periodic.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "geometry/shape_text.hpp"
#include "packbed/limits.hpp"
#include "packbed/volume.hpp"

namespace packbed {

double Periodic::sphere_volume(const Vec3& c, double r, double z_low, double z_high) const {
    return sphere_slab_volume(c.z, r, z_low, z_high);
}

std::string Periodic::spec() const {
    return fmt::format("periodic:{:.9g},{:.9g}", lx(), ly());
}

std::string Periodic::describe() const {
    return spec();
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
    return detail::widths_problem(bounds(), 2.0 * largest,
                                  "twice the largest sphere, for the minimum image");
}

double Periodic::fill_height(double solid, double e0) const {
    return detail::prism_fill_height(cross_section_area(), solid, e0);
}

/// Anywhere in the cell.
Vec3 Periodic::uniform_point(double, double u, double v) const {
    return {lx() * u, ly() * v, 0.0};
}

std::vector<std::pair<double, double>> Periodic::search_lines() const {
    return detail::lines_in(bounds());
}

nlohmann::json Periodic::summary_json() const {
    nlohmann::json j = detail::prism_json(name(), bounds(), spec());
    j["periodic"] = "x and y";
    return j;
}

nlohmann::ordered_json Periodic::export_json(double height) const {
    return detail::prism_export_json(name(), bounds(), height);
}

/// No wall: boundary p p, the box the cell.
LammpsSide Periodic::lammps_side(std::span<const double>, double) const {
    return {"p p", bounds(), "", {}};
}

std::optional<Periodic> Periodic::from_numbers(std::span<const double> v) {
    if (v.size() != 2 || !detail::lengths_in(v, limits::max_length))
        return std::nullopt;
    return Periodic(v[0], v[1]);
}

std::string Periodic::allowed() {
    return fmt::format("periodic:LX,LY, a cell periodic in x and y, each in (0, {:g}]",
                       limits::max_length);
}

Periodic Periodic::scaled(double factor) const {
    return Periodic(lx() * factor, ly() * factor);
}

} // namespace packbed
