#include "packbed/box.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
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

std::string Box::spec(bool exact) const {
    std::string out = fmt::format("box:{},{}", detail::spec_length(m_x_high - m_x_low, exact),
                                  detail::spec_length(m_y_high - m_y_low, exact));
    if (m_x_low != 0.0 || m_y_low != 0.0)
        out += fmt::format("@{},{}", detail::spec_length(m_x_low, exact),
                           detail::spec_length(m_y_low, exact));
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
    return {4.0 * lx * ly / (2.0 * (lx + ly)), hydraulic_formula};
}

BoxMargin Box::box_margin() const {
    return {depth(), "a hundredth of half the narrower width", spec()};
}

std::string Box::fit_problem(double largest, const FitWords& words) const {
    return detail::widths_problem(bounds(), largest, words.particle, words);
}

double Box::fill_height(double solid, double e0) const {
    return detail::prism_fill_height(cross_section_area(), solid, e0);
}

/// Each coordinate uniform between the faces less r_i.
Vec3 Box::uniform_point(double radius, double u, double v, double z) const {
    return {m_x_low + radius + (m_x_high - m_x_low - 2.0 * radius) * u,
            m_y_low + radius + (m_y_high - m_y_low - 2.0 * radius) * v, z};
}

std::optional<double> Box::top() const {
    return std::nullopt;
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

/// LX, LY each in (0, max_length].
std::optional<Box> Box::from_numbers(std::span<const double> v) {
    if (v.size() != 2 || !detail::lengths_in(v, limits::max_length))
        return std::nullopt;
    return Box(v[0], v[1]);
}

/// {size: [LX, LY]} (summary.json, from 0 to LX and LY) or a lattice region's [LX, LY, LZ].
std::optional<Box> Box::from_record(const nlohmann::json& record) {
    return from_numbers(detail::record_widths(record, limits::max_length));
}

std::string Box::record_allowed() {
    return detail::widths_record_allowed();
}

std::string Box::allowed() {
    return fmt::format("box:LX,LY, walls at x = 0, LX and y = 0, LY, each in (0, {:g}]",
                       limits::max_length);
}

Box Box::scaled(double factor) const {
    return Box(m_x_low * factor, m_x_high * factor, m_y_low * factor, m_y_high * factor);
}

std::vector<Solid> Box::solids(double z_low, double z_high, double edge) const {
    // Cells per side: ceil(length / edge), the quotient's last bits forgiven, so that a side
    // of exactly k edges gets k cells.
    const auto cells = [edge](double length) {
        return std::clamp(static_cast<int>(std::ceil(length / edge * (1.0 - 1e-12))), 1, 4096);
    };
    const double x0 = m_x_low, x1 = m_x_high, y0 = m_y_low, y1 = m_y_high;
    const int nx = cells(x1 - x0), ny = cells(y1 - y0), nz = cells(z_high - z_low);
    // Grid coordinates, the last one the end itself: every face computes a shared rim
    // vertex by the same expression, so its coordinates are the same bits.
    const auto at = [](double low, double high, int k, int n) {
        return k == 0 ? low : k == n ? high : low + (high - low) * k / n;
    };
    // The four sides, each a grid of its points along the rim (counter-clockwise seen from
    // above, both ends included) times the rows in z.
    const auto side = [&](const char* name, std::vector<std::pair<double, double>> along) {
        Solid face{name, {}};
        for (int row = 0; row <= nz; ++row)
            for (const auto& [x, y] : along)
                face.mesh.vertices.push_back({x, y, at(z_low, z_high, row, nz)});
        const auto s = static_cast<std::uint32_t>(along.size());
        for (std::uint32_t row = 0; row < static_cast<std::uint32_t>(nz); ++row)
            for (std::uint32_t k = 0; k + 1 < s; ++k) {
                // Going round counter-clockwise with z up, the outward normal is on the right.
                const std::uint32_t a = row * s + k, b = a + 1;
                face.mesh.triangles.push_back({a, b, b + s});
                face.mesh.triangles.push_back({a, b + s, a + s});
            }
        return face;
    };
    std::vector<std::pair<double, double>> x_low, x_high, y_low, y_high;
    for (int i = 0; i <= nx; ++i) {
        y_low.emplace_back(at(x0, x1, i, nx), y0);
        y_high.emplace_back(at(x0, x1, nx - i, nx), y1);
    }
    for (int j = 0; j <= ny; ++j) {
        x_high.emplace_back(x1, at(y0, y1, j, ny));
        x_low.emplace_back(x0, at(y0, y1, ny - j, ny));
    }
    std::vector<Solid> solids;
    solids.push_back(side("x_low", std::move(x_low)));
    solids.push_back(side("x_high", std::move(x_high)));
    solids.push_back(side("y_low", std::move(y_low)));
    solids.push_back(side("y_high", std::move(y_high)));
    Solid bottom{"bottom", {}}, top{"top", {}};
    // Bottom and top: the (nx + 1) x (ny + 1) grid of the rectangle at z_low and z_high.
    const auto ux = static_cast<std::uint32_t>(nx + 1);
    for (Solid* face : {&bottom, &top}) {
        const double z = face == &bottom ? z_low : z_high;
        for (int j = 0; j <= ny; ++j)
            for (int i = 0; i <= nx; ++i)
                face->mesh.vertices.push_back({at(x0, x1, i, nx), at(y0, y1, j, ny), z});
        for (std::uint32_t j = 0; j < static_cast<std::uint32_t>(ny); ++j)
            for (std::uint32_t i = 0; i < static_cast<std::uint32_t>(nx); ++i) {
                const std::uint32_t a = j * ux + i, b = a + 1, c = a + ux + 1, d = a + ux;
                if (face == &top) { // normal +z: counter-clockwise seen from above
                    face->mesh.triangles.push_back({a, b, c});
                    face->mesh.triangles.push_back({a, c, d});
                } else {
                    face->mesh.triangles.push_back({a, c, b});
                    face->mesh.triangles.push_back({a, d, c});
                }
            }
    }
    solids.push_back(std::move(bottom));
    solids.push_back(std::move(top));
    return solids;
}

DemSettleWall Box::settle_wall(double height, std::string_view contact) const {
    // Block faces 1 to 6 are xlo, xhi, ylo, yhi, zlo, zhi: the floor and the top open.
    return {fmt::format("box x in [{:.9g}, {:.9g}], y in\n# [{:.9g}, {:.9g}] from the floor z = 0 "
                        "to z = {:.9g}, and the data file's box\n# holds it",
                        x_low(), x_high(), y_low(), y_high(), height),
            fmt::format("# The container: its four sides as a block region open at the floor and "
                        "the top\n# (LAMMPS 2022 has no STL walls for granular fixes; the "
                        "LIGGGHTS input uses packbed's\n# STL), its floor as the plane z = 0.\n"
                        "region          container block {} {} {} {} 0 {} side in open 5 open 6 "
                        "units box\n",
                        x_low(), x_high(), y_low(), y_high(), height) +
                detail::region_wall("side", contact, "container"),
            "the box's four faces"};
}

/// A box: the background is the box itself, [x_low, x_high] x [y_low, y_high] x [0, height],
/// ceil(length / cell) cells along each axis (the quotient's last bits forgiven), so that no
/// cell is longer than `cell`; its four sides are the patch `wall` (type wall). No wall
/// surface, and so no wall refinement.
OpenFoamBackground Box::openfoam_background(double height, double cell,
                                            const OpenFoamMeshOptions& options) const {
    const auto cells = [cell](double length) {
        return std::max(1, static_cast<int>(std::ceil(length / cell * (1.0 - 1e-12))));
    };
    const double x0 = x_low(), x1 = x_high(), y0 = y_low(), y1 = y_high();
    const int nx = cells(x1 - x0), ny = cells(y1 - y0), nz = cells(height);
    OpenFoamBackground b;
    b.block_mesh = fmt::format(
        "// The box x {x0} to {x1}, y {y0} to {y1}, z 0 to {h}: its sides are the wall.\n"
        "// Cells of at most {cell} (Dp / {cpd}) along each axis.\n"
        "scale 1;\n\nvertices\n(\n"
        "    ({x0} {y0} 0) ({x1} {y0} 0) ({x1} {y1} 0) ({x0} {y1} 0)\n"
        "    ({x0} {y0} {h}) ({x1} {y0} {h}) ({x1} {y1} {h}) ({x0} {y1} {h})\n);\n\n"
        "blocks\n(\n    hex (0 1 2 3 4 5 6 7) ({nx} {ny} {nz}) simpleGrading (1 1 1)\n);\n\n"
        "edges\n(\n);\n\nboundary\n(\n"
        "    inlet\n    {{\n        type patch;\n        faces ((0 3 2 1));\n    }}\n"
        "    outlet\n    {{\n        type patch;\n        faces ((4 5 6 7));\n    }}\n"
        "    wall\n    {{\n        type wall;\n"
        "        faces ((0 1 5 4) (1 2 6 5) (2 3 7 6) (3 0 4 7));\n    }}\n);\n",
        fmt::arg("x0", x0), fmt::arg("x1", x1), fmt::arg("y0", y0), fmt::arg("y1", y1),
        fmt::arg("h", height), fmt::arg("cell", cell), fmt::arg("cpd", options.cells_per_diameter),
        fmt::arg("nx", nx), fmt::arg("ny", ny), fmt::arg("nz", nz));
    b.where = fmt::format("the box x {} to {}, y {} to {}", x0, x1, y0, y1);
    b.surfaces = ". No `wall.stl`: the box's four sides are the background mesh's own faces "
                 "(patch `wall`, type wall)";
    b.patches = ", `wall`";
    b.cells = fmt::format(
        "Background cells of {} x {} x {} ({} x {} x {} cells: at most Dp / {} = {}); "
        "refinement level {} at the particles (cells of {}); the wall keeps the background "
        "cells (--wall-level is for a cylinder's wall)",
        (x1 - x0) / nx, (y1 - y0) / ny, height / nz, nx, ny, nz, options.cells_per_diameter, cell,
        options.particle_level, detail::refined(cell, options.particle_level));
    return b;
}

std::vector<double> Box::spec_numbers() const {
    return {m_x_high - m_x_low, m_y_high - m_y_low};
}

/// LX LY H.
double Box::prism_volume(double height) const {
    return (m_x_high - m_x_low) * (m_y_high - m_y_low) * height;
}

/// {shape, size: [LX, LY, H]}.
nlohmann::json Box::region_json(double height) const {
    return {{"shape", "box"}, {"size", {m_x_high - m_x_low, m_y_high - m_y_low, height}}};
}

std::string Box::region_allowed() {
    return fmt::format("three lengths > 0 and at most {:g}", limits::max_length);
}

/// The box less `margin` on every side.
FillWindow Box::fill_window(double margin, double) const {
    return {{m_x_low + margin, m_x_high - margin, m_y_low + margin, m_y_high - margin}};
}

/// The line clipped by the two pairs of faces (Liang-Barsky's slab test).
Chord Box::side_chord(const Vec3& p, const Vec3& u) const {
    double low = -std::numeric_limits<double>::infinity();
    double high = std::numeric_limits<double>::infinity();
    auto clip = [&](double start, double along, double lo, double hi) {
        if (along == 0.0) {
            if (start < lo || start > hi)
                high = low; // parallel to the faces and outside: nothing
            return;
        }
        const double a = (lo - start) / along, b = (hi - start) / along;
        low = std::max(low, std::min(a, b));
        high = std::min(high, std::max(a, b));
    };
    clip(p.x, u.x, m_x_low, m_x_high);
    clip(p.y, u.y, m_y_low, m_y_high);
    return Chord::between(low, high);
}

/// Each of the four faces by one support point along its outward normal (exact).
void Box::convex_wall_contacts(const SupportFunction& support, const Vec3&,
                               const ConvexWallFunction& f) const {
    const Vec3 x_high = support({1.0, 0.0, 0.0}), x_low = support({-1.0, 0.0, 0.0});
    const Vec3 y_high = support({0.0, 1.0, 0.0}), y_low = support({0.0, -1.0, 0.0});
    f({x_high.x - m_x_high, {-1.0, 0.0, 0.0}, x_high});
    f({m_x_low - x_low.x, {1.0, 0.0, 0.0}, x_low});
    f({y_high.y - m_y_high, {0.0, -1.0, 0.0}, y_high});
    f({m_y_low - y_low.y, {0.0, 1.0, 0.0}, y_low});
}

} // namespace packbed
