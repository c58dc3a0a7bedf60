// Bed analysis: exact profiles against hand-computed single spheres, lattices of known
// porosity and coordination, identities, and thread independence.
#include <bit>
#include <cmath>
#include <cstdint>
#include <numbers>
#include <random>
#include <string>

#include <gtest/gtest.h>
#include <omp.h>

#include "packbed/analysis.hpp"
#include "packbed/error.hpp"

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

/// FNV-1a over the bits of every number of an analysis: equal only if every bit is.
inline std::uint64_t fingerprint(const BedAnalysis& a) {
    std::uint64_t h = 14695981039346656037ull;
    auto add = [&](std::uint64_t v) {
        for (int b = 0; b < 8; ++b) {
            h ^= (v >> (8 * b)) & 0xff;
            h *= 1099511628211ull;
        }
    };
    auto real = [&](double v) { add(std::bit_cast<std::uint64_t>(v)); };
    real(a.diameter);
    real(a.band.z_low);
    real(a.band.z_high);
    real(a.void_fraction);
    for (const auto* profile : {&a.radial_void_fraction, &a.axial_void_fraction,
                                &a.centre_distribution, &a.pair_correlation}) {
        add(profile->size());
        for (const ProfileBin& b : *profile) {
            real(b.low);
            real(b.high);
            real(b.value);
        }
    }
    const Coordination& c = a.coordination;
    real(c.mean);
    real(c.mean_without_rattlers);
    for (const std::size_t v : {c.rattlers, c.spheres, c.wall_contacts, c.wall_contacts_in_band})
        add(v);
    for (const std::size_t v : c.histogram)
        add(v);
    return h;
}

/// 2000 spheres of radii 0.35 to 0.65 at random (overlapping) in a cylinder of radius 5 up to
/// z = 30, and one of radius 2 at (0, 0, 15): a fixed bed for the fingerprint of the analysis.
inline Packing random_bed() {
    std::mt19937_64 rng(7);
    auto uniform = [&] { return static_cast<double>(rng() >> 11) * 0x1.0p-53; };
    Packing p;
    for (int i = 0; i < 2000; ++i) {
        const double r = 0.35 + 0.3 * uniform();
        const double rho = (5.0 - r) * std::sqrt(uniform());
        const double theta = 2.0 * std::numbers::pi * uniform();
        p.add({rho * std::cos(theta), rho * std::sin(theta), r + (30.0 - 2.0 * r) * uniform()}, r);
    }
    p.add({0.0, 0.0, 15.0}, 2.0);
    return p;
}

/// \return the message of the InvalidInput analyze_bed throws, or "accepted".
std::string refusal(const Packing& p, double rt, const AnalysisOptions& o = {}) {
    try {
        analyze_bed(p, Cylinder(rt), o);
    } catch (const InvalidInput& e) {
        return e.what();
    }
    return "accepted";
}

/// 40 spheres of diameter 1: 8 layers of 5 (a cross) in a cylinder of radius 1.5, top z = 8.
Packing forty() {
    return lattice(simple_cubic, 1.0, 1.5, 8);
}

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

TEST(Analysis, SameBitsAsBeforeTheLimits) {
    // Fingerprints of every number of the analysis of a fixed polydisperse bed with one large
    // sphere, taken with the analysis before the bin and pair-search limits (a NeighborList
    // for contacts and g(r), one histogram per chunk): the limits change no result.
    const Packing p = random_bed();
    AnalysisOptions o;
    o.contact_tolerance = 0.05;
    const BedAnalysis a = analyze_bed(p, Cylinder(5.0), o);
    EXPECT_EQ(a.coordination.histogram.size(), 86u); // the large sphere touches 85
    EXPECT_EQ(a.coordination.histogram.back(), 1u);
    EXPECT_EQ(fingerprint(a), 0x29b494ad52950405u);
    EXPECT_EQ(fingerprint(analyze_bed(p, Cylinder(5.0))), 0x03a633497bf6adebu);
}

TEST(AnalysisLimits, SphereFarAboveTheRestIsRefusedSayingWhy) {
    // A row 0,0,1e7,0.5 made 2e8 slabs (16 GB, a 6 GB table); at 1e15 bad_alloc was thrown in
    // an OpenMP region (terminate).
    Packing p = forty();
    ASSERT_EQ(p.size(), 40u);
    p.add({0.0, 0.0, 1e7}, 0.5);
    EXPECT_EQ(refusal(p, 1.5),
              "the bed is 1e+07 tall (the top of its highest sphere), which needs 2e+08 "
              "slabs of --slab-height 0.05 Dp (Dp = 1) for the axial profile; allowed: at most "
              "1e+06 (41 spheres: the larger of 1e+06 and 100 per sphere); its highest sphere "
              "(top at z = 1e+07) is 1e+07 Dp above the next highest (top at z = 8): remove it, "
              "or raise --slab-height");
    p.centers.back().z = 1e15;
    EXPECT_EQ(refusal(p, 1.5),
              "the bed is 1e+15 tall (the top of its highest sphere), which needs 2e+16 "
              "slabs of --slab-height 0.05 Dp (Dp = 1) for the axial profile; allowed: at most "
              "1e+06 (41 spheres: the larger of 1e+06 and 100 per sphere); its highest sphere "
              "(top at z = 1e+15) is 1e+15 Dp above the next highest (top at z = 8): remove it, "
              "or raise --slab-height");
    // Within the limit (5e4 Dp of 0.05 Dp slabs) it is measured: 40 000.5 / 0.05 slabs, the
    // last holding a cap of the far sphere (to the rounding of slab bounds near 4e4).
    p.centers.back().z = 4e4;
    const BedAnalysis a = analyze_bed(p, Cylinder(1.5));
    ASSERT_EQ(a.axial_void_fraction.size(), 800010u);
    const double cap = pi * 0.05 * 0.05 * (1.5 - 0.05) / 3.0; // height 0.05 of a sphere R 0.5
    EXPECT_NEAR(1.0 - a.axial_void_fraction.back().value, cap / (pi * 1.5 * 1.5 * 0.05), 1e-10);
    EXPECT_EQ(a.axial_void_fraction[400000].value, 1.0); // empty slabs between
}

TEST(AnalysisLimits, ContainerFarWiderThanTheBedIsRefused) {
    const Packing p = forty();
    // 1e300 overflowed the float-to-size cast of the shell count (SIGSEGV).
    EXPECT_EQ(refusal(p, 1e300), "--container-radius = 1e+300 is not allowed; allowed: > "
                                 "0 and at most 1e+15");
    // 1e9 asked for 5e10 shells (bad_alloc).
    EXPECT_EQ(refusal(p, 1e9),
              "--container-radius 1000000000 needs 5e+10 shells of --shell-width 0.02 Dp "
              "(Dp = 1) for the radial profile; allowed: at most 1e+06 (40 spheres: the larger of "
              "1e+06 and 100 per sphere); the spheres reach only 1.5 from the axis");
    AnalysisOptions o;
    o.shell_width = 1.0;
    EXPECT_EQ(refusal(p, 1e5, o),
              "--container-radius 100000 needs 5e+06 bins of --centre-bin 0.02 Dp (Dp = "
              "1) for the centre distribution; allowed: at most 1e+06 (40 spheres: the larger of "
              "1e+06 and 100 per sphere); the spheres reach only 1.5 from the axis");
    o = {};
    o.rdf_bin = 1e-6;
    EXPECT_EQ(refusal(p, 1.5, o),
              "--rdf-range 3 Dp needs 3e+06 bins of --rdf-bin 1e-06 Dp for g(r); "
              "allowed: at most 1e+06 (40 spheres: the larger of 1e+06 and 100 per sphere)");
    EXPECT_EQ(refusal(p, 2e4), "accepted"); // 1e6 shells: at the limit
}

TEST(AnalysisLimits, ReferenceDiameterFarFromTheSpheresIsRefused) {
    // 1e-9 gave bad_alloc, 1e-6 ran 27 s and aborted: bins and g(r) in units of a diameter
    // a million times smaller than the spheres.
    const Packing p = forty();
    AnalysisOptions o;
    o.diameter = 1e-9;
    EXPECT_EQ(refusal(p, 1.5, o), "--diameter = 1e-09 is not allowed; allowed: 0.1 to 10 "
                                  "(0.1 to 10 times the spheres' mean diameter, 1)");
    o.diameter = 1e-6;
    EXPECT_EQ(refusal(p, 1.5, o), "--diameter = 1e-06 is not allowed; allowed: 0.1 to 10 "
                                  "(0.1 to 10 times the spheres' mean diameter, 1)");
    o.diameter = 10.5;
    EXPECT_EQ(refusal(p, 1.5, o), "--diameter = 10.5 is not allowed; allowed: 0.1 to 10 "
                                  "(0.1 to 10 times the spheres' mean diameter, 1)");
    o.diameter = 0.1;
    EXPECT_EQ(analyze_bed(p, Cylinder(1.5), o).diameter, 0.1);
}

TEST(AnalysisLimits, SpheresPiledOnEachOtherAreRefused) {
    // 20 000 spheres at one point: every pair a contact, N^2 = 4e8 distance checks (and the
    // rows of a neighbour list of as many entries).
    Packing p;
    p.add({0.0, 0.0, 0.5}, 0.5);
    for (int i = 0; i < 20000; ++i)
        p.add({0.0, 0.0, 5.0}, 0.5);
    p.add({0.0, 0.0, 9.5}, 0.5);
    EXPECT_EQ(refusal(p, 1.0),
              "finding the contacts would take 4e+08 distance checks; allowed: at most "
              "1e+08 for 20002 spheres (1000 per sphere, times the cube of the search distance "
              "1 over the mean diameter 1): the spheres are piled on each other (up to 20000 "
              "centres within 1) or far larger than the mean (the largest diameter is 1)");
}

TEST(AnalysisLimits, OneHugeSphereCountsItsContactsWithoutSearchingEveryPair) {
    // One sphere of radius 50 resting on a layered bed of spheres of diameter 1: its contacts
    // are found by its own search, the others' in cells of about 1 Dp; the histogram is the
    // brute-force one.
    Packing p = lattice(simple_cubic, 1.0, 12.0, 6); // top z = 6
    const std::size_t small = p.size();
    p.add({0.3, 0.2, 6.0 + 50.0 - 0.02}, 50.0); // sinks 0.02 into the top layer
    AnalysisOptions o;
    o.contact_tolerance = 0.05;
    o.band_clearance = 0.5;
    const BedAnalysis a = analyze_bed(p, Cylinder(60.0), o);
    const double tolerance = 0.05 * a.diameter;
    std::vector<std::size_t> expected;
    std::size_t huge_contacts = 0;
    for (std::size_t i = 0; i < p.size(); ++i) {
        if (!(p.centers[i].z >= a.band.z_low && p.centers[i].z <= a.band.z_high))
            continue;
        std::size_t k = 0;
        for (std::size_t j = 0; j < p.size(); ++j)
            k += j != i && norm(p.centers[j] - p.centers[i]) - p.radii[i] - p.radii[j] <= tolerance;
        if (expected.size() <= k)
            expected.resize(k + 1, 0);
        ++expected[k];
        if (i == small)
            huge_contacts = k;
    }
    EXPECT_EQ(a.coordination.histogram, expected);
    EXPECT_GT(huge_contacts, 4u);
}
