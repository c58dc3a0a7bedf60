// The estimate of the time left in a stage (StageTimeLeft) against runs whose end is known.
#include <gtest/gtest.h>

#include <cmath>
#include <optional>

#include "packbed/time_left.hpp"

namespace packbed {
namespace {

Progress report(std::string_view stage, double overlap, double mass_centre = 10.0) {
    return {stage, 0, 0.0, overlap, 0.5 * overlap, mass_centre};
}

TEST(StageTimeLeft, GeometricFallOfTheOverlapsGivesTheTimeToTheTolerance) {
    SoftSphereParameters p;
    StageTimeLeft estimate(p);
    // overlap = 100 tolerance e^{-t/2}: it reaches the tolerance at t = 2 ln 100 = 9.21 s.
    std::optional<double> left;
    for (int t = 0; t <= 8; ++t) {
        left = estimate.update(report("initial", 100.0 * p.tolerance * std::exp(-0.5 * t)), t);
        if (t + 1 < static_cast<int>(StageTimeLeft::min_reports)) {
            EXPECT_FALSE(left) << "t = " << t;
        }
    }
    ASSERT_TRUE(left);
    EXPECT_NEAR(*left, 2.0 * std::log(100.0) - 8.0, 1e-9);
    // Below the tolerance the stage is over.
    EXPECT_EQ(estimate.update(report("initial", 0.5 * p.tolerance), 9.0), 0.0);
}

TEST(StageTimeLeft, NoEstimateWhileTheOverlapsDoNotFall) {
    SoftSphereParameters p;
    StageTimeLeft estimate(p);
    for (int t = 0; t < 20; ++t)
        EXPECT_FALSE(estimate.update(report("final", 3.0 * p.tolerance * (1.0 + 0.01 * t)), t));
    StageTimeLeft flat(p);
    for (int t = 0; t < 20; ++t)
        EXPECT_FALSE(flat.update(report("final", 3.0 * p.tolerance), t));
}

TEST(StageTimeLeft, FinalStageCountsTheCgHalvingsStillNeeded) {
    SoftSphereParameters p;
    StageTimeLeft estimate(p);
    // The stage starts with overlaps of 64 tolerances at Cg0 and halves Cg every 2 s, four
    // reports a halving: overlaps proportional to Cg reach the tolerance during the halving
    // held from t = 12 s, so the stage ends between 12 and 14 s. The reported overlaps lag
    // behind Cg (they settle), which must not matter.
    const double cg0 = 1e-5;
    std::optional<double> left;
    for (int report = 0; report < 24; ++report) { // up to t = 5.75 s
        const double t = 0.25 * report;
        const int halvings = static_cast<int>(t / 2.0);
        const double cg = cg0 * std::pow(0.5, halvings);
        const double lagging = 64.0 * p.tolerance * std::pow(0.5, std::max(0, halvings - 1));
        left = estimate.update({"final", 0, cg, lagging, 0.0, 10.0}, t);
    }
    ASSERT_TRUE(left);
    // Fitted over the stage: ln q falls by ln 2 every 2 s. Half a second of slack for the
    // fit to a staircase.
    EXPECT_GT(*left, 12.0 - 5.75 - 0.5);
    EXPECT_LT(*left, 14.0 - 5.75 + 0.5);
}

TEST(StageTimeLeft, SettlingMassCentreGivesTheTimeToThePapersRule) {
    SoftSphereParameters p;
    p.mc_tolerance = SoftSphereParameters::paper_schedule.mc_tolerance; // 1e-4 %, window 10
    StageTimeLeft estimate(p);
    // A new stage starts afresh: a history of the initial stage must not count.
    for (int t = 0; t < 10; ++t)
        estimate.update(report("initial", 1e3 * p.tolerance * std::exp(-t)), t);
    // One record a second, mass centre 10 + 0.01 e^{-t/5} Dp.
    auto mc = [](double t) { return 10.0 + 0.01 * std::exp(-0.2 * t); };
    // The rule holds once the spread of the last 10 records is below 1e-6 of their mean.
    auto spread_ratio = [&](double t) {
        double mean = 0.0;
        for (int k = 0; k < 10; ++k)
            mean += mc(t - k) / 10.0;
        return (mc(t - 9) - mc(t)) / (1e-6 * mean);
    };
    double lo = 0.0, hi = 200.0; // spread_ratio falls through 1 in between
    for (int i = 0; i < 200; ++i)
        (spread_ratio(0.5 * (lo + hi)) > 1.0 ? lo : hi) = 0.5 * (lo + hi);
    const double settles_at = lo;
    ASSERT_GT(settles_at, 30.0);
    std::optional<double> left;
    for (int t = 0; t <= 30; ++t) {
        left = estimate.update(report("intermediate", 7e-3, mc(t)), 10.0 + t);
        if (t < 9) {
            EXPECT_FALSE(left) << "no full window yet at t = " << t;
        }
    }
    ASSERT_TRUE(left);
    EXPECT_NEAR(*left, settles_at - 30.0, 0.05);
}

TEST(LayerTimeLeft, MeanLayerTimeTimesTheLayersToCome) {
    // Four layers; the first reported from t = 0 to 10 s, the second from t = 10 s. At t = 12 s:
    // two layers still to come after the current one, 10 s each, and 8 s of the current one.
    LayerTimeLeft estimate;
    auto at = [&](std::uint32_t layer, double seconds) {
        Progress p{"intermediate", 0, 1e-5, 7e-3, 0.0, 12.0};
        p.layer = layer;
        p.layers = 4;
        return estimate.update(p, seconds);
    };
    for (double t = 0.0; t < 10.0; t += 1.0)
        EXPECT_FALSE(at(0, t)) << "no layer over yet at t = " << t;
    ASSERT_TRUE(at(1, 10.0));
    const std::optional<double> left = at(1, 12.0);
    ASSERT_TRUE(left);
    EXPECT_DOUBLE_EQ(*left, 2 * 10.0 + 8.0);
    // A layer slower than the mean: nothing left of it, the rest by the mean.
    EXPECT_DOUBLE_EQ(*at(1, 25.0), 2 * 10.0);
    // Second layer over after 20 s: mean 15 s, one layer to come plus all of the current one.
    EXPECT_DOUBLE_EQ(*at(2, 30.0), 15.0 + 15.0);
    // The last layer: only what is left of it.
    EXPECT_DOUBLE_EQ(*at(3, 45.0), 15.0);
    EXPECT_DOUBLE_EQ(*at(3, 70.0), 0.0);
}

} // namespace
} // namespace packbed
