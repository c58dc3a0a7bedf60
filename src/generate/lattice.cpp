#include "packbed/lattice.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <numbers>
#include <optional>
#include <type_traits>

#include <fmt/format.h>
#include <fmt/ranges.h>

#include "packbed/error.hpp"
#include "packbed/files.hpp"
#include "packbed/limits.hpp"
#include "packbed/memory.hpp"
#include "packbed/neighbor_list.hpp"
#include "packbed/text.hpp"
#include "packbed/version.hpp"

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

const Registry<LatticeType>& lattice_types() {
    static const Registry<LatticeType> types("type", {{"diamond", LatticeType::diamond},
                                                      {"sc", LatticeType::sc},
                                                      {"bcc", LatticeType::bcc},
                                                      {"fcc", LatticeType::fcc},
                                                      {"hcp", LatticeType::hcp}});
    return types;
}

std::string to_string(LatticeType type) {
    return lattice_types().name(type);
}

const Registry<LatticeKeep>& lattice_keeps() {
    static const Registry<LatticeKeep> keeps(
        "keep", {{"whole", LatticeKeep::whole}, {"centres", LatticeKeep::centres}});
    return keeps;
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
    return region.container.prism_volume(region.height);
}

std::string region_text(const LatticeRegion& region) {
    return fmt::format("{}:{},{}", region.container.name(),
                       fmt::join(region.container.spec_numbers(), ","), region.height);
}

namespace {

/// The checks of single values (LatticeParameters::validate without the fill's size).
void check_values(const LatticeParameters& p) {
    require(std::isfinite(p.diameter) && p.diameter >= limits::min_diameter &&
                p.diameter <= limits::max_diameter,
            fmt::format("diameter = {} is not allowed; allowed: {:g} to {:g}", p.diameter,
                        limits::min_diameter, limits::max_diameter));
    auto length_ok = [](double v) {
        return std::isfinite(v) && v > 0.0 && v <= limits::max_length;
    };
    const Container& container = p.region.container;
    const std::vector<double> numbers = container.spec_numbers();
    require(std::all_of(numbers.begin(), numbers.end(), length_ok) && length_ok(p.region.height) &&
                container.well_formed(),
            fmt::format("--region {} is not allowed; allowed: {}", region_text(p.region),
                        container.region_allowed()));
    if (const std::optional<Periods> cell = container.periods()) {
        const std::string region = region_text(p.region);
        require(p.rotations.empty(),
                fmt::format("--rotate is not allowed with --region {}; allowed: no rotation (the "
                            "lattice must repeat across the periodic cell)",
                            region));
        // The lattice repeats across the cell: whole periods along x and y, at least 2 d.
        const Vec3 edges = unit_cell(p.type).edges * p.diameter;
        const auto periods = [](double length, double edge) {
            const double q = length / edge;
            return std::abs(q - std::round(q)) <= 1e-9 * std::max(1.0, q) ? std::round(q) : 0.0;
        };
        const double nx = periods(cell->lx(), edges.x), ny = periods(cell->ly(), edges.y);
        const auto suggest = [](double length, double edge, double least) {
            return std::max(std::ceil(least / edge - 1e-9), std::round(length / edge)) * edge;
        };
        require(nx >= 1.0 && ny >= 1.0 && cell->lx() >= 2.0 * p.diameter &&
                    cell->ly() >= 2.0 * p.diameter,
                fmt::format("--region {} is not allowed with the {} lattice of --diameter {}; "
                            "allowed: LX and LY whole multiples of its periods {} (x) and {} (y), "
                            "each at least 2 d, e.g. {}:{},{},{}",
                            region, to_string(p.type), p.diameter, edges.x, edges.y,
                            container.name(), suggest(cell->lx(), edges.x, 2.0 * p.diameter),
                            suggest(cell->ly(), edges.y, 2.0 * p.diameter), p.region.height));
    }
    for (const auto& [axis, degrees] : p.rotations)
        require((axis == 'x' || axis == 'y' || axis == 'z') && std::isfinite(degrees),
                fmt::format("rotation {}:{} is not allowed; allowed: x, y or z and a finite angle "
                            "in degrees",
                            axis, degrees));
    if (p.origin)
        require(is_finite(*p.origin),
                fmt::format("origin = {},{},{} is not allowed; allowed: finite coordinates",
                            p.origin->x, p.origin->y, p.origin->z));
}

/// Where fill_lattice looks: the box the kept centres lie in (and, for a cylinder, their
/// largest squared distance from the axis), and the cells whose balls can reach that box.
struct FillPlan {
    Vec3 lo, hi, origin;
    double reach2 = 0.0;
    double inner2 = -1.0;     // an annulus: the smallest squared distance from the axis
    bool by_distance = false; // a cone: keep centres at least `margin` from the wall
    double margin = 0.0;
    std::optional<Periods> period; // a periodic cell: one period of cells, moved into it
    bool is_box = true;
    bool empty = false; // the region is thinner than a ball: nothing to keep
    Rotation rotation;
    std::int64_t i0 = 0, i1 = -1, j0 = 0, j1 = -1, k0 = 0, k1 = -1;
};

/// \throws InvalidInput when the origin is so far from the region that the positions lose
/// their precision, or the region holds or needs trying too many balls.
FillPlan plan_fill(const LatticeParameters& p, const UnitCell& cell) {
    FillPlan f;
    const double d = p.diameter;
    const double r = 0.5 * d;
    const Vec3 edges = cell.edges * d;
    const bool whole = p.keep == LatticeKeep::whole;
    const double slack = 1e-9 * d; // balls touching a wall exactly stay in
    const double margin = whole ? r - slack : -slack;
    const Container& container = p.region.container;
    f.period = container.periods();
    // A periodic cell keeps every centre in x and y (moved into it by whole periods).
    const FillWindow window = container.fill_window(f.period ? 0.0 : margin, p.region.height);
    f.by_distance = window.by_distance;
    f.margin = margin;
    f.reach2 = window.reach2;
    f.inner2 = window.inner2;
    f.is_box = window.reach2 < 0.0;
    f.lo = {window.box.x_low, window.box.y_low, margin};
    f.hi = {window.box.x_high, window.box.y_high, p.region.height - margin};
    // d/2 from each wall at the low corner of a prism, on the axis of a round container.
    f.origin = p.origin.value_or(container.axis().empty() ? Vec3{r, r, r} : Vec3{0.0, 0.0, r});
    if (!(f.hi.x >= f.lo.x && f.hi.y >= f.lo.y && f.hi.z >= f.lo.z)) {
        f.empty = true;
        return f;
    }
    // The positions are origin + (a multiple of the cell edges): the farther the origin, the
    // fewer of their bits remain.
    const Vec3& o = f.origin;
    const double away = std::max(
        {f.lo.x - o.x, o.x - f.hi.x, f.lo.y - o.y, o.y - f.hi.y, f.lo.z - o.z, o.z - f.hi.z, 0.0});
    require(away <= limits::max_lattice_origin_offset * d,
            fmt::format("--origin {},{},{} is not allowed ({:.3g} ball diameters from the region: "
                        "the positions would lose their precision); allowed: within {:g} ball "
                        "diameters of the region",
                        o.x, o.y, o.z, away / d, limits::max_lattice_origin_offset));
    for (const auto& [axis, degrees] : p.rotations)
        f.rotation = f.rotation.then(about(axis, degrees));
    // Cells whose balls can reach the bounding box: its corners in lattice coordinates (every
    // ball lies in [0, edge) of its cell).
    Vec3 qlo{1e300, 1e300, 1e300}, qhi{-1e300, -1e300, -1e300};
    for (int corner = 0; corner < 8; ++corner) {
        const Vec3 w{corner & 1 ? f.hi.x : f.lo.x, corner & 2 ? f.hi.y : f.lo.y,
                     corner & 4 ? f.hi.z : f.lo.z};
        const Vec3 q = f.rotation.apply_inverse(w - f.origin);
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
    require(estimate <= 1.2 * static_cast<double>(limits::max_spheres),
            fmt::format("--region {} holds about {:.3g} {} balls of --diameter {}; allowed: at "
                        "most {:g} (a larger --diameter or a smaller --region)",
                        region_text(p.region), estimate, to_string(p.type), d,
                        static_cast<double>(limits::max_spheres)));
    check_memory(fmt::format("--region {} (about {:.3g} balls)", region_text(p.region), estimate),
                 generation_memory(static_cast<std::uint64_t>(1.2 * estimate)),
                 "a larger --diameter or a smaller --region, or a machine with more memory");
    // A region thin in some direction holds few balls but may span many cells in another.
    const double ni = i1 - i0 + 1.0, nj = j1 - j0 + 1.0, nk = k1 - k0 + 1.0;
    const double positions = ni * nj * nk * static_cast<double>(cell.balls.size());
    require(positions <= limits::max_lattice_positions,
            fmt::format("--region {} is not allowed with {} balls of diameter {}: filling it "
                        "would try {:.3g} ball positions ({:.3g} x {:.3g} x {:.3g} cells, {} per "
                        "cell); allowed: at most {:g} (a larger diameter or a smaller region)",
                        region_text(p.region), to_string(p.type), d, positions, ni, nj, nk,
                        cell.balls.size(), limits::max_lattice_positions));
    // The ranges now span at most 1e9 cells, within max_lattice_origin_offset diameters (plus
    // the region) of the origin: integer loop counters (a double one past 2^53 has i + 1 == i).
    f.i0 = static_cast<std::int64_t>(i0);
    f.i1 = static_cast<std::int64_t>(i1);
    f.j0 = static_cast<std::int64_t>(j0);
    f.j1 = static_cast<std::int64_t>(j1);
    if (f.period) { // exactly one period along x and y (check_values: whole periods)
        f.i0 = f.j0 = 0;
        f.i1 = static_cast<std::int64_t>(std::round(f.period->lx() / edges.x)) - 1;
        f.j1 = static_cast<std::int64_t>(std::round(f.period->ly() / edges.y)) - 1;
    }
    f.k0 = static_cast<std::int64_t>(k0);
    f.k1 = static_cast<std::int64_t>(k1);
    return f;
}

} // namespace

void LatticeParameters::validate() const {
    check_values(*this);
    plan_fill(*this, unit_cell(type));
}

Packing fill_lattice(const LatticeParameters& p) {
    check_values(p);
    const UnitCell cell = unit_cell(p.type);
    const FillPlan f = plan_fill(p, cell);
    const double d = p.diameter;
    const double r = 0.5 * d;
    const Vec3 edges = cell.edges * d;
    Packing packing;
    for (std::int64_t k = f.k0; !f.empty && k <= f.k1; ++k)
        for (std::int64_t j = f.j0; j <= f.j1; ++j)
            for (std::int64_t i = f.i0; i <= f.i1; ++i)
                for (const Vec3& b : cell.balls) {
                    Vec3 c =
                        f.origin + f.rotation.apply({static_cast<double>(i) * edges.x + b.x * d,
                                                     static_cast<double>(j) * edges.y + b.y * d,
                                                     static_cast<double>(k) * edges.z + b.z * d});
                    if (f.period) {
                        c = f.period->wrapped(c);
                        if (c.z < f.lo.z || c.z > f.hi.z)
                            continue;
                        packing.add(c, r);
                        continue;
                    }
                    if (c.x < f.lo.x || c.x > f.hi.x || c.y < f.lo.y || c.y > f.hi.y ||
                        c.z < f.lo.z || c.z > f.hi.z)
                        continue;
                    if (!f.is_box &&
                        (c.x * c.x + c.y * c.y > f.reach2 || c.x * c.x + c.y * c.y < f.inner2))
                        continue;
                    if (f.by_distance && !(p.region.container.wall_distance(c) >= f.margin))
                        continue;
                    packing.add(c, r);
                }
    require(packing.size() <= limits::max_spheres,
            fmt::format("--region {} holds {} {} balls of --diameter {}; allowed: at most {:g}",
                        region_text(p.region), packing.size(), to_string(p.type), d,
                        static_cast<double>(limits::max_spheres)));
    require(packing.size() > 0,
            fmt::format("--region {} holds no {} ball of --diameter {}{}; allowed: a region "
                        "that holds one",
                        region_text(p.region), to_string(p.type), d,
                        p.keep == LatticeKeep::whole ? " wholly inside it" : " centred in it"));
    return packing;
}

LatticeContacts lattice_contacts(const Packing& packing, double tolerance) {
    return lattice_contacts(packing, Periods(0.0, 0.0), tolerance);
}

LatticeContacts lattice_contacts(const Packing& packing, const Periods& cell, double tolerance) {
    const bool periodic = cell.lx() > 0.0; // Periods(0, 0): not periodic
    LatticeContacts out;
    out.contacts.assign(packing.size(), 0);
    out.closest = std::numeric_limits<double>::infinity();
    if (packing.size() < 2)
        return out;
    const double d = packing.mean_diameter();
    NeighborList list;
    if (periodic)
        list.wrap(cell);
    list.build(packing.centers, packing.radii, 0.5 * d);
    // In a cell exactly 2 d wide a ball touches both copies of its neighbour across that
    // period (d away on either side), which the minimum image counts once: every copy one
    // period either way is looked at too (farther than d in any wider cell).
    const int reach = periodic ? 1 : 0;
    for (std::size_t i = 0; i < packing.size(); ++i)
        for (const std::uint32_t j : list.neighbors_of(i)) {
            const Vec3 between = periodic ? cell.separation(packing.centers[i], packing.centers[j])
                                          : packing.centers[j] - packing.centers[i];
            for (int sx = -reach; sx <= reach; ++sx)
                for (int sy = -reach; sy <= reach; ++sy) {
                    const Vec3 copy = between + Vec3{sx * cell.lx(), sy * cell.ly(), 0.0};
                    const double dist = norm(copy) / d;
                    out.closest = std::min(out.closest, dist);
                    if (std::abs(dist - 1.0) <= tolerance)
                        ++out.contacts[i];
                }
        }
    return out;
}

LatticeRegion parse_lattice_region(std::string_view text) {
    const std::string allowed = fmt::format(
        "allowed: a container's spec and the region's height after its numbers, {},HEIGHT, "
        "with lengths > 0 and at most {:g}",
        fmt::join(all_forms, ",HEIGHT, "), limits::max_length);
    // The container's spec and the height after its numbers, every length at most max_length.
    const KindSpec parts = split_kind(text);
    const auto values = parts.parameters ? parse_finite_list(*parts.parameters) : std::nullopt;
    if (values && values->size() >= 2 && std::all_of(values->begin(), values->end(), [](double v) {
            return v > 0.0 && v <= limits::max_length;
        })) {
        const std::string_view spec = text.substr(0, text.rfind(','));
        if (const std::optional<Container> container = parse_container(spec)) {
            // A cone narrowing to its apex below the height would end in a point.
            const double height = values->back();
            if (!(container->cross_section_area(height, height) > 0.0))
                throw InvalidInput(fmt::format(
                    "--region '{}' is not allowed: {} has no cross-section at the region's "
                    "height {} (its apex is below it); allowed: a height where it has one",
                    printable(text.substr(0, 80)), container->spec(), height));
            return {*container, height};
        }
    }
    // A known kind: what its own numbers allow (an annulus's DI below D).
    const auto known = std::find(all_shapes.begin(), all_shapes.end(), parts.kind);
    throw InvalidInput(
        fmt::format("--region '{}' is not allowed; {}{}", printable(text.substr(0, 80)), allowed,
                    known == all_shapes.end()
                        ? std::string()
                        : "; its container: " + allowed_containers(std::span(&*known, 1))));
}

Vec3 parse_lattice_origin(std::string_view text) {
    const auto xyz = parse_finite_list(text);
    if (!xyz || xyz->size() != 3)
        throw InvalidInput(
            fmt::format("--origin '{}' is not allowed; allowed: x,y,z (three finite numbers)",
                        printable(text.substr(0, 80))));
    return Vec3{(*xyz)[0], (*xyz)[1], (*xyz)[2]};
}

std::vector<std::pair<char, double>> parse_rotations(std::string_view text) {
    std::vector<std::pair<char, double>> rotations;
    for (std::string_view rest = text; !rest.empty();) { // AXIS:DEGREES,AXIS:DEGREES...
        const std::size_t comma = rest.find(',');
        const std::string_view item = rest.substr(0, comma);
        const auto angle =
            item.size() > 2 && item[1] == ':' ? parse_finite(item.substr(2)) : std::nullopt;
        if (!angle || (item[0] != 'x' && item[0] != 'y' && item[0] != 'z'))
            throw InvalidInput(fmt::format("--rotate '{}' is not allowed; allowed: AXIS:DEGREES "
                                           "pairs separated by commas, AXIS x, y or z (e.g. "
                                           "z:30,x:10)",
                                           printable(text.substr(0, 80))));
        rotations.emplace_back(item[0], *angle);
        rest = comma == std::string_view::npos ? std::string_view{} : rest.substr(comma + 1);
    }
    return rotations;
}

nlohmann::json lattice_summary(const LatticeParameters& p, const Packing& packing) {
    using nlohmann::json;
    const UnitCell cell = unit_cell(p.type);
    const double d = p.diameter;
    const double r = 0.5 * d;
    json summary;
    summary["version"] = std::string(version);
    summary["generator"] = "lattice";
    summary["type"] = to_string(p.type);
    summary["diameter"] = d;
    summary["keep"] = lattice_keeps().name(p.keep);
    const double volume = region_volume(p.region);
    // A periodic cell is the container (analyze reads it): no side wall, so each ball counts
    // whole between the floor and the top (Periodic::sphere_volume).
    const Container& container = p.region.container;
    const double height = p.region.height;
    summary["region"] = container.region_json(height);
    summary["container"] = container.summary_json();
    const std::optional<Periods> period = container.periods();
    if (period) {
        const Vec3 edges = unit_cell(p.type).edges * d;
        summary["periods"] = {std::round(period->lx() / edges.x),
                              std::round(period->ly() / edges.y)};
    }
    double solid = 0.0;
    for (const Vec3& centre : packing.centers)
        solid += container.sphere_volume(centre, r, 0.0, height);
    const Vec3 origin =
        p.origin.value_or(container.axis().empty() ? Vec3{r, r, r} : Vec3{0.0, 0.0, r});
    summary["origin"] = {origin.x, origin.y, origin.z};
    summary["rotations"] = json::array();
    for (const auto& [axis, degrees] : p.rotations)
        summary["rotations"].push_back({{"axis", std::string(1, axis)}, {"degrees", degrees}});
    summary["balls"] = packing.size();
    summary["lattice"] = {{"porosity", cell.porosity},
                          {"coordination", cell.coordination},
                          {"cell_edges", {cell.edges.x * d, cell.edges.y * d, cell.edges.z * d}},
                          {"balls_per_cell", cell.balls.size()}};
    summary["porosity_region"] = 1.0 - solid / volume;
    const LatticeContacts contacts =
        period ? lattice_contacts(packing, *period) : lattice_contacts(packing);
    std::vector<std::uint64_t> histogram;
    double total = 0.0;
    for (const std::uint32_t k : contacts.contacts) {
        if (histogram.size() <= k)
            histogram.resize(k + 1, 0);
        ++histogram[k];
        total += k;
    }
    summary["contacts"] = {
        {"tolerance_d", 1e-9},
        {"mean", packing.size() ? total / static_cast<double>(packing.size()) : 0.0},
        {"histogram", histogram},
        {"closest_distance_d",
         std::isfinite(contacts.closest) ? json(contacts.closest) : json(nullptr)}};
    return summary;
}

} // namespace packbed
