// Hydraulics (Tsayger 2013 eq. (1), Ergun, Eisfeld & Schnitzlein, Wen & Yu, the band of
// pressure-drop correlations) against values computed by hand from the formulas or by an
// independent implementation.
#include <cmath>
#include <limits>
#include <numbers>
#include <stdexcept>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include <gtest/gtest.h>

#include "packbed/error.hpp"
#include "packbed/hydraulics.hpp"
#include "packbed/pipeline.hpp"

namespace packbed {
namespace {

/// 1 mm glass-like spheres (2500 kg/m^3) in water (1000 kg/m^3, 1 mPa s).
FluidAndParticles water() {
    FluidAndParticles f;
    f.diameter = 1e-3;
    f.particle_density = 2500.0;
    f.fluid_density = 1000.0;
    f.viscosity = 1e-3;
    return f;
}

TEST(Hydraulics, ArchimedesNumber) {
    // 9.80665 * 1e-9 * 1000 * 1500 / 1e-6
    EXPECT_NEAR(archimedes_number(water()), 14709.975, 1e-9);
}

TEST(Hydraulics, CoefficientsOfEquation1AtTsaygersPorosities) {
    // Eqs. (2)-(4) from eq. (1) with the paper's rounded porosities. The linear terms and eqs.
    // (3)-(4) agree with the printed 177.394, 728.79 and 16.226, 6397.5 and 100.7; the
    // quadratic term of eq. (2) is 1.75 / 0.66^3 = 6.087, printed 5.087 (docs/hydraulics.md).
    const auto tetrahedral = fluidization_coefficients(0.660);
    EXPECT_NEAR(tetrahedral.linear, 177.394, 5e-4);
    EXPECT_NEAR(tetrahedral.quadratic, 6.08704, 1e-5);
    const auto cubic = fluidization_coefficients(0.476);
    EXPECT_NEAR(cubic.linear, 728.79, 5e-3);
    EXPECT_NEAR(cubic.quadratic, 16.226, 5e-4);
    const auto hexagonal = fluidization_coefficients(0.259);
    EXPECT_NEAR(hexagonal.linear, 6397.5, 0.05);
    EXPECT_NEAR(hexagonal.quadratic, 100.7, 0.05);
    // Permeability ratios (reciprocal linear terms): hexagonal to tetrahedral 36, as printed;
    // hexagonal to cubic 8.78, printed 9.8.
    EXPECT_NEAR(hexagonal.linear / tetrahedral.linear, 36.06, 0.01);
    EXPECT_NEAR(hexagonal.linear / cubic.linear, 8.778, 0.001);
}

TEST(Hydraulics, CriticalReynoldsSolvesTheQuadraticAtEveryAr) {
    const double e = 0.66;
    const auto [a, b] = fluidization_coefficients(e);
    for (const double ar : {1e-12, 1e-3, 1.0, 14709.975, 1e7, 1e30, 1e300}) {
        const double re = critical_reynolds(ar, e);
        ASSERT_TRUE(std::isfinite(re)) << ar;
        EXPECT_NEAR((a * re + b * re * re) / ar, 1.0, 1e-13) << "Ar = " << ar;
    }
    // Limits: Stokes (Ar / A) and inertial (sqrt(Ar / B)).
    EXPECT_NEAR(critical_reynolds(1e-12, e) / (1e-12 / a), 1.0, 1e-12);
    EXPECT_NEAR(critical_reynolds(1e300, e) / std::sqrt(1e300 / b), 1.0, 1e-12);
    EXPECT_EQ(critical_reynolds(0.0, e), 0.0);
}

TEST(Hydraulics, SuperficialVelocityOfTheCriticalReynolds) {
    const FluidAndParticles f = water();
    const double re = critical_reynolds(archimedes_number(f), 0.66);
    // w = Re mu / (rho d) = Re * 1e-3 m/s here.
    EXPECT_NEAR(superficial_velocity(re, f), re * 1e-3, 1e-15);
}

TEST(Hydraulics, ErgunPressureGradient) {
    // 150 * 1e-3 * 0.01 * 0.36 / (0.064 * 1e-6) + 1.75 * 1000 * 1e-4 * 0.6 / (0.064 * 1e-3)
    EXPECT_NEAR(ergun_pressure_gradient(0.4, 0.01, water()), 8437.5 + 1640.625, 1e-9);
    // The fluid's own form: the same number, and a fluid of the densest allowed (3e4 kg/m^3),
    // which no particle density can settle in: 150 * 1e-3 * 0.01 * 0.36 / (0.064 * 1e-6) +
    // 1.75 * 3e4 * 1e-4 * 0.6 / (0.064 * 1e-3).
    EXPECT_EQ(ergun_pressure_gradient(0.4, 0.01, 1e-3, 1000.0, 1e-3),
              ergun_pressure_gradient(0.4, 0.01, water()));
    EXPECT_NEAR(ergun_pressure_gradient(0.4, 0.01, 1e-3, 3e4, 1e-3), 8437.5 + 49218.75, 1e-8);
}

TEST(Hydraulics, EisfeldSchnitzleinWithTheWallEffect) {
    // Re = 10, A_w = 1 + 2/18, B_w = (0.0115 + 0.87)^2, psi = 120.35: dP/L = psi rho u^2 / d.
    const CorrelationValue v = eisfeld_schnitzlein_pressure_gradient(0.4, 0.01, 10.0, water());
    EXPECT_NEAR(v.value, 12034.99789, 1e-4);
    EXPECT_TRUE(v.warning.empty());
    // A tube of aspect ratio 300 is outside 1.624 <= a <= 250: a warning naming it.
    const CorrelationValue wide = eisfeld_schnitzlein_pressure_gradient(0.4, 0.01, 300.0, water());
    EXPECT_EQ(wide.warning, "Eisfeld & Schnitzlein (2001) evaluated outside its range: a = 300 "
                            "(1.624 to 250)");
    // The wall adds resistance: above Ergun at a = 10.
    EXPECT_GT(v.value, ergun_pressure_gradient(0.4, 0.01, water()));
}

/// The correlation `name` of pressure_drop_correlations().
const PressureDropCorrelation& correlation(std::string_view name) {
    for (const PressureDropCorrelation& c : pressure_drop_correlations())
        if (c.name == name)
            return c;
    throw std::out_of_range(std::string(name));
}

TEST(Hydraulics, PressureDropCorrelationsAgreeWithAnIndependentImplementation) {
    // The examples of the Python library `fluids` (C. Bell, fluids/packed_bed.py, written from
    // Erdim et al.'s 2015 review): d = 0.8 mm, e = 0.4, u = 1 mm/s, water-like, L = 1 m, so
    // Re_p = 0.8 and Re_m = 1.333; Harrison's with D = 10 mm (a = 12.5).
    FluidAndParticles f = water();
    f.diameter = 8e-4;
    const double none = std::numeric_limits<double>::infinity();
    const auto at = [&](std::string_view name, double a) {
        return correlation(name).gradient(0.4, 1e-3, a, f).value;
    };
    EXPECT_NEAR(at("ergun-1952", none) / 1338.8671874999995, 1.0, 1e-12);
    EXPECT_NEAR(at("carman-1937", none) / 1614.721678121775, 1.0, 1e-12);
    EXPECT_NEAR(at("kta-1981", none) / 1440.409277034248, 1.0, 1e-12);
    EXPECT_NEAR(at("erdim-2015", none) / 1438.2826958844414, 1.0, 1e-12);
    EXPECT_NEAR(at("harrison-2013", 12.5) / 1255.1625662548427, 1.0, 1e-12);
    // Ergun's as the function of its own.
    EXPECT_NEAR(at("ergun-1952", none) / ergun_pressure_gradient(0.4, 1e-3, f), 1.0, 1e-14);
}

TEST(Hydraulics, PressureDropCorrelationsReachTheirCreepingConstants) {
    // As Re -> 0, f_v = (dP/L) d^2 e^3 / (mu u (1-e)^2) -> the viscous constant: 150, 180, 160,
    // 160, Harrison's 119.8 (1 + pi / (6 a (1-e)))^2 and Eisfeld & Schnitzlein's 154 A_w^2.
    const FluidAndParticles f = water();
    const double e = 0.4, u = 1e-12, a = 5.0;
    const double scale =
        f.diameter * f.diameter * e * e * e / (f.viscosity * u * (1 - e) * (1 - e));
    const double harrison = std::pow(1.0 + std::numbers::pi / (6.0 * a * (1 - e)), 2);
    const double aw = 1.0 + 2.0 / (3.0 * a * (1 - e));
    const std::vector<std::pair<std::string_view, double>> constants = {
        {"ergun-1952", 150.0},
        {"carman-1937", 180.0},
        {"kta-1981", 160.0},
        {"erdim-2015", 160.0},
        {"harrison-2013", 119.8 * harrison},
        {"eisfeld-schnitzlein-2001", 154.0 * aw * aw}};
    ASSERT_EQ(constants.size(), pressure_drop_correlations().size());
    for (const auto& [name, constant] : constants)
        EXPECT_NEAR(correlation(name).gradient(e, u, a, f).value * scale / constant, 1.0, 1e-7)
            << name;
    // With no wall (a infinite) the wall terms vanish: Harrison's 119.8, E&S's 154.
    const double none = std::numeric_limits<double>::infinity();
    EXPECT_NEAR(correlation("harrison-2013").gradient(e, u, none, f).value * scale, 119.8, 1e-5);
    EXPECT_NEAR(correlation("eisfeld-schnitzlein-2001").gradient(e, u, none, f).value * scale,
                154.0, 1e-5);
}

TEST(Hydraulics, PressureDropCorrelationsWarnOutsideTheirRanges) {
    const FluidAndParticles f = water(); // d = 1 mm: u = 1 mm/s is Re_p = 1
    const double none = std::numeric_limits<double>::infinity();
    // Re_m = 1 / 0.6 = 1.667: below KTA's 100 and Erdim's 2; a = 5 below Harrison's 8.3.
    EXPECT_EQ(correlation("kta-1981").gradient(0.4, 1e-3, none, f).warning,
              "KTA 3102.3 (1981) evaluated outside its range: Re_m = 1.667 (100 to 100000)");
    EXPECT_EQ(correlation("erdim-2015").gradient(0.4, 1e-3, 5.0, f).warning,
              "Erdim et al. (2015) evaluated outside its range: Re_m = 1.667 (2 to 3582)");
    EXPECT_EQ(correlation("harrison-2013").gradient(0.4, 1e-3, 5.0, f).warning,
              "Harrison et al. (2013) evaluated outside its range: a = 5 (8.3 to 50)");
    // Inside every range: no warning; a formula without a wall term is not held to its data's
    // a when there is no wall.
    EXPECT_EQ(correlation("erdim-2015").gradient(0.4, 3e-3, 10.0, f).warning, "");
    EXPECT_EQ(correlation("erdim-2015").gradient(0.4, 3e-3, none, f).warning, "");
    EXPECT_EQ(correlation("harrison-2013").gradient(0.4, 3e-3, 10.0, f).warning, "");
    // A wall formula with no wall lies outside its data.
    EXPECT_EQ(correlation("harrison-2013").gradient(0.4, 3e-3, none, f).warning,
              "Harrison et al. (2013) evaluated outside its range: a = inf (8.3 to 50)");
    // Ergun and Carman state no range here: never a warning.
    EXPECT_EQ(correlation("carman-1937").gradient(0.9, 1e-9, 1.0, f).warning, "");
    // Bad input: refused like the other functions.
    EXPECT_THROW(correlation("kta-1981").gradient(0.4, 0.0, 5.0, f), InvalidInput);
    EXPECT_THROW(correlation("kta-1981").gradient(0.4, 1e-3, -none, f), InvalidInput);
    EXPECT_THROW(correlation("kta-1981").gradient(1.0, 1e-3, 5.0, f), InvalidInput);
}

TEST(Hydraulics, WenYuMinimumFluidization) {
    EXPECT_NEAR(wen_yu_reynolds(14709.975), 7.963616981726, 1e-9);
    EXPECT_NEAR(wen_yu_reynolds(1e-9) / (0.0408e-9 / (2 * 33.7)), 1.0, 1e-9);
}

TEST(Hydraulics, Permeabilities) {
    EXPECT_NEAR(carman_kozeny_permeability(0.4, 1e-3), 1e-6 * 0.064 / (180 * 0.36), 1e-22);
    EXPECT_NEAR(ergun_permeability(0.4, 1e-3), 1e-6 * 0.064 / (150 * 0.36), 1e-22);
}

TEST(Hydraulics, DragOfPeriodicAndRandomArraysOfSpheres) {
    // Zick & Homsy (1982), Table 2: the entries, matched within 1e-3, none between them.
    using Entry = std::pair<double, double>;
    EXPECT_EQ(zick_homsy_simple_cubic(0.216), Entry(0.216, 7.442));
    EXPECT_EQ(zick_homsy_simple_cubic(0.2169), Entry(0.216, 7.442));
    EXPECT_EQ(zick_homsy_simple_cubic(0.45), Entry(0.45, 28.1));
    EXPECT_EQ(zick_homsy_simple_cubic(std::numbers::pi / 6.0), Entry(0.5236, 42.1)); // touching
    // touching, its 6 contacts flattened by caps 0.02 apart: pi/6 - 6 caps of height 0.01
    const double caps = 6.0 * std::numbers::pi * 1e-4 * (1.5 - 0.01) / 3.0;
    EXPECT_EQ(zick_homsy_simple_cubic(std::numbers::pi / 6.0 - caps), Entry(0.5236, 42.1));
    EXPECT_FALSE(zick_homsy_simple_cubic(0.2171));
    EXPECT_FALSE(zick_homsy_simple_cubic(0.3));
    // van der Hoef et al. (2005), eq. (9), by hand: 10 phi / (1 - phi)^2 + (1 - phi)^2 (1 + 1.5
    // sqrt(phi)); at phi = 0.5: 20 + 0.25 (1 + 1.5 sqrt(0.5)) = 20.515165.
    EXPECT_NEAR(van_der_hoef_drag(0.5), 20.0 + 0.25 * (1.0 + 1.5 * std::sqrt(0.5)), 1e-12);
    EXPECT_NEAR(van_der_hoef_drag(0.216), 4.5573162, 1e-6);
    // The dilute limit is Stokes's drag on one sphere: F -> 1.
    EXPECT_NEAR(van_der_hoef_drag(1e-12), 1.0, 1e-5);
    EXPECT_THROW(van_der_hoef_drag(1.0), InvalidInput);
    EXPECT_THROW(van_der_hoef_drag(0.0), InvalidInput);
}

TEST(Hydraulics, GridConvergenceRecoversAPowerLaw) {
    // Values on phi = 1 + 0.1 h^p exactly: the order, the limit 1 and Celik et al.'s GCI
    // 1.25 |(phi_1 - phi_2) / phi_1| / (r^p - 1). Constant ratio (q = 0), p = 2:
    const GridConvergence a = grid_convergence({1.0, 1.5, 2.25}, {1.1, 1.225, 1.50625});
    EXPECT_NEAR(a.order, 2.0, 1e-12);
    EXPECT_NEAR(a.extrapolated, 1.0, 1e-12);
    EXPECT_NEAR(a.approximate_error, 0.125 / 1.1, 1e-12);
    EXPECT_NEAR(a.gci_fine, 1.25 * (0.125 / 1.1) / 1.25, 1e-12);
    EXPECT_FALSE(a.oscillating);
    // Ratios 1.3 and 2 / 1.3 (q != 0: the iteration), p = 1.5:
    const auto f = [](double h) { return 1.0 + 0.1 * std::pow(h, 1.5); };
    const GridConvergence b = grid_convergence({1.0, 1.3, 2.0}, {f(1.0), f(1.3), f(2.0)});
    EXPECT_NEAR(b.order, 1.5, 1e-9);
    EXPECT_NEAR(b.extrapolated, 1.0, 1e-9);
    EXPECT_NEAR(b.extrapolated_error, 0.1, 1e-9); // |(1 - 1.1) / 1|
    // Differences of opposite signs: oscillating (s = -1).
    EXPECT_TRUE(grid_convergence({1.0, 2.0, 4.0}, {1.0, 1.1, 0.95}).oscillating);
    EXPECT_THROW(grid_convergence({1.0, 2.0, 4.0}, {1.0, 1.0, 1.2}), InvalidInput);
    EXPECT_THROW(grid_convergence({2.0, 1.0, 4.0}, {1.0, 1.1, 1.2}), InvalidInput);
}

TEST(Hydraulics, BadInputsNameTheValue) {
    FluidAndParticles f = water();
    f.viscosity = 0.0;
    try {
        archimedes_number(f);
        FAIL();
    } catch (const InvalidInput& e) {
        EXPECT_STREQ(e.what(), "viscosity = 0 is not allowed; allowed: 1e-07 to 10000 Pa s");
    }
    f = water();
    f.particle_density = 900.0;
    try {
        archimedes_number(f);
        FAIL();
    } catch (const InvalidInput& e) {
        EXPECT_STREQ(e.what(), "particle-density = 900 is not allowed; allowed: > the fluid "
                               "density (1000 kg/m^3): a particle lighter than the fluid does "
                               "not settle or fluidize");
    }
    for (const double e : {0.0, 1.0, -0.2, 1.5, std::nan("")})
        EXPECT_THROW(fluidization_coefficients(e), InvalidInput) << e;
    try {
        fluidization_coefficients(1.2);
        FAIL();
    } catch (const InvalidInput& e) {
        EXPECT_STREQ(e.what(), "porosity = 1.2 is not allowed; allowed: 0 < porosity < 1");
    }
}

/// \return the message of the InvalidInput `f` throws, or "accepted".
template <class F> std::string refusal(F&& f) {
    try {
        f();
    } catch (const InvalidInput& e) {
        return e.what();
    }
    return "accepted";
}

TEST(Hydraulics, PhysicalRangesAreRefusedBeyondTheirEnds) {
    // A diameter of 1e-300 m gave Ar = 0, then Ergun 0 / 0: "-nan Pa/m".
    FluidAndParticles f = water();
    f.diameter = 1e-300;
    EXPECT_EQ(refusal([&] { archimedes_number(f); }),
              "diameter = 1e-300 is not allowed; allowed: 1e-09 to 10 m");
    f.diameter = 1e200; // Ar overflowed to inf
    EXPECT_EQ(refusal([&] { archimedes_number(f); }),
              "diameter = 1e+200 is not allowed; allowed: 1e-09 to 10 m");
    f = water();
    f.fluid_density = 1e-4;
    EXPECT_EQ(refusal([&] { archimedes_number(f); }),
              "fluid-density = 0.0001 is not allowed; allowed: 0.001 to 30000 kg/m^3");
    f = water();
    f.particle_density = 1e5;
    EXPECT_EQ(refusal([&] { archimedes_number(f); }),
              "particle-density = 100000 is not allowed; allowed: 0.001 to 30000 kg/m^3");
    f = water();
    f.gravity = 1e7;
    EXPECT_EQ(refusal([&] { archimedes_number(f); }),
              "gravity = 10000000 is not allowed; allowed: 1e-06 to 1e+06 m/s^2");
    EXPECT_EQ(refusal([&] { eisfeld_schnitzlein_pressure_gradient(0.4, 0.1, 2e4, water()); }),
              "aspect-ratio = 20000 is not allowed; allowed: 1 to 10000");
}

TEST(Hydraulics, EveryResultIsFiniteAtTheEndsOfTheRanges) {
    // Every corner of the ranges, at a near-solid, the densest lattice's and a near-empty
    // porosity, with the critical velocity, the largest and the smallest: all numbers finite.
    int corners = 0;
    for (const double d : {1e-9, 10.0})
        for (const double g : {1e-6, 1e6})
            for (const double rho : {1e-3, 29999.0})
                for (const double rho_p : {2e-3, 3e4})
                    for (const double mu : {1e-7, 1e4})
                        for (const double e : {1e-3, 0.2595, 0.999}) {
                            if (rho_p <= rho)
                                continue;
                            const FluidAndParticles f{d, rho_p, rho, mu, g};
                            const double ar = archimedes_number(f);
                            const double re = critical_reynolds(ar, e);
                            const double w = superficial_velocity(re, f);
                            const double u_mf = superficial_velocity(wen_yu_reynolds(ar), f);
                            for (const double u : {w, 1e4, 1e-300}) {
                                const double dp = ergun_pressure_gradient(e, u, f);
                                const double es =
                                    eisfeld_schnitzlein_pressure_gradient(e, u, 1e4, f).value;
                                ASSERT_TRUE(std::isfinite(dp) && std::isfinite(es))
                                    << d << " " << g << " " << rho << " " << rho_p << " " << mu
                                    << " " << e << " " << u;
                                EXPECT_LT(dp, 1e38);
                                for (const PressureDropCorrelation& c :
                                     pressure_drop_correlations())
                                    for (const double a :
                                         {1.0, 1e4, std::numeric_limits<double>::infinity()})
                                        ASSERT_TRUE(std::isfinite(c.gradient(e, u, a, f).value))
                                            << c.name << " " << d << " " << rho << " " << mu << " "
                                            << e << " " << u << " " << a;
                            }
                            EXPECT_TRUE(std::isfinite(ar) && std::isfinite(w) &&
                                        std::isfinite(u_mf));
                            EXPECT_TRUE(std::isfinite(carman_kozeny_permeability(e, d)));
                            ++corners;
                        }
    EXPECT_EQ(corners, 72); // 96 less the 24 of a particle lighter than the fluid
}

TEST(Hydraulics, TheFluidsErgunRefusesWhatTheFullOneRefuses) {
    FluidAndParticles thin = water();
    thin.viscosity = 0.0;
    const std::string message = refusal([&] { ergun_pressure_gradient(0.4, 0.01, thin); });
    EXPECT_NE(message, "accepted");
    EXPECT_EQ(refusal([] { ergun_pressure_gradient(0.4, 0.01, 1e-3, 1000.0, 0.0); }), message);
    EXPECT_EQ(refusal([] { ergun_pressure_gradient(0.4, 0.01, 1e-3, 0.0, 1e-3); }), refusal([] {
                  FluidAndParticles f = water();
                  f.fluid_density = 0.0;
                  ergun_pressure_gradient(0.4, 0.01, f);
              }));
}

TEST(Hydraulics, ResultsThatAreNotFiniteAreRefusedNamingTheInputs) {
    // A porosity of 1e-300: e^3 underflows to 0, the coefficients and Ergun are infinite.
    EXPECT_EQ(refusal([] { fluidization_coefficients(1e-300); }),
              "the coefficient A of eq. (1) is not a finite number (inf) for porosity = 1e-300; "
              "allowed: inputs that give one (change porosity)");
    EXPECT_EQ(refusal([] { ergun_pressure_gradient(1e-300, 0.1, water()); }),
              "the Ergun pressure gradient is not a finite number (inf) for porosity = 1e-300, "
              "velocity = 0.1, diameter = 0.001, fluid-density = 1000, viscosity = 0.001; "
              "allowed: inputs that give one (change porosity, velocity, diameter, fluid-density "
              "or viscosity)");
    EXPECT_EQ(refusal([] { ergun_pressure_gradient(1e-300, 0.0, water()); }), // 0 / 0
              "the Ergun pressure gradient is not a finite number (nan) for porosity = 1e-300, "
              "velocity = 0, diameter = 0.001, fluid-density = 1000, viscosity = 0.001; allowed: "
              "inputs that give one (change porosity, velocity, diameter, fluid-density or "
              "viscosity)");
    FluidAndParticles syrup = water();
    syrup.viscosity = 10.0; // w = Re mu / (rho d) = 10 Re m/s
    EXPECT_EQ(refusal([&] { superficial_velocity(1e308, syrup); }),
              "the velocity is not a finite number (inf) for Re = 1e+308, viscosity = 10, "
              "fluid-density = 1000, diameter = 0.001; allowed: inputs that give one (change Re, "
              "viscosity, fluid-density or diameter)");
}

} // namespace
} // namespace packbed
