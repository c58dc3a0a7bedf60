// The cylinder pellet (cylinder_shape.hpp) against closed forms: its volume, support function
// and surface; the overlap of two pellets side by side, end to end and crossed; how far it
// reaches into each container's walls (Container::convex_wall_overlap) and where a line crosses
// each side (Container::side_chord); its volume in a slab, a cylindrical shell, a box and
// sticking out of a tube's wall; and the loops that are templates on the shape, run with it.
// Where no closed form exists the reference is a brute-force count that shares no code with
// the shape: points on a grid of the body tested against the region.
#include <cmath>
#include <limits>
#include <numbers>
#include <random>
#include <vector>

#include <gtest/gtest.h>
#include <omp.h>

#include "rotations.hpp"

#include "particles/section_volume.hpp"

#include "packbed/analysis.hpp"
#include "packbed/annulus.hpp"
#include "packbed/bed_volume.hpp"
#include "packbed/box.hpp"
#include "packbed/cone.hpp"
#include "packbed/container.hpp"
#include "packbed/cylinder.hpp"
#include "packbed/cylinder_shape.hpp"
#include "packbed/multilobe_shape.hpp"
#include "packbed/periodic.hpp"
#include "packbed/soft_sphere.hpp"

using namespace packbed;

namespace {

constexpr double pi = std::numbers::pi;

/// A uniformly random rotation (Shoemake 1992, from three uniform numbers).
Quaternion random_rotation(std::mt19937_64& rng) {
    std::uniform_real_distribution<double> u(0.0, 1.0);
    const double u1 = u(rng), u2 = u(rng), u3 = u(rng);
    return uniform_rotation(u1, u2, u3);
}

/// The area of the part of a circle of radius r beyond a chord at distance d from its centre.
double segment_area(double r, double d) {
    if (d >= r)
        return 0.0;
    if (d <= -r)
        return pi * r * r;
    return r * r * std::acos(d / r) - d * std::sqrt(r * r - d * d);
}

/// The area shared by circles of radii a and b whose centres lie `c` apart.
double lens_area(double a, double b, double c) {
    if (c >= a + b)
        return 0.0;
    if (c <= std::abs(a - b))
        return pi * std::min(a, b) * std::min(a, b);
    const double x = (c * c + a * a - b * b) / (2.0 * c); // the chord's distance from a's centre
    return segment_area(a, x) + segment_area(b, c - x);
}

/// Brute force: the volume of the cylinder's points (radius r, half-length h, placed by p)
/// for which `inside` holds, by the midpoint rule on n x n x n cells of its body coordinates
/// (rho^2 / 2 uniform, phi, t): each cell holds the same volume.
template <class Inside>
double counted_volume(const Placement& p, double r, double h, int n, Inside&& inside) {
    const Vec3 e1 = rotate(p.orientation, {1.0, 0.0, 0.0});
    const Vec3 e2 = rotate(p.orientation, {0.0, 1.0, 0.0});
    const Vec3 a = rotate(p.orientation, {0.0, 0.0, 1.0});
    long count = 0;
    for (int i = 0; i < n; ++i) {
        const double rho = r * std::sqrt((i + 0.5) / n);
        for (int j = 0; j < n; ++j) {
            const double phi = 2.0 * pi * (j + 0.5) / n;
            for (int k = 0; k < n; ++k) {
                const double t = -h + 2.0 * h * (k + 0.5) / n;
                const Vec3 x =
                    p.position + rho * std::cos(phi) * e1 + rho * std::sin(phi) * e2 + t * a;
                count += inside(x) ? 1 : 0;
            }
        }
    }
    return 2.0 * pi * r * r * h * static_cast<double>(count) / (static_cast<double>(n) * n * n);
}

const CylinderShape unit_cylinder = CylinderShape::of_aspect(1.0);

} // namespace

TEST(CylinderShape, OfAspectHasTheUnitBallsVolume) {
    for (const double aspect : {0.25, 1.0, 3.0}) {
        const CylinderShape c = CylinderShape::of_aspect(aspect);
        EXPECT_NEAR(c.volume(1.0), 4.0 / 3.0 * pi, 1e-14);
        EXPECT_NEAR(c.half_length / c.radius, aspect, 1e-14);
        EXPECT_NEAR(c.volume(0.5), 4.0 / 3.0 * pi / 8.0, 1e-14);
    }
    // L = D: D / d_v = (2/3)^(1/3) = 0.87358.
    EXPECT_NEAR(unit_cylinder.radius, 0.8735804647362989, 1e-15);
    EXPECT_NEAR(unit_cylinder.bounding_radius(2.0), 2.0 * std::sqrt(2.0) * 0.8735804647362989,
                1e-14);
}

TEST(CylinderShape, SupportIsTheFarthestPointOfTheSurface) {
    std::mt19937_64 rng(11);
    std::normal_distribution<double> g;
    const CylinderShape c{0.7, 1.3};
    for (int trial = 0; trial < 20; ++trial) {
        const Placement p{{g(rng), g(rng), g(rng)}, random_rotation(rng), 1.5};
        const Vec3 v{g(rng), g(rng), g(rng)};
        const Vec3 s = c.support(p, v);
        // The rims hold the farthest point along any direction: the support's projection is
        // the largest of theirs, and the support is a point of a rim.
        double best = -1e300;
        for (int k = 0; k < 20000; ++k) {
            const double phi = 2.0 * pi * k / 20000.0;
            for (const double z : {-c.half_length, c.half_length}) {
                const Vec3 body{c.radius * std::cos(phi), c.radius * std::sin(phi), z};
                best = std::max(best, dot(v, p.position + rotate(p.orientation, body) * p.size));
            }
        }
        EXPECT_GE(dot(v, s), best - 1e-12);
        EXPECT_NEAR(dot(v, s), best, 1e-6 * norm(v));
        const Vec3 body = rotate(conjugate(p.orientation), s - p.position) * (1.0 / p.size);
        EXPECT_NEAR(std::hypot(body.x, body.y), c.radius, 1e-12);
        EXPECT_NEAR(std::abs(body.z), c.half_length, 1e-12);
    }
}

TEST(CylinderShape, SurfaceIsClosedOutwardAndInscribed) {
    for (const int level : {0, 2}) {
        const TriangleMesh m = unit_cylinder.unit_surface(level);
        const int n = 12 << level;
        // The inscribed prism: n / 2 sin(2 pi / n) R^2 L.
        const double prism = 0.5 * n * std::sin(2.0 * pi / n) * unit_cylinder.radius *
                             unit_cylinder.radius * 2.0 * unit_cylinder.half_length;
        EXPECT_NEAR(m.volume(), prism, 1e-12);
        EXPECT_EQ(m.triangles.size(), 4u * static_cast<unsigned>(n));
    }
}

TEST(CylinderShape, DemSpheresLieInsideAndReachTheSurface) {
    for (const double aspect : {0.3, 1.0, 2.5}) {
        const CylinderShape c = CylinderShape::of_aspect(aspect);
        const Placement p{{1.0, 2.0, 3.0}, about({0.0, 1.0, 0.0}, 0.4), 2.0};
        double reach_side = 0.0, reach_end = 0.0;
        int count = 0;
        c.dem_spheres(p, [&](const DemSphere& s) {
            const Vec3 body = rotate(conjugate(p.orientation), s.centre - p.position);
            const double side = std::hypot(body.x, body.y) + s.radius;
            const double end = std::abs(body.z) + s.radius;
            EXPECT_LE(side, c.radius * p.size + 1e-12);
            EXPECT_LE(end, c.half_length * p.size + 1e-12);
            reach_side = std::max(reach_side, side);
            reach_end = std::max(reach_end, end);
            EXPECT_NEAR(s.radius, 0.5 * std::min(c.radius, c.half_length) * p.size, 1e-15);
            ++count;
        });
        EXPECT_NEAR(reach_side, c.radius * p.size, 1e-12);
        EXPECT_NEAR(reach_end, c.half_length * p.size, 1e-12);
        EXPECT_GT(count, 1);
    }
}

TEST(CylinderShape, PairOverlapSideBySideEndToEndAndCrossed) {
    const CylinderShape c{0.5, 1.0};
    std::mt19937_64 rng(5);
    for (int trial = 0; trial < 5; ++trial) {
        const Quaternion q = random_rotation(rng);
        const Vec3 axis = rotate(q, {0.0, 0.0, 1.0}), across = rotate(q, {1.0, 0.0, 0.0});
        const Placement a{{0.3, -0.2, 4.0}, q, 1.0};
        // Parallel, side by side 0.9 apart: 2 R - 0.9 = 0.1 along the line of centres,
        // touching in the middle of the overlap (R - 0.05 from a's axis) along their length.
        {
            const Vec3 ab = 0.9 * across;
            const PairOverlap o = c.pair_overlap(a, c, {a.position + ab, q, 1.0}, ab);
            EXPECT_NEAR(o.depth, 0.1, 1e-9);
            EXPECT_NEAR(dot(o.normal, across), 1.0, 1e-8);
            EXPECT_NEAR(dot(o.point, across), 0.45, 1e-8);
            EXPECT_LE(std::abs(dot(o.point, axis)), 1.0);
        }
        // Coaxial, end to end 1.97 apart: L - 1.97 = 0.03 along the axis.
        {
            const Vec3 ab = 1.97 * axis;
            const PairOverlap o = c.pair_overlap(a, c, {a.position + ab, q, 1.0}, ab);
            EXPECT_NEAR(o.depth, 0.03, 1e-9);
            EXPECT_NEAR(dot(o.normal, axis), 1.0, 1e-8);
        }
        // Crossed (the second turned a quarter about the line of centres), 0.98 apart across:
        // 2 R - 0.98 = 0.02.
        {
            const Vec3 ab = 0.98 * across;
            const Quaternion qb = about(across, 0.5 * pi) * q;
            ASSERT_NEAR(dot(rotate(qb, {0.0, 0.0, 1.0}), axis), 0.0, 1e-14);
            const PairOverlap o = c.pair_overlap(a, c, {a.position + ab, qb, 1.0}, ab);
            EXPECT_NEAR(o.depth, 0.02, 1e-9);
            const PairOverlap back = c.pair_overlap({a.position + ab, qb, 1.0}, c, a, -1.0 * ab);
            EXPECT_NEAR(back.depth, o.depth, 1e-10);
        }
        // Apart: 1.01 across.
        {
            const Vec3 ab = 1.01 * across;
            EXPECT_EQ(c.pair_overlap(a, c, {a.position + ab, q, 1.0}, ab).depth, 0.0);
        }
    }
}

/// Brute force: whether a point lies inside the cylinder (radius r, half-length h) placed by p.
bool inside_cylinder(const Vec3& x, const Placement& p, double r, double h) {
    const Vec3 body = rotate(conjugate(p.orientation), x - p.position);
    return std::hypot(body.x, body.y) < r && std::abs(body.z) < h;
}

/// Brute force: whether two cylinders (both radius r, half-length h) overlap, by points on a
/// grid of each one's surface (n around, n along, n across the ends) tested inside the other.
bool surfaces_meet(const Placement& a, const Placement& b, double r, double h, int n) {
    const auto any_inside = [&](const Placement& from, const Placement& to) {
        for (int i = 0; i <= n; ++i)
            for (int j = 0; j < n; ++j) {
                const double phi = 2.0 * pi * j / n;
                const Vec3 side{r * std::cos(phi), r * std::sin(phi), -h + 2.0 * h * i / n};
                const Vec3 end{r * i / n * std::cos(phi), r * i / n * std::sin(phi), h};
                for (const Vec3& body : {side, end, Vec3{end.x, end.y, -h}})
                    if (inside_cylinder(from.position + rotate(from.orientation, body), to, r, h))
                        return true;
            }
        return false;
    };
    return any_inside(a, b) || any_inside(b, a);
}

TEST(CylinderShape, PairGapIsTheDistanceOrMinusTheDepth) {
    // R = 0.5, L = 2, turned at random: apart and overlapping side by side, end to end, crossed,
    // and rim to rim (coaxial-parallel, offset across by d and along by e: the nearest points
    // are on the rims, sqrt((d - 2 R)^2 + (e - L)^2) apart).
    const CylinderShape c{0.5, 1.0};
    std::mt19937_64 rng(9);
    for (int trial = 0; trial < 5; ++trial) {
        const Quaternion q = random_rotation(rng);
        const Vec3 axis = rotate(q, {0.0, 0.0, 1.0}), across = rotate(q, {1.0, 0.0, 0.0});
        const Placement a{{0.3, -0.2, 4.0}, q, 1.0};
        const auto gap = [&](const Vec3& ab, const Quaternion& qb) {
            return c.pair_gap(a, c, {a.position + ab, qb, 1.0}, ab);
        };
        for (const double g : {0.2, 1e-3, -0.01}) {
            EXPECT_NEAR(gap((1.0 + g) * across, q), g, 1e-9) << g;
            EXPECT_NEAR(gap((2.0 + g) * axis, q), g, 1e-9) << g;
            EXPECT_NEAR(gap((1.0 + g) * across, about(across, 0.5 * pi) * q), g, 1e-9) << g;
        }
        const double d = 1.3, e = 2.4;
        EXPECT_NEAR(gap(d * across + e * axis, q), std::hypot(d - 1.0, e - 2.0), 1e-9);
    }
}

TEST(CylinderShape, PairOverlapSeparatesByBruteForce) {
    // Random overlapping pairs: moved apart by the depth along the normal (and 1e-6 more) no
    // point of either surface lies inside the other; by 0.9 of it they still meet (tried
    // where the brute force sees them meet at first).
    const CylinderShape c{0.5, 0.8};
    std::mt19937_64 rng(21);
    std::normal_distribution<double> g;
    int tried = 0;
    for (int trial = 0; trial < 60; ++trial) {
        const Placement a{{0.0, 0.0, 0.0}, random_rotation(rng), 1.0};
        const Vec3 ab = Vec3{g(rng), g(rng), g(rng)} * 0.5;
        const Placement b{ab, random_rotation(rng), 1.0};
        if (!surfaces_meet(a, b, 0.5, 0.8, 60))
            continue;
        ++tried;
        const PairOverlap o = c.pair_overlap(a, c, b, ab);
        ASSERT_GT(o.depth, 0.0);
        EXPECT_NEAR(norm(o.normal), 1.0, 1e-9);
        const Placement cleared{ab + (o.depth + 1e-6) * o.normal, b.orientation, 1.0};
        EXPECT_FALSE(surfaces_meet(a, cleared, 0.5, 0.8, 60)) << trial;
        const Placement short_of{ab + 0.9 * o.depth * o.normal, b.orientation, 1.0};
        EXPECT_TRUE(surfaces_meet(a, short_of, 0.5, 0.8, 60) || o.depth < 1e-3) << trial;
    }
    EXPECT_GE(tried, 20);
}

/// Brute force: the cylinder's (radius r, half-length h, placed by p) farthest point along u
/// among 2048 points on each rim (the test's own; at most 6e-7 r short of the cylinder's).
double sampled_support(const Placement& p, double r, double h, const Vec3& u) {
    double far = -1e300;
    for (int k = 0; k < 2048; ++k) {
        const double phi = 2.0 * pi * k / 2048.0;
        for (const double z : {-h, h}) {
            const Vec3 body{r * std::cos(phi), r * std::sin(phi), z};
            far = std::max(far, dot(u, p.position + rotate(p.orientation, body)));
        }
    }
    return far;
}

/// Brute force: the least depth of two overlapping cylinders, the least over the unit
/// directions u of sampled_support(a, u) + sampled_support(b, -u) (the distance from the
/// origin to the boundary of their Minkowski difference): 2000 directions of a Fibonacci
/// lattice, then a random search about the lowest, shrinking from 0.03 rad to 1e-8.
std::pair<double, Vec3> least_depth(const Placement& a, const Placement& b, double r, double h) {
    auto depth = [&](const Vec3& u) {
        return sampled_support(a, r, h, u) + sampled_support(b, r, h, -1.0 * u);
    };
    double best = 1e300;
    Vec3 at;
    const int n = 2000;
    for (int k = 0; k < n; ++k) {
        const double z = 1.0 - 2.0 * (k + 0.5) / n, rho = std::sqrt(1.0 - z * z);
        const double phi = k * pi * (3.0 - std::sqrt(5.0));
        const Vec3 u{rho * std::cos(phi), rho * std::sin(phi), z};
        if (const double d = depth(u); d < best) {
            best = d;
            at = u;
        }
    }
    std::mt19937_64 rng(1);
    std::normal_distribution<double> g;
    for (double step = 0.03; step > 1e-8; step *= 0.85)
        for (int k = 0; k < 30; ++k) {
            Vec3 u = at + step * Vec3{g(rng), g(rng), g(rng)};
            u = u * (1.0 / norm(u));
            if (const double d = depth(u); d < best) {
                best = d;
                at = u;
            }
        }
    return {best, at};
}

TEST(CylinderShape, PairOverlapIsTheLeastDepth) {
    // Random pairs turned at random, deep, and moved along their least-depth direction until
    // it is about 0.01 (as in a bed): the depth is the brute force's least within 2e-6 (its
    // rims' sampling and search), where MPR's alone was up to 12 % above and libccd's EPA up
    // to 1.4 % below.
    const CylinderShape c{0.5, 0.8};
    std::mt19937_64 rng(33);
    std::normal_distribution<double> g;
    int tried = 0;
    for (int trial = 0; trial < 4; ++trial) {
        const Placement a{{0.0, 0.0, 0.0}, random_rotation(rng), 1.0};
        const Vec3 ab = Vec3{g(rng), g(rng), g(rng)} * 0.4;
        const Quaternion qb = random_rotation(rng);
        const auto [deep, u] = least_depth(a, {ab, qb, 1.0}, 0.5, 0.8);
        if (!(deep > 0.02))
            continue;
        for (const double shift : {0.0, deep - 0.01}) {
            const Vec3 moved = ab + shift * u;
            const Placement b{moved, qb, 1.0};
            const auto [reference, direction] = least_depth(a, b, 0.5, 0.8);
            const PairOverlap o = c.pair_overlap(a, c, b, moved);
            EXPECT_NEAR(o.depth, reference, 2e-6) << trial;
            EXPECT_NEAR(dot(o.normal, direction), 1.0, 1e-3) << trial;
            ++tried;
        }
    }
    EXPECT_GE(tried, 4);
}

TEST(CylinderShape, WallOverlapInEveryContainer) {
    const CylinderShape c{0.5, 1.0};
    const Quaternion upright{};
    const Quaternion lying = about({0.0, 1.0, 0.0}, 0.5 * pi); // axis along x
    // A tube of radius 3: upright at 2.6 from the axis reaches 3.1 (0.1 beyond).
    const Container tube = Container::tube(6.0);
    EXPECT_NEAR(c.wall_overlap(tube, {{2.6, 0.0, 2.0}, upright, 1.0}), 0.1, 1e-12);
    EXPECT_NEAR(c.wall_overlap(tube, {{0.0, 2.45, 2.0}, upright, 1.0}), 0.0, 1e-15);
    // Lying along x at x0 = 2: the rim point (x0 + L/2, +-R) at sqrt(3^2 + 0.25).
    EXPECT_NEAR(c.wall_overlap(tube, {{2.0, 0.0, 2.0}, lying, 1.0}), std::hypot(3.0, 0.5) - 3.0,
                1e-12);
    // A box: tilted by 0.3 about y, its extent along x is L/2 sin + R cos.
    const Container box(Box(-2.0, 2.0, -1.0, 1.0));
    const double extent = 1.0 * std::sin(0.3) + 0.5 * std::cos(0.3);
    EXPECT_NEAR(c.wall_overlap(box, {{2.0 - extent + 0.04, 0.0, 2.0}, about({0, 1, 0}, 0.3), 1.0}),
                0.04, 1e-12);
    EXPECT_NEAR(c.wall_overlap(box, {{0.0, -0.55, 2.0}, upright, 1.0}), 0.05, 1e-12);
    // An annulus' rod of radius 1: upright at 1.45 from the axis reaches 0.95 (0.05 into it).
    const Container annulus(Annulus(3.0, 1.0));
    EXPECT_NEAR(c.wall_overlap(annulus, {{0.0, 1.45, 2.0}, upright, 1.0}), 0.05, 1e-12);
    // Lying across the rod's direction (axis along x) at y = 1.4: its lowest side 0.9 from the
    // axis at x = 0: 0.1 into the rod, pushed back along y.
    EXPECT_NEAR(c.wall_overlap(annulus, {{0.0, 1.4, 2.0}, lying, 1.0}), 0.1, 1e-12);
    // A cone narrowing upwards: the top rim is the deepest point, as a point's wall law has it.
    const Container cone(Cone(3.0, 2.0, 10.0));
    const Placement in_cone{{2.3, 0.0, 4.0}, upright, 1.0};
    const double rim = cone.wall_overlap({2.8, 0.0, 5.0}, 0.0);
    EXPECT_GT(rim, 0.0);
    EXPECT_NEAR(c.wall_overlap(cone, in_cone), rim, 1e-12);
    // The contact itself: the upright pellet at 2.6 from the tube's axis is pushed back along
    // -x at its rim, 3.1 from the axis, somewhere along its length.
    int walls = 0;
    const Placement at_wall{{2.6, 0.0, 2.0}, upright, 1.0};
    tube.convex_wall_contacts([&](const Vec3& v) { return c.support(at_wall, v); },
                              at_wall.position, c.bounding_radius(1.0),
                              [&](const ConvexWallContact& w) {
                                  ++walls;
                                  EXPECT_NEAR(w.depth, 0.1, 1e-12);
                                  EXPECT_NEAR(w.push.x, -1.0, 1e-12);
                                  EXPECT_NEAR(w.point.x, 3.1, 1e-12);
                                  EXPECT_LE(std::abs(w.point.z - 2.0), 1.0 + 1e-12);
                              });
    EXPECT_EQ(walls, 1);
    // A periodic cell has no wall.
    EXPECT_EQ(c.wall_overlap(Container(Periodic(2.0, 2.0)), {{0.0, 0.0, 1.0}, lying, 1.0}), 0.0);
}

TEST(ContainerSideChord, EveryShape) {
    const auto expect = [](const Chord& chord, std::vector<std::pair<double, double>> parts) {
        ASSERT_EQ(chord.count, parts.size());
        for (std::size_t k = 0; k < parts.size(); ++k) {
            EXPECT_NEAR(chord.parts[k].low, parts[k].first, 1e-12);
            EXPECT_NEAR(chord.parts[k].high, parts[k].second, 1e-12);
        }
    };
    const Vec3 along_x{1.0, 0.0, 0.0};
    expect(Container::tube(6.0).side_chord({0.0, 0.0, 7.0}, along_x), {{-3.0, 3.0}});
    expect(Container::tube(6.0).side_chord({0.0, 4.0, 7.0}, along_x), {});
    EXPECT_EQ(Container::tube(6.0).side_chord({1.0, 1.0, 0.0}, {0.0, 0.0, 1.0}).parts[0].low,
              -std::numeric_limits<double>::infinity());
    expect(Container(Box(-2.0, 2.0, -1.0, 1.0)).side_chord({0.0, 0.5, 1.0}, {2.0, 0.0, 5.0}),
           {{-1.0, 1.0}});
    expect(Container(Annulus(3.0, 1.0)).side_chord({0.0, 0.0, 1.0}, along_x),
           {{-3.0, -1.0}, {1.0, 3.0}});
    // A cone narrowing upwards (R = 3 - z / 10): across at z = 5, R = 2.5; up the axis at
    // rho = 2, inside while R(z) >= 2 (z <= 10).
    const Container cone(Cone(3.0, 2.0, 10.0));
    expect(cone.side_chord({0.0, 0.0, 5.0}, along_x), {{-2.5, 2.5}});
    const Chord up = cone.side_chord({2.0, 0.0, 0.0}, {0.0, 0.0, 1.0});
    ASSERT_EQ(up.count, 1u);
    EXPECT_NEAR(up.parts[0].high, 10.0, 1e-12);
    EXPECT_EQ(up.parts[0].low, -std::numeric_limits<double>::infinity()); // it widens below
    EXPECT_EQ(Container(Periodic(2.0, 2.0)).side_chord({0.0, 0.0, 0.0}, along_x).count, 1u);
}

TEST(CylinderShape, VolumeInASlab) {
    const CylinderShape c{0.5, 1.0};
    const Container tube = Container::tube(10.0);
    // Upright at z = 2 (from 1 to 3): the slab 2.5..4 holds a quarter of its length.
    EXPECT_NEAR(c.volume_in(tube, {{0.0, 0.0, 2.0}, {}, 1.0}, 2.5, 4.0), pi * 0.25 * 0.5, 1e-12);
    // Lying along x at z = 2: the slab 2.2..5 holds the segment beyond 0.2 of the centre.
    const Placement lying{{0.3, 0.1, 2.0}, about({0.0, 1.0, 0.0}, 0.5 * pi), 1.0};
    EXPECT_NEAR(c.volume_in(tube, lying, 2.2, 5.0), segment_area(0.5, 0.2) * 2.0, 1e-12);
    EXPECT_NEAR(c.volume_in(tube, lying, 1.9, 2.2),
                (segment_area(0.5, -0.1) - segment_area(0.5, 0.2)) * 2.0, 1e-12);
    // Turned at random: slabs that partition it add up to its volume, and each agrees with
    // the count.
    std::mt19937_64 rng(3);
    for (int trial = 0; trial < 3; ++trial) {
        const Placement p{{0.2, -0.1, 3.0}, random_rotation(rng), 1.3};
        double sum = 0.0;
        for (int k = 0; k < 8; ++k) {
            const double lo = 1.0 + 0.5 * k, hi = lo + 0.5;
            const double v = c.volume_in(tube, p, lo, hi);
            sum += v;
            const double counted = counted_volume(
                p, 0.5 * 1.3, 1.0 * 1.3, 100, [&](const Vec3& x) { return x.z >= lo && x.z < hi; });
            EXPECT_NEAR(v, counted, 3e-3 * c.volume(1.3));
        }
        EXPECT_NEAR(sum, c.volume(1.3), 1e-12);
    }
}

TEST(CylinderShape, VolumeInAShellAndAtTheWall) {
    const CylinderShape c{0.5, 1.0};
    const Container tube = Container::tube(6.0); // radius 3
    // Upright at 2.2 from the axis: the part at least d = 0.5 from the wall is the lens of its
    // circle with the circle of radius 2.5, times L.
    const Placement p{{2.2, 0.0, 3.0}, {}, 1.0};
    EXPECT_NEAR(c.volume_from_wall(tube, 0, 0.5, p, 0.0, 10.0), lens_area(0.5, 2.5, 2.2) * 2.0,
                1e-7 * c.volume(1.0));
    // The shell 0.3..0.5 from the wall holds the difference.
    const double shell = c.volume_from_wall(tube, 0, 0.3, p, 0.0, 10.0) -
                         c.volume_from_wall(tube, 0, 0.5, p, 0.0, 10.0);
    EXPECT_NEAR(shell, (lens_area(0.5, 2.7, 2.2) - lens_area(0.5, 2.5, 2.2)) * 2.0,
                1e-7 * c.volume(1.0));
    // Pressed 0.05 into the wall: the part inside the tube is its lens with the tube.
    const Placement pressed{{2.55, 0.0, 3.0}, {}, 1.0};
    EXPECT_NEAR(c.volume_in(tube, pressed, 0.0, 10.0), lens_area(0.5, 3.0, 2.55) * 2.0,
                1e-7 * c.volume(1.0));
    EXPECT_LT(c.volume_in(tube, pressed, 0.0, 10.0), c.volume(1.0));
    // Turned at random and cut by the shell 0.2..0.6 from the wall: against the count.
    std::mt19937_64 rng(8);
    for (int trial = 0; trial < 3; ++trial) {
        const Placement q{{2.0, 0.4, 3.0}, random_rotation(rng), 1.0};
        const double v = c.volume_from_wall(tube, 0, 0.2, q, 0.0, 10.0) -
                         c.volume_from_wall(tube, 0, 0.6, q, 0.0, 10.0);
        const double counted = counted_volume(q, 0.5, 1.0, 100, [](const Vec3& x) {
            const double rho = std::hypot(x.x, x.y);
            return rho <= 2.8 && rho > 2.4;
        });
        EXPECT_NEAR(v, counted, 3e-3 * c.volume(1.0));
    }
}

TEST(CylinderShape, TubeSectionsAgreeWithTheRegionIntegral) {
    // Two independent integrals of the part of a turned pellet inside a tube between two
    // heights: a tube's, by closed-form horizontal sections (Green's theorem on the ellipse,
    // its end chords and the wall's circle), and a cone with equal radii (the same wall, no
    // tube for the correlations), by polar coordinates on the pellet's own cross-sections and
    // the wall's chords. Pellets cut by the wall, by a shell's inner surface and by both
    // heights; upright and level ones too (the region integral's hardest: 2.2e-6 of the
    // pellet's volume off the tube's closed form for the upright one, 1e-7 for turned ones).
    const CylinderShape c = CylinderShape::of_aspect(1.6);
    const Container tube = Container::tube(5.0);
    const Container same(Cone(2.5, 2.5, 100.0));
    std::mt19937_64 rng(17);
    std::vector<Quaternion> turns{Quaternion{}, about({0.0, 1.0, 0.0}, 0.5 * pi)};
    for (int k = 0; k < 2; ++k)
        turns.push_back(random_rotation(rng));
    for (std::size_t k = 0; k < turns.size(); ++k) {
        const Placement p{{2.1 - 0.05 * static_cast<double>(k), 0.3, 3.0}, turns[k], 0.5};
        for (const double d : {0.0, 0.3}) {
            const double by_tube = c.volume_from_wall(tube, 0, d, p, 2.8, 3.25);
            const double by_region = c.volume_from_wall(same, 0, d, p, 2.8, 3.25);
            EXPECT_NEAR(by_tube, by_region, 5e-6 * c.volume(0.5)) << k << " " << d;
        }
    }
}

TEST(CylinderShape, TubeSectionsFindAWallPokedThroughALittle) {
    // A pellet pressed 1e-4 of its size through the wall meets the wall's circle twice within
    // a small angle of its sections' ellipses, and a pellet lying all but level (its axis
    // 1e-9 off the horizontal) has ellipses 1e9 times longer than wide: the tube's closed-form
    // sections against the region integral (a cone of equal radii), and never more than the
    // pellet. (Found in a poured bed: a level pellet at the wall counted 0.9 % over its
    // volume.)
    const CylinderShape c = CylinderShape::of_aspect(1.0);
    const Container tube = Container::tube(5.0);
    const Container same(Cone(2.5, 2.5, 100.0));
    std::mt19937_64 rng(23);
    std::vector<Quaternion> turns{about({0.0, 1.0, 0.0}, 0.5 * pi - 1e-9),
                                  about({std::sqrt(0.5), std::sqrt(0.5), 0.0}, 0.5 * pi + 3e-8)};
    for (int k = 0; k < 3; ++k)
        turns.push_back(random_rotation(rng));
    for (std::size_t k = 0; k < turns.size(); ++k) {
        // Moved out along x until it reaches 1e-4 through the wall.
        double in = 0.0, out = 2.5;
        for (int it = 0; it < 60; ++it) {
            const double x = 0.5 * (in + out);
            (c.wall_overlap(tube, {{x, 0.0, 3.0}, turns[k], 0.5}) > 1e-4 * 0.5 ? out : in) = x;
        }
        const Placement p{{in, 0.0, 3.0}, turns[k], 0.5};
        ASSERT_NEAR(c.wall_overlap(tube, p), 5e-5, 1e-9) << k;
        const double by_tube = c.volume_in(tube, p, 0.0, 10.0);
        const double by_region = c.volume_in(same, p, 0.0, 10.0);
        EXPECT_NEAR(by_tube, by_region, 5e-6 * c.volume(0.5)) << k;
        EXPECT_LE(by_tube, (1.0 + 1e-8) * c.volume(0.5)) << k; // quadrature: 2e-9 over
    }
    // The pellet of the poured bed (generate --shape cylinder:3,3 -a 4 -n 12 -s 3): level to
    // 1e-10, 3.6e-4 through the wall and 2.6e-3 through the floor (the band from 0).
    const Container wide = Container::tube_of_radius(6.868285455319992);
    const Container wide_same(Cone(6.868285455319992, 6.868285455319992, 100.0));
    const Placement found{
        {5.144651244557413, 0.7560459702630469, 1.4974281331599704},
        {-0.5486241449377397, 0.47661036651981725, 0.5223433339969951, 0.4461071032230748},
        1.717071363829998};
    const double v = c.volume(found.size);
    EXPECT_NEAR(c.volume_in(wide, found, 0.0, 6.434), c.volume_in(wide_same, found, 0.0, 6.434),
                5e-6 * v);
    EXPECT_LE(c.volume_in(wide, found, 0.0, 6.434), v);
}

TEST(CylinderShape, VolumeInABox) {
    const CylinderShape c{0.5, 1.0};
    // Upright, the box's face x = 0.2 through it: the disc less its segment beyond 0.2, over
    // the box's heights 2.5..3.5 (half the length).
    const Placement p{{0.0, 0.0, 3.0}, {}, 1.0};
    EXPECT_NEAR(c.volume_in_box(p, {-1.0, -1.0, 2.5}, {0.2, 1.0, 3.5}),
                (pi * 0.25 - segment_area(0.5, 0.2)) * 1.0, 1e-7 * c.volume(1.0));
    EXPECT_EQ(c.volume_in_box(p, {2.0, -1.0, 0.0}, {3.0, 1.0, 5.0}), 0.0);
    // Eight boxes that tile space about a turned pellet add up to its volume.
    const Placement q{{0.1, -0.2, 0.3}, about({0.6, 0.0, 0.8}, 1.1), 1.0};
    double sum = 0.0;
    for (int k = 0; k < 8; ++k) {
        const Vec3 low{k & 1 ? 0.0 : -5.0, k & 2 ? 0.0 : -5.0, k & 4 ? 0.0 : -5.0};
        sum += c.volume_in_box(q, low, low + Vec3{5.0, 5.0, 5.0});
    }
    EXPECT_NEAR(sum, c.volume(1.0), 1e-7 * c.volume(1.0));
}

TEST(CylinderShape, TheTemplatedLoopsTakeIt) {
    // Three pellets in a tube of radius 3: one upright, one lying, one tilted, apart.
    Packing packing;
    packing.centers = {{0.0, 0.0, 1.0}, {1.6, 0.0, 0.6}, {-1.2, 1.0, 2.0}};
    packing.radii = {1.0, 1.0, 1.0};
    packing.orientations = {Quaternion{}, about({0.0, 1.0, 0.0}, 0.5 * pi),
                            about({1.0, 0.0, 0.0}, 0.7)};
    const ShapedBed<CylinderShape> bed(packing, {CylinderShape{0.5, 1.0}});
    const Container tube = Container::tube(6.0);
    EXPECT_NEAR(solid_volume(bed, tube, 0.0, 10.0), 3.0 * pi * 0.25 * 2.0, 1e-9);
    // The highest point: the tilted one's rim, cos(0.7) L/2 + sin(0.7) R above its centre.
    EXPECT_NEAR(bed_top(bed), 2.0 + std::cos(0.7) + 0.5 * std::sin(0.7), 1e-12);
    const Overlaps apart = measure_overlaps(bed, tube);
    EXPECT_EQ(apart.pair, 0.0);
    EXPECT_EQ(apart.wall, 0.0);
    // Moved 0.1 into each other side by side (upright beside upright) and into the wall.
    packing.centers = {{0.0, 0.0, 1.0}, {0.9, 0.0, 1.0}, {2.6, 0.0, 3.0}};
    packing.orientations = {Quaternion{}, Quaternion{}, Quaternion{}};
    const Overlaps pressed =
        measure_overlaps(ShapedBed<CylinderShape>(packing, {CylinderShape{0.5, 1.0}}), tube);
    EXPECT_NEAR(pressed.pair, 0.1, 1e-9);
    EXPECT_NEAR(pressed.wall, 0.1, 1e-12);
}

TEST(IntegrateWithFloor, BoostsBitsAboveTheFloorAndStopsAtIt) {
    using Kronrod = boost::math::quadrature::gauss_kronrod<double, 15>;
    // Above the floor (none): Boost's adaptive rule, bit for bit; the integral of sqrt(x) over
    // [0, 1] is 2/3, its kink at 0 halved to.
    const auto root = [](double x) { return std::sqrt(x); };
    const double boost = Kronrod::integrate(root, 0.0, 1.0, 10, 1e-9);
    EXPECT_EQ(detail::integrate_with_floor(root, 0.0, 1.0, 10, 1e-9, 0.0), boost);
    EXPECT_NEAR(boost, 2.0 / 3.0, 1e-9);
    // 1 + 1e-7 sin(1e6 x): its ripple keeps every error estimate near 1e-7, above the relative
    // tolerance of 1e-12, so Boost halves all 2 047 pieces of a ten-level tree (15 points each);
    // with a floor of 1e-6 the first piece is enough, within the floor of
    // 1 + 1e-7 (1 - cos 1e6) / 1e6.
    int calls = 0;
    const auto ripple = [&calls](double x) {
        ++calls;
        return 1.0 + 1e-7 * std::sin(1e6 * x);
    };
    const double exact = 1.0 + 1e-7 * (1.0 - std::cos(1e6)) / 1e6;
    EXPECT_NEAR(Kronrod::integrate(ripple, 0.0, 1.0, 10, 1e-12), exact, 1e-6);
    EXPECT_EQ(calls, 2047 * 15);
    calls = 0;
    EXPECT_NEAR(detail::integrate_with_floor(ripple, 0.0, 1.0, 10, 1e-12, 1e-6), exact, 1e-6);
    EXPECT_EQ(calls, 15);
}

TEST(PelletAnalysis, TwoPelletsByHand) {
    // Two cylinders of L = D (R = h = 0.4368 d_v at size 0.5) in a tube of radius 2: one
    // upright on the axis (z 0 to 2h), one lying along x above it at 2 h + R. In the band
    // 0.1 .. 0.7 only the upright one: void fraction 1 - R^2 / Rt^2, its shells from the wall
    // empty beyond R from the axis and full inside it; the orientations cos^2 = 1 and 0.
    const CylinderShape c = CylinderShape::of_aspect(1.0);
    const double r = c.radius * 0.5, h = c.half_length * 0.5;
    Packing p;
    p.add({0.0, 0.0, h}, 0.5);
    p.add({0.0, 0.0, 2.0 * h + r}, 0.5);
    p.orientations = {Quaternion{}, about({0.0, 1.0, 0.0}, 0.5 * pi)};
    const Container tube = Container::tube_of_radius(2.0);
    AnalysisOptions o;
    o.band = Band{0.1, 0.7};
    const PelletAnalysis a = analyze_pellet_bed(p, MultilobeShape::cylinder(c), tube, o);
    EXPECT_NEAR(a.void_fraction, 1.0 - r * r / 4.0, 1e-9);
    ASSERT_FALSE(a.radial_void_fraction.empty());
    for (const ProfileBin& b : a.radial_void_fraction) {
        if (b.high <= 2.0 - r) { // the shell lies beyond R from the axis
            EXPECT_NEAR(b.value, 1.0, 1e-12) << b.low;
        } else if (b.low >= 2.0 - r) {
            EXPECT_NEAR(b.value, 0.0, 1e-9) << b.low;
        }
    }
    EXPECT_EQ(a.overall.pellets, 1u); // the lying one's centroid is above the band
    EXPECT_DOUBLE_EQ(a.overall.mean_cos2, 1.0);
    EXPECT_DOUBLE_EQ(a.overall.order, 1.0);
    // The whole height: both, S = (3 / 2 - 1) / 2 = 1/4; the bins hold them at 2 from the wall.
    o.band = Band{0.0, 3.0 * h + 2.0 * r};
    const PelletAnalysis all = analyze_pellet_bed(p, MultilobeShape::cylinder(c), tube, o);
    EXPECT_EQ(all.overall.pellets, 2u);
    EXPECT_NEAR(all.overall.order, 0.25, 1e-15);
    std::uint64_t counted = 0;
    for (const OrientationBin& b : all.orientation)
        if (b.pellets > 0) {
            EXPECT_LE(b.low, 2.0);
            EXPECT_GE(b.high, 2.0 - 1e-12);
            counted += b.pellets;
        }
    EXPECT_EQ(counted, 2u);
    // The void fraction with the pellets' exact volumes: both whole inside.
    EXPECT_NEAR(all.void_fraction, 1.0 - 2.0 * c.volume(0.5) / (pi * 4.0 * (3.0 * h + 2.0 * r)),
                1e-9);
}

TEST(PelletAnalysis, TheAxesAgainstTheWallsNormalByHand) {
    // Four cylinders (size 0.5) in a tube of radius 3, each at its own distance from the wall
    // and height: the axis along the radius (pointing at the wall: cos^2 psi = 1), level along
    // the wall (0), upright (0), and 45 degrees between the radius and z (1/2). Each one's bin
    // of 0.1 d_v holds it alone; over all four, (1 + 0 + 0 + 1/2) / 4.
    const CylinderShape c = CylinderShape::of_aspect(1.0);
    Packing p;
    p.add({1.0, 0.0, 1.0}, 0.5);  // 2.0 from the wall, axis along x: radial
    p.add({0.0, 1.5, 3.0}, 0.5);  // 1.5 from the wall, axis along x: along the wall
    p.add({0.0, -2.0, 5.0}, 0.5); // 1.0 from the wall, upright
    p.add({-0.5, 0.0, 7.0}, 0.5); // 2.5 from the wall, halfway between -x (radial) and z
    const Quaternion level = about({0.0, 1.0, 0.0}, 0.5 * pi);
    p.orientations = {level, level, Quaternion{}, about({0.0, 1.0, 0.0}, -0.25 * pi)};
    AnalysisOptions o;
    o.band = Band{0.0, 8.0};
    o.shell_width = 0.5;
    const PelletAnalysis a =
        analyze_pellet_bed(p, MultilobeShape::cylinder(c), Container::tube_of_radius(3.0), o);
    EXPECT_NEAR(a.overall.mean_cos2_wall, 1.5 / 4.0, 1e-9);
    const std::vector<std::pair<double, double>> expected{
        {2.0, 1.0}, {1.5, 0.0}, {1.0, 0.0}, {2.5, 0.5}};
    for (const auto& [d, cos2] : expected) {
        bool found = false;
        for (const OrientationBin& b : a.orientation)
            if (b.pellets > 0 && b.low <= d && d < b.high) {
                EXPECT_EQ(b.pellets, 1u) << d;
                EXPECT_NEAR(b.mean_cos2_wall, cos2, 1e-9) << d;
                found = true;
            }
        EXPECT_TRUE(found) << d;
    }
    // In a box the normal is the nearest face's: a level pellet along x, 1 from the face x = 0
    // and 2.5 from the others, points at it.
    Packing q;
    q.add({1.0, 3.5, 1.0}, 0.5);
    q.orientations = {level};
    const PelletAnalysis in_box =
        analyze_pellet_bed(q, MultilobeShape::cylinder(c), Container(Box(6.0, 7.0)), o);
    EXPECT_NEAR(in_box.overall.mean_cos2_wall, 1.0, 1e-9);
}

TEST(PelletAnalysis, SameBitsWhateverTheThreads) {
    // Four cylinders (d_v = 1) in a tube of radius 1.5, each profile's pellets computed on
    // their own in parallel and added in order: one lying on the floor 2e-5 rad from level and
    // 1e-3 through the wall, one upright on the axis, two turned; one thread and two give the
    // same bits.
    const CylinderShape c = CylinderShape::of_aspect(1.0);
    const double r = c.radius * 0.5, h = c.half_length * 0.5;
    Packing p;
    p.add({1.5 - r + 1e-3, 0.0, r}, 0.5);
    p.add({0.0, 0.0, h}, 0.5);
    p.add({-0.8, 0.2, 1.2}, 0.5);
    p.add({0.2, -0.9, 0.9}, 0.5);
    p.orientations = {about({1.0, 0.0, 0.0}, 0.5 * pi + 2e-5), Quaternion{},
                      about(Vec3{1.0, 1.0, 0.0} * (1.0 / std::sqrt(2.0)), 0.7),
                      about({1.0, 0.0, 0.0}, 1.2)};
    const Container tube = Container::tube_of_radius(1.5);
    AnalysisOptions o;
    o.band = Band{0.2, 1.4};
    o.shell_width = 0.1;
    o.slab_height = 0.1;
    const int saved = omp_get_max_threads();
    omp_set_num_threads(1);
    const PelletAnalysis one = analyze_pellet_bed(p, MultilobeShape::cylinder(c), tube, o);
    omp_set_num_threads(2);
    const PelletAnalysis two = analyze_pellet_bed(p, MultilobeShape::cylinder(c), tube, o);
    omp_set_num_threads(saved);
    EXPECT_EQ(one.void_fraction, two.void_fraction);
    ASSERT_EQ(one.radial_void_fraction.size(), two.radial_void_fraction.size());
    for (std::size_t k = 0; k < one.radial_void_fraction.size(); ++k)
        EXPECT_EQ(one.radial_void_fraction[k].value, two.radial_void_fraction[k].value) << k;
    ASSERT_EQ(one.axial_void_fraction.size(), two.axial_void_fraction.size());
    for (std::size_t k = 0; k < one.axial_void_fraction.size(); ++k)
        EXPECT_EQ(one.axial_void_fraction[k].value, two.axial_void_fraction[k].value) << k;
    // The slabs hold the pellets' volume in the tube (1e-3 of the level one's side lies beyond
    // the wall) to the integrals' relative tolerance of 1e-9 (twice it on 2.09).
    double solid = 0.0;
    for (const ProfileBin& b : one.axial_void_fraction)
        solid += (1.0 - b.value) * pi * 1.5 * 1.5 * (b.high - b.low);
    const double whole = 4.0 * c.volume(0.5);
    EXPECT_LT(solid, whole - 1e-5);
    EXPECT_NEAR(solid, solid_volume(ShapedBed<CylinderShape>(p, {c}), tube, 0.0, 10.0), 4e-9);
}

TEST(PelletAnalysis, ContactsByHand) {
    // Cylinders of L = D (R = h = 0.4368 d_v, d_v = 1) in a tube of radius 2: P0 upright on
    // the axis; P1 lying along x on P0's top (gap 0); P2 upright 5e-4 from the wall and 0.69
    // from P0; P3 upright at x = -1.2, 0.33 from P0 and 0.36 from the wall, touching nothing.
    const CylinderShape c = CylinderShape::of_aspect(1.0);
    const double r = c.radius * 0.5, h = c.half_length * 0.5;
    Packing p;
    p.add({0.0, 0.0, h}, 0.5);
    p.add({0.0, 0.0, 2.0 * h + r}, 0.5);
    p.add({2.0 - r - 5e-4, 0.0, h}, 0.5);
    p.add({-1.2, 0.0, h}, 0.5);
    p.orientations = {Quaternion{}, about({0.0, 1.0, 0.0}, 0.5 * pi), Quaternion{}, Quaternion{}};
    const Container tube = Container::tube_of_radius(2.0);
    AnalysisOptions o;
    o.band = Band{0.0, 3.0 * h + 2.0 * r};
    const Coordination k = analyze_pellet_bed(p, MultilobeShape::cylinder(c), tube, o).coordination;
    EXPECT_EQ(k.spheres, 4u);
    EXPECT_EQ(k.histogram, (std::vector<std::size_t>{2, 2}));
    EXPECT_DOUBLE_EQ(k.mean, 0.5);
    EXPECT_EQ(k.wall_contacts, 1u); // P2
    EXPECT_EQ(k.rattlers, 1u);      // P3; P2 is held by the wall
    EXPECT_DOUBLE_EQ(k.mean_without_rattlers, 2.0 / 3.0);
    // A tolerance below P2's gap to the wall: P2 touches nothing either.
    o.contact_tolerance = 1e-4;
    const Coordination tight =
        analyze_pellet_bed(p, MultilobeShape::cylinder(c), tube, o).coordination;
    EXPECT_EQ(tight.wall_contacts, 0u);
    EXPECT_EQ(tight.rattlers, 2u);
    EXPECT_DOUBLE_EQ(tight.mean_without_rattlers, 1.0);
    // P1 lifted 2e-4 off P0: still a contact at 1e-3 d_v, none at 1e-4.
    p.centers[1].z += 2e-4;
    EXPECT_EQ(analyze_pellet_bed(p, MultilobeShape::cylinder(c), tube, o).coordination.histogram[0],
              4u);
    o.contact_tolerance = 1e-3;
    EXPECT_EQ(analyze_pellet_bed(p, MultilobeShape::cylinder(c), tube, o).coordination.histogram[1],
              2u);
}
