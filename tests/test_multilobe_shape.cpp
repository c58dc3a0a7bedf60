// The multilobe pellet (multilobe_shape.hpp) against closed forms and counts that share no code
// with it: the section's area (two discs' union by their lens; three by a grid), the unit
// ball's volume, the overlap of two trilobes lobe to lobe, how far a lobe reaches into a wall,
// the volume upright in a slab and in a cylindrical shell and turned at the tube's wall, the
// surface nodes and circles on the union's surface (never inside another lobe), and the
// triangulated surface; the cylinder as its one-lobe case answers as CylinderShape does; the
// pellet solver's hull tests (pellet_hull.hpp) against the exact gaps and sampled depths.
#include <cmath>
#include <numbers>
#include <random>
#include <vector>

#include <gtest/gtest.h>

#include "rotations.hpp"

#include "generate/pellet_hull.hpp"
#include "packbed/box.hpp"
#include "packbed/container.hpp"
#include "packbed/cylinder_shape.hpp"
#include "packbed/multilobe_shape.hpp"

using namespace packbed;

namespace {

constexpr double pi = std::numbers::pi;

/// Whether the body-frame point (x, y) lies in one of n discs of radius r whose centres lie
/// at distance c from the origin at the angles 2 pi k / n: the test's own union.
bool in_discs(int n, double r, double c, double x, double y) {
    for (int k = 0; k < n; ++k) {
        const double a = 2.0 * pi * k / n;
        if (std::hypot(x - c * std::cos(a), y - c * std::sin(a)) <= r)
            return true;
    }
    return false;
}

/// The area of the union of the discs by the midpoint rule on an m x m grid over its box.
double counted_area(int n, double r, double c, int m) {
    const double half = c + r;
    long count = 0;
    for (int i = 0; i < m; ++i)
        for (int j = 0; j < m; ++j)
            count += in_discs(n, r, c, -half + 2.0 * half * (i + 0.5) / m,
                              -half + 2.0 * half * (j + 0.5) / m);
    return 4.0 * half * half * static_cast<double>(count) / (static_cast<double>(m) * m);
}

/// The brute force's depth of a body-frame point inside the union (positive inside): the
/// deepest of the lobes' min(r - distance from its axis, h - |z|).
double union_depth(const MultilobeShape& s, const Vec3& q) {
    double best = -1e300;
    for (int k = 0; k < s.lobes; ++k) {
        const double a = 2.0 * pi * k / s.lobes;
        const double rho = std::hypot(q.x - s.circle * std::cos(a), q.y - s.circle * std::sin(a));
        best = std::max(best, std::min(s.lobe.radius - rho, s.lobe.half_length - std::abs(q.z)));
    }
    return best;
}

const MultilobeShape trilobe{{0.5, 0.8}, 3, 0.4};

} // namespace

TEST(MultilobeShape, SectionAreaIsTheLobesUnion) {
    // Two discs: 2 pi r^2 less their lens (centres 2c apart: 2 r^2 acos(c / r) - 2 c sqrt(r^2 -
    // c^2)).
    for (const double c : {0.1, 0.3, 0.5}) {
        const MultilobeShape two{{0.5, 1.0}, 2, c};
        const double lens = 2.0 * 0.25 * std::acos(c / 0.5) - 2.0 * c * std::sqrt(0.25 - c * c);
        EXPECT_NEAR(two.section_area(), 2.0 * pi * 0.25 - lens, 1e-14) << c;
    }
    // Three and five lobes against the grid's count (error about the perimeter over m).
    for (const int n : {3, 5})
        for (const double c : {0.2, 0.5}) {
            const MultilobeShape s{{0.5, 1.0}, n, c};
            EXPECT_NEAR(s.section_area(), counted_area(n, 0.5, c, 2000), 2e-4) << n << " " << c;
        }
    // One lobe is the disc.
    EXPECT_DOUBLE_EQ(MultilobeShape::cylinder({0.7, 1.0}).section_area(), pi * 0.49);
}

TEST(MultilobeShape, OfHasTheUnitBallsVolumeAndTheGivenProportions) {
    const MultilobeShape s = MultilobeShape::of(3, 1.2, 0.9, 2.0);
    EXPECT_NEAR(s.volume(1.0), 4.0 * pi / 3.0, 1e-12);
    EXPECT_NEAR(s.circle / s.lobe.radius, 0.9 / 1.2, 1e-14);
    EXPECT_NEAR(s.lobe.half_length / s.lobe.radius, 2.0 / 1.2, 1e-14);
    EXPECT_NEAR(s.bounding_radius(2.0),
                2.0 * std::hypot(s.circle + s.lobe.radius, s.lobe.half_length), 1e-14);
}

TEST(MultilobeShape, TheArcsMeetInTheGrooves) {
    // The arc's end on lobe 0 is the point the ray at pi / 3 leaves lobe 0 and lobe 1 at once.
    const double half = trilobe.arc_half_angle();
    const Vec3 end{trilobe.circle + trilobe.lobe.radius * std::cos(half),
                   trilobe.lobe.radius * std::sin(half), 0.0};
    EXPECT_NEAR(std::atan2(end.y, end.x), pi / 3.0, 1e-14);
    const double a1 = 2.0 * pi / 3.0;
    EXPECT_NEAR(
        std::hypot(end.x - trilobe.circle * std::cos(a1), end.y - trilobe.circle * std::sin(a1)),
        trilobe.lobe.radius, 1e-14);
    EXPECT_GT(half, pi / 3.0);
    EXPECT_LT(half, pi);
}

TEST(MultilobeShape, NodesAndCirclesLieOnTheUnionsSurface) {
    const double spacing = 0.02;
    double ends = 0.0, all = 0.0;
    for (const SurfaceNode& n : trilobe.surface_nodes(spacing)) {
        all += n.area;
        // On the surface: depth 0 by the brute force's union (to rounding), or on an end.
        EXPECT_NEAR(union_depth(trilobe, n.point), 0.0, 1e-12)
            << n.point.x << " " << n.point.y << " " << n.point.z;
    }
    for (const SurfaceNode& n : trilobe.surface_nodes(spacing, false))
        ends += n.area;
    // The nodes stand for the two sections and the N arcs, within the rings' and rows'
    // discretisation (a node's band is cut by the wedges' edges); so do the ends' inner rings
    // with the circles' arcs.
    const double section = trilobe.section_area();
    const double side = 3.0 * 2.0 * trilobe.arc_half_angle() * trilobe.lobe.radius * 1.6;
    double arcs = 0.0;
    for (const SurfaceCircle& c : trilobe.surface_circles(spacing))
        arcs += c.area_per_length * 2.0 * c.arc_half * c.radius;
    EXPECT_NEAR(all, 2.0 * section + side, 0.01 * (2.0 * section + side));
    EXPECT_NEAR(ends + arcs, 2.0 * section + side, 0.01 * (2.0 * section + side));
    EXPECT_NEAR(trilobe.surface_area(1.0), 2.0 * section + side, 1e-12);
    // Each circle's arc on the surface, its ends in the grooves and beyond them inside a
    // neighbour.
    const auto circles = trilobe.surface_circles(spacing);
    ASSERT_EQ(circles.size() % 3, 0u);
    for (const SurfaceCircle& c : circles) {
        for (const double t : {-1.0, -0.5, 0.0, 0.7, 1.0}) {
            const double phi = c.arc_middle + t * c.arc_half;
            const Vec3 q{c.x + c.radius * std::cos(phi), c.y + c.radius * std::sin(phi), c.z};
            EXPECT_NEAR(union_depth(trilobe, q), 0.0, 1e-12) << t;
        }
        if (std::abs(c.z) >= trilobe.lobe.half_length) // a rim: beyond it, still on an end
            continue;
        const double beyond = c.arc_middle + c.arc_half + 0.05;
        const Vec3 q{c.x + c.radius * std::cos(beyond), c.y + c.radius * std::sin(beyond), c.z};
        EXPECT_GT(union_depth(trilobe, q), 0.0);
    }
}

TEST(MultilobeShape, UprightPairsOverlapByTheirDeepestLobes) {
    // Both upright at the same height: each pair of lobes is two parallel cylinders side by
    // side, overlapping by 2 r less their axes' distance. Turned about z at random and moved
    // in the plane, the pellets overlap by the largest of these (apart: the gap is the least
    // of the axes' distances less 2 r).
    std::mt19937_64 rng(9);
    std::uniform_real_distribution<double> u(0.0, 1.0);
    int overlapping = 0, apart = 0;
    for (int trial = 0; trial < 40; ++trial) {
        const double ta = 2.0 * pi * u(rng), tb = 2.0 * pi * u(rng);
        const double d = 1.5 + 0.45 * u(rng), angle = 2.0 * pi * u(rng);
        const Placement a{{0.0, 0.0, 0.0}, about({0.0, 0.0, 1.0}, ta), 1.0};
        const Placement b{
            {d * std::cos(angle), d * std::sin(angle), 0.0}, about({0.0, 0.0, 1.0}, tb), 1.0};
        double deepest = -1e300;
        for (int k = 0; k < 3; ++k)
            for (int l = 0; l < 3; ++l) {
                const double ak = ta + 2.0 * pi * k / 3.0, bl = tb + 2.0 * pi * l / 3.0;
                const double dx = b.position.x + 0.4 * std::cos(bl) - 0.4 * std::cos(ak);
                const double dy = b.position.y + 0.4 * std::sin(bl) - 0.4 * std::sin(ak);
                deepest = std::max(deepest, 1.0 - std::hypot(dx, dy));
            }
        const PairOverlap o = trilobe.pair_overlap(a, trilobe, b, b.position);
        EXPECT_NEAR(trilobe.pair_gap(a, trilobe, b, b.position), -deepest, 1e-9) << trial;
        if (deepest > 0.0) {
            EXPECT_NEAR(o.depth, deepest, 1e-9) << trial;
            EXPECT_NEAR(o.normal.z, 0.0, 1e-6);
            ++overlapping;
        } else {
            EXPECT_LE(o.depth, 0.0);
            ++apart;
        }
    }
    EXPECT_GT(overlapping, 5);
    EXPECT_GT(apart, 5);
}

TEST(MultilobeShape, WallOverlapIsTheDeepestLobes) {
    // Upright in a box whose wall is at x = 2: lobe k reaches x + c cos(2 pi k / 3) + r.
    const Container box(Box(-2.0, 2.0, -2.0, 2.0));
    for (const double turn : {0.0, pi / 3.0, 0.4}) {
        const Placement p{{1.0, 0.0, 3.0}, about({0.0, 0.0, 1.0}, turn), 1.0};
        double reach = 0.0;
        for (int k = 0; k < 3; ++k)
            reach = std::max(reach, 1.0 + 0.4 * std::cos(turn + 2.0 * pi * k / 3.0) + 0.5);
        EXPECT_NEAR(trilobe.wall_overlap(box, p), std::max(0.0, reach - 2.0), 1e-9) << turn;
        // Grown by 0.6, it reaches the wall in every turn.
        EXPECT_NEAR(trilobe.wall_overlap(box, p, 0.6), reach + 0.6 - 2.0, 1e-9) << turn;
    }
    // The support along x of the unturned pellet is lobe 0's tip.
    const Vec3 s = trilobe.support({{0.0, 0.0, 0.0}, {}, 1.0}, {1.0, 0.0, 0.0});
    EXPECT_NEAR(s.x, 0.9, 1e-15);
}

TEST(MultilobeShape, VolumeUprightInASlabAndAShell) {
    const Container tube = Container::tube(6.0); // radius 3
    const Placement upright{{0.3, -0.2, 2.0}, about({0.0, 0.0, 1.0}, 0.3), 1.0};
    // Upright (from 1.2 to 2.8): a slab holds the section times its part of the length.
    EXPECT_NEAR(trilobe.volume_in(tube, upright, 2.5, 4.0), trilobe.section_area() * 0.3,
                1e-8 * trilobe.volume(1.0));
    EXPECT_NEAR(trilobe.volume_in(tube, upright, 0.0, 10.0), trilobe.volume(1.0),
                1e-8 * trilobe.volume(1.0));
    // Upright on the axis: the part at least 2.2 from the wall (radius 0.8 about the axis)
    // is the whole section where it reaches less than 0.8 (c + r = 0.9): by the grid's count
    // of the section within the radius 0.8, times L.
    const Placement centred{{0.0, 0.0, 2.0}, {}, 1.0};
    const int m = 2000;
    long count = 0;
    for (int i = 0; i < m; ++i)
        for (int j = 0; j < m; ++j) {
            const double x = -0.9 + 1.8 * (i + 0.5) / m, y = -0.9 + 1.8 * (j + 0.5) / m;
            count += in_discs(3, 0.5, 0.4, x, y) && std::hypot(x, y) <= 0.8;
        }
    const double within = 1.8 * 1.8 * static_cast<double>(count) / (double(m) * m);
    EXPECT_NEAR(trilobe.volume_from_wall(tube, 0, 2.2, centred, 0.0, 10.0), within * 1.6,
                3e-4 * 1.6);
}

TEST(MultilobeShape, VolumeTurnedAtTheWallAgreesWithTheCount) {
    // Turned at random with a lobe through a tube's wall: the part inside the tube, and a box's
    // share, against points on a grid of the pellet's own box tested by the union.
    const Container tube = Container::tube(4.0); // radius 2
    std::mt19937_64 rng(5);
    std::uniform_real_distribution<double> u(0.0, 1.0);
    for (int trial = 0; trial < 2; ++trial) {
        const Placement p{{1.4, 0.3, 3.0}, uniform_rotation(u(rng), u(rng), u(rng)), 1.0};
        const double v = trilobe.volume_in(tube, p, 0.0, 10.0);
        const int m = 120;
        long count = 0, total = 0;
        for (int i = 0; i < m; ++i)
            for (int j = 0; j < m; ++j)
                for (int k = 0; k < m; ++k) {
                    const Vec3 q{-0.9 + 1.8 * (i + 0.5) / m, -0.9 + 1.8 * (j + 0.5) / m,
                                 -0.8 + 1.6 * (k + 0.5) / m};
                    if (union_depth(trilobe, q) < 0.0)
                        continue;
                    ++total;
                    const Vec3 x = p.position + rotate(p.orientation, q);
                    count += std::hypot(x.x, x.y) <= 2.0;
                }
        const double cell = 1.8 * 1.8 * 1.6 / (double(m) * m * m);
        EXPECT_NEAR(static_cast<double>(total) * cell, trilobe.volume(1.0),
                    3e-3 * trilobe.volume(1.0));
        EXPECT_NEAR(v, static_cast<double>(count) * cell, 3e-3 * trilobe.volume(1.0));
        EXPECT_LT(v, trilobe.volume(1.0) - 0.01); // a part is outside
    }
}

TEST(MultilobeShape, SurfaceIsClosedAndInscribed) {
    for (const int level : {0, 2}) {
        const TriangleMesh m = trilobe.unit_surface(level);
        // Chords of each lobe's arc: inside the pellet, within the cylinder's chord error.
        const double n = 12 << level;
        const double error = trilobe.lobe.radius * (1.0 - std::cos(pi / n));
        EXPECT_LT(m.volume(), trilobe.volume(1.0));
        EXPECT_GT(m.volume(), trilobe.volume(1.0) - error * trilobe.surface_area(1.0));
        for (const Vec3& v : m.vertices)
            EXPECT_NEAR(std::max(union_depth(trilobe, v), 0.0), 0.0, 1e-12);
    }
}

TEST(MultilobeShape, OneLobeAnswersAsTheCylinder) {
    const CylinderShape c = CylinderShape::of_aspect(1.3);
    const MultilobeShape one = MultilobeShape::cylinder(c);
    const Placement a{{0.1, 0.2, 1.0}, about({1.0, 0.0, 0.0}, 0.7), 0.5};
    const Placement b{{0.7, 0.1, 1.1}, about({0.0, 1.0, 0.0}, 1.1), 0.5};
    const Vec3 ab = b.position - a.position;
    EXPECT_EQ(one.pair_overlap(a, one, b, ab).depth, c.pair_overlap(a, c, b, ab).depth);
    EXPECT_EQ(one.volume(0.5), c.volume(0.5));
    EXPECT_EQ(one.bounding_radius(0.5), c.bounding_radius(0.5));
    EXPECT_EQ(one.surface_nodes(0.05).size(), c.surface_nodes(0.05).size());
    const Container tube = Container::tube(3.0);
    EXPECT_EQ(one.volume_in(tube, a, 0.8, 1.2), c.volume_in(tube, a, 0.8, 1.2));
}

namespace {

/// A rotation drawn from `rng`: about a direction uniform on the sphere by an angle uniform in
/// [0, pi].
Quaternion random_turn(std::mt19937_64& rng) {
    std::normal_distribution<double> g;
    std::uniform_real_distribution<double> angle(0.0, pi);
    Vec3 axis{g(rng), g(rng), g(rng)};
    return about(axis * (1.0 / norm(axis)), angle(rng));
}

/// The hull the pellet solver takes for `s` at `size`: its length, the lobes' circle widened by
/// a lobe's radius.
detail::HullCylinder hull_of(const MultilobeShape& s, double size) {
    return {s.lobe.half_length * size, (s.circle + s.lobe.radius) * size};
}

} // namespace

// A plane the hull test finds between two pellets parts them: their exact gap (the least
// support of their lobes' Minkowski difference, cylinder_depth, which shares no code with the
// test) is positive every time; and the test finds such a plane for most pairs whose bounding
// spheres meet but that are apart by more than a tenth of d_v. Every third pair has its second
// pellet at 0.6 of the first's size (the hulls of a bed with sizes).
TEST(PelletHull, APlaneItFindsPartsThePelletsAsTheirExactGapSays) {
    std::mt19937_64 rng(7);
    std::uniform_real_distribution<double> uniform(0.0, 1.0);
    for (const MultilobeShape& s : {MultilobeShape::cylinder(CylinderShape::of_aspect(1.0)),
                                    MultilobeShape::cylinder(CylinderShape::ring(1.0, 0.5, 1.0)),
                                    MultilobeShape::of(3, 1.0, 0.8, 1.5)}) {
        const double reach = 2.0 * s.bounding_radius(1.0);
        int apart = 0, wide = 0, found = 0;
        for (int trial = 0; trial < 3000; ++trial) {
            const Quaternion qa = random_turn(rng), qb = random_turn(rng);
            Vec3 dir{uniform(rng) - 0.5, uniform(rng) - 0.5, uniform(rng) - 0.5};
            const Vec3 u = dir * (reach * (0.3 + 0.7 * uniform(rng)) / norm(dir));
            const double size_b = trial % 3 == 2 ? 0.6 : 1.0;
            const Placement a{{0.0, 0.0, 0.0}, qa, 1.0}, b{u, qb, size_b};
            const bool parted = detail::hulls_apart(hull_of(s, 1.0), hull_of(s, size_b),
                                                    rotate(qa, {0.0, 0.0, 1.0}),
                                                    rotate(qb, {0.0, 0.0, 1.0}), u, 1e-9);
            const double gap = s.pair_gap(a, s, b, u);
            if (parted) {
                ++apart;
                EXPECT_GT(gap, 0.0) << trial;
            }
            if (gap > 0.2) { // a tenth of d_v = 2
                ++wide;
                found += parted ? 1 : 0;
            }
        }
        EXPECT_GT(apart, 300);
        EXPECT_GT(found, wide / 2) << found << " of " << wide;
    }
}

// A circle or a sphere the hull test calls clear of a pellet holds no point inside it: 720
// points about each circle (and the sphere's poles and equator) have a signed depth of at most
// zero in the pellet (its own signed_depth, in its body frame).
TEST(PelletHull, ACircleOrSphereClearOfTheHullHasNoPointInThePellet) {
    std::mt19937_64 rng(11);
    std::uniform_real_distribution<double> uniform(-1.0, 1.0);
    for (const MultilobeShape& s : {MultilobeShape::cylinder(CylinderShape::of_aspect(1.0)),
                                    MultilobeShape::of(3, 1.0, 0.8, 1.5)}) {
        const detail::HullCylinder hull = hull_of(s, 1.0);
        const Vec3 axis{0.0, 0.0, 1.0}; // the pellet in its own frame
        int clear = 0;
        for (int trial = 0; trial < 4000; ++trial) {
            const Vec3 centre{2.0 * uniform(rng), 2.0 * uniform(rng), 2.0 * uniform(rng)};
            Vec3 m{uniform(rng), uniform(rng), uniform(rng)};
            m = m * (1.0 / norm(m));
            const double radius = 0.2 + 0.6 * std::abs(uniform(rng));
            const Vec3 side = cross(m, std::abs(m.x) < 0.9 ? Vec3{1, 0, 0} : Vec3{0, 1, 0});
            const Vec3 e1 = side * (1.0 / norm(side));
            const Vec3 e2 = cross(m, e1);
            const double tilt = dot(m, axis);
            if (detail::clear_of_hull(hull, axis, centre, radius,
                                      radius * std::sqrt(std::max(0.0, 1.0 - tilt * tilt)), 1e-9)) {
                ++clear;
                for (int k = 0; k < 720; ++k) {
                    const double t = 2.0 * pi * k / 720;
                    const Vec3 q =
                        centre + e1 * (radius * std::cos(t)) + e2 * (radius * std::sin(t));
                    ASSERT_LE(s.signed_depth(q), 0.0) << trial << " " << k;
                }
            }
            if (detail::clear_of_hull(hull, axis, centre, radius, radius, 1e-9)) {
                for (const Vec3& v : {e1, e2, m, -1.0 * e1, -1.0 * e2, -1.0 * m})
                    ASSERT_LE(s.signed_depth(centre + v * radius), 0.0) << trial;
            }
        }
        EXPECT_GT(clear, 1000);
    }
}
