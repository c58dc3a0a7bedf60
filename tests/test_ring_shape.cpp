// The ring pellet (a hollow cylinder: CylinderShape with a bore) against closed forms and
// brute forces that share no code with it: its volume and section, the volume upright in a
// slab, in a cylindrical shell and cut by a box's wall, turned through a tube's wall against a
// grid count, depths by hand, the nodes' areas, the triangulated surface's volume, the DEM
// spheres inside it, a rod through the bore that touches nothing, and the depth of random
// pairs against points on a fine grid of both surfaces.
#include <algorithm>
#include <cmath>
#include <numbers>
#include <random>
#include <vector>

#include <gtest/gtest.h>

#include "rotations.hpp"

#include "packbed/annulus.hpp"
#include "packbed/box.hpp"
#include "packbed/container.hpp"
#include "packbed/cylinder_shape.hpp"
#include "packbed/multilobe_shape.hpp"

using namespace packbed;

namespace {

constexpr double pi = std::numbers::pi;

/// The test's own ring: outer radius 1, bore 0.5, half-length 0.6.
const CylinderShape ring{1.0, 0.6, 0.5};

/// The brute force's depth of a body-frame point in a ring: inside, its distance from the
/// nearest face; outside, minus its distance from the ring's section (the rectangle bore <=
/// rho <= radius, |z| <= half_length of the plane through the axis).
double ring_depth(const CylinderShape& c, const Vec3& q) {
    const double rho = std::hypot(q.x, q.y);
    const double inside = std::min({c.radius - rho, rho - c.bore, c.half_length - std::abs(q.z)});
    if (inside >= 0.0)
        return inside;
    const double across = std::max({rho - c.radius, c.bore - rho, 0.0});
    const double along = std::max(std::abs(q.z) - c.half_length, 0.0);
    return -std::hypot(across, along);
}

/// The area of the part of a disc of radius r beyond a chord at distance x from its centre
/// (0 <= x <= r): r^2 acos(x / r) - x sqrt(r^2 - x^2).
double segment(double r, double x) {
    if (x >= r)
        return 0.0;
    return r * r * std::acos(x / r) - x * std::sqrt(r * r - x * x);
}

/// Points on a grid of the ring's surface (n around, m along each family: the side, the bore
/// and the two ends), in its body frame.
std::vector<Vec3> surface_grid(const CylinderShape& c, int n, int m) {
    std::vector<Vec3> out;
    for (int i = 0; i < n; ++i) {
        const double phi = 2.0 * pi * i / n;
        for (int j = 0; j <= m; ++j) {
            const double z = -c.half_length + 2.0 * c.half_length * j / m;
            const double r = c.bore + (c.radius - c.bore) * j / m;
            for (const double rr : {c.radius, c.bore})
                out.push_back({rr * std::cos(phi), rr * std::sin(phi), z});
            for (const double zz : {-c.half_length, c.half_length})
                out.push_back({r * std::cos(phi), r * std::sin(phi), zz});
        }
    }
    return out;
}

} // namespace

TEST(RingShape, HasTheUnitBallsVolumeAndTheGivenProportions) {
    const CylinderShape r = CylinderShape::ring(1.0, 0.5, 1.2);
    EXPECT_NEAR(r.volume(1.0), 4.0 * pi / 3.0, 1e-12);
    EXPECT_NEAR(r.bore / r.radius, 0.5, 1e-15);
    EXPECT_NEAR(r.half_length / r.radius, 1.2, 1e-15);
    EXPECT_NEAR(ring.section_area(), pi * 0.75, 1e-15);
    EXPECT_NEAR(ring.volume(2.0), pi * 0.75 * 1.2 * 8.0, 1e-12);
    // The pellet: its surface, and its smallest dimension the wall, (D - DI) / 2 over d_v.
    const MultilobeShape p = MultilobeShape::cylinder(ring);
    EXPECT_NEAR(p.surface_area(1.0), 2.0 * pi * 0.75 + 2.0 * pi * 1.5 * 1.2, 1e-12);
    EXPECT_NEAR(p.smallest_dimension(), 0.25, 1e-15);
    EXPECT_NEAR(p.section_area(), pi * 0.75, 1e-15);
}

TEST(RingShape, DepthsByHand) {
    // In the wall, nearer the bore: out through the bore (towards the axis).
    InsideDepth d = ring.inside({0.6, 0.0, 0.0});
    EXPECT_NEAR(d.depth, 0.1, 1e-15);
    EXPECT_NEAR(d.normal.x, -1.0, 1e-15);
    d = ring.inside({0.0, 0.9, 0.1});
    EXPECT_NEAR(d.depth, 0.1, 1e-15);
    EXPECT_NEAR(d.normal.y, 1.0, 1e-15);
    d = ring.inside({0.75, 0.0, 0.55});
    EXPECT_NEAR(d.depth, 0.05, 1e-15);
    EXPECT_NEAR(d.normal.z, 1.0, 1e-15);
    // In the bore and on the axis: outside.
    EXPECT_EQ(ring.inside({0.3, 0.2, 0.0}).depth, 0.0);
    EXPECT_EQ(ring.inside({0.0, 0.0, 0.0}).depth, 0.0);
    EXPECT_NEAR(ring.signed_depth({0.0, 0.0, 0.0}), -0.5, 1e-15);
    EXPECT_NEAR(ring.signed_depth({0.3, 0.0, 0.8}), -std::hypot(0.2, 0.2), 1e-15);
    EXPECT_NEAR(ring.signed_depth({0.7, 0.0, 0.1}), 0.2, 1e-15);
    EXPECT_NEAR(ring.signed_depth({1.3, 0.0, 0.0}), -0.3, 1e-15);
}

TEST(RingShape, NodesLieOnTheSurfaceAndTheirAreasAddUp) {
    for (const double spacing : {0.05, 0.3, 0.6}) {
        const double area = 2.0 * pi * 0.75 + 2.0 * pi * 1.5 * 1.2;
        double all = 0.0, ends = 0.0, circles = 0.0;
        for (const SurfaceNode& n : ring.surface_nodes(spacing)) {
            all += n.area;
            EXPECT_NEAR(ring_depth(ring, n.point), 0.0, 1e-12);
        }
        for (const SurfaceNode& n : ring.surface_nodes(spacing, false))
            ends += n.area;
        for (const SurfaceCircle& c : ring.surface_circles(spacing)) {
            circles += c.area_per_length * 2.0 * pi * c.radius;
            EXPECT_TRUE(c.radius == 1.0 || c.radius == 0.5);
            EXPECT_LE(std::abs(c.z), 0.6);
        }
        EXPECT_NEAR(all, area, 1e-12 * area) << spacing;
        EXPECT_NEAR(ends + circles, area, 1e-12 * area) << spacing;
    }
}

TEST(RingShape, VolumeUprightInASlabAShellAndAtABoxsWall) {
    const Container tube = Container::tube(6.0); // radius 3
    const Placement upright{{0.3, -0.2, 2.0}, about({0.0, 0.0, 1.0}, 0.3), 1.0};
    // From 1.4 to 2.6: a slab holds the annulus times its part of the length.
    EXPECT_NEAR(ring.volume_in(tube, upright, 2.5, 4.0), pi * 0.75 * 0.1, 1e-9);
    EXPECT_NEAR(ring.volume_in(tube, upright, 0.0, 10.0), ring.volume(1.0), 1e-9);
    // On the axis: the part at least d from the wall lies within 3 - d of the axis, the
    // annulus from the bore out to that radius.
    const Placement centred{{0.0, 0.0, 2.0}, {}, 1.0};
    EXPECT_NEAR(ring.volume_from_wall(tube, 0, 2.1, centred, 0.0, 10.0), pi * (0.81 - 0.25) * 1.2,
                1e-9);
    EXPECT_NEAR(ring.volume_from_wall(tube, 0, 2.3, centred, 0.0, 10.0), pi * (0.49 - 0.25) * 1.2,
                1e-9);
    EXPECT_NEAR(ring.volume_from_wall(tube, 0, 2.6, centred, 0.0, 10.0), 0.0, 1e-12);
    EXPECT_NEAR(ring.volume_from_wall(tube, 0, 1.5, centred, 0.0, 10.0), pi * 0.75 * 1.2, 1e-9);
    // Upright with its centre 0.1 to 0.7 from a box's wall at x = 2: the wall cuts off a
    // segment of the outer disc less one of the bore's (to the integration's tolerance, 1e-8
    // of each piece's volume).
    const Container box(Box(-2.0, 2.0, -2.0, 2.0));
    for (const double x : {1.3, 1.6, 1.9}) {
        const Placement p{{x, 0.0, 3.0}, about({0.0, 0.0, 1.0}, 0.2), 1.0};
        const double cut = segment(1.0, 2.0 - x) - segment(0.5, 2.0 - x);
        EXPECT_NEAR(ring.volume_in(box, p, 0.0, 10.0), (pi * 0.75 - cut) * 1.2, 1e-7) << x;
        EXPECT_NEAR(ring.volume_in_box(p, {-2.0, -2.0, 0.0}, {2.0, 2.0, 10.0}),
                    (pi * 0.75 - cut) * 1.2, 1e-7)
            << x;
    }
}

/// The area common to two discs of radii a and b whose centres are d apart (the lens).
double lens(double a, double b, double d) {
    if (d >= a + b)
        return 0.0;
    if (d <= std::abs(a - b))
        return pi * std::min(a, b) * std::min(a, b);
    const double wa = std::acos((d * d + a * a - b * b) / (2.0 * d * a));
    const double wb = std::acos((d * d + b * b - a * a) / (2.0 * d * b));
    return a * a * (wa - std::sin(2.0 * wa) / 2.0) + b * b * (wb - std::sin(2.0 * wb) / 2.0);
}

TEST(RingShape, VolumeUprightThroughATubesWallByTheLenses) {
    // Upright with its centre 2.001 from the axis of a tube of radius 3: 1e-3 of it through the
    // wall; inside the tube, and inside the tube shrunk by 0.5 and by 1.7 (a shell's sides),
    // the outer disc's lens with the wall's circle less the bore's, times the length.
    const Container tube = Container::tube(6.0);
    const Placement upright{{2.001, 0.0, 2.0}, about({0.0, 0.0, 1.0}, 0.4), 1.0};
    const auto exact = [](double radius) {
        return (lens(1.0, radius, 2.001) - lens(0.5, radius, 2.001)) * 1.2;
    };
    EXPECT_NEAR(ring.volume_in(tube, upright, 0.0, 10.0), exact(3.0), 1e-12);
    EXPECT_LT(exact(3.0), ring.volume(1.0) - 1e-5);
    for (const double d : {0.5, 1.7})
        EXPECT_NEAR(ring.volume_from_wall(tube, 0, d, upright, 0.0, 10.0), exact(3.0 - d), 1e-12)
            << d;
    // Turned 1e-9 from upright: the surface moves by less than 1e-9, the volumes by less than
    // its area times that.
    const Placement tilted{upright.position, about({1.0, 0.0, 0.0}, 1e-9), 1.0};
    EXPECT_NEAR(ring.volume_in(tube, tilted, 0.0, 10.0), exact(3.0), 1e-8);
    EXPECT_NEAR(ring.volume_from_wall(tube, 0, 0.5, tilted, 0.0, 10.0), exact(2.5), 1e-8);
}

TEST(RingShape, VolumeTurnedAtTheWallAgreesWithTheCount) {
    const Container tube = Container::tube(4.0); // radius 2
    std::mt19937_64 rng(5);
    std::uniform_real_distribution<double> u(0.0, 1.0);
    for (int trial = 0; trial < 2; ++trial) {
        const Placement p{{1.3, 0.3, 3.0}, uniform_rotation(u(rng), u(rng), u(rng)), 1.0};
        const double v = ring.volume_in(tube, p, 0.0, 10.0);
        const int m = 120;
        long count = 0, total = 0;
        for (int i = 0; i < m; ++i)
            for (int j = 0; j < m; ++j)
                for (int k = 0; k < m; ++k) {
                    const Vec3 q{-1.0 + 2.0 * (i + 0.5) / m, -1.0 + 2.0 * (j + 0.5) / m,
                                 -0.6 + 1.2 * (k + 0.5) / m};
                    if (ring_depth(ring, q) < 0.0)
                        continue;
                    ++total;
                    const Vec3 x = p.position + rotate(p.orientation, q);
                    count += std::hypot(x.x, x.y) <= 2.0;
                }
        const double cell = 2.0 * 2.0 * 1.2 / (double(m) * m * m);
        EXPECT_NEAR(static_cast<double>(total) * cell, ring.volume(1.0), 3e-3 * ring.volume(1.0));
        EXPECT_NEAR(v, static_cast<double>(count) * cell, 3e-3 * ring.volume(1.0));
        EXPECT_LT(v, ring.volume(1.0) - 0.01); // a part is outside
    }
}

TEST(RingShape, SurfaceIsClosedWithTheBoreOpen) {
    // n-gons inscribed in both circles: the solid between them is L (n/2) sin(2 pi / n)
    // (R^2 - R_i^2), the mesh's volume only when every triangle faces out.
    for (const int level : {0, 2}) {
        const TriangleMesh m = ring.unit_surface(level);
        const double n = 12 << level;
        EXPECT_NEAR(m.volume(), 1.2 * 0.5 * n * std::sin(2.0 * pi / n) * 0.75, 1e-12);
        for (const Vec3& v : m.vertices)
            EXPECT_NEAR(ring_depth(ring, v), 0.0, 1e-12);
    }
}

TEST(RingShape, DemSpheresFillTheWallAndTouchItsFourFaces) {
    double inner = 1e300, outer = 0.0, top = 0.0;
    int count = 0;
    ring.dem_spheres({{0.0, 0.0, 0.0}, {}, 1.0}, [&](const DemSphere& s) {
        const double rho = std::hypot(s.centre.x, s.centre.y);
        EXPECT_NEAR(s.radius, 0.125, 1e-15); // a quarter of the wall, (1 - 0.5) / 4
        EXPECT_GE(rho - s.radius, 0.5 - 1e-12);
        EXPECT_LE(rho + s.radius, 1.0 + 1e-12);
        EXPECT_LE(std::abs(s.centre.z) + s.radius, 0.6 + 1e-12);
        inner = std::min(inner, rho - s.radius);
        outer = std::max(outer, rho + s.radius);
        top = std::max(top, s.centre.z + s.radius);
        ++count;
    });
    EXPECT_NEAR(inner, 0.5, 1e-12);
    EXPECT_NEAR(outer, 1.0, 1e-12);
    EXPECT_NEAR(top, 0.6, 1e-12);
    EXPECT_GT(count, 50);
}

TEST(RingShape, ARodThroughTheBoreTouchesOnlyWhereItPressesTheBore) {
    // A long thin cylinder along the ring's axis, moved across it by s: apart by the bore
    // less its radius and s, overlapping by the excess once it presses the bore's wall, though
    // the hulls overlap throughout.
    const CylinderShape rod{0.2, 2.0};
    for (const double s : {0.0, 0.1, 0.25, 0.31, 0.35}) {
        const Placement a{{0.0, 0.0, 0.0}, about({0.0, 0.0, 1.0}, 0.4), 1.0};
        const Placement b{{s, 0.0, 0.0}, {}, 1.0};
        const double gap = 0.5 - 0.2 - s;
        EXPECT_NEAR(ring.pair_gap(a, rod, b, b.position), gap, 1e-9) << s;
        EXPECT_NEAR(rod.pair_gap(b, ring, a, -1.0 * b.position), gap, 1e-9) << s;
        const PairOverlap o = ring.pair_overlap(a, rod, b, b.position);
        if (gap < 0.0) {
            EXPECT_NEAR(o.depth, -gap, 1e-9) << s;
            EXPECT_NEAR(o.normal.x, -1.0, 1e-6) << s; // the rod is pushed back to the axis
        } else {
            EXPECT_EQ(o.depth, 0.0) << s;
        }
    }
    // The same with an annulus' rod of radius 0.2 through the ring.
    const Container annulus(Annulus(3.0, 0.2));
    for (const double s : {0.0, 0.2, 0.35}) {
        const Placement p{{s, 0.0, 2.0}, about({0.0, 0.0, 1.0}, 0.4), 1.0};
        EXPECT_NEAR(ring.wall_overlap(annulus, p), std::max(0.0, s - 0.3), 1e-9) << s;
    }
}

TEST(RingShape, StackedAndSideBySideOverlapByHand) {
    // Coaxial, one above the other by 1.2 - delta: their ends overlap by delta along z.
    const Placement a{{0.0, 0.0, 0.0}, {}, 1.0};
    for (const double delta : {0.01, 0.05}) {
        const Placement b{{0.1, 0.0, 1.2 - delta}, about({0.0, 0.0, 1.0}, 0.5), 1.0};
        const PairOverlap o = ring.pair_overlap(a, ring, b, b.position);
        EXPECT_NEAR(o.depth, delta, 1e-9);
        EXPECT_NEAR(std::abs(o.normal.z), 1.0, 1e-9);
        EXPECT_NEAR(ring.pair_gap(a, ring, b, b.position), -delta, 1e-9);
    }
    // Upright side by side at distance 1.97 and 2.1: 2 R less the distance.
    for (const double d : {1.97, 2.1}) {
        const Placement b{{0.0, d, 0.0}, about({0.0, 0.0, 1.0}, 1.0), 1.0};
        EXPECT_NEAR(ring.pair_gap(a, ring, b, b.position), d - 2.0, 1e-9);
        EXPECT_NEAR(ring.pair_overlap(a, ring, b, b.position).depth, std::max(0.0, 2.0 - d), 1e-9);
    }
}

/// The deepest of a's grid points in b and of b's in a, by the brute force's depth: at most
/// the true depth (the grid's points are surface points), less by at most about the grid's
/// spacing where the deepest point lies at a crease.
double grid_depth(const CylinderShape& sa, const Placement& a, const CylinderShape& sb,
                  const Placement& b) {
    const auto one_way = [](const CylinderShape& from, const Placement& pf,
                            const CylinderShape& into, const Placement& pi_) {
        double best = -1e300;
        for (const Vec3& q : surface_grid(from, 720, 120)) {
            const Vec3 at = pf.position + rotate(pf.orientation, q);
            best = std::max(
                best, ring_depth(into, rotate(conjugate(pi_.orientation), at - pi_.position)));
        }
        return best;
    };
    return std::max(one_way(sa, a, sb, b), one_way(sb, b, sa, a));
}

TEST(RingShape, PairDepthAgreesWithAFineGridOfBothSurfaces) {
    // Random pairs, b moved towards a along a random direction until they overlap.
    std::mt19937_64 rng(11);
    std::uniform_real_distribution<double> u(0.0, 1.0);
    int touching = 0;
    for (int trial = 0; trial < 16; ++trial) {
        const Placement a{{0.0, 0.0, 0.0}, uniform_rotation(u(rng), u(rng), u(rng)), 1.0};
        Placement b{{}, uniform_rotation(u(rng), u(rng), u(rng)), 1.0};
        const Vec3 dir = rotate(uniform_rotation(u(rng), u(rng), u(rng)), {1.0, 0.0, 0.0});
        // b moved in along dir until the search's depth is the target (bisection), then the
        // grid's depth compared with it.
        const double target = 0.03 * u(rng);
        double far = 2.4, near = 0.0;
        for (int it = 0; it < 30; ++it) {
            b.position = dir * (0.5 * (far + near));
            (-ring.pair_gap(a, ring, b, b.position) > target ? near : far) = 0.5 * (far + near);
        }
        b.position = dir * far;
        const double brute = grid_depth(ring, a, ring, b);
        const double search = ring.pair_overlap(a, ring, b, b.position).depth;
        EXPECT_LE(brute, search + 1e-9) << trial;
        EXPECT_GE(brute, search - 5e-3) << trial;
        EXPECT_NEAR(ring.pair_gap(a, ring, b, b.position), -search, 1e-12) << trial;
        touching += brute > 0.0;
    }
    EXPECT_GE(touching, 12);
}

TEST(RingShape, LinkedRingsTouchOnlyWhereOnePressesTheOthersBore) {
    // b, a thinner ring (bore 0.8, length 0.4) turned to lie along y, hangs through a's bore
    // like a chain's link: its centre at x0 on the x axis, its wall crossing the axis of a
    // about x = x0 - 0.9. At x0 = 0.9 it passes a's bore clear; moved towards the axis, its
    // wall presses the bore's far side (x = -0.5) from x0 = 0.5 on.
    const CylinderShape link{1.0, 0.2, 0.8};
    const Placement a{{0.0, 0.0, 0.0}, {}, 1.0};
    for (const double x0 : {0.9, 0.6, 0.45}) {
        const Placement b{{x0, 0.0, 0.0}, about({1.0, 0.0, 0.0}, 0.5 * pi), 1.0};
        const double brute = grid_depth(ring, a, link, b);
        const PairOverlap o = ring.pair_overlap(a, link, b, b.position);
        const double gap = ring.pair_gap(a, link, b, b.position);
        EXPECT_LE(brute, -gap + 1e-9) << x0;
        EXPECT_GE(brute, -gap - 5e-3) << x0;
        if (x0 > 0.5) {
            EXPECT_GT(gap, 0.0) << x0;
            EXPECT_EQ(o.depth, 0.0) << x0;
        } else {
            EXPECT_GT(o.depth, 0.05) << x0; // its edge at y = 0.2 reaches 0.55 from a's axis
            EXPECT_NEAR(o.depth, -gap, 1e-12);
            EXPECT_GT(o.normal.x, 0.5) << x0; // b is pushed back towards +x
        }
    }
}
