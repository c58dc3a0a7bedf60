// Beds of cylinder pellets (pellet_bed.hpp) and the surface the level-set contact presses
// (CylinderShape::surface_nodes, surface_circles, inside, signed_depth): the nodes' areas
// against the cylinder's closed-form area, depths against the distances by hand, and a poured
// bed checked by a brute force that shares no code with the solver: points drawn uniformly on
// each pellet's surface by their own formulas, each tested against every other pellet and the
// walls by its own inside test.
#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <random>
#include <string>
#include <type_traits>
#include <variant>
#include <vector>

#include <gtest/gtest.h>
#include <omp.h>

#include "packbed/bed_volume.hpp"
#include "packbed/container.hpp"
#include "packbed/cylinder_shape.hpp"
#include "packbed/error.hpp"
#include "packbed/pellet_bed.hpp"
#include "packbed/pipeline.hpp"

using namespace packbed;

namespace {

constexpr double pi = std::numbers::pi;

TEST(SurfaceNodes, AreasAddUpToTheCylinders) {
    const CylinderShape c{0.7, 1.1};
    const double area = 2.0 * pi * c.radius * c.radius + 2.0 * pi * c.radius * 2.0 * c.half_length;
    for (const double spacing : {0.3, 0.1, 0.05}) {
        double all = 0.0, ends = 0.0, circles = 0.0;
        for (const SurfaceNode& n : c.surface_nodes(spacing))
            all += n.area;
        for (const SurfaceNode& n : c.surface_nodes(spacing, false)) {
            ends += n.area;
            EXPECT_DOUBLE_EQ(std::abs(n.point.z), c.half_length); // only the ends' inner rings
        }
        for (const SurfaceCircle& k : c.surface_circles(spacing))
            circles += k.area_per_length * 2.0 * pi * k.radius;
        EXPECT_NEAR(all, area, 1e-12 * area) << spacing;
        EXPECT_NEAR(ends + circles, area, 1e-12 * area) << spacing;
    }
}

TEST(SurfaceNodes, LieOnTheSurfaceAtMostASpacingApartAround) {
    const CylinderShape c{0.7, 1.1};
    const double spacing = 0.1;
    for (const SurfaceNode& n : c.surface_nodes(spacing)) {
        const double r = std::hypot(n.point.x, n.point.y);
        const bool end = std::abs(std::abs(n.point.z) - c.half_length) < 1e-12 && r <= c.radius;
        const bool side = std::abs(r - c.radius) < 1e-12 && std::abs(n.point.z) <= c.half_length;
        EXPECT_TRUE(end || side) << n.point.x << " " << n.point.y << " " << n.point.z;
    }
    const auto circles = c.surface_circles(spacing);
    ASSERT_GE(circles.size(), 2u);
    std::vector<double> heights;
    for (const SurfaceCircle& k : circles)
        heights.push_back(k.z);
    std::sort(heights.begin(), heights.end());
    EXPECT_DOUBLE_EQ(heights.front(), -c.half_length);
    EXPECT_DOUBLE_EQ(heights.back(), c.half_length);
    for (std::size_t i = 1; i < heights.size(); ++i)
        EXPECT_LE(heights[i] - heights[i - 1], spacing + 1e-12);
}

TEST(CylinderDepth, InsideAndOutsideByHand) {
    const CylinderShape c{1.0, 2.0};
    // Nearer the side: out through it.
    InsideDepth in = c.inside({0.7, 0.0, 0.5});
    EXPECT_DOUBLE_EQ(in.depth, 0.3);
    EXPECT_DOUBLE_EQ(in.normal.x, 1.0);
    // Nearer the top end.
    in = c.inside({0.0, 0.2, 1.9});
    EXPECT_NEAR(in.depth, 0.1, 1e-15);
    EXPECT_DOUBLE_EQ(in.normal.z, 1.0);
    in = c.inside({0.0, 0.2, -1.95});
    EXPECT_NEAR(in.depth, 0.05, 1e-15);
    EXPECT_DOUBLE_EQ(in.normal.z, -1.0);
    EXPECT_EQ(c.inside({1.2, 0.0, 0.0}).depth, 0.0);
    EXPECT_NEAR(c.signed_depth({0.7, 0.0, 0.5}), 0.3, 1e-15);
    EXPECT_NEAR(c.signed_depth({1.3, 0.0, 0.5}), -0.3, 1e-15);
    EXPECT_NEAR(c.signed_depth({0.0, 0.0, 2.5}), -0.5, 1e-15);
    // Beyond the rim: the distance to the rim circle, 3-4-5.
    EXPECT_NEAR(c.signed_depth({1.3, 0.0, 2.4}), -0.5, 1e-15);
}

TEST(CylinderDepth, TheBlendIsSmoothUnderAnEdgeAndExactAwayFromIt) {
    const CylinderShape c{1.0, 2.0};
    const double blend = 0.01;
    // Away from the edge (the side 0.3 nearer than the end): as without the blend.
    EXPECT_DOUBLE_EQ(c.inside({0.7, 0.0, 1.0}, blend).depth, 0.3);
    // Where the side and the end are equally near (0.05 each): blend / 4 less.
    const InsideDepth at = c.inside({0.95, 0.0, 1.95}, blend);
    EXPECT_NEAR(at.depth, 0.05 - blend / 4.0, 1e-15);
    EXPECT_NEAR(at.normal.x, 0.5, 1e-12);
    EXPECT_NEAR(at.normal.z, 0.5, 1e-12);
    // Across the bisector the depth and the normal change by no more than the step allows.
    InsideDepth before = c.inside({0.95 - 0.02, 0.0, 1.95}, blend);
    for (int k = -199; k <= 200; ++k) {
        const InsideDepth now = c.inside({0.95 + 1e-4 * k, 0.0, 1.95}, blend);
        EXPECT_LE(std::abs(now.depth - before.depth), 1.0001e-4 + 1e-15) << k;
        EXPECT_LE(std::abs(now.normal.x - before.normal.x), 1e-4 / blend + 1e-12) << k;
        before = now;
    }
    // The normal is the depth's gradient: a finite difference along x and z.
    const double h = 1e-7;
    const Vec3 q{0.951, 0.0, 1.948};
    const InsideDepth d = c.inside(q, blend);
    EXPECT_NEAR(
        (c.inside(q - Vec3{h, 0, 0}, blend).depth - c.inside(q + Vec3{h, 0, 0}, blend).depth) /
            (2 * h),
        d.normal.x, 1e-6);
    EXPECT_NEAR(
        (c.inside(q - Vec3{0, 0, h}, blend).depth - c.inside(q + Vec3{0, 0, h}, blend).depth) /
            (2 * h),
        d.normal.z, 1e-6);
}

/// A point uniform on the cylinder's surface (by area) from three uniform numbers: the ends
/// by sqrt of the radius, the side by angle and height; a ring's ends from its bore out, and
/// its bore as a second side.
Vec3 surface_point(const CylinderShape& c, double u, double v, double w) {
    const double end_area = pi * (c.radius * c.radius - c.bore * c.bore);
    const double side_area = 2.0 * pi * c.radius * 2.0 * c.half_length;
    const double bore_area = 2.0 * pi * c.bore * 2.0 * c.half_length;
    const double pick = u * (2.0 * end_area + side_area + bore_area);
    const double phi = 2.0 * pi * v;
    if (pick < 2.0 * end_area) {
        const double r = std::sqrt(c.bore * c.bore + w * (c.radius * c.radius - c.bore * c.bore));
        return {r * std::cos(phi), r * std::sin(phi),
                pick < end_area ? -c.half_length : c.half_length};
    }
    const double r = pick < 2.0 * end_area + side_area ? c.radius : c.bore;
    return {r * std::cos(phi), r * std::sin(phi), c.half_length * (2.0 * w - 1.0)};
}

/// Lobe k's axis in the body frame, by the brute force's own formula.
Vec3 lobe_axis(const MultilobeShape& s, int k) {
    const double a = 2.0 * pi * k / s.lobes;
    return {s.circle * std::cos(a), s.circle * std::sin(a), 0.0};
}

/// How deep the body-frame point q lies in the cylinder of radius r and half-length h about
/// the z axis through `axis` (negative outside); in a ring of bore `bore` > 0, also at most
/// its distance from the bore.
double cylinder_depth(double r, double h, const Vec3& axis, const Vec3& q, double bore = 0.0) {
    const double rho = std::hypot(q.x - axis.x, q.y - axis.y);
    const double depth = std::min(r - rho, h - std::abs(q.z));
    return bore > 0.0 ? std::min(depth, rho - bore) : depth;
}

/// A point on a multilobe's surface: on a lobe drawn at random (none for one lobe), uniform
/// on its surface, drawn again while it lies strictly inside another lobe (the ends' shared
/// parts are kept by each lobe: denser there, still on the surface).
Vec3 surface_point(const MultilobeShape& s, std::mt19937_64& rng) {
    std::uniform_real_distribution<double> u(0.0, 1.0);
    for (;;) {
        const int k = s.lobes == 1 ? 0 : static_cast<int>(u(rng) * s.lobes) % s.lobes;
        const double a = u(rng), b = u(rng), c = u(rng);
        const Vec3 q = surface_point(s.lobe, a, b, c) + lobe_axis(s, k);
        bool inside = false;
        for (int j = 0; j < s.lobes; ++j)
            inside = inside || (j != k && cylinder_depth(s.lobe.radius, s.lobe.half_length,
                                                         lobe_axis(s, j), q) > 1e-12);
        if (!inside)
            return q;
    }
}

/// The brute force's own rotation of v by the unit quaternion q (v' = q v q*).
Vec3 turn(const Quaternion& q, const Vec3& v) {
    const double w = q.w, x = q.x, y = q.y, z = q.z;
    return {(1 - 2 * (y * y + z * z)) * v.x + 2 * (x * y - w * z) * v.y + 2 * (x * z + w * y) * v.z,
            2 * (x * y + w * z) * v.x + (1 - 2 * (x * x + z * z)) * v.y + 2 * (y * z - w * x) * v.z,
            2 * (x * z - w * y) * v.x + 2 * (y * z + w * x) * v.y +
                (1 - 2 * (x * x + y * y)) * v.z};
}

/// How deep a point lies inside a placed multilobe by the brute force's own test: its
/// coordinates along the axis and across it, the deepest of the lobes.
double depth_in(const MultilobeShape& s, const Vec3& centre, const Quaternion& q, double size,
                const Vec3& p) {
    const Vec3 d = p - centre;
    const Vec3 body{dot(d, turn(q, {1.0, 0.0, 0.0})), dot(d, turn(q, {0.0, 1.0, 0.0})),
                    dot(d, turn(q, {0.0, 0.0, 1.0}))};
    double best = -1e300;
    for (int k = 0; k < s.lobes; ++k)
        best = std::max(best, cylinder_depth(s.lobe.radius * size, s.lobe.half_length * size,
                                             lobe_axis(s, k) * size, body, s.lobe.bore * size));
    return best;
}

/// A point uniform on a spherocylinder's surface (by area): the side by angle and height, a
/// cap by Archimedes' uniform height on the sphere, moved to its end of the segment.
Vec3 surface_point(const SpherocylinderShape& s, std::mt19937_64& rng) {
    std::uniform_real_distribution<double> u(0.0, 1.0);
    const double side = 4.0 * pi * s.radius * s.half_length, caps = 4.0 * pi * s.radius * s.radius;
    const double phi = 2.0 * pi * u(rng);
    if (u(rng) * (side + caps) < side)
        return {s.radius * std::cos(phi), s.radius * std::sin(phi),
                s.half_length * (2.0 * u(rng) - 1.0)};
    const double z = 2.0 * u(rng) - 1.0, across = std::sqrt(1.0 - z * z);
    return {s.radius * across * std::cos(phi), s.radius * across * std::sin(phi),
            s.radius * z + (z < 0.0 ? -s.half_length : s.half_length)};
}

/// How deep a point lies inside a placed spherocylinder by the brute force's own test: the
/// radius less its distance from the nearest point of the axis' segment.
double depth_in(const SpherocylinderShape& s, const Vec3& centre, const Quaternion& q, double size,
                const Vec3& p) {
    const Vec3 axis = turn(q, {0.0, 0.0, 1.0});
    const double along =
        std::clamp(dot(p - centre, axis), -s.half_length * size, s.half_length * size);
    return s.radius * size - norm(p - centre - axis * along);
}

class PouredBed : public ::testing::Test {
protected:
    static void SetUpTestSuite() {
        params = new PelletBedParameters;
        params->particles = 12;
        params->container = Container::tube(4.0);
        params->seed = 3;
        bed = new PelletBed(generate_pellet_bed(*params));
    }
    static void TearDownTestSuite() {
        delete bed;
        delete params;
    }
    static PelletBedParameters* params;
    static PelletBed* bed;
};

PelletBedParameters* PouredBed::params = nullptr;
PelletBed* PouredBed::bed = nullptr;

TEST_F(PouredBed, EndsBelowTheToleranceByTheExactDepth) {
    const double tol = params->tolerance * params->smallest_dimension();
    EXPECT_EQ(bed->packing.size(), 12u);
    EXPECT_LE(bed->max_depth_pair, tol);
    EXPECT_LE(bed->max_depth_wall, tol);
    EXPECT_LE(bed->max_depth_nodes, tol);
    // The bed rests: the pellets touch (the depths are not all zero) and the stages ran.
    EXPECT_GT(bed->max_depth_pair, 0.0);
    ASSERT_EQ(bed->stages.size(), 2u);
    EXPECT_LT(bed->stages[1].gravity, bed->stages[0].gravity);
}

/// The deepest a surface point of one pellet lies inside another, and below the floor or
/// through the wall: 20 000 points drawn on each pellet's surface by surface_point, each tested
/// against every other pellet by depth_in. In a periodic cell of periods lx, ly (> 0) each
/// other pellet is taken at its copy nearest the point, by the brute force's own rounding;
/// in a tube of radius rt (> 0), the wall is the circle.
struct Deepest {
    double pair = 0.0, wall = 0.0;
};
template <class Shape>
Deepest brute_force(const Shape& c, const Packing& p, double rt, double lx = 0.0, double ly = 0.0) {
    std::mt19937_64 rng(7);
    Deepest out;
    for (std::size_t i = 0; i < p.size(); ++i) {
        EXPECT_NEAR(p.orientations[i].w * p.orientations[i].w +
                        p.orientations[i].x * p.orientations[i].x +
                        p.orientations[i].y * p.orientations[i].y +
                        p.orientations[i].z * p.orientations[i].z,
                    1.0, 1e-12);
        for (int k = 0; k < 20000; ++k) {
            const Vec3 body = surface_point(c, rng);
            const Vec3 at = p.centers[i] + turn(p.orientations[i], body * p.radii[i]);
            out.wall = std::max(out.wall, -at.z);
            if (rt > 0.0)
                out.wall = std::max(out.wall, std::hypot(at.x, at.y) - rt);
            for (std::size_t j = 0; j < p.size(); ++j) {
                if (j == i)
                    continue;
                Vec3 other = p.centers[j];
                if (lx > 0.0) {
                    other.x -= lx * std::round((other.x - at.x) / lx);
                    other.y -= ly * std::round((other.y - at.y) / ly);
                }
                out.pair =
                    std::max(out.pair, depth_in(c, other, p.orientations[j], p.radii[j], at));
            }
        }
    }
    return out;
}

TEST_F(PouredBed, NoSurfacePointLiesDeeperThanTheToleranceInAnotherPellet) {
    const double tol = params->tolerance * params->smallest_dimension();
    const Deepest d = brute_force(std::get<MultilobeShape>(params->shape), bed->packing,
                                  0.5 * params->container.tube_diameter().value());
    EXPECT_LE(d.pair, tol);
    EXPECT_LE(d.wall, tol);
    // The exact penetration depth is at least the deepest point's depth.
    EXPECT_LE(d.pair, bed->max_depth_pair + 1e-12);
}

/// Pairs of a bed in a square periodic cell that meet only as copies across its sides: their
/// nearest copies within `reach`, the centres themselves farther. Every centre must lie in the
/// cell.
int pairs_across(const Packing& p, double reach, double period) {
    int across = 0;
    for (std::size_t i = 0; i < p.size(); ++i) {
        const Vec3& c = p.centers[i];
        EXPECT_TRUE(c.x >= 0.0 && c.x < period && c.y >= 0.0 && c.y < period) << c.x << " " << c.y;
        for (std::size_t j = i + 1; j < p.size(); ++j) {
            Vec3 d = p.centers[j] - c;
            const bool far = norm(d) >= reach;
            d.x -= period * std::round(d.x / period);
            d.y -= period * std::round(d.y / period);
            across += far && norm(d) < reach;
        }
    }
    return across;
}

/// A bed in a cell periodic in x and y, 3.2 d_v wide (the pellet's bounding sphere 1.24 d_v
/// across): pellets touch their neighbours' copies across the cell's sides.
TEST(PeriodicPelletBed, EndsBelowTheToleranceAcrossTheCellsSides) {
    PelletBedParameters params;
    params.particles = 12;
    params.seed = 3;
    const double period = 3.2;
    params.container = Container(Periodic(period, period));
    const PelletBed bed = generate_pellet_bed(params);
    const double tol = params.tolerance * params.smallest_dimension();
    ASSERT_EQ(bed.packing.size(), 12u);
    EXPECT_LE(bed.max_depth_pair, tol);
    EXPECT_LE(bed.max_depth_wall, tol);
    EXPECT_GT(bed.max_depth_pair, 0.0);
    // Every centre in the cell, and pairs that meet only as copies across its sides (their
    // nearest copies within the bounding spheres' reach, the centres themselves farther).
    const MultilobeShape& shape = std::get<MultilobeShape>(params.shape);
    EXPECT_GE(pairs_across(bed.packing, 2.0 * shape.bounding_radius(0.5), period), 3);
    const Deepest d = brute_force(shape, bed.packing, 0.0, period, period);
    EXPECT_LE(d.pair, tol);
    EXPECT_LE(d.wall, tol);
    EXPECT_LE(d.pair, bed.max_depth_pair + 1e-12);
    // The void fraction of the first layer by the exact volumes (whole pellets, wrapped into
    // the cell) against points drawn in the cell, each tested by depth_in at the copy of each
    // pellet nearest it.
    const double low = 0.2, high = 0.6;
    const ShapedBed<MultilobeShape> shaped(bed.packing, {shape});
    const double exact = void_fraction(shaped, params.container, low, high);
    std::mt19937_64 rng(11);
    std::uniform_real_distribution<double> u(0.0, 1.0);
    const int points = 200000;
    int solid = 0;
    for (int k = 0; k < points; ++k) {
        const Vec3 at{period * u(rng), period * u(rng), low + (high - low) * u(rng)};
        for (std::size_t j = 0; j < bed.packing.size(); ++j) {
            Vec3 c = bed.packing.centers[j];
            c.x -= period * std::round((c.x - at.x) / period);
            c.y -= period * std::round((c.y - at.y) / period);
            if (depth_in(shape, c, bed.packing.orientations[j], bed.packing.radii[j], at) >= 0.0) {
                ++solid;
                break;
            }
        }
    }
    const double f = static_cast<double>(solid) / points;
    const double sigma = std::sqrt(f * (1.0 - f) / points);
    EXPECT_NEAR(exact, 1.0 - f, 4.0 * sigma) << "sigma " << sigma;
    EXPECT_GT(exact, 0.2);
    EXPECT_LT(exact, 0.8);
}

TEST_F(PouredBed, TheSameSeedGivesTheSameBits) {
    const PelletBed again = generate_pellet_bed(*params);
    ASSERT_EQ(again.packing.size(), bed->packing.size());
    for (std::size_t i = 0; i < again.packing.size(); ++i) {
        EXPECT_EQ(again.packing.centers[i], bed->packing.centers[i]);
        EXPECT_EQ(again.packing.orientations[i].w, bed->packing.orientations[i].w);
    }
    EXPECT_EQ(again.steps, bed->steps);
}

TEST_F(PouredBed, TheSameBitsOnOneThreadAndOnTwo) {
    // 12 pellets make enough pairs for the force loops to run on the threads.
    const int threads = omp_get_max_threads();
    omp_set_num_threads(1);
    const PelletBed one = generate_pellet_bed(*params);
    omp_set_num_threads(2);
    const PelletBed two = generate_pellet_bed(*params);
    omp_set_num_threads(threads);
    ASSERT_EQ(one.packing.size(), two.packing.size());
    EXPECT_EQ(one.steps, two.steps);
    for (std::size_t i = 0; i < one.packing.size(); ++i) {
        EXPECT_EQ(one.packing.centers[i], two.packing.centers[i]);
        EXPECT_EQ(one.packing.orientations[i].x, two.packing.orientations[i].x);
    }
}

/// Trilobes (three lobes of diameter DL on a circle of 0.8 DL, L = 1.5 DL), unions of three
/// convex lobes, at nodes 0.08 d_v apart: poured into a tube (8 in a = 4) and into a
/// periodic cell (10), each ends below the tolerance by the lobes' exact depths and by the
/// brute force's points (drawn on the union's surface, tested by its own union).
PelletBedParameters trilobe_bed(std::uint64_t particles, const Container& container,
                                std::uint64_t seed) {
    PelletBedParameters p;
    p.particles = particles;
    p.seed = seed;
    p.shape = MultilobeShape::of(3, 1.0, 0.8, 1.5);
    p.container = container;
    p.node_spacing = 0.08;
    return p;
}

/// A bed poured in a tube (`period` 0) or in a square periodic cell: it ends below the
/// tolerance by the solver's exact depths and by the brute force's points, the pellets touch,
/// and in a cell at least two pairs meet only across its sides.
PelletBed expect_below_tolerance(const PelletBedParameters& params, double period = 0.0) {
    const PelletBed bed = generate_pellet_bed(params);
    // The smallest pellet's (PelletBedParameters::scales).
    const double tol = params.tolerance * params.smallest_dimension() * params.scale_range().first;
    EXPECT_LE(bed.max_depth_pair, tol);
    EXPECT_LE(bed.max_depth_wall, tol);
    EXPECT_GT(bed.max_depth_pair, 0.0);
    if (period > 0.0) {
        EXPECT_GE(pairs_across(bed.packing, 2.0 * bounding_radius(params.shape, 0.5), period), 2);
    }
    const Deepest d = std::visit(
        [&](const auto& shape) {
            return period > 0.0 ? brute_force(shape, bed.packing, 0.0, period, period)
                                : brute_force(shape, bed.packing,
                                              0.5 * params.container.tube_diameter().value());
        },
        params.shape);
    EXPECT_LE(d.pair, tol);
    EXPECT_LE(d.wall, tol);
    EXPECT_LE(d.pair, bed.max_depth_pair + 1e-12);
    return bed;
}

TEST(TrilobeBed, EndsBelowTheToleranceInATube) {
    expect_below_tolerance(trilobe_bed(8, Container::tube(4.0), 1));
}

TEST(TrilobeBed, EndsBelowTheToleranceAcrossTheCellsSides) {
    // A cell 3.2 d_v wide (the pellet's bounding sphere 1.33 d_v across).
    const double period = 3.2;
    expect_below_tolerance(trilobe_bed(10, Container(Periodic(period, period)), 2), period);
}

/// Rings (D = L, DI = D / 2: their walls D / 4 thick, the tolerance 1e-3 of that), which no
/// union of convex pieces makes, at nodes 0.08 d_v apart: poured into a tube (8 in a = 3.5) and
/// into a periodic cell (9 in 2.8 d_v), each ends below the tolerance by the surfaces' search
/// and by the brute force's points (drawn on the side, the bore and the ends, tested by its
/// own ring).
PelletBedParameters ring_bed(std::uint64_t particles, const Container& container,
                             std::uint64_t seed) {
    PelletBedParameters p;
    p.particles = particles;
    p.seed = seed;
    p.shape = MultilobeShape::cylinder(CylinderShape::ring(1.0, 0.5, 1.0));
    p.container = container;
    p.node_spacing = 0.08;
    return p;
}

TEST(RingBed, EndsBelowTheToleranceInATube) {
    const PelletBedParameters params = ring_bed(8, Container::tube(3.5), 1);
    // The tolerance is 1e-3 of the wall, (D - DI) / 2 over d_v.
    EXPECT_NEAR(params.tolerance * params.smallest_dimension(), 1e-3 * 0.25 / std::cbrt(1.5 * 0.75),
                1e-15);
    expect_below_tolerance(params);
}

TEST(RingBed, EndsBelowTheToleranceAcrossTheCellsSides) {
    // A cell 2.8 d_v wide (the ring's bounding sphere 1.36 d_v across).
    const double period = 2.8;
    expect_below_tolerance(ring_bed(9, Container(Periodic(period, period)), 3), period);
}

/// Spherocylinders (L = D, the whole pellet 2 D long), convex and smooth, pressed by one spring
/// on their exact depth: poured into a tube (20 in a = 4) and into a periodic cell (16 in
/// 3.2 d_v), each ends below the tolerance (1e-3 of D) by the segments' closed form and by the
/// brute force's points (drawn on the side and the caps, tested by their own distance from the
/// other's segment).
PelletBedParameters spherocylinder_bed(std::uint64_t particles, const Container& container,
                                       std::uint64_t seed) {
    PelletBedParameters p;
    p.particles = particles;
    p.seed = seed;
    p.shape = SpherocylinderShape::of_aspect(1.0);
    p.container = container;
    return p;
}

TEST(SpherocylinderBed, EndsBelowTheToleranceInATube) {
    const PelletBedParameters params = spherocylinder_bed(20, Container::tube(4.0), 1);
    // The tolerance is 1e-3 of D over d_v: D / d_v = (1 + 3/2)^(-1/3).
    EXPECT_NEAR(params.tolerance * params.smallest_dimension(), 1e-3 / std::cbrt(2.5), 1e-15);
    const PelletBed bed = expect_below_tolerance(params);
    EXPECT_EQ(bed.nodes, 0u);
    EXPECT_LE(bed.residual_force, params.force_tolerance);
    // At rest under gravity every pellet overlaps something it rests on.
    EXPECT_EQ(bed.touching_nothing, 0u);
}

// summary.json's warning on a column still falling: one pellet in a small bed may be caught
// between contacts, more than one in a hundred is not at rest (the 1e4 rods in one piece of
// docs/generate.md left 7 004 touching nothing).
TEST(SpherocylinderBed, SummaryWarnsWhereMoreThanOneInAHundredTouchNothing) {
    EXPECT_FALSE(unsettled_pellets_warning(0, 20));
    EXPECT_FALSE(unsettled_pellets_warning(1, 20));
    EXPECT_FALSE(unsettled_pellets_warning(100, 10000));
    const auto small = unsettled_pellets_warning(2, 20);
    ASSERT_TRUE(small);
    EXPECT_NE(small->find("2 of 20 pellets touch nothing"), std::string::npos) << *small;
    EXPECT_NE(small->find("--layer-height"), std::string::npos) << *small;
    const auto large = unsettled_pellets_warning(7004, 10000);
    ASSERT_TRUE(large);
    EXPECT_NE(large->find("7004 of 10000"), std::string::npos) << *large;
    EXPECT_TRUE(unsettled_pellets_warning(101, 10000));
}

TEST(SpherocylinderBed, EndsBelowTheToleranceAcrossTheCellsSides) {
    const double period = 3.2;
    expect_below_tolerance(spherocylinder_bed(16, Container(Periodic(period, period)), 2), period);
}

/// Pellets of two sizes, 0.8 and 1.25 of the reference (a ratio of 1.5625) in turn: each one's
/// size in the packing is its scale's, and the bed ends below the smallest pellet's tolerance
/// by the exact depths and by the brute force's points (each pellet drawn at its own size).
PelletBedParameters two_sizes(PelletBedParameters p) {
    p.scales.resize(p.particles);
    for (std::size_t i = 0; i < p.scales.size(); ++i)
        p.scales[i] = i % 2 == 0 ? 0.8 : 1.25;
    return p;
}

void expect_sizes(const PelletBedParameters& params, const PelletBed& bed) {
    ASSERT_EQ(bed.packing.size(), params.scales.size());
    for (std::size_t i = 0; i < bed.packing.size(); ++i)
        EXPECT_EQ(bed.packing.radii[i], 0.5 * params.scales[i]) << i;
}

TEST(SizedPelletBed, CylindersOfTwoSizesEndBelowTheSmallestsTolerance) {
    PelletBedParameters p;
    p.particles = 12;
    p.seed = 2;
    p.container = Container::tube(4.0);
    const PelletBedParameters params = two_sizes(p);
    EXPECT_EQ(params.scale_range(), (std::pair{0.8, 1.25}));
    expect_sizes(params, expect_below_tolerance(params));
}

// Scales of 1 are the bed without scales, bit for bit.
TEST(SizedPelletBed, ScalesOfOneGiveTheBedWithoutScales) {
    PelletBedParameters params = spherocylinder_bed(12, Container::tube(4.0), 4);
    const PelletBed plain = generate_pellet_bed(params);
    params.scales.assign(params.particles, 1.0);
    const PelletBed ones = generate_pellet_bed(params);
    EXPECT_EQ(plain.steps, ones.steps);
    ASSERT_EQ(plain.packing.size(), ones.packing.size());
    for (std::size_t i = 0; i < plain.packing.size(); ++i) {
        EXPECT_EQ(plain.packing.centers[i], ones.packing.centers[i]);
        EXPECT_EQ(plain.packing.orientations[i].w, ones.packing.orientations[i].w);
    }
}

TEST(PelletBedInput, RefusesScalesThatAreNotOnePerPelletOrTooFarApart) {
    PelletBedParameters p;
    p.particles = 3;
    const auto refusal = [&] {
        try {
            p.validate();
        } catch (const InvalidInput& e) {
            return std::string(e.what());
        }
        return std::string("accepted");
    };
    p.scales = {1.0, 1.0};
    EXPECT_EQ(refusal(), "scales = 2 is not allowed; allowed: one per pellet");
    p.scales = {1.0, 0.0, 1.0};
    EXPECT_EQ(refusal(), "scale = 0 is not allowed; allowed: a finite number > 0");
    p.scales = {0.5, 1.0, 5.5};
    EXPECT_EQ(refusal(), "size ratio = 11 is not allowed; allowed: at most 10");
    p.scales = {0.5, 1.0, 5.0};
    EXPECT_EQ(refusal(), "accepted");
}

/// The bed of `params` made on one thread (generate_pellet_bed) and on two (by `make`),
/// asserted to be the same bits. \return the second.
template <class Make>
PelletBed same_bits_on_one_thread_and_two(const PelletBedParameters& params, Make make) {
    const int threads = omp_get_max_threads();
    omp_set_num_threads(1);
    const PelletBed one = generate_pellet_bed(params);
    omp_set_num_threads(2);
    const PelletBed two = make(params);
    omp_set_num_threads(threads);
    EXPECT_EQ(one.steps, two.steps);
    EXPECT_EQ(one.packing.size(), two.packing.size());
    for (std::size_t i = 0; i < std::min(one.packing.size(), two.packing.size()); ++i) {
        EXPECT_EQ(one.packing.centers[i], two.packing.centers[i]);
        EXPECT_EQ(one.packing.orientations[i].x, two.packing.orientations[i].x);
    }
    return two;
}

TEST(SizedPelletBed, SpherocylindersOfTwoSizesEndBelowTheSmallestsToleranceOnAnyThreads) {
    const PelletBedParameters params = two_sizes(spherocylinder_bed(16, Container::tube(4.0), 2));
    expect_sizes(params, same_bits_on_one_thread_and_two(params, [](const PelletBedParameters& p) {
                     return expect_below_tolerance(p);
                 }));
}

// A tall bed in layers: 100 rods in a tube of a = 3 inserted over a column of 57 d_v, in layers
// of 10 d_v: five layers, each relaxed by its two stages; the whole bed (its seams included)
// ends below the tolerance by the exact depths and by the brute force, with the same bits on
// one thread and on two.
TEST(SpherocylinderBed, ATallBedInLayersEndsBelowTheToleranceOnAnyThreads) {
    PelletBedParameters params = spherocylinder_bed(100, Container::tube(3.0), 1);
    params.layer_height = 10.0;
    EXPECT_EQ(pellet_layers(params, 57.0), 5u);
    EXPECT_EQ(pellet_layers(params, 20.0), 1u);
    const PelletBed bed = same_bits_on_one_thread_and_two(
        params, [](const PelletBedParameters& p) { return expect_below_tolerance(p); });
    EXPECT_EQ(bed.layers, 5u);
    ASSERT_EQ(bed.stages.size(), 10u);
    for (std::uint32_t l = 0; l < 5; ++l) {
        EXPECT_EQ(bed.stages[2 * l].name, "settle");
        EXPECT_EQ(bed.stages[2 * l + 1].name, "final");
        EXPECT_EQ(bed.stages[2 * l + 1].layer, l);
    }
}

/// Seed 2 of that bed locks its first layer: six rods lying flat on the floor, pressed edge to
/// edge and against the wall in the floor's plane (every contact normal level, 0.0061 d_v deep
/// at gravity 2.5e-8 of the stiffness), which lowering the gravity does not free. One tap (the
/// rods tilted 0.02 rad, the gravity raised again) frees it, and the bed ends below the
/// tolerance by the brute force's points, balanced within 0.02 weights.
TEST(SpherocylinderBed, AFloorLayerLockedFlatIsTappedFree) {
    PelletBedParameters params = spherocylinder_bed(100, Container::tube(3.0), 2);
    params.layer_height = 10.0;
    const PelletBed bed = expect_below_tolerance(params);
    EXPECT_EQ(bed.kicks, 1u);
    EXPECT_LT(bed.residual_force, 0.02);
    EXPECT_LT(bed.residual_torque, 0.02);
}

/// Seed 3 of 60 rods of L / D = 0.45 in a tube of a = 5: its last relaxation, every exact depth
/// below the tolerance, stalls with 0.25 weights of force left (5 000 steps without the largest
/// residual 1 % lower); run on with the patience of a bed at rest it ends balanced within 1 % of
/// a pellet's weight, force and torque, still below the tolerance.
TEST(SpherocylinderBed, ARelaxationStalledAtRestRunsOnUntilBalanced) {
    PelletBedParameters params = spherocylinder_bed(60, Container::tube(5.0), 3);
    params.shape = SpherocylinderShape::of_aspect(0.45);
    const PelletBed bed = expect_below_tolerance(params);
    EXPECT_EQ(bed.kicks, 0u);
    EXPECT_LE(bed.residual_force, params.force_tolerance);
    EXPECT_LE(bed.residual_torque, params.force_tolerance);
}

TEST(SpherocylinderBed, TheSameBitsOnOneThreadAndOnTwo) {
    same_bits_on_one_thread_and_two(
        spherocylinder_bed(20, Container::tube(4.0), 1),
        [](const PelletBedParameters& p) { return generate_pellet_bed(p); });
}

/// The void fraction of `bed` (poured by `params`) between the heights low and high, by the
/// exact volumes.
double band_void_fraction(const PelletBedParameters& params, const PelletBed& bed, double low,
                          double high) {
    return std::visit(
        [&](const auto& shape) {
            using S = std::decay_t<decltype(shape)>;
            return void_fraction(ShapedBed<S>(bed.packing, {shape}), params.container, low, high);
        },
        params.shape);
}

/// Friction (mu = 0.5 between pellets and at the walls and floor): 40 spherocylinders poured
/// into a tube of a = 4 stand looser than without it (a poured bed against the dense limit:
/// 0.530 against 0.367 in the band 0.5-2.5 d_v, measured), end below the tolerance by the
/// brute force's points, and give the same bits on one thread and on two; a friction of 0
/// is the frictionless bed, bit for bit.
TEST(FrictionalPelletBed, SpherocylindersPourLooserWithTheSameBitsOnAnyThreads) {
    PelletBedParameters params = spherocylinder_bed(40, Container::tube(4.0), 1);
    const PelletBed dense = generate_pellet_bed(params);
    params.friction = params.wall_friction = 0.0; // given as 0: the same bed
    EXPECT_EQ(generate_pellet_bed(params).packing.centers, dense.packing.centers);
    params.friction = params.wall_friction = 0.5;
    const PelletBed two = same_bits_on_one_thread_and_two(
        params, [](const PelletBedParameters& p) { return expect_below_tolerance(p); });
    const double loose = band_void_fraction(params, two, 0.5, 2.5);
    const double packed = band_void_fraction(params, dense, 0.5, 2.5);
    EXPECT_GT(loose, packed + 0.05) << loose << " " << packed;
}

/// The level-set contact with friction: 12 cylinders (L = D) in a tube of a = 3 end below the
/// tolerance by the brute force's points, looser than without friction in the band 0.2-1.2 d_v
/// (0.631 against 0.461, measured).
TEST(FrictionalPelletBed, CylindersEndBelowTheToleranceAndLooser) {
    PelletBedParameters params;
    params.particles = 12;
    params.seed = 3;
    params.container = Container::tube(3.0);
    const PelletBed dense = generate_pellet_bed(params);
    params.friction = params.wall_friction = 0.5;
    const PelletBed loose = expect_below_tolerance(params);
    const double e_loose = band_void_fraction(params, loose, 0.2, 1.2);
    const double e_dense = band_void_fraction(params, dense, 0.2, 1.2);
    EXPECT_GT(e_loose, e_dense + 0.05) << e_loose << " " << e_dense;
}

TEST(PelletBedInput, AColumnTooDenseToPourIsLoosenedAndAnEmptyOneRefused) {
    // At e0 = 0.3 the bounding spheres would fill more of the column than random addition
    // reaches: the column is drawn again looser (0.65, 0.825, ...) and the bed goes on to its
    // relaxation, which the run control stops at once (Cancelled, not InvalidInput). Each
    // draw that finds no room costs 10 000 tries, so this takes a few seconds.
    PelletBedParameters p;
    p.particles = 50;
    p.e0 = 0.3;
    p.container = Container::tube(4.0);
    RunControl stop;
    stop.should_stop = [] { return true; };
    EXPECT_THROW(generate_pellet_bed(p, stop), Cancelled);
    p.e0 = 1.0;
    EXPECT_THROW(generate_pellet_bed(p), InvalidInput);
}

TEST(PelletBedInput, RefusesAFrictionOutOfRange) {
    PelletBedParameters p;
    p.friction = -0.1;
    EXPECT_THROW(p.validate(), InvalidInput);
    p.friction = 0.3;
    p.wall_friction = std::numeric_limits<double>::quiet_NaN();
    EXPECT_THROW(p.validate(), InvalidInput);
    p.wall_friction = 101.0;
    EXPECT_THROW(p.validate(), InvalidInput);
    p.wall_friction = 100.0;
    EXPECT_NO_THROW(p.validate());
}

} // namespace
