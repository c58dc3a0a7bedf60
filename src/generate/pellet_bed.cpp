#include "packbed/pellet_bed.hpp"

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <limits>
#include <map>
#include <numbers>
#include <optional>
#include <random>
#include <string>
#include <tuple>
#include <type_traits>
#include <variant>
#include <vector>

#include <fmt/format.h>

#include "../base/fnv1a.hpp"
#include "../base/parallel.hpp"
#include "../base/require.hpp"
#include "generate/friction.hpp"
#include "generate/layers.hpp"
#include "generate/pellet_hull.hpp"
#include "packbed/error.hpp"
#include "packbed/neighbor_list.hpp"
#include "packbed/quaternion.hpp"
#include "packbed/sizes.hpp"
#include "random.hpp"

using packbed::portable_random::uniform01;

namespace packbed {

namespace {

void validate_shape(const MultilobeShape& shape) {
    using detail::require;
    require(shape.lobe.radius > 0.0 && shape.lobe.half_length > 0.0 &&
                std::isfinite(shape.lobe.radius) && std::isfinite(shape.lobe.half_length),
            "shape radius", shape.lobe.radius, "lobes of positive, finite radius and length");
    require(shape.lobes >= 1 && shape.lobes <= 8, "lobes", shape.lobes, "1 to 8");
    require(shape.lobe.bore >= 0.0 && shape.lobe.bore < shape.lobe.radius &&
                (shape.lobes == 1 || shape.lobe.bore == 0.0),
            "bore", shape.lobe.bore, "0 to less than the radius (0 for a multilobe)");
    require(shape.circle >= 0.0 && shape.circle <= shape.lobe.radius &&
                (shape.lobes > 1 || shape.circle == 0.0),
            "lobes' circle", shape.circle, "0 to the lobe's radius (0 for one lobe)");
}

void validate_shape(const SpherocylinderShape& shape) {
    using detail::require;
    require(shape.radius > 0.0 && shape.half_length >= 0.0 && std::isfinite(shape.radius) &&
                std::isfinite(shape.half_length),
            "shape radius", shape.radius, "a positive, finite radius and a length >= 0");
}

} // namespace

void PelletBedParameters::validate() const {
    using detail::require;
    require(particles >= 1 && particles <= 10'000'000, "particles", static_cast<double>(particles),
            "1 to 10^7");
    std::visit([](const auto& s) { validate_shape(s); }, shape);
    require(e0 > 0.0 && e0 < 1.0, "e0", e0, "0 < e0 < 1");
    require(tolerance > 0.0 && tolerance <= 0.1, "tolerance", tolerance, "0 < tolerance <= 0.1");
    require(band_low > tolerance && band_high > band_low && band_high <= 0.2, "band", band_high,
            "tolerance < low < high <= 0.2");
    require(node_spacing >= 0.01 && node_spacing <= 0.2, "node spacing", node_spacing,
            "0.01 to 0.2 d_v");
    require(force_tolerance > 0.0 && force_tolerance <= 1.0, "force tolerance", force_tolerance,
            "0 < force tolerance <= 1");
    require(friction >= 0.0 && friction <= 100.0, "friction", friction, "0 to 100");
    require(wall_friction >= 0.0 && wall_friction <= 100.0, "wall friction", wall_friction,
            "0 to 100");
    require(layer_height == 0.0 || (layer_height >= 10.0 && layer_height <= 1e6), "layer height",
            layer_height, "0 (one piece) or 10 to 1000000 d_v");
    if (scales.empty())
        return;
    require(scales.size() == particles, "scales", static_cast<double>(scales.size()),
            "one per pellet");
    for (const double s : scales)
        require(std::isfinite(s) && s > 0.0, "scale", s, "a finite number > 0");
    const auto [low, high] = scale_range();
    require(high <= max_size_ratio * low, "size ratio", high / low,
            fmt::format("at most {:g}", max_size_ratio));
}

std::pair<double, double> PelletBedParameters::scale_range() const {
    if (scales.empty())
        return {1.0, 1.0};
    const auto [low, high] = std::minmax_element(scales.begin(), scales.end());
    return {*low, *high};
}

double PelletBedParameters::smallest_dimension() const {
    return packbed::smallest_dimension(shape);
}

namespace {

/// A rotation as its matrix, rows first: cheaper than the quaternion for many points.
struct Rotation {
    double m[9];

    explicit Rotation(const Quaternion& q) {
        const double w = q.w, x = q.x, y = q.y, z = q.z;
        m[0] = 1 - 2 * (y * y + z * z);
        m[1] = 2 * (x * y - w * z);
        m[2] = 2 * (x * z + w * y);
        m[3] = 2 * (x * y + w * z);
        m[4] = 1 - 2 * (x * x + z * z);
        m[5] = 2 * (y * z - w * x);
        m[6] = 2 * (x * z - w * y);
        m[7] = 2 * (y * z + w * x);
        m[8] = 1 - 2 * (x * x + y * y);
    }
    Vec3 operator()(const Vec3& v) const {
        return {m[0] * v.x + m[1] * v.y + m[2] * v.z, m[3] * v.x + m[4] * v.y + m[5] * v.z,
                m[6] * v.x + m[7] * v.y + m[8] * v.z};
    }
    Vec3 inverse(const Vec3& v) const {
        return {m[0] * v.x + m[3] * v.y + m[6] * v.z, m[1] * v.x + m[4] * v.y + m[7] * v.z,
                m[2] * v.x + m[5] * v.y + m[8] * v.z};
    }
};

/// What one pair of pellets does to each other: the force on the first (the second gets its
/// opposite), the torques about each one's centroid, the deepest node; and where it presses:
/// the sum of its pushes' sizes (`load`) and of each size times its point from the first's
/// centroid (`lever`): the contact point, lever / load, of a frictional pair's spring.
struct PairPush {
    Vec3 force, torque_first, torque_second, lever;
    double depth = 0.0, load = 0.0;

    /// One push of `size` at `point` from the first's centroid, `depth_here` deep.
    void add_load(double size, const Vec3& point, double depth_here) {
        load += size;
        lever += point * size;
        depth = std::max(depth, depth_here);
    }
};

/// A pellet's contacts with the walls and the floor, one per wall (told apart by their push's
/// direction, as detail::WallSprings does): each one's force, load and lever as PairPush's.
struct WallTouches {
    static constexpr std::size_t capacity = detail::WallSprings::capacity;
    std::array<Vec3, capacity> direction{}, force{}, lever{};
    std::array<double, capacity> load{}, depth{};
    std::size_t count = 0;

    /// A push `f` along the unit `push` at `point` from the centroid, `d` deep.
    void add(const Vec3& f, const Vec3& push, const Vec3& point, double d) {
        std::size_t w = 0;
        while (w < count && dot(direction[w], push) <= 0.9)
            ++w;
        if (w == count) {
            if (count == capacity)
                return;
            direction[count++] = push;
        }
        const double size = norm(f);
        force[w] += f;
        lever[w] += point * size;
        load[w] += size;
        depth[w] = std::max(depth[w], d);
    }
};

/// Nodes begin .. end of a pellet's list, all within `radius` of the body-frame `centre`.
struct NodeGroup {
    std::size_t begin, end;
    Vec3 centre;
    double radius;
};

/// FIRE's constants (Bitzek et al. 2006; Guenole et al. 2020's FIRE 2.0 order of updates).
struct Fire {
    static constexpr int delay = 5;
    static constexpr double grow = 1.1, shrink = 0.5, alpha_start = 0.1, alpha_shrink = 0.99;
    /// dt_min: a floor, so that a kink of the contact law (where the force turns at once)
    /// cannot stop the descent.
    static constexpr double dt_start = 0.05, dt_max = 0.25, dt_min = 1e-3;
    /// The farthest a centroid (or a bounding-sphere point, turning) moves in one step, d_v.
    static constexpr double max_move = 0.02;
};

/// A part of a bed in layers (generate_pellet_bed): its pellets' centroids and orientations,
/// the first `fixed` of them held still, the whole bed's least and greatest scale (so that each
/// part has the bed's tolerance and nodes), and the steps run before it.
struct Part {
    std::vector<Vec3> centre;
    std::vector<Quaternion> turn;
    std::size_t fixed = 0;
    std::pair<double, double> scale_range{1.0, 1.0};
    std::uint64_t steps = 0;
    std::uint32_t layer = 0, layers = 1;
};

/// The solver for pellets of shape S: MultilobeShape (cylinders, rings, multilobes) pressed
/// by its surface's nodes and circles (the level-set contact), SpherocylinderShape by springs
/// on exact depths (its pair_springs and wall_springs).
template <class S> class PelletSolver {
public:
    /// Whether the pellets touch by their surfaces' nodes (else by their exact depths).
    static constexpr bool level_set = std::is_same_v<S, MultilobeShape>;

    /// \param part a part of a bed in layers: its pellets are placed, not inserted
    PelletSolver(const PelletBedParameters& params, const S& shape, const RunControl& control,
                 const Part* part = nullptr)
        : m_params(params)
        , m_shape(shape)
        , m_control(control)
        , m_container(params.container)
        , m_cell(params.container.periods())
        , m_mu(params.friction)
        , m_wall_mu(params.wall_friction) {
        params.validate();
        m_size = 0.5; // d_v = 1
        m_reach = m_shape.bounding_radius(m_size);
        m_volume = m_shape.volume(m_size);
        std::tie(m_scale_low, m_scale_high) = part ? part->scale_range : params.scale_range();
        m_scale =
            params.scales.empty() ? std::vector<double>(params.particles, 1.0) : params.scales;
        m_dmin = params.smallest_dimension() * m_scale_low;
        m_tol = m_params.tolerance * m_dmin;
        if constexpr (level_set)
            place_nodes();
        if (part) {
            m_centre = part->centre;
            m_turn = part->turn;
            m_fixed = part->fixed;
            m_steps = part->steps;
            m_layer = part->layer;
            m_layers = part->layers;
        }
    }

    /// The pellets as insert() places them: centroids and orientations.
    std::pair<std::vector<Vec3>, std::vector<Quaternion>> inserted() {
        insert();
        return {m_centre, m_turn};
    }

    /// The bed as it stands (its depths measured, nothing moved): the packing, the deepest
    /// node and the exact depths.
    PelletBed measured() {
        start_motion();
        forces();
        PelletBed out;
        out.max_depth_nodes = m_depth;
        measure_exact(out);
        fill_packing(out);
        return out;
    }

    PelletBed run() {
        if (m_fixed == 0 && m_centre.empty())
            insert();
        else
            start_motion();
        PelletBed out;
        // A frictional bed pours and goes to the final stage: the settling's band of depths,
        // 15-30 times the tolerance, would lock overlaps that friction holds at any gravity
        // (docs/notes/pellets.md, "Friction: overlaps that friction locks").
        const bool frictional_bed = frictional();
        if (ring() || frictional_bed)
            pour();
        if (!frictional_bed)
            settle();
        lower();
        out.stages = m_stages;
        out.steps = m_steps;
        out.neighbor_builds = m_list.builds();
        out.nodes = m_nodes.size();
        forces();
        out.max_depth_nodes = m_depth;
        out.sliding_pairs = m_sliding.size();
        out.sliding_walls = static_cast<std::size_t>(
            std::count(m_sliding_wall.begin(), m_sliding_wall.end(), char{1}));
        out.friction_kept = frictional();
        out.kicks = m_kicks;
        std::tie(out.residual_force, out.residual_torque) = residual();
        measure_exact(out);
        fill_packing(out);
        return out;
    }

private:
    /// The pellets' centroids (wrapped into a periodic cell), orientations and sizes.
    void fill_packing(PelletBed& out) const {
        out.packing.centers = m_centre;
        out.packing.orientations = m_turn;
        out.packing.radii.resize(m_centre.size());
        for (std::size_t i = 0; i < m_centre.size(); ++i)
            out.packing.radii[i] = size(i);
        if (m_cell)
            for (Vec3& c : out.packing.centers)
                c = m_cell->wrapped(c);
    }

    /// A ring: a cylinder with a bore (its tolerance is of its wall).
    bool ring() const {
        if constexpr (level_set)
            return m_shape.lobe.bore > 0.0;
        else
            return false;
    }

    /// The level-set contact's nodes, circles and node groups, and a ring's blend.
    void place_nodes() {
        const bool ring = this->ring();
        // At size 1 the spacing the largest pellet's nodes have in the bed, and the tolerance of
        // the smallest one's depths.
        const double spacing = m_params.node_spacing / (m_size * m_scale_high);
        // A multilobe's and a ring's wall nodes close enough that a rim between two of them
        // reaches at most half the tolerance past them (a chord s of a circle of radius R lies
        // s^2 / (8 R) inside it): s = sqrt(4 R tol), both at size 1. Coarser, a rim can press
        // a wall deeper than the tolerance while no node feels it (docs/notes/pellets.md,
        // "Wall nodes"). A cylinder's keep the spacing its beds were measured with.
        const double tol_at_size = m_tol / (m_size * m_scale_high);
        const double wall_spacing =
            m_shape.lobes > 1 || ring
                ? std::min(spacing, std::sqrt(4.0 * m_shape.lobe.radius * tol_at_size))
                : spacing;
        for (const bool rows : {false, true})
            for (SurfaceNode node : m_shape.surface_nodes(rows ? wall_spacing : spacing, rows)) {
                node.point = node.point * m_size;
                node.area *= m_size * m_size;
                (rows ? m_wall_nodes : m_nodes).push_back(node);
            }
        // A ring's rows as close as its wall nodes: two sides crossing at the tolerance's
        // depth touch over about sqrt(8 R tol) along each, which coarser rows can straddle.
        m_circles = m_shape.surface_circles(spacing, ring ? wall_spacing : 0.0);
        // The nodes off the circles in two groups, below and above the body's middle (a
        // cylinder's ends), each with the sphere about its mean that holds it.
        const auto below = std::stable_partition(
            m_nodes.begin(), m_nodes.end(), [](const SurfaceNode& o) { return o.point.z < 0.0; });
        const std::size_t split = static_cast<std::size_t>(below - m_nodes.begin());
        for (const auto& [begin, end] :
             {std::pair{std::size_t{0}, split}, std::pair{split, m_nodes.size()}}) {
            if (begin == end)
                continue;
            NodeGroup group{begin, end, {}, 0.0};
            for (std::size_t k = begin; k < end; ++k)
                group.centre += m_nodes[k].point * (1.0 / static_cast<double>(end - begin));
            for (std::size_t k = begin; k < end; ++k)
                group.radius = std::max(group.radius, norm(m_nodes[k].point - group.centre));
            m_groups.push_back(group);
        }
        if (ring)
            m_blend = std::min(edge_blend, tol_at_size);
    }

    /// Section 3.1 of the paper over the container's cross-section with the pellet's bounding
    /// radius for the sphere's, each pellet turned uniformly at random, and without overlap:
    /// a draw whose bounding sphere meets an earlier one's is drawn again (random sequential
    /// addition), so that the pellets start apart and pour. A deep overlap of two pellets
    /// can hold the level-set contact in a local minimum (nodes pushed out through opposite
    /// faces), which a pour never makes.
    void insert() {
        const std::size_t n = m_params.particles;
        // A ring's bounding sphere holds 2.5 times its volume (D = L = 2 DI), more than the
        // cylinder's 1.9 that e0 = 0.87 leaves a quarter of the column: its column is loosened
        // until the spheres fill a quarter of it again.
        double e0 = m_params.e0;
        if (ring())
            e0 = std::max(e0,
                          1.0 - 0.25 * m_volume /
                                    (4.0 / 3.0 * std::numbers::pi * m_reach * m_reach * m_reach));
        // Random addition jams below the column's e0 where the tube is narrow beside the
        // pellet (rings at a = 3: no room for the 19th of 20 in 10 000 draws): the column is
        // then drawn again from the start with its solid fraction halved, up to
        // column_loosenings times. A column that draws at the first try keeps its bits.
        for (int loosened = 0;; ++loosened) {
            if (draw_column(e0))
                break;
            if (loosened == column_loosenings)
                throw InvalidInput(fmt::format(
                    "particles = {} is not allowed in {}: {} draws found no room for a pellet "
                    "even in a column of void fraction {:.6g}; allowed: fewer pellets or a "
                    "wider container",
                    n, m_container.describe(), insert_attempts, e0));
            e0 = 1.0 - 0.5 * (1.0 - e0);
        }
        start_motion();
    }

    /// Every pellet at rest, its friction's springs unstretched.
    void start_motion() {
        const std::size_t n = m_centre.size();
        m_velocity.assign(n, Vec3{});
        m_spin.assign(n, Vec3{});
        m_force.assign(n, Vec3{});
        m_torque.assign(n, Vec3{});
        if (frictional()) {
            m_moved.assign(n, Vec3{});
            m_turned.assign(n, Vec3{});
            m_wall_springs.assign(n, detail::WallSprings{});
            m_sliding_wall.assign(n, 0);
            m_order.resize(n);
            for (std::size_t i = 0; i < n; ++i)
                m_order[i] = static_cast<std::uint32_t>(i);
        }
    }

    /// Random sequential addition of the pellets into the column of void fraction e0 (insert()):
    /// each one's position (and a spherocylinder's orientation) drawn until it keeps apart from
    /// the earlier ones (a draw that failed before is cleared first). \return false where a
    /// pellet finds no room in insert_attempts draws.
    bool draw_column(double e0) {
        const std::size_t n = m_params.particles;
        m_centre.clear();
        m_turn.clear();
        const double reach = m_reach * m_scale_high; // the largest pellet's
        const double height = m_container.fill_height(column_volume(), e0);
        if (const auto top = m_container.top(); top && height + 2.0 * reach > *top)
            throw InvalidInput(fmt::format(
                "particles = {} is not allowed in {}: the pellets' column ({:.6g} d_v at e0 = "
                "{}) reaches above its top; allowed: fewer pellets or a taller container",
                n, m_container.describe(), height + 2.0 * reach, e0));
        std::mt19937_64 rng(m_params.seed);
        const double cell = 2.0 * reach;
        const auto key = [cell](const Vec3& p) {
            return std::array<long, 3>{static_cast<long>(std::floor(p.x / cell)),
                                       static_cast<long>(std::floor(p.y / cell)),
                                       static_cast<long>(std::floor(p.z / cell))};
        };
        std::map<std::array<long, 3>, std::vector<std::uint32_t>> grid;
        // Apart: their bounding spheres (level-set pellets), or their exact gap at least
        // insert_gap (a spherocylinder, whose bounding sphere holds 3.2 times its volume at
        // L = D and more as it grows longer: the spheres' addition would jam far below the
        // column's e0).
        // Pellet i (the one drawn) apart from the earlier j, d from i's centroid to j's.
        const auto apart = [&](std::size_t i, const Vec3& p, const Quaternion& turn,
                               std::uint32_t j, const Vec3& d) {
            const double both = reach_of(i) + reach_of(j);
            if (!(norm2(d) < both * both))
                return true;
            if constexpr (level_set)
                return false;
            else
                return m_shape.pair_gap({p, turn, size(i)}, m_shape, {p + d, m_turn[j], size(j)},
                                        d) >= insert_gap;
        };
        const auto clear = [&](std::size_t i, const Vec3& p, const Quaternion& turn) {
            if (m_cell) { // the minimum image: every earlier pellet (the grid's cells do not wrap)
                for (std::size_t j = 0; j < m_centre.size(); ++j)
                    if (!apart(i, p, turn, static_cast<std::uint32_t>(j),
                               m_cell->separation(p, m_centre[j])))
                        return false;
                return true;
            }
            const auto k = key(p);
            for (long dx = -1; dx <= 1; ++dx)
                for (long dy = -1; dy <= 1; ++dy)
                    for (long dz = -1; dz <= 1; ++dz) {
                        const auto found = grid.find({k[0] + dx, k[1] + dy, k[2] + dz});
                        if (found == grid.end())
                            continue;
                        for (const std::uint32_t j : found->second)
                            if (!apart(i, p, turn, j, m_centre[j] - p))
                                return false;
                    }
            return true;
        };
        for (std::size_t i = 0; i < n; ++i) {
            Vec3 p;
            Quaternion turn;
            int tries = 0;
            do {
                if (++tries > insert_attempts)
                    return false;
                const double u = uniform01(rng), v = uniform01(rng);
                const double z = height * uniform01(rng) + reach_of(i);
                p = m_container.uniform_point(reach_of(i), u, v, z);
                if constexpr (!level_set) { // drawn with the position: the gap depends on it
                    const double u1 = uniform01(rng), u2 = uniform01(rng), u3 = uniform01(rng);
                    turn = uniform_rotation(u1, u2, u3);
                }
            } while (!clear(i, m_cell ? m_cell->wrapped(p) : p, turn));
            if (m_cell)
                p = m_cell->wrapped(p);
            grid[key(p)].push_back(static_cast<std::uint32_t>(i));
            m_centre.push_back(p);
            if constexpr (level_set) {
                const double u1 = uniform01(rng), u2 = uniform01(rng), u3 = uniform01(rng);
                turn = uniform_rotation(u1, u2, u3);
            }
            m_turn.push_back(turn);
        }
        return true;
    }

    /// Pellet i's size (Placement::size: d_v / 2 of the reference pellet times its scale) and
    /// its bounding radius.
    double size(std::size_t i) const { return m_size * m_scale[i]; }
    double reach_of(std::size_t i) const { return m_reach * m_scale[i]; }

    /// The pellets' volume in units of the reference pellet's: their number, or the sum of
    /// their scales cubed.
    double column_volume() const {
        if (m_params.scales.empty())
            return static_cast<double>(m_params.particles);
        double volume = 0.0;
        for (const double s : m_scale)
            volume += s * s * s;
        return volume;
    }

    /// The cylinder that holds a pellet of scale `scale` (detail::HullCylinder), in the bed's
    /// lengths.
    detail::HullCylinder hull(double scale) const {
        return {m_shape.lobe.half_length * m_size * scale,
                (m_shape.circle + m_shape.lobe.radius) * m_size * scale};
    }

    /// Nodes of pellet a (scale sa) pressed out of pellet b (scale sb), b's centroid at u from
    /// a's: adds to `push` (force on a, torques on a and b).
    void press(const Rotation& ra, const Rotation& rb, double sa, double sb, const Vec3& u,
               double sign, PairPush& push) const {
        const double reach_b = m_reach * sb, reach2 = reach_b * reach_b, size_b = m_size * sb;
        const MultilobeShape& shape = m_shape;
        const Vec3 b_axis = rb(Vec3{0.0, 0.0, 1.0});
        const detail::HullCylinder hull = this->hull(sb);
        // The nodes in groups (an end's disc) whose bounding sphere is skipped when it misses
        // b's or b's hull.
        for (const NodeGroup& group : m_groups) {
            const Vec3 centre = ra(group.centre * sa) - u;
            const double radius = group.radius * sa;
            if (norm(centre) >= radius + reach_b ||
                detail::clear_of_hull(hull, b_axis, centre, radius, radius, hull_margin * size_b))
                continue;
            for (std::size_t g = group.begin; g < group.end; ++g) {
                const SurfaceNode& node = m_nodes[g];
                const Vec3 p = ra(node.point * sa);
                const Vec3 d = p - u;
                if (norm2(d) >= reach2)
                    continue;
                const InsideDepth in = shape.inside(rb.inverse(d) * (1.0 / size_b), m_blend);
                if (in.depth <= 0.0)
                    continue;
                const double depth = in.depth * size_b;
                const Vec3 f = rb(in.normal) * (node.area * (sa * sa) * depth);
                // f pushes a's node out of b: on a at p, on b (opposite) at d from b's centroid.
                push.force += f * sign;
                (sign > 0 ? push.torque_first : push.torque_second) += cross(p, f);
                (sign > 0 ? push.torque_second : push.torque_first) -= cross(d, f);
                push.add_load(node.area * (sa * sa) * depth, sign > 0 ? p : d, depth);
            }
        }
    }

    /// Pellet a's circles (its side's rows and rims) pressed out of pellet b as curves: the
    /// energy k/2 lambda integral of depth^2 along each circle's part inside b (lambda its
    /// area per length), force and torque the integrals of the nodes' along it. Only the arc
    /// inside b's bounding sphere is searched: points on it 2 pi / circle_samples apart, each
    /// local maximum of the signed depth within half a step's arc of b's surface (the depth
    /// changes at most as fast as the point moves) refined by golden-section search (a
    /// crossing shorter than the step), the ends of the parts
    /// inside by bisection; each piece between found points is integrated by 4-point
    /// Gauss-Legendre.
    void press_circles(const Rotation& ra, const Rotation& rb, double sa, double sb, const Vec3& u,
                       double sign, PairPush& push) const {
        const MultilobeShape& shape = m_shape;
        const Vec3 axis = ra(Vec3{0.0, 0.0, 1.0}), x = ra(Vec3{1.0, 0.0, 0.0}),
                   y = ra(Vec3{0.0, 1.0, 0.0}), b_axis = rb(Vec3{0.0, 0.0, 1.0});
        const detail::HullCylinder hull = this->hull(sb);
        const double size_a = m_size * sa, size_b = m_size * sb;
        // cos and sin of the fixed sample angles k 2 pi / circle_samples.
        constexpr double step = 2.0 * std::numbers::pi / circle_samples;
        static const std::array<std::pair<double, double>, circle_samples> around = [] {
            std::array<std::pair<double, double>, circle_samples> out;
            for (int k = 0; k < circle_samples; ++k)
                out[k] = {std::cos(k * step), std::sin(k * step)};
            return out;
        }();
        const double reach_b = m_reach * sb, reach2 = reach_b * reach_b;
        for (const SurfaceCircle& circle : m_circles) {
            // The circle's centre from b's, and the disc b's bounding sphere cuts its plane in.
            const bool off_axis = circle.x != 0.0 || circle.y != 0.0;
            const Vec3 centre = off_axis ? ra(Vec3{circle.x, circle.y, circle.z} * size_a) - u
                                         : axis * (circle.z * size_a) - u;
            const double h = dot(centre, axis);
            if (h * h >= reach2)
                continue;
            // A circle outside b's hull: by its centre's distance less its radius from b's
            // axis, or beyond an end plane by its reach along b's axis.
            const double radius = circle.radius * size_a, tilt = dot(axis, b_axis);
            if (detail::clear_of_hull(hull, b_axis, centre, radius,
                                      radius * std::sqrt(std::max(0.0, 1.0 - tilt * tilt)),
                                      hull_margin * size_b))
                continue;
            const double disc = std::sqrt(reach2 - h * h);
            const Vec3 towards = axis * h - centre; // to b's centre, in the plane
            const double d = norm(towards);
            if (d - radius >= disc || radius - d >= disc)
                continue;
            const double mid = std::atan2(dot(towards, y), dot(towards, x));
            const double half =
                d + radius <= disc || d == 0.0
                    ? std::numbers::pi
                    : std::acos(std::clamp(
                          (radius * radius + d * d - disc * disc) / (2.0 * radius * d), -1.0, 1.0));
            // The circle in b's body frame at b's size 1: q(t) = q0 + e1 cos t + e2 sin t.
            const Vec3 q0 = rb.inverse(centre) * (1.0 / size_b);
            const double across = circle.radius * (sa / sb);
            const Vec3 e1 = rb.inverse(x) * across, e2 = rb.inverse(y) * across;
            const auto at = [&](double t) { return q0 + e1 * std::cos(t) + e2 * std::sin(t); };
            // Off the circle's arc (a lobe's side inside its neighbours) nothing presses.
            const bool whole = circle.arc_half >= std::numbers::pi;
            const auto on_arc = [&](double t) {
                return whole || std::abs(std::remainder(t - circle.arc_middle,
                                                        2.0 * std::numbers::pi)) <= circle.arc_half;
            };
            constexpr double off = -std::numeric_limits<double>::infinity();
            const auto depth_at = [&](double t) {
                return on_arc(t) ? shape.signed_depth(at(t)) * size_b : off;
            };
            // The samples at fixed angles k 2 pi / circle_samples, from the last before the
            // arc to the first after it: they do not move with the pellets, so neither do the
            // pieces the integral is split into.
            const long k_first = static_cast<long>(std::floor((mid - half) / step));
            const long k_last = std::min(static_cast<long>(std::ceil((mid + half) / step)),
                                         k_first + circle_samples);
            std::vector<std::pair<double, double>>& points = m_points;
            points.clear();
            double best = -std::numeric_limits<double>::infinity();
            for (long k = k_first; k <= k_last; ++k) {
                const auto& [c, s] = around[static_cast<std::size_t>(
                    ((k % circle_samples) + circle_samples) % circle_samples)];
                points.emplace_back(
                    k * step,
                    on_arc(k * step) ? shape.signed_depth(q0 + e1 * c + e2 * s) * size_b : off);
                best = std::max(best, points.back().second);
            }
            const int n = static_cast<int>(points.size()) - 1;
            // The depth changes at most as fast as the point moves: a part inside b lies within
            // half a step's arc of a sample at least this deep.
            const double probe = 0.5 * step * radius;
            if (best < -probe)
                continue;
            // Each sampled local maximum near b's surface refined: inserted in order of angle.
            for (int k = n - 1; k >= 1; --k) {
                const double here = points[k].second;
                if (here < points[k - 1].second || here < points[k + 1].second || here < -probe)
                    continue;
                double lo = points[k - 1].first, hi = points[k + 1].first;
                constexpr double golden = 0.6180339887498949;
                double x1 = hi - golden * (hi - lo), x2 = lo + golden * (hi - lo);
                double f1 = depth_at(x1), f2 = depth_at(x2);
                for (int it = 0; it < 24; ++it) {
                    if (f1 < f2) {
                        lo = x1;
                        x1 = x2;
                        f1 = f2;
                        x2 = lo + golden * (hi - lo);
                        f2 = depth_at(x2);
                    } else {
                        hi = x2;
                        x2 = x1;
                        f2 = f1;
                        x1 = hi - golden * (hi - lo);
                        f1 = depth_at(x1);
                    }
                }
                const double t = 0.5 * (lo + hi);
                points.insert(points.begin() + (t < points[k].first ? k : k + 1), {t, depth_at(t)});
            }
            for (std::size_t k = 0; k + 1 < points.size(); ++k) {
                double t0 = points[k].first, t1 = points[k + 1].first;
                const double d0 = points[k].second, d1 = points[k + 1].second;
                if (d0 <= 0.0 && d1 <= 0.0)
                    continue;
                // The piece's end inside b, the other end moved to the crossing.
                if (d0 <= 0.0 || d1 <= 0.0) {
                    double in = d0 > 0.0 ? t0 : t1, out = d0 > 0.0 ? t1 : t0;
                    for (int it = 0; it < 24; ++it) {
                        const double m = 0.5 * (in + out);
                        (depth_at(m) > 0.0 ? in : out) = m;
                    }
                    (d0 > 0.0 ? t1 : t0) = in;
                }
                // 4-point Gauss-Legendre over [t0, t1].
                static constexpr std::array<double, 4> gx{-0.8611363115940526, -0.3399810435848563,
                                                          0.3399810435848563, 0.8611363115940526};
                static constexpr std::array<double, 4> gw{0.3478548451374538, 0.6521451548625461,
                                                          0.6521451548625461, 0.3478548451374538};
                const double span = 0.5 * (t1 - t0), centre_t = 0.5 * (t1 + t0);
                for (int g = 0; g < 4; ++g) {
                    if (!on_arc(centre_t + span * gx[g]))
                        continue;
                    const Vec3 q = at(centre_t + span * gx[g]);
                    const InsideDepth in = shape.inside(q, m_blend);
                    if (in.depth <= 0.0)
                        continue;
                    const double depth = in.depth * size_b;
                    const double weight = gw[g] * span * radius * circle.area_per_length * size_a;
                    const Vec3 f = rb(in.normal) * (weight * depth);
                    const Vec3 from_b = rb(q) * size_b;
                    const Vec3 from_a = from_b + u;
                    push.force += f * sign;
                    (sign > 0 ? push.torque_first : push.torque_second) += cross(from_a, f);
                    (sign > 0 ? push.torque_second : push.torque_first) -= cross(from_b, f);
                    push.add_load(weight * depth, sign > 0 ? from_a : from_b, depth);
                }
            }
        }
    }

    /// A pair pressed apart by its springs (SpherocylinderShape::pair_springs), each of
    /// exact_contact_stiffness along its normal at its point, as two soft spheres; the depth
    /// recorded is the exact one (pair_overlap).
    void press_exact(std::size_t a, std::size_t b, const Vec3& u, PairPush& push) const {
        const Placement pa{m_centre[a], m_turn[a], size(a)},
            pb{m_centre[a] + u, m_turn[b], size(b)};
        const double depth = m_shape.pair_springs(
            pa, m_shape, pb, u, [&](double spring, const Vec3& normal, const Vec3& point) {
                const Vec3 f = normal * (exact_contact_stiffness * spring); // on b, from a
                push.force -= f;
                push.load += exact_contact_stiffness * spring;
                push.lever += point * (exact_contact_stiffness * spring);
                push.torque_first -= cross(point, f);
                push.torque_second += cross(point - u, f);
            });
        push.depth = std::max(0.0, depth);
    }

    /// Pellet i pressed out of the floor and the side walls by the same springs
    /// (SpherocylinderShape::wall_springs): adds to `force` and `torque`; \return the deepest
    /// exact depth (the side walls' by the springs' law, exact where they are convex towards
    /// the inside; measure_exact's search at the end).
    double press_walls_exact(std::size_t i, Vec3& force, Vec3& torque, WallTouches& touches) const {
        const Placement p{m_centre[i], m_turn[i], size(i)};
        const double side = m_shape.wall_springs(
            m_container, p, [&](double depth, const Vec3& push, const Vec3& at) {
                const Vec3 f = push * (exact_contact_stiffness * depth);
                force += f;
                torque += cross(at - p.position, f);
                // Where friction grips: the pellet's point farthest into the wall.
                if (frictional())
                    touches.add(f, push, m_shape.support(p, -push) - p.position, depth);
            });
        return std::max(side, -m_shape.support(p, {0, 0, -1}).z);
    }

    /// Whether pellets a and b, b's centroid at u from a's, are closer than their bounding
    /// radii together.
    bool within_reach(std::size_t a, std::size_t b, const Vec3& u) const {
        const double both = reach_of(a) + reach_of(b);
        return norm2(u) < both * both;
    }

    Vec3 separation(std::size_t a, std::size_t b) const {
        return m_cell ? m_cell->separation(m_centre[a], m_centre[b]) : m_centre[b] - m_centre[a];
    }

    /// Forces and torques on every pellet at the current state; m_depth the deepest node.
    void forces() {
        const std::size_t n = m_centre.size();
        if (m_list.needs_rebuild(m_centre)) {
            if (m_cell)
                for (Vec3& c : m_centre)
                    c = m_cell->wrapped(c);
            if (m_cell)
                m_list.wrap(*m_cell);
            if (frictional())
                m_carry.save(m_list.pair_first(), m_list.pair_second(), m_pair_spring, m_order);
            std::vector<double> radii(n);
            for (std::size_t i = 0; i < n; ++i)
                radii[i] = reach_of(i);
            m_list.build(m_centre, radii, skin);
            if (frictional()) {
                m_pair_spring.resize(m_list.pairs());
                const auto first = m_list.pair_first();
                const auto second = m_list.pair_second();
                for (std::size_t k = 0; k < m_list.pairs(); ++k)
                    m_pair_spring[k] = m_carry.find(first[k], second[k]);
            }
        }
        std::vector<Rotation> turn;
        turn.reserve(n);
        for (const Quaternion& q : m_turn)
            turn.emplace_back(q);
        const std::size_t pairs = m_list.pairs();
        m_push.assign(pairs, PairPush{});
        const auto first = m_list.pair_first();
        const auto second = m_list.pair_second();
#pragma omp parallel for schedule(dynamic, 4) if (pairs >= parallel_min_pellets)
        for (std::size_t k = 0; k < pairs; ++k) {
            const std::size_t a = first[k], b = second[k];
            if (a < m_fixed && b < m_fixed) // two held pellets: nothing of theirs moves
                continue;
            const Vec3 u = separation(a, b);
            if (!within_reach(a, b, u))
                continue;
            if constexpr (level_set) {
                // A pair whose hulls a plane parts presses nothing: skipped.
                const double sa = m_scale[a], sb = m_scale[b];
                if (detail::hulls_apart(hull(sa), hull(sb), turn[a](Vec3{0.0, 0.0, 1.0}),
                                        turn[b](Vec3{0.0, 0.0, 1.0}), u,
                                        hull_margin * m_size * std::min(sa, sb)))
                    continue;
                press(turn[a], turn[b], sa, sb, u, 1.0, m_push[k]);
                press(turn[b], turn[a], sb, sa, -u, -1.0, m_push[k]);
                press_circles(turn[a], turn[b], sa, sb, u, 1.0, m_push[k]);
                press_circles(turn[b], turn[a], sb, sa, -u, -1.0, m_push[k]);
            } else {
                press_exact(a, b, u, m_push[k]);
            }
        }
        m_wall_depth.assign(n, 0.0);
        const double weight = m_gravity * m_volume;
#pragma omp parallel for schedule(dynamic, 4) if (n >= parallel_min_pellets)
        for (std::size_t i = m_fixed; i < n; ++i) {
            const double s = m_scale[i], reach = reach_of(i);
            Vec3 force{0.0, 0.0, -weight * (s * s * s)}, torque;
            const Vec3& c = m_centre[i];
            const bool floor = c.z < reach;
            WallTouches touches;
            if constexpr (!level_set) {
                if (floor || m_container.wall_overlap(c, reach) > 0.0)
                    m_wall_depth[i] = press_walls_exact(i, force, torque, touches);
            } else if (floor || m_container.wall_overlap(c, reach) > 0.0) {
                double deepest = 0.0;
                for (const SurfaceNode& node : m_wall_nodes) {
                    const Vec3 p = turn[i](node.point * s);
                    const Vec3 at = c + p;
                    const auto add = [&](double depth, const Vec3& push) {
                        const Vec3 f = push * (node.area * (s * s) * depth);
                        force += f;
                        torque += cross(p, f);
                        deepest = std::max(deepest, depth);
                        if (frictional())
                            touches.add(f, push, p, depth);
                    };
                    if (at.z < 0.0)
                        add(-at.z, {0.0, 0.0, 1.0});
                    m_container.wall_contacts(at, 0.0, add);
                }
                m_wall_depth[i] = deepest;
            }
            if (frictional())
                wall_friction(i, touches, force, torque);
            m_force[i] = force;
            m_torque[i] = torque;
        }
        // The pairs' shares added in pair order: the same sums whatever the thread count.
        double deepest = 0.0;
        for (std::size_t k = 0; k < pairs; ++k) {
            const PairPush& p = m_push[k];
            m_force[first[k]] += p.force;
            m_force[second[k]] -= p.force;
            m_torque[first[k]] += p.torque_first;
            m_torque[second[k]] += p.torque_second;
            deepest = std::max(deepest, p.depth);
            if (frictional())
                pair_friction(k);
        }
        m_pair_depth = deepest;
        if (frictional()) { // each step's moves are slipped once
            std::fill(m_moved.begin(), m_moved.end(), Vec3{});
            std::fill(m_turned.begin(), m_turned.end(), Vec3{});
        }
        // The pairs whose exact depth the nodes leave above tolerance (lower()): a spring on
        // the depth's excess over half the tolerance, along the normal at the contact point.
        for (const auto& [a, b] : m_exact_pairs) {
            const Vec3 u = separation(a, b);
            const PairOverlap o = m_shape.pair_overlap({m_centre[a], m_turn[a], size(a)}, m_shape,
                                                       {m_centre[a] + u, m_turn[b], size(b)}, u);
            const double excess = o.depth - 0.5 * m_tol;
            if (!(excess > 0.0))
                continue;
            const Vec3 f = o.normal * (exact_stiffness * excess); // on b, from a
            m_force[a] -= f;
            m_force[b] += f;
            m_torque[a] -= cross(o.point, f);
            m_torque[b] += cross(o.point - u, f);
        }
        m_wall_max = 0.0;
        for (const double d : m_wall_depth)
            m_wall_max = std::max(m_wall_max, d);
        m_depth = std::max(m_pair_depth, m_wall_max);
    }

    /// Whether the contacts carry tangential springs (PelletBedParameters::friction,
    /// wall_friction), until lower() lets them go.
    bool frictional() const {
        return m_mu > 0.0 || m_wall_mu > 0.0;
    }

    /// The tangential spring's stiffness of a contact that bears `load` at `depth`: 2/7 of its
    /// normal stiffness, as detail::tangential_stiffness for two spheres, the normal stiffness
    /// taken as the secant load / depth (a node's push is its area times its depth: a contact's
    /// stiffness is about the area it presses over, which grows with its depth).
    static double tangential_stiffness(double load, double depth) {
        return detail::tangential_stiffness * load / depth;
    }

    /// Listed pair k's tangential spring (detail::tangential_spring: Cundall & Strack's, capped
    /// at mu F_n), at the pair's contact point (its pushes' centre, PairPush's lever / load),
    /// along the plane normal to its net push F_n, moved on by the slip of the two pellets'
    /// material points there in the last step; its force and torques added to both pellets. A
    /// pair that presses in two places (a ring across another's rim) has one spring at their
    /// centre.
    void pair_friction(std::size_t k) {
        const PairPush& p = m_push[k];
        const double normal = norm(p.force);
        if (!(p.load > 0.0) || !(normal > 0.0) || !(p.depth > 0.0) || m_mu == 0.0) {
            m_pair_spring[k] = Vec3{};
            return;
        }
        const std::size_t a = m_list.pair_first()[k], b = m_list.pair_second()[k];
        if (!m_sliding.empty() &&
            std::binary_search(m_sliding.begin(), m_sliding.end(),
                               std::pair{static_cast<std::uint32_t>(std::min(a, b)),
                                         static_cast<std::uint32_t>(std::max(a, b))})) {
            m_pair_spring[k] = Vec3{};
            return;
        }
        const Vec3 on_a = p.lever * (1.0 / p.load), on_b = on_a - separation(a, b);
        const Vec3 slip =
            m_moved[b] + cross(m_turned[b], on_b) - m_moved[a] - cross(m_turned[a], on_a);
        const Vec3 f =
            detail::tangential_spring(m_pair_spring[k], p.force * (1.0 / normal), slip,
                                      m_mu * normal, tangential_stiffness(p.load, p.depth));
        m_force[a] += f;
        m_force[b] -= f;
        m_torque[a] += cross(on_a, f);
        m_torque[b] -= cross(on_b, f);
    }

    /// Pellet i's springs against the walls and the floor (one per wall it touches, as a
    /// sphere's: detail::WallSprings), as pair_friction's, the wall's point held still.
    void wall_friction(std::size_t i, const WallTouches& touches, Vec3& force, Vec3& torque) {
        detail::WallSprings kept;
        for (std::size_t w = 0; w < touches.count && m_wall_mu > 0.0 && !m_sliding_wall[i]; ++w) {
            const double normal = norm(touches.force[w]);
            if (!(touches.load[w] > 0.0) || !(normal > 0.0) || !(touches.depth[w] > 0.0))
                continue;
            const Vec3 n = touches.force[w] * (1.0 / normal);
            const Vec3 at = touches.lever[w] * (1.0 / touches.load[w]);
            Vec3 spring = m_wall_springs[i].along(n);
            const Vec3 slip = -(m_moved[i] + cross(m_turned[i], at)); // the wall's, from ours
            const Vec3 f =
                detail::tangential_spring(spring, n, slip, m_wall_mu * normal,
                                          tangential_stiffness(touches.load[w], touches.depth[w]));
            kept.add(n, spring);
            force += f;
            torque += cross(at, f);
        }
        m_wall_springs[i] = kept;
    }

    /// Every spring times `factor` (lower()'s cut of the gravity: the loads it bears scale by
    /// it); 0 lets friction go for the rest of the run.
    void scale_springs(double factor) {
        for (Vec3& s : m_pair_spring)
            s *= factor;
        for (detail::WallSprings& w : m_wall_springs)
            for (Vec3& s : w.spring)
                s *= factor;
        if (factor == 0.0)
            m_mu = m_wall_mu = 0.0;
    }

    /// The largest force and torque over the bounding radius on a pellet, in its own weights.
    std::pair<double, double> residual() const {
        double f = 0.0, t = 0.0;
        for (std::size_t i = m_fixed; i < m_force.size(); ++i) {
            const double s = m_scale[i], s3 = s * s * s;
            f = std::max(f, norm2(m_force[i]) / (s3 * s3));
            t = std::max(t, norm2(m_torque[i]) / (s3 * s3 * s * s));
        }
        const double weight = m_gravity * m_volume;
        return {std::sqrt(f) / weight, std::sqrt(t) / (weight * m_reach)};
    }

    /// The mean height of the pellets that move.
    double mass_centre_z() const {
        double z = 0.0;
        for (std::size_t i = m_fixed; i < m_centre.size(); ++i)
            z += m_centre[i].z;
        return z / static_cast<double>(m_centre.size() - m_fixed);
    }

    /// The forces of one more step, counted. \throws Cancelled when the run is stopped,
    /// ConvergenceError past max_steps
    void count_step() {
        forces();
        ++m_steps;
        if (m_control.should_stop && m_steps % 100 == 0 && m_control.should_stop())
            throw Cancelled();
        if (m_steps > m_params.max_steps)
            throw ConvergenceError(fmt::format(
                "the pellet bed did not settle within {} steps (deepest node {:.3g} d_v)",
                m_params.max_steps, m_depth));
    }

    /// One FIRE step (FIRE 2.0's order: power, then the velocity update and the mixing, then
    /// the move). Rotations are moved as the arc of the bounding sphere, so that a torque
    /// over the bounding radius and a force weigh alike.
    void step() {
        count_step();
        const std::size_t n = m_centre.size();
        double power = 0.0;
        for (std::size_t i = m_fixed; i < n; ++i)
            power +=
                dot(m_force[i], m_velocity[i]) + dot(m_torque[i], m_spin[i]) * (1.0 / reach_of(i));
        if (power > 0.0) {
            if (++m_positive > Fire::delay) {
                m_dt = std::min(m_dt * Fire::grow, Fire::dt_max);
                m_alpha *= Fire::alpha_shrink;
            }
        } else {
            m_positive = 0;
            m_dt = std::max(m_dt * Fire::shrink, Fire::dt_min);
            m_alpha = Fire::alpha_start;
            std::fill(m_velocity.begin(), m_velocity.end(), Vec3{});
            std::fill(m_spin.begin(), m_spin.end(), Vec3{});
        }
        double v2 = 0.0, f2 = 0.0;
        for (std::size_t i = m_fixed; i < n; ++i) {
            const double inv_reach = 1.0 / reach_of(i);
            m_velocity[i] += m_force[i] * m_dt;
            m_spin[i] += m_torque[i] * (inv_reach * m_dt);
            v2 += norm2(m_velocity[i]) + norm2(m_spin[i]);
            f2 += norm2(m_force[i]) + norm2(m_torque[i]) * inv_reach * inv_reach;
        }
        const double mix = f2 > 0.0 ? m_alpha * std::sqrt(v2 / f2) : 0.0;
        for (std::size_t i = m_fixed; i < n; ++i) {
            const double inv_reach = 1.0 / reach_of(i);
            m_velocity[i] = m_velocity[i] * (1.0 - m_alpha) + m_force[i] * mix;
            m_spin[i] = m_spin[i] * (1.0 - m_alpha) + m_torque[i] * (inv_reach * mix);
            move(i, m_velocity[i] * m_dt, m_spin[i] * m_dt);
        }
    }

    /// Pellet i moved by `shift` and turned by the arc `arc` of its bounding sphere, both cut
    /// to at most Fire::max_move.
    void move(std::size_t i, Vec3 shift, Vec3 arc) {
        const double longest = std::max(norm(shift), norm(arc));
        if (longest > Fire::max_move) {
            shift = shift * (Fire::max_move / longest);
            arc = arc * (Fire::max_move / longest);
        }
        m_centre[i] += shift;
        m_turn[i] = normalized(rotation_by(arc * (1.0 / reach_of(i))) * m_turn[i]);
        if (frictional()) {
            m_moved[i] += shift;
            m_turned[i] += arc * (1.0 / reach_of(i));
        }
    }

    void report(std::string_view stage) const {
        if (!m_control.on_progress || m_steps % 100 != 0)
            return;
        Progress p{stage,      m_steps,         m_gravity, m_pair_depth,
                   m_wall_max, mass_centre_z(), m_layer,   m_layers};
        m_control.on_progress(p);
    }

    /// A ring column's pour (the loosened columns, insert()), and every frictional bed's (its
    /// contacts form at depths near the pour's, about a third of the settling band's): the
    /// pellets fall at a held
    /// gravity, each one's velocity and spin zeroed alone when its own power turns negative
    /// (so that a landing stops the pellet that lands, not the whole column, as FIRE's reset
    /// does), the step pour_dt, until every pellet touches a neighbour or a wall and the mass
    /// centre moved less than 1e-3 of its height in pour_check steps. The gravity is the one
    /// at which the settled column's weight presses its lowest contacts to about the settling
    /// band's high end: the depth at rest grows with the column's height times the gravity
    /// (docs/notes/pellets.md, "Rings in a tall column"), so it is pour_load times the band's
    /// high end over the column's height at a void fraction of 0.6 (2e-6 for 105 rings
    /// D = L = 2 DI in a tube of a = 4), at most the settle stage's start.
    void pour() {
        const std::size_t n = m_centre.size();
        const double height = m_container.fill_height(column_volume(), 0.6);
        m_gravity = std::min(settle_gravity, pour_load * m_params.band_high * m_dmin / height);
        const std::uint64_t start = m_steps;
        const double dt = level_set ? pour_dt : Fire::dt_max;
        std::vector<char> touching(n);
        double last = mass_centre_z();
        for (;;) {
            count_step();
            // Whether every pellet touches, asked only where the mass centre is tested.
            const bool check = m_steps % pour_check == 0;
            bool all = check;
            if (check) {
                std::fill(touching.begin(), touching.end(), 0);
                const auto first = m_list.pair_first();
                const auto second = m_list.pair_second();
                for (std::size_t k = 0; k < m_list.pairs(); ++k)
                    if (m_push[k].depth > 0.0)
                        touching[first[k]] = touching[second[k]] = 1;
                for (std::size_t i = m_fixed; i < n; ++i)
                    all = all && (touching[i] || m_wall_depth[i] > 0.0);
            }
            for (std::size_t i = m_fixed; i < n; ++i) {
                const double inv_reach = 1.0 / reach_of(i);
                if (dot(m_force[i], m_velocity[i]) + dot(m_torque[i], m_spin[i]) * inv_reach <
                    0.0) {
                    m_velocity[i] = Vec3{};
                    m_spin[i] = Vec3{};
                }
                m_velocity[i] += m_force[i] * dt;
                m_spin[i] += m_torque[i] * (inv_reach * dt);
                move(i, m_velocity[i] * dt, m_spin[i] * dt);
            }
            report("pour");
            if (!check)
                continue;
            const double mc = mass_centre_z();
            if (all && std::abs(mc - last) <= 1e-3 * mc)
                break;
            last = mc;
        }
        std::fill(m_velocity.begin(), m_velocity.end(), Vec3{});
        std::fill(m_spin.begin(), m_spin.end(), Vec3{});
        m_stages.push_back({"pour", m_steps - start, m_gravity, m_depth, mass_centre_z(), m_layer});
    }

    /// The paper's initial and intermediate stages in one: gravity raised while the deepest
    /// node is above the band's low end and lowered while it is above the high end, every
    /// `period` steps, until the mass centre's last `window` records agree within
    /// `spread` of their mean.
    void settle() {
        constexpr int period = 50, window = 10;
        constexpr double spread = 5e-4;
        const double band = level_set ? m_dmin : exact_band_scale * m_dmin;
        const double low = m_params.band_low * band, high = m_params.band_high * band;
        std::vector<double> records;
        const std::uint64_t start = m_steps;
        for (;;) {
            step();
            report("settle");
            if (m_steps % period != 0)
                continue;
            if (m_depth > high)
                m_gravity *= 0.8;
            else if (m_depth < low)
                m_gravity *= 1.15;
            if (m_steps % (2 * period) != 0)
                continue;
            records.push_back(mass_centre_z());
            if (records.size() < window)
                continue;
            const auto [lo, hi] = std::minmax_element(records.end() - window, records.end());
            const double mean = 0.5 * (*lo + *hi);
            if (*hi - *lo <= spread * mean && m_depth <= 1.5 * high)
                break;
        }
        m_stages.push_back(
            {"settle", m_steps - start, m_gravity, m_depth, mass_centre_z(), m_layer});
    }

    /// The final stage: relaxed until every force and torque is below force_tolerance
    /// weights, then, while the exact penetration depth (pair or wall) is above tolerance,
    /// the gravity scaled down by the square of the depth's excess (at most tenfold): at a
    /// crossing of two edges the contact stiffens with depth (the part of the curve inside
    /// grows with it), and its depth falls slower than the load.
    void lower() {
        const double tol = m_tol;
        const std::uint64_t start = m_steps;
        std::vector<double> rounds; // the deepest exact depth after each relaxation
        double last_cut = 1.0;      // the gravity's last factor
        // After a kick (at the jam's low gravity), the gravity is raised again tenfold a
        // relaxation, up to where the stalled relaxations began, while the depths stay below
        // tolerance: a bed balanced at a weight it can be measured against.
        double raise_to = 0.0, rounds_gravity = m_gravity;
        // A relaxation that stalled with every depth below tolerance is run on with the
        // patience of a bed that ends there (patience_at_rest).
        bool at_rest = false;
        for (;;) {
            m_dt = Fire::dt_start;
            m_alpha = Fire::alpha_start;
            m_positive = 0;
            double least = std::numeric_limits<double>::infinity();
            std::uint64_t since = 0;
            const std::uint64_t wait = at_rest ? patience_at_rest : patience;
            bool stalled = false;
            for (;;) {
                step();
                report("final");
                const auto [f, t] = residual();
                const double worst = std::max(f, t);
                if (worst <= m_params.force_tolerance)
                    break;
                // Stalled: no step took the residual 1 % below its least for `patience` steps
                // (a pellet held at a kink of the contact law, where the force turns at once).
                if (worst < 0.99 * least) {
                    least = worst;
                    since = 0;
                } else if (++since > wait) {
                    stalled = true;
                    break;
                }
            }
            PelletBed exact;
            std::vector<std::pair<std::uint32_t, std::uint32_t>> over;
            std::vector<std::uint32_t> over_wall;
            measure_exact(exact, tol, &over, &over_wall);
            const double deepest = std::max(exact.max_depth_pair, exact.max_depth_wall);
            if (deepest <= tol) {
                if (m_gravity < raise_to) {
                    const double up = std::min(10.0, raise_to / m_gravity);
                    if (frictional())
                        scale_springs(up);
                    m_gravity *= up;
                    continue;
                }
                if (stalled && !at_rest && patience_at_rest > patience) {
                    at_rest = true;
                    continue;
                }
                break;
            }
            at_rest = false;
            if (raise_to > 0.0) // raised too far: lowered from here on, not raised again
                raise_to = 0.0;
            if (rounds.empty())
                rounds_gravity = m_gravity;
            rounds.push_back(deepest);
            // Friction holds the overlap: the last cut of the gravity took the deepest depth
            // down less than a contact stiffening up to cubically with its depth would have
            // gone (a linear one falls with the load c, an edge's crossing about as sqrt(c)).
            // A ring of pellets wedged across a narrow tube holds its overlaps by friction at
            // any gravity. The contacts above tolerance let go of their friction, the rest of
            // the bed keeps it, and the bed relaxes again at the same gravity; where every
            // such contact already slides, friction goes everywhere (as in the sphere beds'
            // final stage, detail::Fire).
            if (frictional() && rounds.size() >= 2 &&
                deepest > std::cbrt(last_cut) * rounds[rounds.size() - 2]) {
                if (!let_go(over, over_wall))
                    scale_springs(0.0);
                rounds.assign(1, deepest);
                last_cut = 1.0;
                continue;
            }
            // An overlap that lowering the gravity does not relieve: the bed is jammed without
            // it, and more relaxations would run on without end.
            const bool jammed = rounds.size() > stalled_rounds &&
                                deepest > 0.99 * rounds[rounds.size() - 1 - stalled_rounds];
            if (jammed && m_kicks < max_kicks) {
                kick(over, over_wall);
                rounds.clear();
                raise_to = rounds_gravity;
                last_cut = 1.0;
                continue;
            }
            if (jammed)
                throw ConvergenceError(fmt::format(
                    "the pellet bed is jammed: {} overlap of {:.3g} d_v (tolerance {:.3g}) "
                    "stayed through {} relaxations, the gravity lowered after each; allowed: a "
                    "wider container or another seed",
                    exact.max_depth_pair >= exact.max_depth_wall ? "a pair's" : "a wall's", deepest,
                    tol, stalled_rounds));
            // The nodes at rest with a pair too deep (the depth fell by less than a tenth in
            // the last relaxation): its exact depth pushes it apart from then on.
            if (level_set && rounds.size() >= 2 && deepest > 0.9 * rounds[rounds.size() - 2])
                for (const auto& pair : over)
                    if (std::find(m_exact_pairs.begin(), m_exact_pairs.end(), pair) ==
                        m_exact_pairs.end())
                        m_exact_pairs.push_back(pair);
            const double excess = 0.8 * tol / deepest;
            last_cut = std::max(0.1, excess * excess);
            m_gravity *= last_cut;
            if (frictional()) // the springs bear loads that scale with it
                scale_springs(last_cut);
        }
        m_stages.push_back(
            {"final", m_steps - start, m_gravity, m_depth, mass_centre_z(), m_layer});
    }

    /// A jam broken by a tap: each pellet of the pairs `over` and at the walls `over_wall` is
    /// tilted by kick_angle about a horizontal axis at an azimuth from the seed, the pellet and
    /// the kick (hash01: the same whatever the order or the threads). A layer of pellets lying
    /// flat and pressed edge to edge in the floor's plane is a saddle of the energy that no
    /// force leaves: every push is horizontal, and lifting one pellet, which relieves the
    /// layer, meets no force until something tilts it.
    void kick(const std::vector<std::pair<std::uint32_t, std::uint32_t>>& over,
              const std::vector<std::uint32_t>& over_wall) {
        std::vector<std::uint32_t> ids(over_wall);
        for (const auto& [a, b] : over) {
            ids.push_back(a);
            ids.push_back(b);
        }
        std::sort(ids.begin(), ids.end());
        ids.erase(std::unique(ids.begin(), ids.end()), ids.end());
        for (const std::uint32_t i : ids) {
            if (i < m_fixed)
                continue;
            const double phi = 2.0 * std::numbers::pi *
                               portable_random::hash01(m_params.seed * 0x9E3779B97F4A7C15ull +
                                                       (std::uint64_t{m_kicks} << 40) + i);
            const Vec3 axis{std::cos(phi), std::sin(phi), 0.0};
            m_turn[i] = normalized(rotation_by(axis * kick_angle) * m_turn[i]);
        }
        ++m_kicks;
        m_velocity.assign(m_velocity.size(), Vec3{});
        m_spin.assign(m_spin.size(), Vec3{});
    }

    /// Friction let go at the pairs `over` and at the walls of the pellets `over_wall`: their
    /// contacts slide freely from now on. \return whether any of them still held friction.
    bool let_go(const std::vector<std::pair<std::uint32_t, std::uint32_t>>& over,
                const std::vector<std::uint32_t>& over_wall) {
        bool any = false;
        for (const auto& [a, b] : over) {
            const std::pair key{std::min(a, b), std::max(a, b)};
            const auto at = std::lower_bound(m_sliding.begin(), m_sliding.end(), key);
            if (m_mu > 0.0 && (at == m_sliding.end() || *at != key)) {
                m_sliding.insert(at, key);
                any = true;
            }
        }
        for (const std::uint32_t i : over_wall)
            if (m_wall_mu > 0.0 && !m_sliding_wall[i]) {
                m_sliding_wall[i] = 1;
                m_wall_springs[i] = detail::WallSprings{};
                any = true;
            }
        return any;
    }

    /// The exact depths of every pair and at the walls into `out`; the pairs deeper than
    /// `over_depth` appended to `over` (in pair order), the pellets deeper than it into a wall
    /// or the floor to `over_wall`.
    void measure_exact(PelletBed& out, double over_depth = 0.0,
                       std::vector<std::pair<std::uint32_t, std::uint32_t>>* over = nullptr,
                       std::vector<std::uint32_t>* over_wall = nullptr) const {
        const S& shape = m_shape;
        const auto first = m_list.pair_first();
        const auto second = m_list.pair_second();
        const std::size_t pairs = m_list.pairs();
        std::vector<double> depth(pairs, 0.0);
#pragma omp parallel for schedule(dynamic, 16)
        for (std::size_t k = 0; k < pairs; ++k) {
            const std::size_t a = first[k], b = second[k];
            const Vec3 u = separation(a, b);
            if ((a < m_fixed && b < m_fixed) || !within_reach(a, b, u))
                continue;
            const Placement pa{m_centre[a], m_turn[a], size(a)};
            const Placement pb{m_centre[a] + u, m_turn[b], size(b)};
            depth[k] = shape.pair_overlap(pa, shape, pb, u).depth;
        }
        std::vector<char> touches(m_centre.size(), 0);
        for (std::size_t k = 0; k < pairs; ++k) {
            if (depth[k] > 0.0)
                touches[first[k]] = touches[second[k]] = 1;
            out.max_depth_pair = std::max(out.max_depth_pair, depth[k]);
            if (over && depth[k] > over_depth)
                over->emplace_back(static_cast<std::uint32_t>(first[k]),
                                   static_cast<std::uint32_t>(second[k]));
        }
        for (std::size_t i = m_fixed; i < m_centre.size(); ++i) {
            const Placement p{m_centre[i], m_turn[i], size(i)};
            const double wall =
                std::max(shape.wall_overlap(m_container, p), -shape.support(p, {0, 0, -1}).z);
            out.max_depth_wall = std::max(out.max_depth_wall, wall);
            if (over_wall && wall > over_depth)
                over_wall->push_back(static_cast<std::uint32_t>(i));
            if (wall > 0.0)
                touches[i] = 1;
        }
        out.touching_nothing = static_cast<std::size_t>(
            std::count(touches.begin() + static_cast<std::ptrdiff_t>(m_fixed), touches.end(), 0));
    }

    static constexpr double skin = 0.3; // d_v
    /// The settle stage's gravity at its start (where no pour ran before it).
    static constexpr double settle_gravity = 1e-3;
    /// pour()'s step for the level-set contact: four times FIRE's largest, which the pour's
    /// per-pellet stop keeps stable (a ring column's deepest node stayed within the settling
    /// band); FIRE's largest for a spherocylinder's stiffer springs, which at pour_dt kept 40
    /// frictional rods in a tube of a = 4 jittering in and out of contact; its gravity's load
    /// factor, and the steps between its tests of the mass centre.
    static constexpr double pour_dt = 1.0, pour_load = 3e-3;
    static constexpr std::uint64_t pour_check = 500;
    /// Pairs (and pellets at the walls) from which the force loops run on the threads: a pair
    /// costs thousands of a sphere pair's work (its nodes and circles), so a few already pay
    /// for the threads' start (a sphere bed waits for detail::parallel_min_spheres).
    static constexpr std::size_t parallel_min_pellets = 8;
    static constexpr std::uint64_t patience = 5000;
    /// The patience of a final relaxation that stalled with every exact depth below tolerance
    /// (the bed it would end with). Spherocylinders' springs change smoothly and a step costs
    /// little: their residual keeps falling there, slowly (100 rods in a tube of a = 3, layers
    /// of 10 d_v, seeds 10-12: 0.054, 0.135 and 1.36 weights left at 5 000 steps, about 0.01
    /// at 50 000). A node-pressed pellet's step costs thousands of times more and its
    /// residual need not fall (40 cylinders at a = 4 with 50 000 for every relaxation: 0.50
    /// weights left instead of 0.51, in 4.3 times the steps; docs/notes/pellets.md).
    static constexpr std::uint64_t patience_at_rest = level_set ? patience : 50000;
    /// Relaxations of the final stage whose deepest exact depth fell by less than 1 % in all
    /// (the gravity cut each time) before the bed is called jammed.
    static constexpr std::size_t stalled_rounds = 4;
    /// The taps a jammed final stage gets (kick) before the bed is called jammed, and the
    /// tilt of each, radians.
    static constexpr std::uint32_t max_kicks = 2;
    static constexpr double kick_angle = 0.02;
    std::uint32_t m_kicks = 0;
    /// The spring on a held pair's exact depth (lower()), in the nodes' unit (a node's force is
    /// its area times its depth): the area of four nodes at the default spacing, d_v^2.
    static constexpr double exact_stiffness = 0.01;
    /// A spherocylinder pair's and wall's spring, force per d_v of depth in the nodes' unit
    /// (area times depth): the stiffness of a flat contact of 1 d_v^2, as a sphere bed's
    /// unit spring; FIRE's largest step (0.25) stays stable for a pellet held by ten.
    static constexpr double exact_contact_stiffness = 1.0;
    /// A spherocylinder bed's settling band, a share of the level-set beds': a layer of rods
    /// lying flat on the floor locks part of the depth it settled at (the rods press each
    /// other and the wall in the floor's plane, and lowering the gravity does not relieve
    /// that), about 7 % of it, which at the full band is above the tolerance
    /// (docs/notes/pellets.md, "Spherocylinders").
    static constexpr double exact_band_scale = 0.5;
    /// The least gap between two spherocylinders at insertion, d_v.
    static constexpr double insert_gap = 0.02;
    /// Draws for one pellet's room before the column is loosened (insert()), and how many
    /// times it may be (each halving its solid fraction).
    static constexpr int insert_attempts = 10'000, column_loosenings = 3;
    /// The width of the smooth minimum of a point's distances to a side and an end (inside's
    /// blend), in units of the size: the pushing face turns over this width instead of at
    /// once. An edge is then 1e-3 of the size (5e-4 d_v) shallower than it is. A ring's
    /// tolerance (1e-3 of its wall) is below that: its blend is its tolerance, an edge at most
    /// a quarter of a tolerance shallower (m_blend).
    static constexpr double edge_blend = 4e-3;
    /// Points about a circle searched for its part inside a neighbour.
    static constexpr int circle_samples = 64;
    /// The room, in units of the size, by which a pellet's part must clear a neighbour's hull
    /// to be skipped (hulls_apart, clear_of_hull): far above the rounding of the nodes'
    /// places, so that a skipped part would have pressed nothing.
    static constexpr double hull_margin = 1e-9;

    const PelletBedParameters& m_params;
    const S& m_shape;
    const RunControl& m_control;
    const Container& m_container;
    std::optional<Periods> m_cell;
    double m_size = 0.5, m_reach = 0.0, m_volume = 0.0, m_dmin = 0.0;
    /// Each pellet's scale (PelletBedParameters::scales, 1 where it is empty), the least and
    /// the greatest.
    std::vector<double> m_scale;
    double m_scale_low = 1.0, m_scale_high = 1.0;
    /// A part of a bed in layers: the first m_fixed pellets are held still (Part).
    std::size_t m_fixed = 0;
    std::uint32_t m_layer = 0, m_layers = 1;
    double m_tol = 0.0;                             ///< the final depth tolerance, d_v
    double m_blend = edge_blend;                    ///< inside's blend (edge_blend)
    std::vector<SurfaceNode> m_nodes, m_wall_nodes; // without and with the side's rows
    std::vector<SurfaceCircle> m_circles;           // the side's rows, whole
    std::vector<NodeGroup> m_groups;
    static thread_local std::vector<std::pair<double, double>> m_points; // press_circles' own
    std::vector<Vec3> m_centre, m_velocity, m_spin, m_force, m_torque;
    std::vector<Quaternion> m_turn;
    std::vector<PairPush> m_push;
    /// Friction (frictional()): the coefficients, each pellet's shift and turn (radians)
    /// since the last forces(), the springs of the listed pairs (seen from the first) and of
    /// each pellet's walls, the pairs' springs carried over a rebuild of the list (keyed by
    /// the pellets' indices, m_order, which never change).
    double m_mu = 0.0, m_wall_mu = 0.0;
    std::vector<Vec3> m_moved, m_turned, m_pair_spring;
    std::vector<detail::WallSprings> m_wall_springs;
    /// The pairs (lower index first, sorted) and the pellets' walls whose friction lower() let
    /// go (let_go).
    std::vector<std::pair<std::uint32_t, std::uint32_t>> m_sliding;
    std::vector<char> m_sliding_wall;
    std::vector<std::uint32_t> m_order;
    detail::PairSpringCarry m_carry;
    std::vector<double> m_wall_depth;
    NeighborList m_list;
    std::vector<PelletStage> m_stages;
    /// Pairs (first, second) above tolerance after a relaxation that took the deepest exact
    /// depth down by less than a tenth, in the order found; pushed apart on their exact depth
    /// from then on (forces()).
    std::vector<std::pair<std::uint32_t, std::uint32_t>> m_exact_pairs;
    double m_gravity = settle_gravity, m_depth = 0.0, m_pair_depth = 0.0, m_wall_max = 0.0;
    double m_dt = Fire::dt_start, m_alpha = Fire::alpha_start;
    int m_positive = 0;
    std::uint64_t m_steps = 0;
};

template <class S> thread_local std::vector<std::pair<double, double>> PelletSolver<S>::m_points;

/// The pellets as the insertion places them and the column they stand in.
struct InsertedColumn {
    std::vector<Vec3> centre;
    std::vector<Quaternion> turn;
    PelletColumn column;
};

template <class S>
InsertedColumn inserted_column(const PelletBedParameters& params, const S& shape,
                               const RunControl& control) {
    InsertedColumn out;
    std::tie(out.centre, out.turn) = PelletSolver<S>(params, shape, control).inserted();
    double height = 0.0;
    for (std::size_t i = 0; i < out.centre.size(); ++i)
        height = std::max(height, out.centre[i].z + shape.bounding_radius(0.5 * params.scale(i)));
    out.column = {height, pellet_layers(params, height),
                  shape.bounding_radius(0.5 * params.scale_range().second)};
    return out;
}

/// A pellet bed in layers, as relax_with_fire builds a tall sphere bed (fire.cpp): the inserted
/// column (in one piece where pellet_layers says 1) cut into slices of equal height; each slice,
/// moved down to just above the bed below, relaxed by the stages with the last layer below it and
/// the top layer_band d_v of the layers under that free, over a shell of held pellets. After
/// each layer the state goes to hooks.on_layer; hooks.resume starts after its layers.
template <class S>
PelletBed pellets_in_layers(const PelletBedParameters& params, const S& shape,
                            const RunControl& control, const PelletLayerHooks& hooks) {
    constexpr double layer_band = 4.0; // d_v
    InsertedColumn inserted = inserted_column(params, shape, control);
    std::vector<Vec3>& centre = inserted.centre;
    std::vector<Quaternion>& turn = inserted.turn;
    const std::size_t n = centre.size();
    const std::pair<double, double> range = params.scale_range();
    const std::uint32_t layers = inserted.column.layers;
    if (layers == 1) { // the inserted pellets relaxed in one piece
        Part whole;
        whole.centre = std::move(centre);
        whole.turn = std::move(turn);
        whole.scale_range = range;
        return PelletSolver<S>(params, shape, control, &whole).run();
    }
    // The shell holds every pellet a free one can touch: two of the largest bounding radii,
    // and a quarter more for the moves of the relaxation.
    const double largest = inserted.column.largest_reach, shell = 2.5 * largest;
    const double slice = inserted.column.height / layers;
    std::vector<std::vector<std::uint32_t>> members(layers);
    for (std::uint32_t i = 0; i < n; ++i) {
        const double z = centre[i].z - shape.bounding_radius(0.5 * params.scale(i));
        members[static_cast<std::uint32_t>(std::clamp(z / slice, 0.0, layers - 1.0))].push_back(i);
    }
    PelletBed out;
    out.layers = layers;
    PelletCheckpoint state; // all but the pellets, which stay in centre and turn
    std::uint32_t first = 0;
    if (hooks.resume) {
        const PelletCheckpoint& resume = *hooks.resume;
        if (resume.layers_done < 1 || resume.layers_done > layers || resume.centre.size() != n ||
            resume.turn.size() != n)
            throw InvalidInput(fmt::format("a checkpoint of {} pellets after layer {} is not "
                                           "allowed; allowed: {} pellets, layers 1 to {}",
                                           resume.centre.size(), resume.layers_done, n, layers));
        state = resume;
        centre = std::move(state.centre);
        turn = std::move(state.turn);
        state.centre.clear();
        state.turn.clear();
        first = resume.layers_done;
    }
    for (std::uint32_t l = first; l < layers; ++l) {
        if (members[l].empty())
            continue;
        detail::LayerPart layer = detail::layer_part(
            members, l, [&](std::uint32_t i) { return centre[i].z; }, layer_band, shell);
        std::vector<std::uint32_t>& ids = layer.ids;
        Part part;
        part.fixed = layer.fixed;
        const double lift = (state.on_floor ? 0.0 : state.top + 2.0 * largest) - l * slice;
        for (const std::uint32_t i : members[l]) {
            centre[i].z += lift;
            ids.push_back(i);
        }
        PelletBedParameters p = params;
        p.particles = ids.size();
        p.layer_height = 0.0;
        if (!params.scales.empty()) {
            p.scales.clear();
            for (const std::uint32_t i : ids)
                p.scales.push_back(params.scales[i]);
        }
        for (const std::uint32_t i : ids) {
            part.centre.push_back(centre[i]);
            part.turn.push_back(turn[i]);
        }
        part.scale_range = range;
        part.steps = state.steps;
        part.layer = l;
        part.layers = layers;
        const PelletBed relaxed = PelletSolver<S>(p, shape, control, &part).run();
        for (std::size_t k = part.fixed; k < ids.size(); ++k) {
            centre[ids[k]] = relaxed.packing.centers[k];
            turn[ids[k]] = relaxed.packing.orientations[k];
            state.top = std::max(state.top, relaxed.packing.centers[k].z);
        }
        state.layers_done = l + 1;
        state.steps = relaxed.steps;
        state.neighbor_builds += relaxed.neighbor_builds;
        state.nodes = relaxed.nodes;
        state.stages.insert(state.stages.end(), relaxed.stages.begin(), relaxed.stages.end());
        state.sliding_pairs += relaxed.sliding_pairs;
        state.sliding_walls += relaxed.sliding_walls;
        state.friction_kept = relaxed.friction_kept;
        state.kicks += relaxed.kicks;
        state.residual_force = std::max(state.residual_force, relaxed.residual_force);
        state.residual_torque = std::max(state.residual_torque, relaxed.residual_torque);
        state.on_floor = false;
        if (hooks.on_layer) {
            state.centre = centre;
            state.turn = turn;
            hooks.on_layer(state);
            state.centre.clear();
            state.turn.clear();
        }
    }
    out.steps = state.steps;
    out.neighbor_builds = state.neighbor_builds;
    out.nodes = state.nodes;
    out.stages = std::move(state.stages);
    out.sliding_pairs = state.sliding_pairs;
    out.sliding_walls = state.sliding_walls;
    out.friction_kept = state.friction_kept;
    out.kicks = state.kicks;
    // The whole bed measured as it stands: its depths across the layers' seams too.
    Part whole;
    whole.centre = std::move(centre);
    whole.turn = std::move(turn);
    whole.scale_range = range;
    PelletBedParameters p = params;
    p.layer_height = 0.0;
    PelletBed measured = PelletSolver<S>(p, shape, control, &whole).measured();
    out.packing = std::move(measured.packing);
    out.max_depth_nodes = measured.max_depth_nodes;
    out.max_depth_pair = measured.max_depth_pair;
    out.max_depth_wall = measured.max_depth_wall;
    out.residual_force = state.residual_force;
    out.residual_torque = state.residual_torque;
    return out;
}

} // namespace

std::uint32_t pellet_layers(const PelletBedParameters& params, double column) {
    if (params.layer_height <= 0.0 || column <= 2.0 * params.layer_height)
        return 1;
    return static_cast<std::uint32_t>(std::min(column / params.layer_height, 1e6));
}

PelletColumn pellet_column(const PelletBedParameters& params) {
    params.validate();
    return std::visit([&](const auto& shape) { return inserted_column(params, shape, {}).column; },
                      params.shape);
}

PelletBed generate_pellet_bed(const PelletBedParameters& params, const RunControl& control,
                              const PelletLayerHooks& layers) {
    params.validate();
    return std::visit(
        [&](const auto& shape) {
            using S = std::decay_t<decltype(shape)>;
            if (params.layer_height <= 0.0)
                return PelletSolver<S>(params, shape, control).run();
            return pellets_in_layers(params, shape, control, layers);
        },
        params.shape);
}

nlohmann::json pellet_bed_parameters_json(const PelletBedParameters& p) {
    using nlohmann::json;
    const json shape = std::visit(
        [](const auto& s) {
            if constexpr (std::is_same_v<std::decay_t<decltype(s)>, MultilobeShape>)
                return json{{"kind", "multilobe"},
                            {"lobes", s.lobes},
                            {"circle", s.circle},
                            {"radius", s.lobe.radius},
                            {"half_length", s.lobe.half_length},
                            {"bore", s.lobe.bore}};
            else
                return json{{"kind", "spherocylinder"},
                            {"radius", s.radius},
                            {"half_length", s.half_length}};
        },
        p.shape);
    // FNV-1a 64 of the scales' bytes (little-endian doubles).
    static_assert(std::endian::native == std::endian::little);
    const std::uint64_t hash = detail::fnv1a(
        {reinterpret_cast<const char*>(p.scales.data()), p.scales.size() * sizeof(double)});
    return {{"particles", p.particles},
            {"seed", p.seed},
            {"shape", shape},
            {"container", p.container.summary_json()},
            {"e0", p.e0},
            {"tolerance", p.tolerance},
            {"band_low", p.band_low},
            {"band_high", p.band_high},
            {"node_spacing", p.node_spacing},
            {"force_tolerance", p.force_tolerance},
            {"friction", p.friction},
            {"wall_friction", p.wall_friction},
            {"layer_height", p.layer_height},
            {"scales", p.scales.size()},
            {"scales_fnv1a64", fmt::format("{:016x}", hash)}};
}

} // namespace packbed
