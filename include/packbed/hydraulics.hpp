// Hydraulics of a bed of mono-sized spheres: the onset of fluidization from the Ergun-type
// relation eq. (1) of Tsayger (2013) (Goroshko, Rosenbaum & Todes 1958), the fluid velocity it
// gives as the initial condition of a DEM run, Ergun's and Eisfeld & Schnitzlein's pressure
// drops, Wen & Yu's minimum fluidization and permeabilities. SI units throughout.
#pragma once

#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "packbed/container.hpp"
#include "packbed/correlations.hpp"

namespace packbed {

/// The particles and the fluid. Plain value type, SI units; the ranges are limits.hpp's.
struct FluidAndParticles {
    double diameter = 1e-3;         ///< particle diameter d, m, 1e-9 to 10
    double particle_density = 2500; ///< kg/m^3, > fluid density (else nothing fluidizes), <= 3e4
    double fluid_density = 1.2;     ///< kg/m^3, 1e-3 to 3e4
    double viscosity = 1.8e-5;      ///< dynamic viscosity mu, Pa s, 1e-7 to 1e4
    double gravity = 9.80665;       ///< g, m/s^2, 1e-6 to 1e6

    /// \throws InvalidInput naming the value and what is allowed
    void validate() const;
};

// Every function below throws InvalidInput for an input outside its range, and for a result
// that is not a finite number (an overflow), naming the inputs it was computed from.

/// Archimedes number \f$Ar = g d^3 \rho (\rho_p - \rho) / \mu^2\f$ (Tsayger 2013).
double archimedes_number(const FluidAndParticles& f);

/// The two coefficients of eq. (1), \f$Ar = A\,Re + B\,Re^2\f$, at porosity e:
/// \f$A = 150 (1 - e) / e^3\f$, \f$B = 1.75 / e^3\f$.
struct FluidizationCoefficients {
    double linear = 0.0;    ///< A
    double quadratic = 0.0; ///< B
};
/// \param porosity e in (0, 1) \throws InvalidInput outside, or when e^3 underflows (e < 1e-103)
FluidizationCoefficients fluidization_coefficients(double porosity);

/// The critical Reynolds number of eq. (1), the positive root of \f$B Re^2 + A Re - Ar = 0\f$,
/// written \f$Re_c = 2 Ar / (A + \sqrt{A^2 + 4 B Ar})\f$ so that it loses no digits at small
/// Ar (where \f$Re_c \to Ar/A\f$) nor overflows at large Ar (\f$\to \sqrt{Ar/B}\f$).
/// \param archimedes Ar >= 0 \param porosity e in (0, 1)
double critical_reynolds(double archimedes, double porosity);

/// Superficial velocity from a particle Reynolds number: \f$w = Re\,\mu / (\rho d)\f$, m/s.
double superficial_velocity(double reynolds, const FluidAndParticles& f);

/// Ergun (1952): \f$\Delta P / L = 150 \mu u (1-e)^2 / (e^3 d^2) + 1.75 \rho u^2 (1-e) /
/// (e^3 d)\f$, Pa/m, at superficial velocity u (m/s, >= 0).
double ergun_pressure_gradient(double porosity, double velocity, const FluidAndParticles& f);
/// The same for a fluid of density rho (kg/m^3) and viscosity mu (Pa s) through spheres of
/// diameter d (m), with no particle density or gravity to check: a pressure drop has neither.
double ergun_pressure_gradient(double porosity, double velocity, double diameter, double rho,
                               double mu);

/// Eisfeld & Schnitzlein (2001), spheres, the wall effect of a tube of aspect ratio a = D/d:
/// \f$\psi = \Delta P\,d / (L \rho u^2) = K_1 A_w^2 (1-e)^2 / (Re\,e^3) + (A_w/B_w)(1-e)/e^3\f$,
/// \f$A_w = 1 + 2/(3 a (1-e))\f$, \f$B_w = (k_1 a^{-2} + k_2)^2\f$, \f$K_1 = 154\f$,
/// \f$k_1 = 1.15\f$, \f$k_2 = 0.87\f$, \f$Re = \rho u d / \mu\f$. Valid for
/// \f$0.01 \le Re \le 17635\f$, \f$1.624 \le a \le 250\f$, \f$0.330 \le e \le 0.882\f$: outside,
/// the value comes with a warning (the entry `eisfeld-schnitzlein-2001` of
/// pressure_drop_correlations()). \return Pa/m (velocity > 0, aspect ratio 1 to 1e4)
CorrelationValue eisfeld_schnitzlein_pressure_gradient(double porosity, double velocity,
                                                       double aspect_ratio,
                                                       const FluidAndParticles& f);

/// A pressure-drop correlation for beds of spheres, written as Erdim, Akgiray & Demir (2015)
/// compare them: the normalised gradient \f$f_v = (\Delta P / L)\, d^2 e^3 / (\mu u
/// (1-e)^2)\f$ as a function of the porosity e, the modified Reynolds number \f$Re_m = \rho u
/// d / (\mu (1-e))\f$ and the aspect ratio a = D/d (infinite: no wall), so that \f$\Delta P /
/// L = f_v \mu u (1-e)^2 / (d^2 e^3)\f$; in the creeping limit f_v is the correlation's
/// constant (Ergun's 150, Carman's 180). Each entry carries its source, formula and validity
/// ranges as the source states them (`modified`: its Reynolds range is on Re_m, else on
/// \f$Re_p = \rho u d / \mu\f$).
struct PressureDropCorrelation {
    std::string_view name;    ///< registry key, e.g. "kta-1981"
    std::string_view label;   ///< what people call it, e.g. "KTA 3102.3 (1981)"
    std::string_view source;  ///< the publication
    std::string_view formula; ///< f_v as plain text
    bool wall = false;        ///< whether a enters the formula
    bool modified = true;     ///< the Reynolds range is on Re_m (else on Re_p)
    double re_low, re_high;   ///< validity range of the Reynolds number
    double e_low, e_high;     ///< ... of the porosity
    double a_low, a_high;     ///< ... of a (of the source's data for a formula without a)
    double (*f_v)(double porosity, double re_m, double aspect_ratio);
    /// \return the pressure gradient, Pa/m, at porosity e, superficial velocity u (m/s, > 0) and
    /// aspect ratio a (>= 1, or infinite for a bed with no wall), with a warning naming what lies
    /// outside the ranges (a is not checked when infinite and the formula has no wall term).
    /// \throws InvalidInput for inputs outside their domains or a result that is not finite
    CorrelationValue gradient(double porosity, double velocity, double aspect_ratio,
                              const FluidAndParticles& f) const;
};

/// The pressure-drop correlations a CFD result is set against (Ergun 1952, Carman 1937, KTA
/// 1981, Erdim et al. 2015, Harrison et al. 2013, Eisfeld & Schnitzlein 2001), filled in one
/// place; how each was checked is in docs/sources.md.
const std::vector<PressureDropCorrelation>& pressure_drop_correlations();

/// One correlation of the band and its value.
struct PressureDropBandValue {
    const PressureDropCorrelation* correlation = nullptr;
    CorrelationValue gradient; ///< Pa/m, with the warning outside its ranges
};
/// Every correlation of pressure_drop_correlations() at porosity e, superficial velocity u and
/// aspect ratio a; with no wall (a infinite), those without a wall term. \throws InvalidInput
/// as PressureDropCorrelation::gradient
std::vector<PressureDropBandValue> pressure_drop_band(double porosity, double velocity,
                                                      double aspect_ratio,
                                                      const FluidAndParticles& f);

/// The hydraulic diameter of a container's cross-section, \f$D_h = 4 A / P\f$ (A its area, P
/// its wetted perimeter): a cylinder's D; an annulus' \f$4 \pi (R^2 - R_i^2) / (2 \pi (R +
/// R_i)) = D - D_I\f$; a box's \f$2 L_x L_y / (L_x + L_y)\f$; nothing for a periodic cell
/// (no wall). Eisfeld & Schnitzlein's \f$A_w = 1 + 2/(3 a (1-e))\f$ comes from the ratio of
/// the wall's surface to the particles' (Mehta & Hawley 1969), which \f$a = D_h / d\f$ gives
/// exactly for any cross-section; their \f$B_w\f$ was fitted to tubes, so using \f$a = D_h /
/// d\f$ there for an annulus or a box is an assumption. \return length, as the container's
std::optional<double> hydraulic_diameter(const Container& container);

/// Wen & Yu (1966): \f$Re_{mf} = \sqrt{33.7^2 + 0.0408\,Ar} - 33.7\f$, computed as
/// \f$0.0408\,Ar / (\sqrt{33.7^2 + 0.0408\,Ar} + 33.7)\f$ (no cancellation at small Ar).
double wen_yu_reynolds(double archimedes);

/// Permeabilities, m^2: Carman-Kozeny \f$k = d^2 e^3 / (180 (1-e)^2)\f$ and the one of Ergun's
/// linear term, \f$k = d^2 e^3 / (150 (1-e)^2)\f$.
double carman_kozeny_permeability(double porosity, double diameter);
double ergun_permeability(double porosity, double diameter);

/// Stokes flow through a simple cubic array of spheres along a cube axis: Zick & Homsy (1982,
/// J. Fluid Mech. 115, 13), Table 2, the dimensionless drag \f$K = F / (6 \pi \mu a U)\f$ (F
/// the whole force on a sphere, the mean pressure gradient's part included, a its radius, U
/// the superficial velocity: the mean over the whole cell) at the solid fractions 0.027, 0.064,
/// 0.125, 0.216, 0.343, 0.45 and 0.5236 (touching): 2.008, 2.810, 4.292, 7.442, 15.4, 28.1,
/// 42.1. \return the entry (its solid fraction, K) within 1e-3 of `solid_fraction` (a
/// touching array whose contacts are flattened by caps 0.02 d apart holds 0.5226), else nothing
/// (no interpolation: the table is what was computed).
std::optional<std::pair<double, double>> zick_homsy_simple_cubic(double solid_fraction);

/// Stokes flow through random arrays of equal spheres: van der Hoef, Beetstra & Kuipers (2005,
/// J. Fluid Mech. 528, 233), eq. (9), the drag over Stokes's for the superficial velocity,
/// \f$F = 10 \phi / (1 - \phi)^2 + (1 - \phi)^2 (1 + 1.5 \sqrt\phi)\f$ with \f$F = F_d / (3 \pi
/// \mu d U_s)\f$ and F_d the fluid's force on a sphere without the mean pressure gradient's
/// part: F = (1 - phi) K in Zick & Homsy's terms. For 0 < phi < 1.
double van_der_hoef_drag(double solid_fraction);

} // namespace packbed
