// Published correlations: hand-computed values and validity-range warnings.
#include <cmath>
#include <limits>
#include <tuple>

#include <gtest/gtest.h>

#include "packbed/correlations.hpp"
#include "packbed/pipeline.hpp"

using namespace packbed;

namespace {
const MeanVoidFractionCorrelation& mean(std::string_view name) {
    for (const auto& c : mean_void_fraction_correlations())
        if (c.name == name)
            return c;
    throw std::out_of_range(std::string(name));
}
const RadialVoidFractionCorrelation& radial(std::string_view name) {
    for (const auto& c : radial_void_fraction_correlations())
        if (c.name == name)
            return c;
    throw std::out_of_range(std::string(name));
}
} // namespace

TEST(MeanVoidFraction, HandComputedValues) {
    // Dixon, x = 0.2: 0.4 + 0.01 + 0.412 * 0.04; middle branch at a = 1.9; a single file
    // of spheres (a = 1) has e = 1 - (pi/6)/(pi/4) = 1/3, which Dixon gives as 1 - 0.667.
    EXPECT_NEAR(mean("dixon-1988")(5.0).value, 0.42648, 1e-12);
    EXPECT_NEAR(mean("dixon-1988")(1.9).value, 0.528 + 2.464 * (1.0 / 1.9 - 0.5), 1e-12);
    EXPECT_NEAR(mean("dixon-1988")(1.0).value, 0.333, 1e-12);
    // Dixon's branches join at x = 0.5.
    EXPECT_NEAR(mean("dixon-1988")(2.0).value, 0.528, 1e-12);
    // Benyahia & O'Neill at a = 50: 0.390 + 1.740 / 51.14^2 = 0.3906653157443224.
    EXPECT_NEAR(mean("benyahia-oneill-2005")(50.0).value, 0.3906653157443224, 1e-15);
    EXPECT_NEAR(mean("jeschar-1975")(5.0).value, 0.443, 1e-12);
    EXPECT_NEAR(mean("zou-yu-1995-dense")(5.0).value, 0.372 + 0.002 * (std::exp(3.0612) - 1),
                1e-12);
    EXPECT_NEAR(mean("zou-yu-1995-loose")(10.0).value, 0.4 + 0.01 * (std::exp(1.0686) - 1), 1e-12);
}

TEST(MeanVoidFraction, OutsideTheRangeWarns) {
    EXPECT_EQ(mean("benyahia-oneill-2005")(20.0).warning, "");
    EXPECT_EQ(mean("benyahia-oneill-2005")(60.0).warning,
              "Benyahia & O'Neill (2005): a = 60 is outside its validity range (1.5 <= a <= 50)");
}

TEST(MeanVoidFraction, AValueThatIsNotAVoidFractionWarns) {
    // Zou & Yu's dense formula at a = 1.5: 0.372 + 0.002 (exp(10.204) - 1) = 54.39; no source
    // we have states its range, so the value itself tells that the formula does not hold.
    const auto dense = mean("zou-yu-1995-dense")(1.5);
    EXPECT_NEAR(dense.value, 0.372 + 0.002 * (std::exp(15.306 / 1.5) - 1), 1e-9);
    EXPECT_NEAR(dense.value, 54.39, 0.005);
    EXPECT_EQ(dense.warning, "Zou & Yu (1995), dense gives 54.39 at a = 1.5, which is not a void "
                             "fraction (it must lie in (0, 1)): the formula does not hold at "
                             "this aspect ratio");
    EXPECT_NEAR(mean("zou-yu-1995-loose")(1.5).value, 12.80, 0.005);
    EXPECT_NE(mean("zou-yu-1995-loose")(1.5).warning, "");
    // At a = 5 both are void fractions (0.413 and 0.475) and no range is stated: no warning.
    EXPECT_EQ(mean("zou-yu-1995-dense")(5.0).warning, "");
    // Its value passes 1 at exp(15.306 / a) = 1 + 0.628 / 0.002, a = 2.66.
    const double a_one = 15.306 / std::log(1.0 + 0.628 / 0.002);
    EXPECT_EQ(mean("zou-yu-1995-dense")(a_one * 1.001).warning, "");
    EXPECT_NE(mean("zou-yu-1995-dense")(a_one * 0.999).warning, "");
}

TEST(Correlations, ValidityRangeForUsers) {
    EXPECT_EQ(validity_range(1.5, 50.0), "1.5 <= a <= 50");
    EXPECT_EQ(validity_range(2.02, std::numeric_limits<double>::infinity()), "a >= 2.02");
    EXPECT_EQ(validity_range(1.0, std::numeric_limits<double>::infinity()),
              "no range stated by the source");
}

TEST(RadialVoidFraction, WallValueMinimumAndBulk) {
    for (const auto& c : radial_void_fraction_correlations()) {
        EXPECT_NEAR(c(0.0, 7.99).value, 1.0, 1e-12) << c.name; // e = 1 at the wall
        // First minimum of about 0.2-0.27 near half a diameter from the wall (Mueller's
        // formula goes deeper: 0.176 at a = 7.99).
        double lowest = 1.0, at = 0.0;
        for (double z = 0.0; z < 1.0; z += 0.001)
            if (c(z, 7.99).value < lowest) {
                lowest = c(z, 7.99).value;
                at = z;
            }
        EXPECT_GT(lowest, 0.17) << c.name;
        EXPECT_LT(lowest, 0.28) << c.name;
        EXPECT_NEAR(at, 0.55, 0.1) << c.name;
        // Damped towards the bulk value 0.365 + 0.220 / a far from the wall.
        EXPECT_NEAR(c(12.0, 7.99).value, 0.365 + 0.22 / 7.99, 0.01) << c.name;
    }
    // de Klerk's two branches meet at z = 0.637 only for e_b = 0.3609; with Mueller's
    // e_b = 0.365 + 0.220/a the profile jumps there by e_b - 0.3609 (0.032 at a = 7.99).
    const double jump = radial("de-klerk-2003")(0.63700001, 7.99).value -
                        radial("de-klerk-2003")(0.637, 7.99).value;
    EXPECT_NEAR(jump, 0.365 + 0.22 / 7.99 - 0.3609, 2e-4);
    EXPECT_NE(radial("mueller-1992")(1.0, 1.5).warning, "");
}

TEST(CorrelationsReport, ProfilesEndAtTheAxisOnExactSteps) {
    // a = 5: the axis is 2.5 d from the wall, so the default --profile-to 5 stops there, at
    // x = k 0.01 (251 points, the last exactly 2.5); a = 20 keeps --profile-to 5.
    for (const auto& [a, points, last] : {std::tuple{5.0, 251u, 2.5}, {20.0, 501u, 5.0}}) {
        const Report r = correlations_report({a, 0.01, 5.0});
        for (const auto& [name, profile] : r.values["radial_void_fraction"].items()) {
            const auto& x = profile["x_from_wall_d"];
            ASSERT_EQ(x.size(), points) << name;
            EXPECT_EQ(x[points - 1].get<double>(), last) << name;
            EXPECT_EQ(x[37].get<double>(), 37 * 0.01) << name;
            EXPECT_EQ(profile["void_fraction"].size(), points) << name;
        }
    }
}
