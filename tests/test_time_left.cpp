// The estimate of the time left in a stage (StageTimeLeft) against runs whose end is known.
#include <gtest/gtest.h>

#include <cmath>
#include <optional>
#include <vector>

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

TEST(StageTimeLeft, FireIntermediateStageByItsTypicalLength) {
    // Under fire's schedule the intermediate stage is estimated by the steps it typically
    // takes, at the stage's own seconds per step, from its second report on: reports every
    // 100 steps, 1 ms a step.
    SoftSphereParameters p; // the fire solver under fire_schedule
    ASSERT_TRUE(StageTimeLeft::typical_lengths_known(p));
    StageTimeLeft estimate(p);
    EXPECT_FALSE(estimate.update({"intermediate", 300, 1e-5, 0.02, 0.0, 16.0}, 0.3));
    // At step 2 300 of the run, the stage has run 2 100 steps (100 before its first report).
    const std::optional<double> left =
        estimate.update({"intermediate", 2300, 1e-5, 0.02, 0.0, 15.0}, 2.3);
    ASSERT_TRUE(left);
    EXPECT_NEAR(*left, 1e-3 * (StageTimeLeft::typical_intermediate_steps - 2100), 1e-9);
    // The paper's schedule (or a band of the user's) has no typical length: nothing before the
    // mass-centre window is full.
    SoftSphereParameters other = p;
    other.overlap_high = 0.04;
    EXPECT_FALSE(StageTimeLeft::typical_lengths_known(other));
    StageTimeLeft fitted(other);
    EXPECT_FALSE(fitted.update({"intermediate", 300, 1e-5, 0.02, 0.0, 16.0}, 0.3));
    EXPECT_FALSE(fitted.update({"intermediate", 2300, 1e-5, 0.02, 0.0, 15.0}, 2.3));
}

TEST(StageTimeLeft, HonestThroughAFireRunsCreep) {
    // A real run (a = 10, 2 250 spheres, 25 Dp, seed 26), timed by its steps (1 ms a step) so
    // that the test does not depend on the machine. Its intermediate stage takes about 10 000
    // steps, the typical length (seeds 1-29: 4 400-11 100, median 7 000; the estimate is meant
    // to be long for the shorter ones, as for small beds). With dt_max 0.2, seed 1's stage of
    // 9 500 steps saw the mass-centre spread fall under 3 times the rule's by about step 6 000
    // and then creep; an exponential fit of that spread said 1.5 s where 6.4 s were left at
    // step 3 100 (docs/notes/fire-schedule.md). From step 2 000 of the stage to 1 000
    // steps before its end, the estimate must be within -20 % and +50 % (plus 0.5 s) of the
    // truth.
    SoftSphereParameters p;
    p.container = Container::tube(10.0);
    p.particles = 2250;
    p.seed = 26;
    std::vector<Progress> reports;
    std::vector<std::string> stages; // Progress holds a view of the stage's name
    RunControl control;
    control.on_progress = [&](const Progress& r) {
        reports.push_back(r);
        stages.emplace_back(r.stage);
    };
    generate_soft_sphere(p, control);
    std::uint64_t first = 0, last = 0;
    for (std::size_t i = 0; i < reports.size(); ++i)
        if (stages[i] == "intermediate") {
            first = first == 0 ? reports[i].iteration : first;
            last = reports[i].iteration;
        }
    ASSERT_GT(last, first + 8000) << "a stage of the length the test is about";
    StageTimeLeft estimate(p);
    int checked = 0;
    for (std::size_t i = 0; i < reports.size(); ++i) {
        Progress r = reports[i];
        r.stage = stages[i];
        const std::optional<double> left = estimate.update(r, 1e-3 * r.iteration);
        if (stages[i] != "intermediate" || r.iteration < first + 2000 || r.iteration + 1000 > last)
            continue;
        const double truth = 1e-3 * (last - r.iteration);
        ASSERT_TRUE(left) << "step " << r.iteration;
        EXPECT_GT(*left, 0.8 * truth) << "step " << r.iteration;
        EXPECT_LT(*left, 1.5 * truth + 0.5) << "step " << r.iteration;
        ++checked;
    }
    EXPECT_GT(checked, 50);
}

TEST(LayerTimeLeft, FirstLayerByTheTypicalStepsOfALayer) {
    // Under fire's schedule, before any layer is over: the typical steps of the layers still to
    // go, at the run's seconds per step (here 1 ms a step, a report every 100 steps).
    SoftSphereParameters parameters;
    LayerTimeLeft estimate(parameters);
    auto at = [&](std::uint64_t iteration) {
        Progress p{"intermediate", iteration, 1e-5, 7e-3, 0.0, 12.0};
        p.layers = 3;
        return estimate.update(p, 1e-3 * iteration);
    };
    EXPECT_FALSE(at(100)) << "one report gives no seconds per step";
    const std::optional<double> left = at(5100);
    ASSERT_TRUE(left);
    const double typical = StageTimeLeft::typical_piece_steps;
    // the bottom layer alone, then two layers each with the one under it, at later_layer_cost
    // times the bottom layer's seconds per step
    const double later = LayerTimeLeft::later_layer_cost;
    EXPECT_NEAR(*left, 1e-3 * (typical - 5000 + later * 2 * typical), 1e-9);
    // Without a typical length (the default constructor), nothing until a layer is over.
    LayerTimeLeft plain;
    Progress p{"intermediate", 5100, 1e-5, 7e-3, 0.0, 12.0};
    p.layers = 3;
    EXPECT_FALSE(plain.update(p, 5.1));
}

TEST(LayerTimeLeft, MeanLayerTimeTimesTheLayersToCome) {
    // Four layers; the bottom one reported from t = 0 to 10 s, the second from t = 10 s. A
    // later layer relaxes the one under it again: later_layer_cost times the bottom one's time.
    LayerTimeLeft estimate;
    auto at = [&](std::uint32_t layer, double seconds) {
        Progress p{"intermediate", 0, 1e-5, 7e-3, 0.0, 12.0};
        p.layer = layer;
        p.layers = 4;
        return estimate.update(p, seconds);
    };
    for (double t = 0.0; t < 10.0; t += 1.0)
        EXPECT_FALSE(at(0, t)) << "no layer over yet at t = " << t;
    const double later = LayerTimeLeft::later_layer_cost * 10.0;
    ASSERT_TRUE(at(1, 10.0));
    const std::optional<double> left = at(1, 12.0);
    ASSERT_TRUE(left);
    // two later layers still to come after the current one, and what is left of it
    EXPECT_DOUBLE_EQ(*left, 2 * later + (later - 2.0));
    // A layer slower than that: nothing left of it, the rest as before.
    EXPECT_DOUBLE_EQ(*at(1, 10.0 + later + 5.0), 2 * later);
    // Second layer over after 35 s: the later layers' mean, 35 s, one to come plus the current.
    EXPECT_DOUBLE_EQ(*at(2, 45.0), 35.0 + 35.0);
    // The last layer: only what is left of it.
    EXPECT_DOUBLE_EQ(*at(3, 80.0), 35.0);
    EXPECT_DOUBLE_EQ(*at(3, 130.0), 0.0);
}

} // namespace
} // namespace packbed
