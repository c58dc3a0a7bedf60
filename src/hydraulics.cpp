#include "packbed/hydraulics.hpp"

#include <cmath>

#include <fmt/format.h>

#include "packbed/error.hpp"
#include "require.hpp"

namespace packbed {

namespace {

using detail::require;

void require_porosity(double e) {
    require(std::isfinite(e) && e > 0.0 && e < 1.0, "porosity", e, "0 < porosity < 1");
}

} // namespace

void FluidAndParticles::validate() const {
    auto positive = [](double v) { return std::isfinite(v) && v > 0.0; };
    require(positive(diameter), "diameter", diameter, "a length > 0 (m)");
    require(positive(fluid_density), "fluid-density", fluid_density, "> 0 (kg/m^3)");
    require(positive(viscosity), "viscosity", viscosity, "> 0 (Pa s)");
    require(positive(gravity), "gravity", gravity, "> 0 (m/s^2)");
    require(std::isfinite(particle_density) && particle_density > fluid_density, "particle-density",
            particle_density,
            fmt::format("> the fluid density ({} kg/m^3): a particle lighter than the fluid "
                        "does not settle or fluidize",
                        fluid_density));
}

double archimedes_number(const FluidAndParticles& f) {
    f.validate();
    return f.gravity * f.diameter * f.diameter * f.diameter * f.fluid_density *
           (f.particle_density - f.fluid_density) / (f.viscosity * f.viscosity);
}

FluidizationCoefficients fluidization_coefficients(double e) {
    require_porosity(e);
    const double e3 = e * e * e;
    return {150.0 * (1.0 - e) / e3, 1.75 / e3};
}

double critical_reynolds(double archimedes, double porosity) {
    require(std::isfinite(archimedes) && archimedes >= 0.0, "Ar", archimedes, ">= 0");
    const auto [a, b] = fluidization_coefficients(porosity);
    // sqrt(A^2 + 4 B Ar) without overflow for huge Ar: A hypot of A and 2 sqrt(B Ar).
    return 2.0 * archimedes / (a + std::hypot(a, 2.0 * std::sqrt(b * archimedes)));
}

double superficial_velocity(double reynolds, const FluidAndParticles& f) {
    f.validate();
    return reynolds * f.viscosity / (f.fluid_density * f.diameter);
}

double ergun_pressure_gradient(double e, double u, const FluidAndParticles& f) {
    require_porosity(e);
    require(std::isfinite(u) && u >= 0.0, "velocity", u, ">= 0 (m/s)");
    f.validate();
    const double e3 = e * e * e, d = f.diameter;
    return 150.0 * f.viscosity * u * (1.0 - e) * (1.0 - e) / (e3 * d * d) +
           1.75 * f.fluid_density * u * u * (1.0 - e) / (e3 * d);
}

CorrelationValue eisfeld_schnitzlein_pressure_gradient(double e, double u, double a,
                                                       const FluidAndParticles& f) {
    require_porosity(e);
    require(std::isfinite(u) && u > 0.0, "velocity", u, "> 0 (m/s)");
    require(std::isfinite(a) && a >= 1.0, "aspect-ratio", a, ">= 1");
    f.validate();
    const double re = f.fluid_density * u * f.diameter / f.viscosity;
    const double aw = 1.0 + 2.0 / (3.0 * a * (1.0 - e));
    const double bw = std::pow(1.15 / (a * a) + 0.87, 2);
    const double e3 = e * e * e;
    const double psi =
        154.0 * aw * aw * (1.0 - e) * (1.0 - e) / (re * e3) + aw / bw * (1.0 - e) / e3;
    CorrelationValue out{psi * f.fluid_density * u * u / f.diameter, {}};
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
    return d * d * e * e * e / (180.0 * (1.0 - e) * (1.0 - e));
}

double ergun_permeability(double e, double d) {
    require_porosity(e);
    return d * d * e * e * e / (150.0 * (1.0 - e) * (1.0 - e));
}

} // namespace packbed
