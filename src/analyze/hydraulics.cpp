#include "packbed/hydraulics.hpp"

#include <array>
#include <cmath>
#include <initializer_list>
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

} // namespace

void FluidAndParticles::validate() const {
    auto in = [](double v, double low, double high) {
        return std::isfinite(v) && v >= low && v <= high;
    };
    require(in(diameter, limits::min_particle_diameter_m, limits::max_particle_diameter_m),
            "diameter", diameter,
            range(limits::min_particle_diameter_m, limits::max_particle_diameter_m, "m"));
    require(in(fluid_density, limits::min_density_kg_m3, limits::max_density_kg_m3),
            "fluid-density", fluid_density,
            range(limits::min_density_kg_m3, limits::max_density_kg_m3, "kg/m^3"));
    require(in(viscosity, limits::min_viscosity_pa_s, limits::max_viscosity_pa_s), "viscosity",
            viscosity, range(limits::min_viscosity_pa_s, limits::max_viscosity_pa_s, "Pa s"));
    require(in(gravity, limits::min_gravity_m_s2, limits::max_gravity_m_s2), "gravity", gravity,
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

double ergun_pressure_gradient(double e, double u, const FluidAndParticles& f) {
    require_porosity(e);
    require(std::isfinite(u) && u >= 0.0, "velocity", u, ">= 0 (m/s)");
    f.validate();
    const double e3 = e * e * e, d = f.diameter;
    return finite(150.0 * f.viscosity * u * (1.0 - e) * (1.0 - e) / (e3 * d * d) +
                      1.75 * f.fluid_density * u * u * (1.0 - e) / (e3 * d),
                  "the Ergun pressure gradient",
                  {{"porosity", e},
                   {"velocity", u},
                   {"diameter", d},
                   {"fluid-density", f.fluid_density},
                   {"viscosity", f.viscosity}});
}

CorrelationValue eisfeld_schnitzlein_pressure_gradient(double e, double u, double a,
                                                       const FluidAndParticles& f) {
    require_porosity(e);
    require(std::isfinite(u) && u > 0.0, "velocity", u, "> 0 (m/s)");
    require(std::isfinite(a) && a >= 1.0 && a <= limits::max_tube_aspect_ratio, "aspect-ratio", a,
            fmt::format("1 to {:g}", limits::max_tube_aspect_ratio));
    f.validate();
    const double re = f.fluid_density * u * f.diameter / f.viscosity;
    const double aw = 1.0 + 2.0 / (3.0 * a * (1.0 - e));
    const double bw = std::pow(1.15 / (a * a) + 0.87, 2);
    const double e3 = e * e * e, d = f.diameter;
    // psi rho u^2 / d with the viscous term's 1 / Re multiplied out (mu u / d^2): no 0 * inf
    // when Re underflows at a tiny velocity.
    const double viscous = 154.0 * aw * aw * (1.0 - e) * (1.0 - e) / e3 * f.viscosity * u / (d * d);
    const double inertial = aw / bw * (1.0 - e) / e3 * f.fluid_density * u * u / d;
    CorrelationValue out{finite(viscous + inertial, "the Eisfeld & Schnitzlein pressure gradient",
                                {{"porosity", e},
                                 {"velocity", u},
                                 {"aspect-ratio", a},
                                 {"diameter", f.diameter},
                                 {"fluid-density", f.fluid_density},
                                 {"viscosity", f.viscosity}}),
                         {}};
    std::vector<std::string> outside;
    if (re < 0.01 || re > 17635)
        outside.push_back(fmt::format("Re = {:.4g} (0.01 to 17635)", re));
    if (a < 1.624 || a > 250)
        outside.push_back(fmt::format("a = {:.4g} (1.624 to 250)", a));
    if (e < 0.330 || e > 0.882)
        outside.push_back(fmt::format("porosity = {:.4g} (0.330 to 0.882)", e));
    if (!outside.empty())
        out.warning = fmt::format("Eisfeld & Schnitzlein (2001) evaluated outside its range: {}",
                                  fmt::join(outside, ", "));
    return out;
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
