#include "packbed/lattice.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>

#include <fmt/format.h>

#include "packbed/error.hpp"
#include "packbed/neighbor_list.hpp"

namespace packbed {

namespace {

constexpr double pi = std::numbers::pi;
const double sqrt3 = std::sqrt(3.0);

/// A cell with the balls given as fractions of its edges; the porosity from the ball count.
UnitCell cell(Vec3 edges, std::vector<Vec3> fractions, int coordination) {
    UnitCell c;
    c.edges = edges;
    for (const Vec3& f : fractions)
        c.balls.push_back({f.x * edges.x, f.y * edges.y, f.z * edges.z});
    c.coordination = coordination;
    c.porosity =
        1.0 - static_cast<double>(c.balls.size()) * (pi / 6.0) / (edges.x * edges.y * edges.z);
    return c;
}

/// A 3 x 3 rotation, rows first.
struct Rotation {
    double m[3][3] = {{1, 0, 0}, {0, 1, 0}, {0, 0, 1}};

    Vec3 apply(const Vec3& v) const {
        return {m[0][0] * v.x + m[0][1] * v.y + m[0][2] * v.z,
                m[1][0] * v.x + m[1][1] * v.y + m[1][2] * v.z,
                m[2][0] * v.x + m[2][1] * v.y + m[2][2] * v.z};
    }
    Vec3 apply_inverse(const Vec3& v) const { // the transpose
        return {m[0][0] * v.x + m[1][0] * v.y + m[2][0] * v.z,
                m[0][1] * v.x + m[1][1] * v.y + m[2][1] * v.z,
                m[0][2] * v.x + m[1][2] * v.y + m[2][2] * v.z};
    }
    /// \return this rotation followed by `r`.
    Rotation then(const Rotation& r) const {
        Rotation out;
        for (int i = 0; i < 3; ++i)
            for (int j = 0; j < 3; ++j) {
                out.m[i][j] = 0.0;
                for (int k = 0; k < 3; ++k)
                    out.m[i][j] += r.m[i][k] * m[k][j];
            }
        return out;
    }
};

/// The rotation by `degrees` about axis x, y or z (right-handed). Multiples of 90 degrees are
/// exact, so a lattice turned onto itself keeps every bit.
Rotation about(char axis, double degrees) {
    const double turns = degrees / 90.0;
    double c = std::cos(degrees * pi / 180.0), s = std::sin(degrees * pi / 180.0);
    if (turns == std::round(turns)) {
        const int q = ((static_cast<int>(std::fmod(turns, 4.0)) % 4) + 4) % 4;
        c = q == 0 ? 1.0 : q == 2 ? -1.0 : 0.0;
        s = q == 1 ? 1.0 : q == 3 ? -1.0 : 0.0;
    }
    Rotation r;
    const int i = axis == 'x' ? 1 : axis == 'y' ? 2 : 0; // the plane the rotation turns
    const int j = axis == 'x' ? 2 : axis == 'y' ? 0 : 1;
    r.m[i][i] = c;
    r.m[i][j] = -s;
    r.m[j][i] = s;
    r.m[j][j] = c;
    return r;
}

void require(bool ok, std::string_view what) {
    if (!ok)
        throw InvalidInput(std::string(what));
}

} // namespace

const std::vector<std::pair<std::string, LatticeType>>& lattice_types() {
    static const std::vector<std::pair<std::string, LatticeType>> types{
        {"diamond", LatticeType::diamond}, {"sc", LatticeType::sc},   {"bcc", LatticeType::bcc},
        {"fcc", LatticeType::fcc},         {"hcp", LatticeType::hcp},
    };
    return types;
}

std::string to_string(LatticeType type) {
    for (const auto& [name, value] : lattice_types())
        if (value == type)
            return name;
    return "unknown";
}

UnitCell unit_cell(LatticeType type) {
    switch (type) {
    case LatticeType::diamond: {
        // Tsayger (2013), Table 1: balls A-H in units of d / sqrt(3), cell edge 4 d / sqrt(3).
        const double edge = 4.0 / sqrt3;
        UnitCell c;
        c.edges = {edge, edge, edge};
        const double table1[8][3] = {{0, 0, 0}, {2, 2, 0}, {2, 0, 2}, {0, 2, 2},
                                     {1, 3, 3}, {3, 1, 3}, {1, 1, 1}, {3, 3, 1}};
        for (const auto& b : table1)
            c.balls.push_back({b[0] / sqrt3, b[1] / sqrt3, b[2] / sqrt3});
        c.coordination = 4;
        c.porosity = 1.0 - 8.0 * (pi / 6.0) / (edge * edge * edge); // = 1 - pi sqrt(3) / 16
        return c;
    }
    case LatticeType::sc:
        return cell({1.0, 1.0, 1.0}, {{0, 0, 0}}, 6);
    case LatticeType::bcc: {
        const double a = 2.0 / sqrt3;
        return cell({a, a, a}, {{0, 0, 0}, {0.5, 0.5, 0.5}}, 8);
    }
    case LatticeType::fcc: {
        const double a = std::sqrt(2.0);
        return cell({a, a, a}, {{0, 0, 0}, {0.5, 0.5, 0}, {0.5, 0, 0.5}, {0, 0.5, 0.5}}, 12);
    }
    case LatticeType::hcp:
        return cell({1.0, sqrt3, 2.0 * std::sqrt(2.0 / 3.0)},
                    {{0, 0, 0}, {0.5, 0.5, 0}, {0.5, 1.0 / 6.0, 0.5}, {0, 2.0 / 3.0, 0.5}}, 12);
    }
    throw InvalidInput("unknown lattice type");
}

double region_volume(const LatticeRegion& region) {
    if (const auto* box = std::get_if<BoxRegion>(&region))
        return box->size.x * box->size.y * box->size.z;
    const auto& c = std::get<CylinderRegion>(region);
    return pi / 4.0 * c.diameter * c.diameter * c.height;
}

void LatticeParameters::validate() const {
    require(std::isfinite(diameter) && diameter >= 1e-12 && diameter <= 1e12,
            fmt::format("diameter = {} is not allowed; allowed: 1e-12 to 1e12", diameter));
    auto length_ok = [](double v) { return std::isfinite(v) && v > 0.0 && v <= 1e15; };
    if (const auto* box = std::get_if<BoxRegion>(&region)) {
        require(length_ok(box->size.x) && length_ok(box->size.y) && length_ok(box->size.z),
                fmt::format("region box:{},{},{} is not allowed; allowed: three lengths > 0",
                            box->size.x, box->size.y, box->size.z));
    } else {
        const auto& c = std::get<CylinderRegion>(region);
        require(length_ok(c.diameter) && length_ok(c.height),
                fmt::format("region cylinder:{},{} is not allowed; allowed: diameter and "
                            "height > 0",
                            c.diameter, c.height));
    }
    for (const auto& [axis, degrees] : rotations)
        require((axis == 'x' || axis == 'y' || axis == 'z') && std::isfinite(degrees),
                fmt::format("rotation {}:{} is not allowed; allowed: x, y or z and a finite angle "
                            "in degrees",
                            axis, degrees));
    if (origin)
        require(is_finite(*origin),
                fmt::format("origin = {},{},{} is not allowed; allowed: finite coordinates",
                            origin->x, origin->y, origin->z));
}

Packing fill_lattice(const LatticeParameters& p) {
    p.validate();
    const UnitCell cell = unit_cell(p.type);
    const double d = p.diameter;
    const double r = 0.5 * d;
    const Vec3 edges = cell.edges * d;
    const bool whole = p.keep == LatticeKeep::whole;
    const double slack = 1e-9 * d; // balls touching a wall exactly stay in
    // Bounding box of the centres to keep, and the test for one centre.
    Vec3 lo, hi, origin;
    double reach2 = 0.0; // cylinder: largest squared distance of a kept centre from the axis
    const bool is_box = std::holds_alternative<BoxRegion>(p.region);
    const double margin = whole ? r - slack : -slack;
    if (is_box) {
        const Vec3 size = std::get<BoxRegion>(p.region).size;
        lo = {margin, margin, margin};
        hi = size - lo;
        origin = p.origin.value_or(Vec3{r, r, r});
    } else {
        const auto& c = std::get<CylinderRegion>(p.region);
        const double reach = 0.5 * c.diameter - margin;
        reach2 = reach * reach;
        lo = {-reach, -reach, margin};
        hi = {reach, reach, c.height - margin};
        origin = p.origin.value_or(Vec3{0.0, 0.0, r});
    }
    Packing packing;
    if (!(hi.x >= lo.x && hi.y >= lo.y && hi.z >= lo.z))
        return packing; // the region is thinner than a ball
    Rotation rotation;
    for (const auto& [axis, degrees] : p.rotations)
        rotation = rotation.then(about(axis, degrees));
    // Cells whose balls can reach the bounding box: its corners in lattice coordinates (every
    // ball lies in [0, edge) of its cell).
    Vec3 qlo{1e300, 1e300, 1e300}, qhi{-1e300, -1e300, -1e300};
    for (int corner = 0; corner < 8; ++corner) {
        const Vec3 w{corner & 1 ? hi.x : lo.x, corner & 2 ? hi.y : lo.y, corner & 4 ? hi.z : lo.z};
        const Vec3 q = rotation.apply_inverse(w - origin);
        qlo = {std::min(qlo.x, q.x), std::min(qlo.y, q.y), std::min(qlo.z, q.z)};
        qhi = {std::max(qhi.x, q.x), std::max(qhi.y, q.y), std::max(qhi.z, q.z)};
    }
    auto range = [](double low, double high, double edge) {
        return std::pair{std::floor(low / edge) - 1.0, std::ceil(high / edge) + 1.0};
    };
    const auto [i0, i1] = range(qlo.x, qhi.x, edges.x);
    const auto [j0, j1] = range(qlo.y, qhi.y, edges.y);
    const auto [k0, k1] = range(qlo.z, qhi.z, edges.z);
    const double estimate =
        region_volume(p.region) * (1.0 - cell.porosity) / (pi / 6.0 * d * d * d);
    require(estimate <= 1.2e8,
            fmt::format("the region holds about {:.3g} balls of diameter {}; allowed: at most "
                        "1e8 (a larger diameter or a smaller region)",
                        estimate, d));
    for (double k = k0; k <= k1; ++k)
        for (double j = j0; j <= j1; ++j)
            for (double i = i0; i <= i1; ++i)
                for (const Vec3& b : cell.balls) {
                    const Vec3 c =
                        origin + rotation.apply({i * edges.x + b.x * d, j * edges.y + b.y * d,
                                                 k * edges.z + b.z * d});
                    if (c.x < lo.x || c.x > hi.x || c.y < lo.y || c.y > hi.y || c.z < lo.z ||
                        c.z > hi.z)
                        continue;
                    if (!is_box && c.x * c.x + c.y * c.y > reach2)
                        continue;
                    packing.add(c, r);
                }
    require(packing.size() <= 100'000'000,
            fmt::format("the region holds {} balls; allowed: at most 1e8", packing.size()));
    return packing;
}

LatticeContacts lattice_contacts(const Packing& packing, double tolerance) {
    LatticeContacts out;
    out.contacts.assign(packing.size(), 0);
    out.closest = std::numeric_limits<double>::infinity();
    if (packing.size() < 2)
        return out;
    const double d = packing.mean_diameter();
    NeighborList list;
    list.build(packing.centers, packing.radii, 0.5 * d);
    for (std::size_t i = 0; i < packing.size(); ++i)
        for (const std::uint32_t j : list.neighbors_of(i)) {
            const double dist = norm(packing.centers[j] - packing.centers[i]) / d;
            out.closest = std::min(out.closest, dist);
            if (std::abs(dist - 1.0) <= tolerance)
                ++out.contacts[i];
        }
    return out;
}

} // namespace packbed
