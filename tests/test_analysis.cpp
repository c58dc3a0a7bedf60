// Bed analysis: exact profiles against hand-computed single spheres, lattices of known
// porosity and coordination, identities, and thread independence.
#include <cmath>
#include <numbers>

#include <gtest/gtest.h>
#include <omp.h>

#include "packbed/analysis.hpp"

using namespace packbed;
constexpr double pi = std::numbers::pi;

namespace {

double ball(double r) {
    return 4.0 / 3.0 * pi * r * r * r;
}

/// Solid volume in each bin of a void-fraction profile: (1 - e) x bin volume.
double solid_in(const ProfileBin& b, double band_height) {
    return (1.0 - b.value) * pi * (b.high * b.high - b.low * b.low) * band_height;
}

/// Spheres of diameter 1 on a lattice (basis in units of the cell edge `a`), kept when wholly
/// inside the cylinder of radius rt, layers from z = 0.5 up to `layers` cells.
Packing lattice(const std::vector<Vec3>& basis, double a, double rt, int layers) {
    Packing p;
    const int n = static_cast<int>(rt / a) + 2;
    for (int k = 0; k < layers; ++k)
        for (int j = -n; j <= n; ++j)
            for (int i = -n; i <= n; ++i)
                for (const Vec3& b : basis) {
                    const Vec3 c{(i + b.x) * a, (j + b.y) * a, 0.5 + (k + b.z) * a};
                    if (std::hypot(c.x, c.y) + 0.5 <= rt + 1e-12)
                        p.add(c, 0.5);
                }
    return p;
}

const std::vector<Vec3> simple_cubic{{0, 0, 0}};
const std::vector<Vec3> face_centred{{0, 0, 0}, {0.5, 0.5, 0}, {0.5, 0, 0.5}, {0, 0.5, 0.5}};

/// Void fraction of the shells inside radius `within`, from the radial profile.
double inner_void_fraction(const BedAnalysis& a, double within) {
    double solid = 0.0, volume = 0.0;
    const double h = a.band.z_high - a.band.z_low;
    for (const auto& b : a.radial_void_fraction)
        if (b.high <= within + 1e-9) {
            solid += solid_in(b, h);
            volume += pi * (b.high * b.high - b.low * b.low) * h;
        }
    return 1.0 - solid / volume;
}

} // namespace

TEST(RadialProfile, SphereOnTheAxisGivesNapkinRingShells) {
    // Shell [a, b] of a sphere R centred on the axis: V(b) - V(a) with
    // V(c) = 4 pi / 3 (R^3 - (R^2 - c^2)^(3/2)) for c <= R.
    Packing p;
    p.add({0, 0, 2.0}, 0.5);
    p.add({0, 0, 0.5}, 0.5); // floor sphere outside the band
    p.add({0, 0, 3.5}, 0.5); // top sphere outside the band
    AnalysisOptions o;
    o.shell_width = 0.1;
    const BedAnalysis a = analyze_bed(p, Cylinder(1.0), o);
    ASSERT_DOUBLE_EQ(a.band.z_low, 1.0);
    ASSERT_DOUBLE_EQ(a.band.z_high, 3.0);
    auto v = [](double c) {
        c = std::min(c, 0.5);
        return 4.0 * pi / 3.0 * (0.125 - std::pow(0.25 - c * c, 1.5));
    };
    ASSERT_EQ(a.radial_void_fraction.size(), 10u);
    for (const auto& b : a.radial_void_fraction)
        EXPECT_NEAR(solid_in(b, 2.0), v(b.high) - v(b.low), 1e-12) << b.low << " " << b.high;
    // The shell-sum identity: the shells hold the whole sphere.
    double sum = 0.0;
    for (const auto& b : a.radial_void_fraction)
        sum += solid_in(b, 2.0);
    EXPECT_NEAR(sum, ball(0.5), 1e-12);
}

TEST(RadialProfile, SphereTouchingTheWallFillsTheOuterShellLikeACap) {
    // Against a wall of radius 1e4 a shell of width w next to the wall holds the cap of height
    // w of a tangent sphere, pi w^2 (3R - w) / 3, to relative order R / Rt.
    const double rt = 1e4, w = 0.1;
    Packing p;
    p.add({rt - 0.5, 0, 2.0}, 0.5);
    p.add({0, 0, 0.5}, 0.5);
    p.add({0, 0, 3.5}, 0.5);
    AnalysisOptions o;
    o.shell_width = w;
    o.rdf_range = 1.0;
    const BedAnalysis a = analyze_bed(p, Cylinder(rt), o);
    const double cap = pi * w * w * (1.5 - w) / 3.0;
    EXPECT_NEAR(solid_in(a.radial_void_fraction[0], 2.0) / cap, 1.0, 1e-3);
    double sum = 0.0;
    for (const auto& b : a.radial_void_fraction)
        sum += solid_in(b, 2.0);
    EXPECT_NEAR(sum, ball(0.5), 1e-9); // shell-sum identity at the wall
    EXPECT_EQ(a.coordination.wall_contacts, 1u);
}

TEST(AxialProfile, SphereCutBySlabsGivesSegments) {
    // One sphere at z = 0.5 (on the floor), slabs of 0.25: segment volumes
    // pi (R^2 (t2 - t1) - (t2^3 - t1^3) / 3) with t measured from the centre.
    Packing p;
    p.add({0.3, 0.2, 0.5}, 0.5);
    AnalysisOptions o;
    o.slab_height = 0.25;
    o.band_clearance = 0.1;
    const BedAnalysis a = analyze_bed(p, Cylinder(2.0), o);
    ASSERT_EQ(a.axial_void_fraction.size(), 4u);
    for (const auto& b : a.axial_void_fraction) {
        const double t1 = b.low - 0.5, t2 = b.high - 0.5;
        const double segment = pi * (0.25 * (t2 - t1) - (t2 * t2 * t2 - t1 * t1 * t1) / 3.0);
        EXPECT_NEAR((1.0 - b.value) * pi * 4.0 * 0.25, segment, 1e-14);
    }
    // The overall void fraction in the band [0.1, 0.9]: the sphere minus two caps of 0.1.
    const double cap = pi * 0.01 * (1.5 - 0.1) / 3.0;
    EXPECT_NEAR(a.void_fraction, 1.0 - (ball(0.5) - 2 * cap) / (pi * 4.0 * 0.8), 1e-14);
}

TEST(Lattices, PorosityAndCoordinationOfSimpleCubicAndFcc) {
    struct Case {
        const std::vector<Vec3>* basis;
        double cell;
        double porosity;
        std::size_t coordination;
    };
    const Case cases[] = {{&simple_cubic, 1.0, 1.0 - pi / 6.0, 6},
                          {&face_centred, std::sqrt(2.0), 1.0 - pi / (3.0 * std::sqrt(2.0)), 12}};
    for (const Case& c : cases) {
        const Packing p = lattice(*c.basis, c.cell, 12.0, 8);
        AnalysisOptions o;
        o.shell_width = 0.25;
        o.rdf_range = 1.5;
        // Band over whole cells: from a lattice plane below the spheres' tops to one above.
        const BedAnalysis a = analyze_bed(p, Cylinder(12.0), o);
        EXPECT_NEAR(inner_void_fraction(a, 8.0), c.porosity, 3e-3) << c.coordination;
        // No sphere has more contacts than the lattice gives, and most have exactly that many.
        ASSERT_EQ(a.coordination.histogram.size(), c.coordination + 1);
        EXPECT_GT(a.coordination.histogram[c.coordination], a.coordination.spheres / 2);
        // g(r) is zero below the contact distance and peaks at it.
        double peak = 0.0, peak_at = 0.0;
        for (const auto& b : a.pair_correlation) {
            if (b.high < 0.999) {
                EXPECT_EQ(b.value, 0.0);
            }
            if (b.value > peak) {
                peak = b.value;
                peak_at = b.low;
            }
        }
        EXPECT_NEAR(peak_at, 1.0, 0.02);
    }
}

TEST(Coordination, ExactlyTouchingSpheresCountAtZeroTolerance) {
    // A column of touching spheres on the axis: every sphere in the band has 2 contacts.
    Packing column;
    for (int k = 0; k < 10; ++k)
        column.add({0, 0, 0.5 + k}, 0.5);
    AnalysisOptions o;
    o.contact_tolerance = 0.0;
    const BedAnalysis a = analyze_bed(column, Cylinder(0.75), o);
    ASSERT_EQ(a.coordination.histogram.size(), 3u);
    EXPECT_EQ(a.coordination.histogram[2], a.coordination.spheres);
    EXPECT_DOUBLE_EQ(a.coordination.mean, 2.0);
}

TEST(PairCorrelation, DistanceJustBelowTheRangeStaysInTheLastBin) {
    // 0.8099999999999999 / 0.03 rounds to 27 = the number of bins: must not write past them.
    Packing p;
    p.add({0, 0, 2.0}, 0.4);
    p.add({0.8099999999999999, 0, 2.0}, 0.4);
    p.add({0, 0, 0.4}, 0.4);
    p.add({0, 0, 3.6}, 0.4);
    AnalysisOptions o;
    o.rdf_range = 0.81 / 0.8; // in units of the mean diameter 0.8
    o.rdf_bin = 0.03 / 0.8;
    const BedAnalysis a = analyze_bed(p, Cylinder(2.0), o);
    ASSERT_EQ(a.pair_correlation.size(), 27u);
    EXPECT_GT(a.pair_correlation.back().value, 0.0); // the pair is counted in [0.78, 0.81)
}

TEST(CentreDistribution, IntegratesToTheCrossSection) {
    // sum over annuli of (relative density x area) = pi Rt^2, whatever the bed.
    const Packing p = lattice(simple_cubic, 1.0, 4.0, 6);
    const BedAnalysis a = analyze_bed(p, Cylinder(4.0));
    double sum = 0.0;
    for (const auto& b : a.centre_distribution)
        sum += b.value * pi * (b.high * b.high - b.low * b.low);
    EXPECT_NEAR(sum, pi * 16.0, 1e-9);
    // No centre within Dp/2 of the wall.
    for (const auto& b : a.centre_distribution) {
        if (b.low >= 3.5 + 1e-9) {
            EXPECT_EQ(b.value, 0.0);
        }
    }
}

TEST(Analysis, SameBitsWhateverTheThreads) {
    const Packing p = lattice(face_centred, std::sqrt(2.0), 7.0, 8); // > 1000: parallel
    ASSERT_GT(p.size(), 1500u);
    const int saved = omp_get_max_threads();
    omp_set_num_threads(1);
    const BedAnalysis one = analyze_bed(p, Cylinder(7.0));
    omp_set_num_threads(2);
    const BedAnalysis two = analyze_bed(p, Cylinder(7.0));
    omp_set_num_threads(saved);
    ASSERT_EQ(one.radial_void_fraction.size(), two.radial_void_fraction.size());
    for (std::size_t k = 0; k < one.radial_void_fraction.size(); ++k)
        EXPECT_EQ(one.radial_void_fraction[k].value, two.radial_void_fraction[k].value);
    for (std::size_t k = 0; k < one.axial_void_fraction.size(); ++k)
        EXPECT_EQ(one.axial_void_fraction[k].value, two.axial_void_fraction[k].value);
    EXPECT_EQ(one.void_fraction, two.void_fraction);
}
