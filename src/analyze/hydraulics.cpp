#include "packbed/hydraulics.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <initializer_list>
#include <limits>
#include <numbers>
#include <string>
#include <string_view>
#include <vector>

#include <fmt/format.h>
#include <fmt/ranges.h>

#include "base/require.hpp"
#include "packbed/error.hpp"
#include "packbed/limits.hpp"

namespace packbed {

namespace {

using detail::require;

void require_porosity(double e) {
    require(std::isfinite(e) && e > 0.0 && e < 1.0, "porosity", e, "0 < porosity < 1");
}

/// An input of a formula, by the name of its option, for the message of a result that is not a
/// finite number.
struct Input {
    std::string_view name;
    double value;
};

/// \return `value` \throws InvalidInput naming `quantity` and the inputs it was computed from
/// when it is not a finite number (an overflow, 0/0): nothing prints NaN or infinity.
double finite(double value, std::string_view quantity, std::initializer_list<Input> inputs) {
    if (std::isfinite(value))
        return value;
    std::vector<std::string> given, names;
    for (const Input& in : inputs) {
        given.push_back(fmt::format("{} = {}", in.name, in.value));
        names.emplace_back(in.name);
    }
    const std::string last = names.back();
    names.pop_back();
    throw InvalidInput(fmt::format(
        "{} is not a finite number ({}) for {}; allowed: inputs that "
        "give one (change {}{}{})",
        quantity, std::isnan(value) ? "nan" : (value > 0.0 ? "inf" : "-inf"),
        fmt::join(given, ", "), fmt::join(names, ", "), names.empty() ? "" : " or ", last));
}

/// "LOW to HIGH UNIT"
std::string range(double low, double high, std::string_view unit) {
    return fmt::format("{:g} to {:g} {}", low, high, unit);
}

bool within(double v, double low, double high) {
    return std::isfinite(v) && v >= low && v <= high;
}

/// The fluid's and the particles' size: what a pressure drop depends on.
void require_fluid(double diameter, double fluid_density, double viscosity) {
    require(within(diameter, limits::min_particle_diameter_m, limits::max_particle_diameter_m),
            "diameter", diameter,
            range(limits::min_particle_diameter_m, limits::max_particle_diameter_m, "m"));
    require(within(fluid_density, limits::min_density_kg_m3, limits::max_density_kg_m3),
            "fluid-density", fluid_density,
            range(limits::min_density_kg_m3, limits::max_density_kg_m3, "kg/m^3"));
    require(within(viscosity, limits::min_viscosity_pa_s, limits::max_viscosity_pa_s), "viscosity",
            viscosity, range(limits::min_viscosity_pa_s, limits::max_viscosity_pa_s, "Pa s"));
}

} // namespace

void FluidAndParticles::validate() const {
    require_fluid(diameter, fluid_density, viscosity);
    require(within(gravity, limits::min_gravity_m_s2, limits::max_gravity_m_s2), "gravity", gravity,
            range(limits::min_gravity_m_s2, limits::max_gravity_m_s2, "m/s^2"));
    require(std::isfinite(particle_density) && particle_density > fluid_density, "particle-density",
            particle_density,
            fmt::format("> the fluid density ({} kg/m^3): a particle lighter than the fluid "
                        "does not settle or fluidize",
                        fluid_density));
    require(particle_density <= limits::max_density_kg_m3, "particle-density", particle_density,
            range(limits::min_density_kg_m3, limits::max_density_kg_m3, "kg/m^3"));
}

double archimedes_number(const FluidAndParticles& f) {
    f.validate();
    return finite(f.gravity * f.diameter * f.diameter * f.diameter * f.fluid_density *
                      (f.particle_density - f.fluid_density) / (f.viscosity * f.viscosity),
                  "Ar",
                  {{"diameter", f.diameter},
                   {"particle-density", f.particle_density},
                   {"fluid-density", f.fluid_density},
                   {"viscosity", f.viscosity},
                   {"gravity", f.gravity}});
}

FluidizationCoefficients fluidization_coefficients(double e) {
    require_porosity(e);
    const double e3 = e * e * e;
    // e^3 underflows below e ~ 1e-103: the coefficients overflow.
    return {finite(150.0 * (1.0 - e) / e3, "the coefficient A of eq. (1)", {{"porosity", e}}),
            finite(1.75 / e3, "the coefficient B of eq. (1)", {{"porosity", e}})};
}

double critical_reynolds(double archimedes, double porosity) {
    require(std::isfinite(archimedes) && archimedes >= 0.0, "Ar", archimedes, ">= 0");
    const auto [a, b] = fluidization_coefficients(porosity);
    // sqrt(A^2 + 4 B Ar) without overflow for huge Ar: A hypot of A and 2 sqrt(B Ar).
    return 2.0 * archimedes / (a + std::hypot(a, 2.0 * std::sqrt(b * archimedes)));
}

double superficial_velocity(double reynolds, const FluidAndParticles& f) {
    f.validate();
    require(std::isfinite(reynolds) && reynolds >= 0.0, "Re", reynolds, ">= 0");
    return finite(reynolds * f.viscosity / (f.fluid_density * f.diameter), "the velocity",
                  {{"Re", reynolds},
                   {"viscosity", f.viscosity},
                   {"fluid-density", f.fluid_density},
                   {"diameter", f.diameter}});
}

double ergun_pressure_gradient(double e, double u, double d, double rho, double mu) {
    require_porosity(e);
    require(std::isfinite(u) && u >= 0.0, "velocity", u, ">= 0 (m/s)");
    require_fluid(d, rho, mu);
    const double e3 = e * e * e;
    return finite(150.0 * mu * u * (1.0 - e) * (1.0 - e) / (e3 * d * d) +
                      1.75 * rho * u * u * (1.0 - e) / (e3 * d),
                  "the Ergun pressure gradient",
                  {{"porosity", e},
                   {"velocity", u},
                   {"diameter", d},
                   {"fluid-density", rho},
                   {"viscosity", mu}});
}

double ergun_pressure_gradient(double e, double u, const FluidAndParticles& f) {
    f.validate();
    return ergun_pressure_gradient(e, u, f.diameter, f.fluid_density, f.viscosity);
}

CorrelationValue eisfeld_schnitzlein_pressure_gradient(double e, double u, double a,
                                                       const FluidAndParticles& f) {
    require(std::isfinite(a) && a >= 1.0 && a <= limits::max_tube_aspect_ratio, "aspect-ratio", a,
            fmt::format("1 to {:g}", limits::max_tube_aspect_ratio));
    // The band's entry.
    static const PressureDropCorrelation& entry = *std::find_if(
        pressure_drop_correlations().begin(), pressure_drop_correlations().end(),
        [](const PressureDropCorrelation& c) { return c.name == "eisfeld-schnitzlein-2001"; });
    return entry.gradient(e, u, a, f);
}

namespace {

// The normalised gradients f_v(e, Re_m, a) of pressure_drop_correlations(), each with its
// source; how each was checked is in docs/sources.md.

/// Ergun (1952): \f$f_v = 150 + 1.75 Re_m\f$.
double ergun_f_v(double, double re_m, double) {
    return 150.0 + 1.75 * re_m;
}
/// Carman (1937): \f$f_v = 180 + 2.871 Re_m^{0.9}\f$. His \f$R_1 / (\rho u_1^2) = 5 / Re_1 +
/// 0.4 / Re_1^{0.1}\f$ is \f$f' / 6\f$ with \f$Re_1 = Re_m / 6\f$ (\f$f' = f_v / Re_m\f$): 180
/// = 6 * 5 * 6 and 2.871 = 6 * 0.4 * 6^0.1.
double carman_f_v(double, double re_m, double) {
    return 180.0 + 2.871 * std::pow(re_m, 0.9);
}
/// KTA 3102.3 (1981): \f$\psi = 320 / Re_m + 6 / Re_m^{0.1}\f$ with \f$\Delta P / L = \psi
/// (1-e) / e^3 \rho u^2 / (2 d)\f$, so \f$f_v = 160 + 3 Re_m^{0.9}\f$.
double kta_f_v(double, double re_m, double) {
    return 160.0 + 3.0 * std::pow(re_m, 0.9);
}
/// Erdim, Akgiray & Demir (2015), their eq. for spheres: \f$f_v = 160 + 2.81 Re_m^{0.904}\f$.
double erdim_f_v(double, double re_m, double) {
    return 160.0 + 2.81 * std::pow(re_m, 0.904);
}
/// Harrison, Brunner & Hecker (2013), with the wall (Liu et al.'s 1994 wall terms): \f$f_v = 119.8
/// A + 4.63 B Re_m^{5/6}\f$, \f$A = (1 + \pi / (6 a (1-e)))^2\f$, \f$B = 1 - \pi^2 / (24 a) (1 - 1
/// / (2 a))\f$ (A = B = 1 without a wall, a infinite).
double harrison_f_v(double e, double re_m, double a) {
    const double pi = std::numbers::pi;
    const double wall = 1.0 + pi / (6.0 * a * (1.0 - e));
    const double b = 1.0 - pi * pi / (24.0 * a) * (1.0 - 1.0 / (2.0 * a));
    return 119.8 * wall * wall + 4.63 * b * std::pow(re_m, 5.0 / 6.0);
}
/// Eisfeld & Schnitzlein (2001), spheres: \f$f_v = K_1 A_w^2 + (A_w / B_w) Re_m\f$ (their
/// \f$\psi = \Delta P\,d / (L \rho u^2)\f$ times \f$Re_p\,e^3 / (1-e)^2\f$).
double eisfeld_schnitzlein_f_v(double e, double re_m, double a) {
    const double aw = 1.0 + 2.0 / (3.0 * a * (1.0 - e));
    const double bw = std::pow(1.15 / (a * a) + 0.87, 2);
    return 154.0 * aw * aw + aw / bw * re_m;
}

constexpr double unbounded = std::numeric_limits<double>::infinity();

} // namespace

const std::vector<PressureDropCorrelation>& pressure_drop_correlations() {
    static const std::vector<PressureDropCorrelation> table = {
        {"ergun-1952", "Ergun (1952)", "S. Ergun, Chem. Eng. Prog. 48 (1952) 89-94",
         "f_v = 150 + 1.75 Re_m", false, true, 0.0, unbounded, 0.0, 1.0, 1.0, unbounded, ergun_f_v},
        {"carman-1937", "Carman (1937)",
         "P. C. Carman, Trans. Inst. Chem. Eng. (London) 15 (1937) 150-166",
         "f_v = 180 + 2.871 Re_m^0.9", false, true, 0.0, unbounded, 0.0, 1.0, 1.0, unbounded,
         carman_f_v},
        {"kta-1981", "KTA 3102.3 (1981)",
         "KTA 3102.3, Reactor core design of high-temperature gas-cooled reactors, part 3: loss "
         "of pressure through friction in pebble bed cores (1981)",
         "f_v = 160 + 3 Re_m^0.9", false, true, 100.0, 1e5, 0.36, 0.42, 1.0, unbounded, kta_f_v},
        {"erdim-2015", "Erdim et al. (2015)",
         "E. Erdim, O. Akgiray, I. Demir, Powder Technol. 283 (2015) 488-504",
         "f_v = 160 + 2.81 Re_m^0.904", false, true, 2.0, 3582.0, 0.377, 0.470, 4.0, 34.1,
         erdim_f_v},
        {"harrison-2013", "Harrison et al. (2013)",
         "L. D. Harrison, K. M. Brunner, W. C. Hecker, AIChE J. (2013), doi:10.1002/aic.14034",
         "f_v = 119.8 A + 4.63 B Re_m^(5/6), A = (1 + pi / (6 a (1-e)))^2, B = 1 - pi^2 / (24 a) "
         "(1 - 1 / (2 a))",
         true, false, 0.72, 7700.0, 0.33, 0.88, 8.3, 50.0, harrison_f_v},
        {"eisfeld-schnitzlein-2001", "Eisfeld & Schnitzlein (2001)",
         "B. Eisfeld, K. Schnitzlein, Chem. Eng. Sci. 56 (2001) 4321-4329",
         "f_v = 154 A_w^2 + (A_w / B_w) Re_m, A_w = 1 + 2 / (3 a (1-e)), B_w = (1.15 / a^2 + "
         "0.87)^2",
         true, false, 0.01, 17635.0, 0.330, 0.882, 1.624, 250.0, eisfeld_schnitzlein_f_v},
    };
    return table;
}

CorrelationValue PressureDropCorrelation::gradient(double e, double u, double a,
                                                   const FluidAndParticles& f) const {
    require_porosity(e);
    require(std::isfinite(u) && u > 0.0, "velocity", u, "> 0 (m/s)");
    require(a == unbounded || (a >= 1.0 && a <= limits::max_tube_aspect_ratio), "aspect-ratio", a,
            fmt::format("1 to {:g}, or none (no wall)", limits::max_tube_aspect_ratio));
    f.validate();
    const double re_p = f.fluid_density * u * f.diameter / f.viscosity;
    const double re_m = re_p / (1.0 - e);
    const double d = f.diameter;
    CorrelationValue out{
        finite(f_v(e, re_m, a) * f.viscosity * u * (1.0 - e) * (1.0 - e) / (d * d * e * e * e),
               fmt::format("the {} pressure gradient", label),
               {{"porosity", e},
                {"velocity", u},
                {"aspect-ratio", a},
                {"diameter", f.diameter},
                {"fluid-density", f.fluid_density},
                {"viscosity", f.viscosity}}),
        {}};
    std::vector<std::string> outside;
    const double re = modified ? re_m : re_p;
    if (re < re_low || re > re_high)
        outside.push_back(fmt::format("{} = {:.4g} ({:g} to {:g})", modified ? "Re_m" : "Re_p", re,
                                      re_low, re_high));
    if (!(a == unbounded && !wall) && (a < a_low || a > a_high))
        outside.push_back(fmt::format("a = {:.4g} ({:g} to {:g})", a, a_low, a_high));
    if (e < e_low || e > e_high)
        outside.push_back(fmt::format("porosity = {:.4g} ({:g} to {:g})", e, e_low, e_high));
    if (!outside.empty())
        out.warning =
            fmt::format("{} evaluated outside its range: {}", label, fmt::join(outside, ", "));
    return out;
}

std::vector<PressureDropBandValue> pressure_drop_band(double e, double u, double a,
                                                      const FluidAndParticles& f) {
    std::vector<PressureDropBandValue> band;
    for (const PressureDropCorrelation& c : pressure_drop_correlations())
        if (!(c.wall && a == unbounded))
            band.push_back({&c, c.gradient(e, u, a, f)});
    return band;
}

double wen_yu_reynolds(double archimedes) {
    require(std::isfinite(archimedes) && archimedes >= 0.0, "Ar", archimedes, ">= 0");
    const double c = 33.7, k = 0.0408 * archimedes;
    return k / (std::sqrt(c * c + k) + c);
}

double carman_kozeny_permeability(double e, double d) {
    require_porosity(e);
    require(std::isfinite(d) && d > 0.0, "diameter", d, "> 0 (m)");
    return finite(d * d * e * e * e / (180.0 * (1.0 - e) * (1.0 - e)),
                  "the Carman-Kozeny permeability", {{"porosity", e}, {"diameter", d}});
}

double ergun_permeability(double e, double d) {
    require_porosity(e);
    require(std::isfinite(d) && d > 0.0, "diameter", d, "> 0 (m)");
    return finite(d * d * e * e * e / (150.0 * (1.0 - e) * (1.0 - e)), "the Ergun permeability",
                  {{"porosity", e}, {"diameter", d}});
}

std::optional<std::pair<double, double>> zick_homsy_simple_cubic(double phi) {
    // Zick & Homsy (1982), Table 2, simple cubic (the same numbers in Basilisk's
    // src/test/spheres.c; Sangani & Acrivos's series agrees to 3-4 digits up to 0.216).
    static constexpr std::array<std::pair<double, double>, 7> table{{{0.027, 2.008},
                                                                     {0.064, 2.810},
                                                                     {0.125, 4.292},
                                                                     {0.216, 7.442},
                                                                     {0.343, 15.4},
                                                                     {0.45, 28.1},
                                                                     {0.5236, 42.1}}};
    for (const auto& entry : table)
        if (std::abs(phi - entry.first) <= 1e-3)
            return entry;
    return std::nullopt;
}

double van_der_hoef_drag(double phi) {
    require(std::isfinite(phi) && phi > 0.0 && phi < 1.0, "solid fraction", phi, "in (0, 1)");
    const double e = 1.0 - phi;
    return 10.0 * phi / (e * e) + e * e * (1.0 + 1.5 * std::sqrt(phi));
}

std::optional<double> hydraulic_diameter(const Container& container) {
    return container.hydraulic_diameter().value;
}

} // namespace packbed
