// Random arrays: hard spheres in a cell periodic on all six faces (random_array.hpp).
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <vector>

#include "packbed/error.hpp"
#include "packbed/random_array.hpp"

namespace packbed {
namespace {

RandomArrayParameters params(std::uint64_t n, double phi, double gap, std::uint64_t seed = 1) {
    RandomArrayParameters p;
    p.count = n;
    p.solid_fraction = phi;
    p.gap = gap;
    p.seed = seed;
    return p;
}

/// The distance between the nearest copies of a and b in a cube of edge l, by brute force
/// over the 27 copies of b (no code shared with the Monte Carlo's minimum image).
double nearest_copy(const Vec3& a, const Vec3& b, double l) {
    double best = std::numeric_limits<double>::infinity();
    for (int i = -1; i <= 1; ++i)
        for (int j = -1; j <= 1; ++j)
            for (int k = -1; k <= 1; ++k)
                best = std::min(best, std::sqrt(norm2(b + Vec3{i * l, j * l, k * l} - a)));
    return best;
}

TEST(RandomArray, NoTwoSpheresCloserThanTheGapAndTheCellHoldsTheSolidFraction) {
    const RandomArrayParameters p = params(400, 0.4, 0.05);
    const RandomArray a = random_array(p);
    ASSERT_EQ(a.packing.size(), 400u);
    const double l = a.cell;
    // phi = N (pi/6) d^3 / L^3, L to 9 digits
    EXPECT_NEAR(400.0 * std::numbers::pi / 6.0 / (l * l * l), 0.4, 1e-8);
    double closest = std::numeric_limits<double>::infinity();
    for (std::size_t i = 0; i < a.packing.size(); ++i) {
        const Vec3& c = a.packing.centers[i];
        EXPECT_TRUE(c.x >= 0.0 && c.x < l && c.y >= 0.0 && c.y < l && c.z >= 0.0 && c.z < l);
        EXPECT_EQ(a.packing.radii[i], 0.5);
        for (std::size_t j = i + 1; j < a.packing.size(); ++j)
            closest = std::min(closest, nearest_copy(c, a.packing.centers[j], l));
    }
    EXPECT_GE(closest, 1.05);
    EXPECT_LT(closest, 1.06); // a fluid at 0.463 of hard spheres has pairs near contact
}

// The contact value of the hard-sphere fluid's pair distribution, Carnahan & Starling (1969):
// g(sigma+) = (1 - phi/2) / (1 - phi)^3, 2.4781 at phi = 0.3, from 24 arrays of 1 000 spheres
// (1.022 of it measured; 500 spheres gave 0.973: the statistics' own scatter is about 2 %). An
// acceptance rule that lets spheres overlap gives pairs below sigma; a lattice, none near it.
TEST(RandomArray, ContactValueOfTheHardSphereFluidFollowsCarnahanStarling) {
    const double phi = 0.3;
    const int bins = 3;
    const double width = 0.02; // in sigma
    std::vector<double> counts(bins, 0.0);
    std::vector<double> shells(bins, 0.0);
    const int arrays = 24;
    const std::uint64_t n = 1000;
    for (int s = 1; s <= arrays; ++s) {
        RandomArrayParameters p = params(n, phi, 0.0, static_cast<std::uint64_t>(s));
        p.sweeps = 200;
        const RandomArray a = random_array(p);
        const double l = a.cell;
        const double rho = static_cast<double>(n) / (l * l * l);
        for (std::size_t i = 0; i < n; ++i)
            for (std::size_t j = i + 1; j < n; ++j) {
                const double r = nearest_copy(a.packing.centers[i], a.packing.centers[j], l);
                ASSERT_GE(r, 1.0 - 1e-12);
                const int b = static_cast<int>((r - 1.0) / width);
                if (b < bins)
                    counts[static_cast<std::size_t>(b)] += 1.0;
            }
        for (int b = 0; b < bins; ++b) {
            const double r0 = 1.0 + b * width, r1 = r0 + width;
            shells[static_cast<std::size_t>(b)] += 0.5 * static_cast<double>(n) * rho * 4.0 / 3.0 *
                                                   std::numbers::pi * (r1 * r1 * r1 - r0 * r0 * r0);
        }
    }
    // g in each bin, and the straight line through the three extrapolated to r = sigma.
    std::vector<double> g(bins);
    for (int b = 0; b < bins; ++b)
        g[static_cast<std::size_t>(b)] =
            counts[static_cast<std::size_t>(b)] / shells[static_cast<std::size_t>(b)];
    const double slope = (g[2] - g[0]) / (2.0 * width);
    const double contact = g[1] - slope * 1.5 * width; // bin 1's centre is 1.5 widths from sigma
    const double carnahan_starling = (1.0 - 0.5 * phi) / std::pow(1.0 - phi, 3);
    EXPECT_NEAR(carnahan_starling, 2.4781, 1e-4);
    EXPECT_NEAR(contact / carnahan_starling, 1.0, 0.04) << "g(sigma+) = " << contact;
}

TEST(RandomArray, TheSameSeedGivesTheSameBitsAndAnotherSeedAnotherArray) {
    const RandomArray a = random_array(params(64, 0.35, 0.02, 7));
    const RandomArray b = random_array(params(64, 0.35, 0.02, 7));
    const RandomArray c = random_array(params(64, 0.35, 0.02, 8));
    ASSERT_EQ(a.packing.size(), b.packing.size());
    for (std::size_t i = 0; i < a.packing.size(); ++i) {
        EXPECT_EQ(a.packing.centers[i].x, b.packing.centers[i].x);
        EXPECT_EQ(a.packing.centers[i].y, b.packing.centers[i].y);
        EXPECT_EQ(a.packing.centers[i].z, b.packing.centers[i].z);
    }
    EXPECT_NE(a.packing.centers[0].x, c.packing.centers[0].x);
}

TEST(RandomArray, RefusesWhatIsNoRandomArray) {
    // hard spheres above their freezing point: 0.45 (1.05)^3 = 0.521
    try {
        random_array(params(100, 0.45, 0.05));
        FAIL() << "no refusal";
    } catch (const InvalidInput& e) {
        EXPECT_NE(std::string(e.what()).find("allowed: at most 0.49"), std::string::npos)
            << e.what();
    }
    // a cell narrower than 2 sigma: 4 spheres at 0.4 make an edge of 1.74 d
    EXPECT_THROW(random_array(params(4, 0.4, 0.0)), InvalidInput);
    EXPECT_THROW(random_array(params(1, 0.3, 0.0)), InvalidInput);
    EXPECT_THROW(random_array(params(100, 0.0, 0.0)), InvalidInput);
    EXPECT_THROW(random_array(params(100, 0.3, 0.6)), InvalidInput);
}

} // namespace
} // namespace packbed
