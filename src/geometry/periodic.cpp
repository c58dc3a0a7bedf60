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

std::string Periodic::spec(bool exact) const {
    return fmt::format("periodic:{},{}", detail::spec_length(lx(), exact),
                       detail::spec_length(ly(), exact));
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
std::string Periodic::fit_problem(double largest, const FitWords& words) const {
    return detail::widths_problem(bounds(), 2.0 * largest,
                                  fmt::format("twice {}, for the minimum image", words.particle),
                                  words);
}

double Periodic::fill_height(double solid, double e0) const {
    return detail::prism_fill_height(cross_section_area(), solid, e0);
}

/// Anywhere in the cell.
Vec3 Periodic::uniform_point(double, double u, double v, double z) const {
    return {lx() * u, ly() * v, z};
}

std::optional<double> Periodic::top() const {
    return std::nullopt;
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

/// LX, LY each in (0, max_length].
std::optional<Periodic> Periodic::from_numbers(std::span<const double> v) {
    if (v.size() != 2 || !detail::lengths_in(v, limits::max_length))
        return std::nullopt;
    return Periodic(v[0], v[1]);
}

/// {size: [LX, LY]} (summary.json) or a lattice region's [LX, LY, LZ].
std::optional<Periodic> Periodic::from_record(const nlohmann::json& record) {
    return from_numbers(detail::record_widths(record, limits::max_length));
}

std::string Periodic::record_allowed() {
    return detail::widths_record_allowed();
}

std::string Periodic::allowed() {
    return fmt::format("periodic:LX,LY, a cell periodic in x and y, each in (0, {:g}]",
                       limits::max_length);
}

Periodic Periodic::scaled(double factor) const {
    return Periodic(lx() * factor, ly() * factor);
}

std::vector<Solid> Periodic::solids(double z_low, double z_high, double edge) const {
    // No side wall: the floor and the top of the cell, as a box's.
    std::vector<Solid> box = Box(0.0, lx(), 0.0, ly()).solids(z_low, z_high, edge);
    box.erase(box.begin(), box.end() - 2); // x_low, x_high, y_low, y_high
    return box;
}

DemSettleWall Periodic::settle_wall(double height, std::string_view) const {
    return {fmt::format("cell periodic in x in\n# [0, {:.9g}) and y in [0, {:.9g}) (boundary p p "
                        "f, no side wall), from the floor z = 0 to\n# z = {:.9g}; the data "
                        "file's box is the cell in x and y",
                        lx(), ly(), height),
            "# The container: a cell periodic in x and y (boundary p p f): no side wall; the "
            "floor as\n# the plane z = 0.\n",
            "", "p p f"};
}

/// A periodic cell: the background is the cell itself, [0, LX] x [0, LY] x [0, height], cells
/// as a box's, its x sides and its y sides pairs of `cyclic` patches (x_low/x_high,
/// y_low/y_high), its bottom and top too (z_low/z_high) with OpenFoamMeshOptions::periodic_z,
/// else the patches inlet and outlet; particles.stl holds the bodies cut by a side and their copies
/// across it (periodic_images), so the geometry the sides cut is periodic. No wall.
OpenFoamBackground Periodic::openfoam_background(double height, double size,
                                                 const OpenFoamMeshOptions& options) const {
    const auto cells = [size](double length) {
        return std::max(1, static_cast<int>(std::ceil(length / size * (1.0 - 1e-12))));
    };
    const double x1 = lx(), y1 = ly();
    const int nx = cells(x1), ny = cells(y1), nz = cells(height);
    OpenFoamBackground b;
    b.block_mesh = fmt::format(
        "// The periodic cell x 0 to {x1}, y 0 to {y1}, z 0 to {h}: its sides are cyclic pairs.\n"
        "// Cells of at most {cell} (Dp / {cpd}) along each axis.\n"
        "scale 1;\n\nvertices\n(\n"
        "    (0 0 0) ({x1} 0 0) ({x1} {y1} 0) (0 {y1} 0)\n"
        "    (0 0 {h}) ({x1} 0 {h}) ({x1} {y1} {h}) (0 {y1} {h})\n);\n\n"
        "blocks\n(\n    hex (0 1 2 3 4 5 6 7) ({nx} {ny} {nz}) simpleGrading (1 1 1)\n);\n\n"
        "edges\n(\n);\n\nboundary\n(\n"
        "{ends}"
        "    x_low\n    {{\n        type cyclic;\n        neighbourPatch x_high;\n"
        "        faces ((3 0 4 7));\n    }}\n"
        "    x_high\n    {{\n        type cyclic;\n        neighbourPatch x_low;\n"
        "        faces ((1 2 6 5));\n    }}\n"
        "    y_low\n    {{\n        type cyclic;\n        neighbourPatch y_high;\n"
        "        faces ((0 1 5 4));\n    }}\n"
        "    y_high\n    {{\n        type cyclic;\n        neighbourPatch y_low;\n"
        "        faces ((2 3 7 6));\n    }}\n);\n",
        fmt::arg("x1", x1), fmt::arg("y1", y1), fmt::arg("h", height), fmt::arg("cell", size),
        fmt::arg("cpd", options.cells_per_diameter), fmt::arg("nx", nx), fmt::arg("ny", ny),
        fmt::arg("nz", nz),
        fmt::arg("ends",
                 options.periodic_z
                     ? "    z_low\n    {\n        type cyclic;\n        neighbourPatch z_high;\n"
                       "        faces ((0 3 2 1));\n    }\n"
                       "    z_high\n    {\n        type cyclic;\n        neighbourPatch z_low;\n"
                       "        faces ((4 5 6 7));\n    }\n"
                     : "    inlet\n    {\n        type patch;\n        faces ((0 3 2 1));\n    }\n"
                       "    outlet\n    {\n        type patch;\n        faces ((4 5 6 7));\n    "
                       "}\n"));
    b.where = fmt::format("the periodic cell x 0 to {}, y 0 to {}", x1, y1);
    b.surfaces = " with the copies across the sides of those a side cuts. No wall: the cell's "
                 "sides are the background mesh's own faces, cyclic pairs";
    b.patches = options.periodic_z
                    ? ", `x_low` and `x_high`, `y_low` and `y_high`, `z_low` and `z_high` (cyclic "
                      "pairs); no wall"
                    : ", `x_low` and `x_high`, `y_low` and `y_high` (cyclic pairs); no wall";
    // checkMesh's own limit: with 20, two faces of the particles at skewness 4.4 failed it
    // in the test's cell (docs/surfaces.md).
    b.boundary_skewness = 4;
    b.cells = fmt::format(
        "Background cells of {} x {} x {} ({} x {} x {} cells: at most Dp / {} = {}); "
        "refinement level {} at the particles (cells of {}); --wall-level does not apply",
        x1 / nx, y1 / ny, height / nz, nx, ny, nz, options.cells_per_diameter, size,
        options.particle_level, detail::refined(size, options.particle_level));
    return b;
}

std::vector<double> Periodic::spec_numbers() const {
    return {lx(), ly()};
}

/// LX LY H.
double Periodic::prism_volume(double height) const {
    return lx() * ly() * height;
}

/// {shape, size: [LX, LY, H]}.
nlohmann::json Periodic::region_json(double height) const {
    return {{"shape", "periodic"}, {"size", {lx(), ly(), height}}};
}

std::string Periodic::region_allowed() {
    return fmt::format("three lengths > 0 and at most {:g}", limits::max_length);
}

/// The whole cell: a centre outside it is moved in by whole periods.
FillWindow Periodic::fill_window(double, double) const {
    return {bounds()};
}

/// The cell's periods.
std::optional<Periods> Periodic::periods() const {
    return Periods(*this);
}

/// A periodic cell has no side: the whole line.
Chord Periodic::side_chord(const Vec3&, const Vec3&) const {
    return Chord::whole();
}

/// No wall.
void Periodic::convex_wall_contacts(const SupportFunction&, const Vec3&,
                                    const ConvexWallFunction&) const {}

} // namespace packbed
