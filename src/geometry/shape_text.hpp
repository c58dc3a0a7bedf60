// What the shapes' files share: the limits of a fit, the words of a prism's answers, the
// LAMMPS numbers. Internal to src/geometry/.
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <numbers>
#include <span>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "packbed/limits.hpp"
#include "packbed/mesh.hpp"
#include "packbed/shape.hpp"

namespace packbed::detail {

/// Widest allowed container, in Dp: as the cylinder's largest aspect ratio.
inline constexpr double widest = 1e4;

/// \return true when every length of a SPEC is in (0, largest] (false for NaN).
inline bool lengths_in(std::span<const double> v, double largest) {
    for (const double x : v)
        if (!(x > 0.0 && x <= largest))
            return false;
    return true;
}

/// The height of `solid` (diameters cubed, Dp^3) over a cross-section of `area` at void
/// fraction e0: (pi / 6) solid / (A (1 - e0)).
inline double prism_fill_height(double area, double solid, double e0) {
    return std::numbers::pi / 6.0 * solid / (area * (1.0 - e0));
}

/// record[key] when it is a number, else NaN (which every range check refuses).
inline double record_number(const nlohmann::json& record, const char* key) {
    const auto it = record.find(key);
    return it != record.end() && it->is_number() ? it->get<double>() : std::nan("");
}

/// record[key] when it is a number, else record[half_of] / 2 (a diameter for a radius), else NaN.
inline double record_radius(const nlohmann::json& record, const char* key, const char* half_of) {
    const double r = record_number(record, key);
    return std::isnan(r) ? 0.5 * record_number(record, half_of) : r;
}

/// The first two numbers of record.size (a prism's [LX, LY] or a lattice region's [LX, LY,
/// LZ]; any third in (0, largest]), or NaN where they are not numbers in (0, largest].
inline std::array<double, 2> record_widths(const nlohmann::json& record, double largest) {
    std::array<double, 2> widths{std::nan(""), std::nan("")};
    const auto size = record.find("size");
    if (size == record.end() || !size->is_array() || size->size() < 2 || size->size() > 3)
        return widths;
    for (std::size_t k = 0; k < size->size(); ++k) {
        const double v = (*size)[k].is_number() ? (*size)[k].get<double>() : std::nan("");
        if (!(v > 0.0 && v <= largest))
            return {std::nan(""), std::nan("")};
        if (k < 2)
            widths[k] = v;
    }
    return widths;
}

/// What record_widths takes.
inline std::string widths_record_allowed() {
    return fmt::format("size, two numbers in (0, {:g}] (three in a lattice's region)",
                       limits::max_length);
}

/// A box's or a periodic cell's fit: widths from `least` to `widest` (in `words`' unit).
inline std::string widths_problem(const Rectangle& b, double least, std::string_view why,
                                  const FitWords& words) {
    const double lx = b.x_high - b.x_low, ly = b.y_high - b.y_low;
    if (!(lx >= least && ly >= least && lx <= widest && ly <= widest))
        return fmt::format("widths from {:.6g}{} ({}) to {:g}{}", least * words.scale, words.unit,
                           why, widest * words.scale, words.unit);
    return {};
}

/// The search lines at irrational fractions of the half widths of `b` from its middle, so
/// that no line lies on a cell face of a background mesh.
inline std::vector<std::pair<double, double>> lines_in(const Rectangle& b) {
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

/// A point at distance sqrt(a^2 + (b^2 - a^2) u) from the axis and angle 2 pi v, at height
/// z: uniform over the ring between the radii a and b.
inline Vec3 ring_point(double a, double b, double u, double v, double z) {
    const double r = std::sqrt(a * a + (b * b - a * a) * u);
    const double theta = 2.0 * std::numbers::pi * v;
    return {r * std::cos(theta), r * std::sin(theta), z};
}

/// Section 3.1 of the paper: a point at distance reach u^(1/2) from the axis and angle 2 pi
/// v, at height z: uniform over the disk of radius `reach`.
inline Vec3 disk_point(double reach, double u, double v, double z) {
    const double r = reach * std::sqrt(u);
    const double theta = 2.0 * std::numbers::pi * v;
    return {r * std::cos(theta), r * std::sin(theta), z};
}

/// A length in a SPEC: 9 significant digits for a message or a title, or `exact`, the shortest
/// text that reads back as the same double (a container rebuilt from its spec is the same).
inline std::string spec_length(double length, bool exact) {
    return exact ? fmt::format("{}", length) : fmt::format("{:.9g}", length);
}

/// A prism's summary: {shape, size [LX, LY], spec}.
inline nlohmann::json prism_json(std::string_view shape, const Rectangle& b,
                                 const std::string& spec) {
    return {{"shape", shape}, {"size", {b.x_high - b.x_low, b.y_high - b.y_low}}, {"spec", spec}};
}

inline nlohmann::ordered_json prism_export_json(std::string_view shape, const Rectangle& b,
                                                double height) {
    return {{"shape", shape},
            {"size", {b.x_high - b.x_low, b.y_high - b.y_low}},
            {"corner", {b.x_low, b.y_low}},
            {"height", height}};
}

/// Shortest round-trip text of a number, as the LAMMPS data file's.
inline std::string num(double value) {
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

/// The rings of a prism circumscribed about a cylinder of radius `rt` (its faces tangent to
/// it from outside) between z_low and z_high: `sides` of about `edge` (48 to 100 000), the
/// corners at rt / cos(pi / sides), in `rows` about as tall as a side is wide (1 to 4 096).
struct PrismGrid {
    int sides, rows;
    double corner, z_low, z_high;
    PrismGrid(double rt, double low, double high, double edge)
        : sides(std::clamp(static_cast<int>(std::ceil(2.0 * std::numbers::pi * rt / edge)), 48,
                           100000))
        , rows(0)
        , corner(rt / std::cos(std::numbers::pi / sides))
        , z_low(low)
        , z_high(high) {
        rows = std::clamp(static_cast<int>(std::ceil(
                              (high - low) / (2.0 * corner * std::sin(std::numbers::pi / sides)))),
                          1, 4096);
    }
    /// Point k of ring `row` at distance `radius` from the axis, every other row turned by
    /// half a side.
    Vec3 point(double radius, int row, std::uint32_t k) const {
        const double angle = 2.0 * std::numbers::pi * (k + 0.5 * (row % 2)) / sides;
        return Vec3{radius * std::cos(angle), radius * std::sin(angle), height(row)};
    }
    /// The height of ring `row`.
    double height(int row) const {
        return row == rows ? z_high : z_low + (z_high - z_low) * row / rows;
    }
};

/// The wall through the rings of `grid`, ring `row` at the distance corner(row) from the axis,
/// its normals away from the axis (`outward`) or towards it. The wall in rows about as tall as
/// a side is wide, every other row turned by half a side, so that no two triangles are
/// coplanar; vertex k of ring `row` is vertex row * sides + k.
template <class Corner>
TriangleMesh ring_wall(const PrismGrid& grid, Corner&& corner, bool outward) {
    const int rows = grid.rows;
    const auto s = static_cast<std::uint32_t>(grid.sides);
    TriangleMesh mesh;
    for (int row = 0; row <= rows; ++row)
        for (std::uint32_t k = 0; k < s; ++k)
            mesh.vertices.push_back(grid.point(corner(row), row, k));
    for (std::uint32_t row = 0; row < static_cast<std::uint32_t>(rows); ++row)
        for (std::uint32_t k = 0; k < s; ++k) {
            // The upper vertex between lower k and k + 1, and the next one.
            const std::uint32_t j = (k + row % 2) % s, j1 = (j + 1) % s;
            const std::uint32_t a = row * s + k, b = row * s + (k + 1) % s;
            const std::uint32_t up = (row + 1) * s + j, up1 = (row + 1) * s + j1;
            if (outward) {
                mesh.triangles.push_back({a, b, up});
                mesh.triangles.push_back({up, b, up1});
            } else {
                mesh.triangles.push_back({a, up, b});
                mesh.triangles.push_back({up, up1, b});
            }
        }
    return mesh;
}

/// A tube's "wall", "bottom" and "top" on the rings of `grid` (ring_wall, outward): a prism
/// circumscribed about a cylinder (corner the grid's), or about a cone (R(z) / cos(pi / sides)
/// at each ring's height); the bottom and top are fans from the axis. Each wall triangle's
/// points at a height lie on a chord at least R(z) from the axis (the chord between the two
/// rows' corners has its middle at (1 - t) R_row + t R_next / cos(pi / sides) >= R(z)): the
/// wall stays outside the tube.
template <class Corner> std::vector<Solid> tube_solids(const PrismGrid& grid, Corner&& corner) {
    const auto s = static_cast<std::uint32_t>(grid.sides);
    Solid wall{"wall", ring_wall(grid, corner, true)}, bottom{"bottom", {}}, top{"top", {}};
    for (std::uint32_t k = 0; k < s; ++k) {
        bottom.mesh.vertices.push_back(grid.point(corner(0), 0, k));
        top.mesh.vertices.push_back(grid.point(corner(grid.rows), grid.rows, k));
    }
    bottom.mesh.vertices.push_back({0.0, 0.0, grid.z_low});
    top.mesh.vertices.push_back({0.0, 0.0, grid.z_high});
    for (std::uint32_t k = 0; k < s; ++k) {
        const std::uint32_t k1 = (k + 1) % s;
        bottom.mesh.triangles.push_back({s, k1, k});
        top.mesh.triangles.push_back({s, k, k1});
    }
    std::vector<Solid> solids;
    solids.push_back(std::move(wall));
    solids.push_back(std::move(bottom));
    solids.push_back(std::move(top));
    return solids;
}

/// The LAMMPS wall fix on region `region`, with the contact model's words.
inline std::string region_wall(std::string_view fix, std::string_view contact,
                               std::string_view region) {
    return fmt::format("fix             {} all wall/gran/region granular {} region {}\n", fix,
                       contact, region);
}

/// The cell size of level `level` of cells of `cell`.
inline double refined(double cell, int level) {
    return cell / std::ldexp(1.0, level);
}

/// The blockMeshDict of a box one cell beyond a tube of radius `rt` sideways, 0 to height in
/// z, its sides `outside`; `about` names what it holds in its first comment.
inline std::string box_about_tube(double rt, const std::string& about, double height, double cell,
                                  const OpenFoamMeshOptions& options) {
    const int n_side = static_cast<int>(std::ceil(2.0 * rt / cell)) + 2;
    const double half = 0.5 * n_side * cell;
    const int n_z = std::max(1, static_cast<int>(std::ceil(height / cell)));
    return fmt::format(
        "// Box around {about}, height {h}); cells of {cell} (Dp / {cpd}).\n"
        "scale 1;\n\nvertices\n(\n"
        "    ({lo} {lo} 0) ({hi} {lo} 0) ({hi} {hi} 0) ({lo} {hi} 0)\n"
        "    ({lo} {lo} {h}) ({hi} {lo} {h}) ({hi} {hi} {h}) ({lo} {hi} {h})\n);\n\n"
        "blocks\n(\n    hex (0 1 2 3 4 5 6 7) ({n} {n} {nz}) simpleGrading (1 1 1)\n);\n\n"
        "edges\n(\n);\n\nboundary\n(\n"
        "    inlet\n    {{\n        type patch;\n        faces ((0 3 2 1));\n    }}\n"
        "    outlet\n    {{\n        type patch;\n        faces ((4 5 6 7));\n    }}\n"
        "    outside // outside the wall: no cells remain on it after snappyHexMesh\n"
        "    {{\n        type patch;\n"
        "        faces ((0 1 5 4) (1 2 6 5) (2 3 7 6) (3 0 4 7));\n    }}\n);\n",
        fmt::arg("about", about), fmt::arg("h", height), fmt::arg("cell", cell),
        fmt::arg("cpd", options.cells_per_diameter), fmt::arg("lo", -half), fmt::arg("hi", half),
        fmt::arg("n", n_side), fmt::arg("nz", n_z));
}

/// The README's words on the cells of a background about a tube: the background cells and
/// the refinement levels at the particles and at `walls` (snappyHexMesh's wall level).
inline std::string tube_cells(double cell, const OpenFoamMeshOptions& options,
                              std::string_view walls) {
    return fmt::format("Background cells of {} (Dp / {}); refinement level {} at the particles "
                       "(cells of {}), {} at {} (cells of {})",
                       cell, options.cells_per_diameter, options.particle_level,
                       refined(cell, options.particle_level), options.wall_level, walls,
                       refined(cell, options.wall_level));
}

} // namespace packbed::detail
