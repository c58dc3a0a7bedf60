// Bed analysis: exact profiles against hand-computed single spheres, lattices of known
// porosity and coordination, identities, and thread independence.
#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>
#include <numbers>
#include <random>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <omp.h>

#include "packbed/analysis.hpp"
#include "packbed/bed_checks.hpp"
#include "packbed/bed_volume.hpp"
#include "packbed/error.hpp"
#include "packbed/soft_sphere.hpp"
#include "packbed/volume.hpp"

using namespace packbed;
constexpr double pi = std::numbers::pi;

namespace {

double ball(double r) {
    return 4.0 / 3.0 * pi * r * r * r;
}

/// The radii [inner, outer] of a shell of the wall profile in a cylinder of radius rt (its
/// bins are distances from the wall, wall first).
std::pair<double, double> radii_of(const ProfileBin& b, double rt) {
    return {rt - b.high, rt - b.low};
}

/// Solid volume in a bin of the wall profile in a cylinder of radius rt: (1 - e) x bin volume.
double solid_in(const ProfileBin& b, double band_height, double rt) {
    const auto [inner, outer] = radii_of(b, rt);
    return (1.0 - b.value) * pi * (outer * outer - inner * inner) * band_height;
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

/// FNV-1a over the bits of every number of an analysis (all but g(r) when `with_g` is false):
/// equal only if every bit is. The wall profiles' bins, distances d from the wall since the
/// containers came, are hashed as the radii rt - d they were before (the same bits: the old
/// bounds were computed as rt - k w), so the fingerprints taken then still hold.
inline std::uint64_t fingerprint(const BedAnalysis& a, bool with_g = true, double rt = 5.0) {
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
        if (!with_g && profile == &a.pair_correlation)
            continue;
        add(profile->size());
        const bool wall = profile == &a.radial_void_fraction || profile == &a.centre_distribution;
        for (const ProfileBin& b : *profile) {
            real(wall ? rt - b.high : b.low);
            real(wall ? rt - b.low : b.high);
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

/// Void fraction of the shells inside radius `within`, from the radial profile in a cylinder
/// of radius rt.
double inner_void_fraction(const BedAnalysis& a, double within, double rt) {
    double solid = 0.0, volume = 0.0;
    const double h = a.band.z_high - a.band.z_low;
    for (const auto& b : a.radial_void_fraction) {
        const auto [inner, outer] = radii_of(b, rt);
        if (outer <= within + 1e-9) {
            solid += solid_in(b, h, rt);
            volume += pi * (outer * outer - inner * inner) * h;
        }
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
    for (const auto& b : a.radial_void_fraction) {
        const auto [inner, outer] = radii_of(b, 1.0);
        EXPECT_NEAR(solid_in(b, 2.0, 1.0), v(outer) - v(inner), 1e-12) << b.low << " " << b.high;
    }
    // The shell-sum identity: the shells hold the whole sphere.
    double sum = 0.0;
    for (const auto& b : a.radial_void_fraction)
        sum += solid_in(b, 2.0, 1.0);
    EXPECT_NEAR(sum, ball(0.5), 1e-12);
}

TEST(RadialProfile, UnequalSpheresFillTheirShellsWithTheirOwnVolumes) {
    // Spheres of radius 0.25 and 0.75 in a tube of radius 2, cut by the shells of
    // the profile and by the band's planes: the shells hold the parts of both inside the band,
    // which slab volumes give exactly (the band [1, 3] cuts the large one at z = 2.8 + 0.75).
    Packing p;
    p.add({0.3, -0.2, 2.0}, 0.25);
    p.add({-0.9, 0.6, 2.8}, 0.75);
    p.add({0.0, 0.0, 0.5}, 0.5);
    p.add({1.0, 0.0, 3.5}, 0.5); // top of the bed at 4: the band is [1, 3]
    AnalysisOptions o;
    o.shell_width = 0.05;
    o.rdf_range = 1.0;
    const BedAnalysis a = analyze_bed(p, Cylinder(2.0), o);
    ASSERT_DOUBLE_EQ(a.band.z_low, 1.0);
    ASSERT_DOUBLE_EQ(a.band.z_high, 3.0);
    double sum = 0.0;
    for (const auto& b : a.radial_void_fraction)
        sum += solid_in(b, 2.0, 2.0);
    // Inside the band: the small sphere whole, the large one below z = 3 (a sphere of radius
    // 0.75 less its cap above 3, of height 2.8 + 0.75 - 3 = 0.55), the others' parts.
    const double large_below = ball(0.75) - pi * 0.55 * 0.55 * (3.0 * 0.75 - 0.55) / 3.0;
    const double others = sphere_volume_in_cylinder_slab({0, 0, 0.5}, 0.5, 2.0, 1.0, 3.0) +
                          sphere_volume_in_cylinder_slab({1, 0, 3.5}, 0.5, 2.0, 1.0, 3.0);
    EXPECT_NEAR(sum, ball(0.25) + large_below + others, 1e-10);
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
    EXPECT_NEAR(solid_in(a.radial_void_fraction[0], 2.0, rt) / cap, 1.0, 1e-3);
    double sum = 0.0;
    for (const auto& b : a.radial_void_fraction)
        sum += solid_in(b, 2.0, rt);
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
        EXPECT_NEAR(inner_void_fraction(a, 8.0, 12.0), c.porosity, 3e-3) << c.coordination;
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

TEST(Coordination, RattlersHaveFewerThanFourContactsOrTwoWithFriction) {
    // A column of touching spheres on the axis of a wide tube, and one sphere beside the
    // column's sphere at z = 5.5. In the band [1, 9]: 8 column spheres with 2 contacts (3 for
    // the one touched from the side) and the side sphere with 1. Without friction every one is
    // a rattler (fewer than 4); with friction only the side sphere (fewer than 2).
    Packing bed;
    for (int k = 0; k < 10; ++k)
        bed.add({0, 0, 0.5 + k}, 0.5);
    bed.add({1, 0, 5.5}, 0.5);
    AnalysisOptions o;
    const BedAnalysis plain = analyze_bed(bed, Cylinder(3.0), o);
    EXPECT_EQ(plain.coordination.spheres, 9u);
    EXPECT_DOUBLE_EQ(plain.coordination.mean, 2.0);
    EXPECT_EQ(plain.coordination.rattler_contacts, 4u);
    EXPECT_EQ(plain.coordination.rattlers, 9u);
    EXPECT_DOUBLE_EQ(plain.coordination.mean_without_rattlers, 0.0);
    o.frictional = true;
    const BedAnalysis rough = analyze_bed(bed, Cylinder(3.0), o);
    EXPECT_DOUBLE_EQ(rough.coordination.mean, 2.0);
    EXPECT_EQ(rough.coordination.rattler_contacts, 2u);
    EXPECT_EQ(rough.coordination.rattlers, 1u);
    EXPECT_DOUBLE_EQ(rough.coordination.mean_without_rattlers, 17.0 / 8.0);
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

TEST(PairRegion, BallVolumesAgreeWithTheExactVolumeRoutine) {
    // ball_volume_in_pair_region integrates cylindrical shells about the ball's own axis;
    // sphere_volume_in_cylinder_slab integrates horizontal slices (test_volume checks it against
    // tanh-sinh to 1e-8). Balls at random inside cylinders of random radius, half of them within
    // 1e-8 to 1 of the wall (inside or out), of radius up to 3.5 (beyond the cylinder).
    std::mt19937_64 rng(11);
    std::uniform_real_distribution<double> u(0.0, 1.0);
    double worst = 0.0;
    for (int k = 0; k < 4000; ++k) {
        const double ra = 0.3 + 9.0 * u(rng);
        double rho = ra * std::sqrt(u(rng));
        if (k % 2 == 0)
            rho =
                std::max(0.0, ra + (k % 4 == 0 ? -1.0 : 1.0) * std::pow(10.0, -8.0 + 8.0 * u(rng)));
        const double theta = 2.0 * pi * u(rng);
        const double r = 0.01 + 3.5 * u(rng);
        const Vec3 c{rho * std::cos(theta), rho * std::sin(theta), 10.0};
        const PairRegion region{Cylinder(ra), {0.0, 20.0}}; // planes beyond every ball
        const double v = ball_volume_in_pair_region(c, r, region);
        const double exact = sphere_volume_in_cylinder_slab(c, r, ra, 0.0, 20.0);
        if (exact > 0.0)
            worst = std::max(worst, std::abs(v - exact) / exact);
        else
            EXPECT_EQ(v, 0.0);
    }
    EXPECT_LT(worst, 2e-8); // measured 2.6e-9
    // Closed forms: a ball inside, and a ball on the axis wider than the cylinder (the
    // cylinder's part of the ball, 4 pi / 3 (r^3 - (r^2 - Ra^2)^(3/2))).
    const PairRegion region{Cylinder(2.0), {0.0, 20.0}};
    EXPECT_DOUBLE_EQ(ball_volume_in_pair_region({1.0, 0.5, 10.0}, 0.7, region), ball(0.7));
    EXPECT_NEAR(ball_volume_in_pair_region({0.0, 0.0, 10.0}, 3.0, region),
                ball(3.0) - 4.0 / 3.0 * pi * std::pow(9.0 - 4.0, 1.5), 1e-12);
    // A ball the planes cut is sphere_volume_in_cylinder_slab's.
    EXPECT_EQ(ball_volume_in_pair_region({1.5, 0.3, 1.0}, 2.5, region),
              sphere_volume_in_cylinder_slab({1.5, 0.3, 1.0}, 2.5, 2.0, 0.0, 20.0));
}

TEST(PairRegion, ABandFromFloorToTopIsClippedToWhereCentresCanBe) {
    // 40 spheres of radius 0.5 in a cylinder of radius 1.5, top at z = 8; the band given as the
    // whole bed: centres lie between 0.5 and 7.5, within 1 of the axis.
    const Packing p = forty();
    AnalysisOptions o;
    o.band = Band{0.0, 8.0};
    const BedAnalysis a = analyze_bed(p, Cylinder(1.5), o);
    EXPECT_EQ(a.band.z_low, 0.0);
    EXPECT_EQ(a.band.z_high, 8.0);
    EXPECT_DOUBLE_EQ(a.pair_region.container.tube_diameter().value() * 0.5, 1.0);
    EXPECT_DOUBLE_EQ(a.pair_region.band.z_low, 0.5);
    EXPECT_DOUBLE_EQ(a.pair_region.band.z_high, 7.5);
    // The nearest pairs are at contact (distance 1: the bin [1, 1.02)), none closer.
    ASSERT_GT(a.pair_correlation.size(), 51u);
    EXPECT_GT(a.pair_correlation[50].value, 0.0);
    for (std::size_t k = 0; k < 50; ++k)
        EXPECT_EQ(a.pair_correlation[k].value, 0.0) << k;
}

namespace {

/// Pair counts of the centres with z in [z_low, z_high]: `within` counts the pairs whose two
/// centres lie there, `any` those whose first centre does (the partner anywhere), each pair
/// once per centre of it that is counted, in bins of `width` up to `range`. O(N x neighbours
/// in z) by sorting on z.
struct PairCounts {
    std::vector<double> within, any;
};
PairCounts count_pairs(const Packing& p, double z_low, double z_high, double range, double width) {
    std::vector<Vec3> c(p.centers.begin(), p.centers.end());
    std::sort(c.begin(), c.end(), [](const Vec3& a, const Vec3& b) { return a.z < b.z; });
    const auto bins = static_cast<std::size_t>(std::ceil(range / width - 1e-9));
    PairCounts out{std::vector<double>(bins, 0.0), std::vector<double>(bins, 0.0)};
    auto in = [&](const Vec3& x) { return x.z >= z_low && x.z <= z_high; };
    for (std::size_t i = 0; i < c.size(); ++i)
        for (std::size_t j = i + 1; j < c.size() && c[j].z - c[i].z < range; ++j) {
            const double d = norm(c[j] - c[i]);
            if (!(d < range))
                continue;
            const std::size_t k = std::min(static_cast<std::size_t>(d / width), bins - 1);
            const int counted = (in(c[i]) ? 1 : 0) + (in(c[j]) ? 1 : 0);
            out.any[k] += counted;
            out.within[k] += counted == 2 ? 2.0 : 0.0;
        }
    return out;
}

/// g(r) as it was before the container correction: pairs with the first centre in the band,
/// over N rho 4/3 pi (hi^3 - lo^3), rho = N / (pi Rt^2 band height).
std::vector<double> uncorrected_g(const Packing& p, const BedAnalysis& a, double rt,
                                  const PairCounts& counts) {
    double n = 0.0;
    for (const Vec3& c : p.centers)
        n += c.z >= a.band.z_low && c.z <= a.band.z_high ? 1.0 : 0.0;
    const double density = n / (pi * rt * rt * (a.band.z_high - a.band.z_low));
    std::vector<double> g;
    for (std::size_t k = 0; k < counts.any.size(); ++k) {
        const double lo = a.pair_correlation[k].low, hi = a.pair_correlation[k].high;
        g.push_back(counts.any[k] / (n * density * (ball(hi) - ball(lo))));
    }
    return g;
}

} // namespace

TEST(PairCorrelation, IdealGasInANarrowCylinderGivesOneAtEveryDistance) {
    // 20 000 points (spheres of radius 0.5, overlapping freely) uniform in the region where
    // their centres can be in a cylinder of a = 5: radius Rt - 0.5 = 2, heights 0.5 to 99.5.
    // g(r) has expectation 1 at every r; its standard error in a bin of C counted pairs
    // (each pair counted from both ends) is sqrt(2 / C) from the pair counts, plus the spread
    // of the shell volumes over the reference centres (pairs sharing a centre are correlated),
    // measured over 20 seeds as a variance of about 0.3 / N at 1 Dp and below at 3 Dp: we
    // allow 4 sigma with sigma^2 = 2 / C + 0.5 / N.
    const double rt = 2.5, radius = 0.5, height = 100.0;
    const int n = 20000;
    std::mt19937_64 rng(3);
    auto uniform = [&] { return static_cast<double>(rng() >> 11) * 0x1.0p-53; };
    Packing p;
    for (int i = 0; i < n; ++i) {
        const double rho = (rt - radius) * std::sqrt(uniform());
        const double theta = 2.0 * pi * uniform();
        p.add({rho * std::cos(theta), rho * std::sin(theta),
               radius + (height - 2.0 * radius) * uniform()},
              radius);
    }
    AnalysisOptions o;
    o.rdf_bin = 0.1;
    o.shell_width = 0.5; // the other profiles coarse: this test is about g(r)
    o.slab_height = 1.0;
    o.centre_bin = 0.5;
    const BedAnalysis a = analyze_bed(p, Cylinder(rt), o);
    EXPECT_DOUBLE_EQ(a.pair_region.container.tube_diameter().value() * 0.5, 2.0);
    EXPECT_EQ(a.pair_region.band.z_low, a.band.z_low);
    EXPECT_EQ(a.pair_region.band.z_high, a.band.z_high);
    ASSERT_EQ(a.pair_correlation.size(), 30u);
    const PairCounts counts = count_pairs(p, a.band.z_low, a.band.z_high, 3.0, 0.1);
    const std::vector<double> old = uncorrected_g(p, a, rt, counts);
    for (std::size_t k = 0; k < 30; ++k) {
        const double sigma = std::sqrt(2.0 / counts.within[k] + 0.5 / n);
        EXPECT_NEAR(a.pair_correlation[k].value, 1.0, 4.0 * sigma)
            << "r = " << a.pair_correlation[k].low << ", " << counts.within[k] << " pairs";
    }
    // The correction matters: without it g fell from 0.61 at 2.5 Dp to 0.49 at 2.9 Dp (the
    // corrected over the uncorrected value: 1.63 to 2.05).
    for (std::size_t k = 25; k < 30; ++k) {
        EXPECT_LT(old[k], 0.65) << k;
        EXPECT_GT(a.pair_correlation[k].value / old[k], 1.5) << k;
    }
}

TEST(PairCorrelation, GeneratedBedAtAspectRatio5TendsToOne) {
    // 300 spheres at a = 5 (seed 1, the default fire solver): beyond 2.5 Dp g(r) oscillates
    // about 1 (measured in bins of 0.1 Dp: 1.057 1.085 0.967 0.896 0.928, mean 0.987, under
    // fire's own schedule 0.984 1.085 0.984 0.948 0.926, mean 0.985, with fire's
    // dt_max 0.3 and skin 0.2 1.068 1.051 1.057 0.971 0.891, mean 1.008); the uncorrected
    // normalisation gave about 0.5 there. The first peak stays at contact.
    SoftSphereParameters parameters;
    parameters.container = Container::tube(5.0);
    parameters.particles = 300;
    parameters.seed = 1;
    const SoftSphereResult bed = generate_soft_sphere(parameters);
    const double rt = bed.container.tube_diameter().value() * 0.5;
    AnalysisOptions o;
    o.rdf_bin = 0.1;
    const BedAnalysis a = analyze_bed(bed.packing, bed.container, o);
    EXPECT_NEAR(a.pair_region.container.tube_diameter().value() * 0.5, 2.0, 1e-12);
    const PairCounts counts = count_pairs(bed.packing, a.band.z_low, a.band.z_high, 3.0, 0.1);
    const std::vector<double> old = uncorrected_g(bed.packing, a, rt, counts);
    double sum = 0.0, sum_old = 0.0;
    int bins = 0;
    for (std::size_t k = 0; k < a.pair_correlation.size(); ++k) {
        const ProfileBin& b = a.pair_correlation[k];
        if (b.low < 2.5 - 1e-9)
            continue;
        EXPECT_NEAR(b.value, 1.0, 0.15) << b.low; // measured: at most 0.104 off (0.085)
        sum += b.value;
        sum_old += old[k];
        ++bins;
    }
    ASSERT_EQ(bins, 5);
    EXPECT_NEAR(sum / bins, 1.008, 0.01);
    EXPECT_NEAR(sum / bins, 1.0, 0.05);
    EXPECT_LT(sum_old / bins, 0.6);
    // The first peak, at the default bins of 0.02 Dp: the bin just below contact (pairs
    // overlap by up to the 1e-4 Dp tolerance), where the uncorrected g had it too.
    const BedAnalysis fine = analyze_bed(bed.packing, bed.container);
    const PairCounts fine_counts =
        count_pairs(bed.packing, fine.band.z_low, fine.band.z_high, 3.0, 0.02);
    const std::vector<double> fine_old = uncorrected_g(bed.packing, fine, rt, fine_counts);
    const auto peak = std::max_element(
        fine.pair_correlation.begin(), fine.pair_correlation.end(),
        [](const ProfileBin& x, const ProfileBin& y) { return x.value < y.value; });
    EXPECT_NEAR(peak->low, 0.98, 1e-12);
    EXPECT_EQ(std::max_element(fine_old.begin(), fine_old.end()) - fine_old.begin(),
              peak - fine.pair_correlation.begin());
    for (const ProfileBin& b : fine.pair_correlation)
        if (b.high < 0.98 - 1e-9) {
            EXPECT_EQ(b.value, 0.0) << b.low; // no pair closer than contact
        }
}

TEST(CentreDistribution, IntegratesToTheCrossSection) {
    // sum over annuli of (relative density x area) = pi Rt^2, whatever the bed.
    const Packing p = lattice(simple_cubic, 1.0, 4.0, 6);
    const BedAnalysis a = analyze_bed(p, Cylinder(4.0));
    double sum = 0.0;
    for (const auto& b : a.centre_distribution) {
        const auto [inner, outer] = radii_of(b, 4.0);
        sum += b.value * pi * (outer * outer - inner * inner);
    }
    EXPECT_NEAR(sum, pi * 16.0, 1e-9);
    // No centre within Dp/2 of the wall.
    for (const auto& b : a.centre_distribution) {
        if (b.high <= 0.5 - 1e-9) {
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
    // g(r): whole-number pair counts and shell volumes summed in fixed chunks.
    ASSERT_EQ(one.pair_correlation.size(), two.pair_correlation.size());
    for (std::size_t k = 0; k < one.pair_correlation.size(); ++k)
        EXPECT_EQ(one.pair_correlation[k].value, two.pair_correlation[k].value) << k;
    EXPECT_EQ(fingerprint(one), fingerprint(two));
}

TEST(Analysis, SameBitsAsBeforeTheLimits) {
    // Fingerprints of every number of the analysis of a fixed polydisperse bed with one large
    // sphere, taken with the analysis before the bin and pair-search limits (a NeighborList
    // for contacts and g(r), one histogram per chunk): the limits change no result. g(r) was
    // then normalised without the container correction: the fingerprints without it are those
    // of that analysis (0x29b494ad52950405 and 0x03a633497bf6adeb with the old g), the whole
    // ones were retaken with the corrected g. Retaken again when
    // the radial profile moved to Container::ball_volume, which agrees with sphere_volume to
    // 3e-9 relative (6e-9 at most in the radial profile of a 500-sphere bed, the other tables
    // the same bits) and small beds were cut into 16 chunks.
    const Packing p = random_bed();
    AnalysisOptions o;
    o.contact_tolerance = 0.05;
    const BedAnalysis a = analyze_bed(p, Cylinder(5.0), o);
    EXPECT_EQ(a.coordination.histogram.size(), 86u); // the large sphere touches 85
    EXPECT_EQ(a.coordination.histogram.back(), 1u);
    EXPECT_EQ(fingerprint(a, false), 0xda44b9178198200fu);
    EXPECT_EQ(fingerprint(a), 0x36b40ab130e095c9u);
    const BedAnalysis b = analyze_bed(p, Cylinder(5.0));
    EXPECT_EQ(fingerprint(b, false), 0xbc567d9f7e3509d1u);
    EXPECT_EQ(fingerprint(b), 0x002208cc3bbf6bcfu);
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

TEST(BoxAnalysis, SimpleCubicLatticeInABoxHasTheLatticePorosityAndFramesThatAddUp) {
    // Spheres of diameter 1 at (0.5 + i, 0.5 + j, 0.5 + k) in the box [0, 4] x [0, 4], six
    // layers: the band [1, 5] holds four whole layers, 64 spheres, in a volume of 64.
    Packing p;
    for (int k = 0; k < 6; ++k)
        for (int j = 0; j < 4; ++j)
            for (int i = 0; i < 4; ++i)
                p.add({0.5 + i, 0.5 + j, 0.5 + k}, 0.5);
    AnalysisOptions o;
    o.shell_width = 0.1;
    o.centre_bin = 0.1;
    o.rdf_range = 1.5;
    const Container box = Box(4.0, 4.0);
    const BedAnalysis a = analyze_bed(p, box, o);
    ASSERT_DOUBLE_EQ(a.band.z_low, 1.0);
    ASSERT_DOUBLE_EQ(a.band.z_high, 5.0);
    EXPECT_NEAR(a.void_fraction, 1.0 - pi / 6.0, 1e-12);
    // Shells of the distance from the nearest face, from the wall to the middle (depth 2).
    ASSERT_EQ(a.radial_void_fraction.size(), 20u);
    EXPECT_DOUBLE_EQ(a.radial_void_fraction.back().high, 2.0);
    // The frames' solid adds up to the band's: 64 spheres.
    double solid = 0.0;
    for (const auto& b : a.radial_void_fraction)
        solid += (1.0 - b.value) * box.shell_area(b.low, b.high, 0.0, 1.0) * 4.0;
    EXPECT_NEAR(solid, 64.0 * ball(0.5), 1e-8);
    // The frame [0, 0.1] touches the 12 spheres of each layer next to a face: a cap of height
    // 0.1 from each of the 8 not in a corner, two from each of the 4 in a corner (their parts
    // within 0.1 of both faces would lie beyond (0.1, 0.1), 0.4 sqrt 2 > 0.5 from the centre:
    // none). Per layer (unit height) 16 caps, exactly.
    const double cap = pi * 0.01 * (1.5 - 0.1) / 3.0;
    const double layer =
        (1.0 - a.radial_void_fraction[0].value) * box.shell_area(0.0, 0.1, 0.0, 1.0);
    EXPECT_NEAR(layer, 16.0 * cap, 1e-13);
    // Centres at 0.5 (12 of 16 per layer) and 1.5 (4) from the nearest face, nowhere else;
    // the relative density times the frame areas adds up to the cross-section.
    double area = 0.0;
    for (const auto& b : a.centre_distribution) {
        area += b.value * box.shell_area(b.low, b.high, 0.0, 1.0);
        const bool holds = (b.low <= 0.5 && 0.5 < b.high) || (b.low <= 1.5 && 1.5 < b.high);
        if (!holds) {
            EXPECT_EQ(b.value, 0.0) << b.low;
        }
    }
    EXPECT_NEAR(area, 16.0, 1e-12);
    // Every sphere of the outer ring touches a face: 12 a layer, 6 layers.
    EXPECT_EQ(a.coordination.wall_contacts, 72u);
    // g(r): the nearest pairs at contact.
    EXPECT_EQ(a.pair_correlation[49].value, 0.0);
    EXPECT_GT(a.pair_correlation[50].value, 0.0);
    EXPECT_EQ(a.pair_region.container.spec(), "box:3,3@0.5,0.5");
}

TEST(BoxAnalysis, SphereTouchingAFlatWallFillsTheFirstFrameWithACap) {
    // Unlike the cylinder's (exact only to order R / Rt), a flat face cuts the frame [0, w]
    // from a tangent sphere as exactly a cap of height w, away from the corners.
    const double w = 0.1;
    Packing p;
    p.add({0.5, 5.0, 2.0}, 0.5);
    p.add({5.0, 5.0, 0.5}, 0.5);
    p.add({5.0, 5.0, 3.5}, 0.5);
    AnalysisOptions o;
    o.shell_width = w;
    o.rdf_range = 1.0;
    const Container box = Box(10.0, 10.0);
    const BedAnalysis a = analyze_bed(p, box, o);
    const double cap = pi * w * w * (1.5 - w) / 3.0;
    const double first =
        (1.0 - a.radial_void_fraction[0].value) * box.shell_area(0.0, w, 0.0, 1.0) * 2.0;
    EXPECT_NEAR(first, cap, 1e-14);
    EXPECT_EQ(a.coordination.wall_contacts, 1u);
}

TEST(SizeClasses, BinaryBedIsMeasuredPerSize) {
    // In the box [0, 6] x [0, 6]: a column of 8 spheres of diameter 1 at (4, 3),
    // touching each other, and a column of 4 of diameter 2 at (1, 3), touching each other and
    // the face x = 0. The reference diameter is the mean, (8 + 8) / 12 = 4/3.
    Packing p;
    for (int k = 0; k < 8; ++k)
        p.add({4.0, 3.0, 0.5 + k}, 0.5);
    for (int k = 0; k < 4; ++k)
        p.add({1.0, 3.0, 1.0 + 2.0 * k}, 1.0);
    AnalysisOptions o;
    o.rdf_range = 1.5;
    const Container box = Box(6.0, 6.0);
    const BedAnalysis a = analyze_bed(p, box, o);
    EXPECT_DOUBLE_EQ(a.diameter, 4.0 / 3.0);
    ASSERT_EQ(a.by_size.size(), 2u);
    const SizeClassAnalysis& small = a.by_size[0];
    const SizeClassAnalysis& large = a.by_size[1];
    EXPECT_EQ(small.low, 1.0);
    EXPECT_EQ(large.high, 2.0);
    EXPECT_EQ(small.spheres, 8u);
    EXPECT_EQ(large.spheres, 4u);
    EXPECT_DOUBLE_EQ(small.number_fraction, 8.0 / 12.0);
    EXPECT_DOUBLE_EQ(large.volume_fraction, 32.0 / 40.0);
    // The bed's sizes: d32 = (8 + 32) / (8 + 16) = 5/3; d50 by volume: Q3 is 8/40 = 0.2 at
    // d = 1 and 1 at d = 2, linear between, so 0.5 at 1 + 0.3 / 0.8 = 1.375.
    EXPECT_DOUBLE_EQ(a.sizes.sauter_mean, 5.0 / 3.0);
    EXPECT_DOUBLE_EQ(a.sizes.d50, 1.375);
    EXPECT_EQ(a.sizes.count, 12u);
    // The band [4/3, 8 - 4/3] holds the small centres 1.5 to 6.5 and the large ones 3 and 5,
    // each with two contacts in its column.
    EXPECT_EQ(small.in_band, 6u);
    EXPECT_EQ(large.in_band, 2u);
    EXPECT_DOUBLE_EQ(small.mean_coordination, 2.0);
    EXPECT_DOUBLE_EQ(large.mean_coordination, 2.0);
    // Each class's centres lie at one distance from the nearest face, 2 (small) and 1
    // (large); each class's density, over its own mean, integrates to the cross-section.
    for (const auto& [c, at] : {std::pair{&small, 2.0}, std::pair{&large, 1.0}}) {
        double area = 0.0;
        for (const ProfileBin& b : c->centre_distribution) {
            area += b.value * box.shell_area(b.low, b.high, 0.0, 1.0);
            if (!(b.low <= at && at < b.high)) {
                EXPECT_EQ(b.value, 0.0) << b.low;
            }
        }
        EXPECT_NEAR(area, 36.0, 1e-9);
    }
    // One size: no classes.
    const BedAnalysis mono = analyze_bed(forty(), Cylinder(1.5));
    EXPECT_TRUE(mono.by_size.empty());
    EXPECT_EQ(mono.sizes.count, 0u);
    EXPECT_EQ(mono.diameter, 1.0);
}

TEST(AnalysisWarnings, AVoidFractionBelowZeroIsNamed) {
    // Balls of radius 1/2 every 0.1 along the axis of a tube of radius 1/2: ten balls' volume,
    // 10 pi / 6, in each unit of height, whose volume is pi / 4: e = 1 - (10 / 6) / (1 / 4) =
    // -17/3 away from the ends (the overlaps counted again for each ball, as a clump's spheres
    // read as a bed would be).
    Packing packing;
    for (int k = 0; k <= 200; ++k)
        packing.add({0.0, 0.0, 0.5 + 0.1 * k}, 0.5);
    const Container tube = Container::tube(1.0);
    AnalysisOptions options;
    options.band = Band{5.0, 15.0};
    const BedAnalysis a = analyze_bed(packing, tube, options);
    EXPECT_NEAR(a.void_fraction, 1.0 - (10.0 / 6.0) / 0.25, 1e-9);
    const std::vector<std::string> warnings = analysis_warnings(packing, tube, a);
    ASSERT_FALSE(warnings.empty());
    EXPECT_EQ(warnings[0].rfind("the void fraction -5.6667 is below 0: ", 0), 0u) << warnings[0];
}
