// Exact sphere volumes inside a cylinder and a slab, checked against hand-computed cases.
#include <cmath>
#include <numbers>

#include <algorithm>
#include <random>
#include <vector>

#include <boost/math/quadrature/tanh_sinh.hpp>
#include <gtest/gtest.h>

#include "packbed/bed_volume.hpp"
#include "packbed/error.hpp"
#include "packbed/volume.hpp"

using namespace packbed;
constexpr double pi = std::numbers::pi;

namespace {
double ball(double r) {
    return 4.0 / 3.0 * pi * r * r * r;
}
/// Spherical cap of height h on a sphere of radius r: pi h^2 (3r - h) / 3.
double cap(double r, double h) {
    return pi * h * h * (3.0 * r - h) / 3.0;
}
} // namespace

TEST(DiskIntersection, HandComputedLenses) {
    // Equal circles r at distance r: r^2 (2 pi / 3 - sqrt(3) / 2).
    EXPECT_NEAR(disk_intersection_area(1.0, 1.0, 1.0), 2.0 * pi / 3.0 - std::sqrt(3.0) / 2.0,
                1e-15);
    EXPECT_DOUBLE_EQ(disk_intersection_area(1.0, 3.0, 0.5), pi);  // small disk inside
    EXPECT_DOUBLE_EQ(disk_intersection_area(2.0, 1.0, 0.0), pi);  // concentric
    EXPECT_DOUBLE_EQ(disk_intersection_area(1.0, 1.0, 2.0), 0.0); // tangent outside
    // Unequal: r1 = 1 centred on the circle r2 = 1e7 (a straight edge): half the disk.
    EXPECT_NEAR(disk_intersection_area(1.0, 1e7, 1e7), pi / 2.0, 1e-6);
}

TEST(SphereInCylinderSlab, SphereOnTheAxisInsideIsWhole) {
    EXPECT_NEAR(sphere_volume_in_cylinder_slab({0, 0, 5}, 0.5, 2.5, 0, 10), ball(0.5), 1e-15);
}

TEST(SphereInCylinderSlab, TouchingTheWallFromInsideIsWhole) {
    // Centre at r = Rt - R: tangent to the wall, nothing cut.
    EXPECT_NEAR(sphere_volume_in_cylinder_slab({2.0, 0, 5}, 0.5, 2.5, 0, 10), ball(0.5), 1e-15);
    EXPECT_NEAR(sphere_volume_in_cylinder_slab({1.2, -1.6, 5}, 0.5, 2.5, 0, 10), ball(0.5), 1e-15);
}

TEST(SphereInCylinderSlab, CutByPlanesGivesCapsAndHalves) {
    // Plane through the centre: half.
    EXPECT_NEAR(sphere_volume_in_cylinder_slab({0, 0, 1}, 0.5, 2.5, 1.0, 9.0), ball(0.5) / 2,
                1e-15);
    // Band lower plane 0.2 below the top of the sphere: a cap of height 0.2.
    EXPECT_NEAR(sphere_volume_in_cylinder_slab({0.3, 0.1, 1.0}, 0.5, 2.5, 1.3, 9.0), cap(0.5, 0.2),
                1e-15);
    // Both planes cut: ball minus two caps (heights 0.1 below, 0.15 above).
    EXPECT_NEAR(sphere_volume_in_cylinder_slab({0, 0, 2.0}, 0.5, 2.5, 1.6, 2.35),
                ball(0.5) - cap(0.5, 0.1) - cap(0.5, 0.15), 1e-15);
    // Outside the band: nothing.
    EXPECT_EQ(sphere_volume_in_cylinder_slab({0, 0, 0.5}, 0.5, 2.5, 1.0, 9.0), 0.0);
}

TEST(SphereInCylinderSlab, CoaxialCylinderThroughTheSphereIsTheNapkinRingComplement) {
    // Sphere R on the axis, cylinder a < R: V = 4 pi / 3 (R^3 - (R^2 - a^2)^(3/2)).
    const double r = 1.0, a = 0.6;
    const double exact = 4.0 * pi / 3.0 * (r * r * r - std::pow(r * r - a * a, 1.5));
    EXPECT_NEAR(sphere_volume_in_cylinder_slab({0, 0, 0}, r, a, -5, 5), exact, 1e-13);
    // And cut in half by a plane through the centre.
    EXPECT_NEAR(sphere_volume_in_cylinder_slab({0, 0, 0}, r, a, 0, 5), exact / 2, 1e-13);
}

TEST(SphereInCylinderSlab, CentredOnAVeryLargeWallIsHalf) {
    // Against a wall of radius 1e6 the cut is a plane through the centre to ~R^2/Rt.
    const double rt = 1e6;
    EXPECT_NEAR(sphere_volume_in_cylinder_slab({rt, 0, 0}, 0.5, rt, -1, 1), ball(0.5) / 2, 1e-7);
}

TEST(SphereInCylinderSlab, SmallWallOverlapRemovesAThinCap) {
    // A sphere pressing 1e-4 into a wall of radius 2.5: the part outside is close to the cap
    // of height 1e-4 (flat-wall limit), slightly more because the wall curves away from it.
    const double h = 1e-4;
    const double inside = sphere_volume_in_cylinder_slab({2.0 + h, 0, 0}, 0.5, 2.5, -1, 1);
    const double removed = ball(0.5) - inside;
    EXPECT_GT(removed, cap(0.5, h));
    EXPECT_LT(removed, 1.5 * cap(0.5, h));
}

TEST(SphereInCylinderSlab, ShellsAddUpToTheSphere) {
    // Volumes in nested cylinders difference to shells; they must sum to the whole sphere.
    const Vec3 c{0.9, -0.7, 3.0};
    double sum = 0.0, previous = 0.0;
    for (int k = 1; k <= 40; ++k) {
        const double v = sphere_volume_in_cylinder_slab(c, 0.5, 0.05 * k, 0, 10);
        EXPECT_GE(v, previous - 1e-15);
        sum += v - previous;
        previous = v;
    }
    EXPECT_NEAR(sum, ball(0.5), 1e-12);
}

TEST(SphereInCylinderSlab, WallCutVolumesAgreeWithAnIndependentQuadrature) {
    // The same volume by tanh-sinh quadrature (tolerance 1e-15) of the lens area between the
    // heights where the slice changes regime (slice radius |Rc - rho| and Rc + rho), for spheres
    // placed at random across the wall of cylinders of random radius, cut at random heights.
    std::mt19937_64 rng(2026);
    std::uniform_real_distribution<double> u(0.0, 1.0);
    boost::math::quadrature::tanh_sinh<double> reference;
    double worst = 0.0;
    int lens_cases = 0;
    for (int k = 0; k < 2000; ++k) {
        const double rc = 0.2 + 5.0 * u(rng);
        const double rho = std::max(0.0, rc + (u(rng) - 0.5) * 0.9); // wall crosses sphere
        const double z_low = -0.5 + 0.4 * u(rng), z_high = 0.1 + 0.4 * u(rng);
        auto slice = [&](double t) {
            return disk_intersection_area(std::sqrt(std::max(0.25 - t * t, 0.0)), rc, rho);
        };
        std::vector<double> cuts{z_low, z_high};
        for (const double s : {std::abs(rc - rho), rc + rho})
            if (s < 0.5)
                for (const double t : {-std::sqrt(0.25 - s * s), std::sqrt(0.25 - s * s)})
                    if (t > z_low && t < z_high)
                        cuts.push_back(t);
        std::sort(cuts.begin(), cuts.end());
        double expected = 0.0;
        for (std::size_t i = 0; i + 1 < cuts.size(); ++i)
            expected += reference.integrate(slice, cuts[i], cuts[i + 1], 1e-15);
        const double got = sphere_volume_in_cylinder_slab({rho, 0, 0}, 0.5, rc, z_low, z_high);
        if (expected > 0.0) {
            worst = std::max(worst, std::abs(got - expected) / expected);
            ++lens_cases;
        }
    }
    EXPECT_GT(lens_cases, 1500);
    EXPECT_LT(worst, 1e-9);
    std::printf("worst relative difference %.3g over %d wall-cut spheres\n", worst, lens_cases);
}

TEST(VoidFraction, ColumnOfSpheresOnTheAxis) {
    // Spheres of diameter 1 stacked on the axis, centres at 0.5, 1.5, ...; band [1, 9] holds
    // exactly 8 sphere volumes' worth: e = 1 - 8 (pi/6) / (pi Rt^2 8).
    Packing column;
    for (int k = 0; k < 10; ++k)
        column.add({0, 0, 0.5 + k}, 0.5);
    const double rt = 0.75;
    EXPECT_NEAR(void_fraction(column, Cylinder(rt), 1.0, 9.0), 1.0 - (1.0 / 6.0) / (rt * rt),
                1e-14);
}

TEST(VoidFraction, EmptyBandIsRefused) {
    Packing p;
    p.add({0, 0, 0.5}, 0.5);
    EXPECT_THROW(void_fraction(p, Cylinder(1.0), 2.0, 2.0), InvalidInput);
}

TEST(Band, ClearOfBothEnds) {
    Packing p;
    p.add({0, 0, 0.5}, 0.5);
    p.add({0, 0, 7.25}, 0.5);
    const auto band = band_clear_of_ends(p, 1.0);
    ASSERT_TRUE(band);
    EXPECT_DOUBLE_EQ(band->z_low, 1.0);
    EXPECT_DOUBLE_EQ(band->z_high, 6.75);
    EXPECT_FALSE(band_clear_of_ends(p, 4.0));
}

namespace packbed {
namespace {

TEST(BoxVolume, DiskInRectanglesOfKnownArea) {
    const double pi = std::numbers::pi, r = 1.3;
    EXPECT_NEAR(disk_rectangle_area(r, -2, 2, -2, 2), pi * r * r, 1e-14);
    EXPECT_NEAR(disk_rectangle_area(r, 0, 5, -5, 5), pi * r * r / 2, 1e-14);
    EXPECT_NEAR(disk_rectangle_area(r, -5, 0, 0, 5), pi * r * r / 4, 1e-14);
    // The circular segment beyond the chord x = h.
    const double h = 0.4;
    EXPECT_NEAR(disk_rectangle_area(r, h, 5, -5, 5),
                r * r * std::acos(h / r) - h * std::sqrt(r * r - h * h), 1e-14);
    EXPECT_NEAR(disk_rectangle_area(r, -5, -h, -5, 5),
                r * r * std::acos(h / r) - h * std::sqrt(r * r - h * h), 1e-14);
    // A square inside the disk, and one far away.
    EXPECT_NEAR(disk_rectangle_area(r, -0.5, 0.4, -0.3, 0.6), 0.9 * 0.9, 1e-14);
    EXPECT_EQ(disk_rectangle_area(r, 2, 3, 2, 3), 0.0);
}

TEST(BoxVolume, SphereOnFacesEdgesAndCornersOfABox) {
    const double pi = std::numbers::pi, r = 0.5, whole = 4.0 / 3.0 * pi * r * r * r;
    const Vec3 lo{0, 0, 0}, hi{3, 4, 5};
    EXPECT_DOUBLE_EQ(sphere_volume_in_box({1.5, 2, 2.5}, r, lo, hi), whole);
    EXPECT_NEAR(sphere_volume_in_box({0, 2, 2.5}, r, lo, hi) / whole, 0.5, 1e-12);  // face
    EXPECT_NEAR(sphere_volume_in_box({1.5, 2, 5}, r, lo, hi) / whole, 0.5, 1e-12);  // top
    EXPECT_NEAR(sphere_volume_in_box({3, 4, 2.5}, r, lo, hi) / whole, 0.25, 1e-12); // edge
    EXPECT_NEAR(sphere_volume_in_box({0, 0, 0}, r, lo, hi) / whole, 0.125, 1e-12);  // corner
    EXPECT_NEAR(sphere_volume_in_box({3, 0, 5}, r, lo, hi) / whole, 0.125, 1e-12);  // corner
    // Cut by the plane x = 0 at distance h from the centre: minus a cap of height r - h.
    const double h = 0.2, cap = pi * (r - h) * (r - h) * (2 * r + h) / 3;
    EXPECT_NEAR(sphere_volume_in_box({h, 2, 2.5}, r, lo, hi), whole - cap, 1e-12 * whole);
    // Cut by x = 0 and y = 0 at the same distance: inclusion-exclusion with the corner piece
    // is what the quadrature must get; by symmetry the x-cut and y-cut alone agree.
    const double two = sphere_volume_in_box({h, h, 2.5}, r, lo, hi);
    EXPECT_LT(two, whole - cap);
    EXPECT_GT(two, whole - 2 * cap);
}

TEST(BoxVolume, AgreesWithTanhSinhOverRandomBallsAtEdgesAndCorners) {
    // sphere_volume_in_box integrates the closed-form slice area (disk_rectangle_area) over z by
    // a 20-point mapped Gauss-Legendre rule per piece between kinks; the reference integrates
    // the same slices by tanh-sinh at 1e-14 over the same pieces found independently (every
    // height where a slice's circle meets an edge line or a corner). Balls of radius 0.05 to 3
    // centred within 1 of a corner region of the box [0, 2] x [0, 3] x [0, 4], cut by 1 to 3
    // faces; relative bound 1e-8, as the cylinder's wall-cut volumes.
    std::mt19937_64 rng(17);
    std::uniform_real_distribution<double> u(0.0, 1.0);
    const Vec3 lo{0, 0, 0}, hi{2, 3, 4};
    boost::math::quadrature::tanh_sinh<double> reference;
    double worst = 0.0;
    for (int k = 0; k < 1000; ++k) {
        const double r = 0.05 + 2.95 * u(rng);
        const Vec3 c{-1.0 + 4.0 * u(rng), -1.0 + 5.0 * u(rng), -1.0 + 6.0 * u(rng)};
        auto slice = [&](double z) {
            const double s = std::sqrt(std::max(0.0, r * r - (z - c.z) * (z - c.z)));
            return disk_rectangle_area(s, lo.x - c.x, hi.x - c.x, lo.y - c.y, hi.y - c.y);
        };
        std::vector<double> cuts{std::max(lo.z, c.z - r), std::min(hi.z, c.z + r)};
        if (!(cuts[1] > cuts[0]))
            continue;
        for (const double dx : {c.x - lo.x, hi.x - c.x})
            for (const double dy : {c.y - lo.y, hi.y - c.y})
                for (const double d : {std::abs(dx), std::abs(dy), std::hypot(dx, dy)})
                    if (d < r)
                        for (const double z :
                             {c.z - std::sqrt(r * r - d * d), c.z + std::sqrt(r * r - d * d)})
                            if (z > cuts[0] && z < cuts[1])
                                cuts.push_back(z);
        std::sort(cuts.begin(), cuts.end());
        double exact = 0.0;
        for (std::size_t i = 0; i + 1 < cuts.size(); ++i)
            if (cuts[i + 1] > cuts[i])
                exact += reference.integrate(slice, cuts[i], cuts[i + 1], 1e-14);
        const double v = sphere_volume_in_box(c, r, lo, hi);
        if (exact > 1e-3 * ball(r))
            worst = std::max(worst, std::abs(v - exact) / exact);
        else
            EXPECT_NEAR(v, exact, 1e-11 * ball(r));
    }
    EXPECT_LT(worst, 1e-8); // measured 2.5e-9 over the first 2 000 balls of this seed
}

} // namespace
} // namespace packbed
