// The reports of `packbed hydraulics` and `packbed correlations` (pipeline.hpp).
#include <cmath>
#include <filesystem>
#include <limits>
#include <optional>
#include <string>
#include <system_error>
#include <vector>

#include <fmt/format.h>

#include "packbed/correlations.hpp"
#include "packbed/error.hpp"
#include "packbed/files.hpp"
#include "packbed/lattice.hpp"
#include "packbed/limits.hpp"
#include "packbed/pipeline.hpp"
#include "packbed/read.hpp"

namespace packbed {

namespace {

namespace fs = std::filesystem;

/// What hydraulics takes from a bed's summary.json.
struct BedFacts {
    double porosity = 0.0;
    std::string porosity_from;
    /// the particles' diameter for Ergun's equation, in the bed's length unit: the spheres', a
    /// pellet's 6 V / S (surface_volume_diameter)
    std::optional<double> diameter;
    /// what the aspect ratio is on, in the bed's length unit: the spheres' diameter, a pellet's
    /// d_v (as generate --shape's -a and cfd-report's)
    std::optional<double> size;
    bool sauter_mean = false;     ///< the diameter is the sizes' Sauter mean d32
    std::string pellets;          ///< a bed of pellets: their shape's spec, else empty
    double pellet_diameter = 0.0; ///< a pellet's D (its spec's), for the check of the unit
    std::optional<double> container_radius; ///< likewise
    std::optional<Container> container;     ///< a box, an annulus or a periodic cell
    std::string shown;                      ///< the summary's path, printable
};

/// The porosity of a bed from its summary.json (or the directory holding it): a generated
/// bed's overall void fraction, or a lattice's exact porosity (the paper's choice for eq. (1));
/// and the spheres' diameter and container radius it records.
BedFacts bed_facts(const std::string& bed) {
    fs::path path(bed);
    std::error_code error;
    if (fs::is_directory(path, error))
        path /= "summary.json";
    BedSummary summary;
    try { // a regular file of bounded size, the porosity in (0, 1)
        summary = read_bed_summary(path);
    } catch (const InvalidInput& e) {
        throw InvalidInput(fmt::format("--bed {}", e.what()));
    }
    const std::string shown = printable(path.native());
    std::optional<Container> container;
    if (const auto& c = summary.container; c && !c->tube_diameter())
        container = c;
    if (!summary.porosity)
        throw InvalidInput(fmt::format("--bed {}: no lattice.porosity or void_fraction; give "
                                       "--porosity",
                                       shown));
    BedFacts facts{*summary.porosity,
                   fmt::format("{} of {}", summary.porosity_source, shown),
                   summary.diameter,
                   summary.diameter,
                   summary.sauter_mean,
                   "",
                   0.0,
                   summary.container_radius,
                   container,
                   shown};
    if (summary.shape) {
        const std::optional<PelletSpec> pellet = parse_pellet_shape(*summary.shape);
        if (!pellet)
            throw InvalidInput(fmt::format("--bed {}: shape '{}' is not allowed; allowed: {}",
                                           shown, printable(*summary.shape), allowed_shapes()));
        facts.pellets = pellet->text;
        facts.pellet_diameter = pellet->diameter;
        // Pellets of several sizes (--sizes): their mean 6 V / S needs every size, which the
        // summary does not hold.
        facts.diameter = facts.size = std::nullopt;
        if (!summary.size_range) {
            facts.diameter = surface_volume_diameter(*pellet);
            facts.size = pellet->volume_diameter;
        }
    }
    return facts;
}

/// \return the path of the first number of `value` that is not finite (nlohmann::json prints
/// them as null), or nothing.
std::string first_not_finite(const nlohmann::json& value, const std::string& path = "") {
    if (value.is_number_float())
        return std::isfinite(value.get<double>()) ? "" : path;
    if (value.is_object() || value.is_array()) {
        std::size_t index = 0;
        for (auto it = value.begin(); it != value.end(); ++it, ++index) {
            const std::string key = value.is_object() ? it.key() : std::to_string(index);
            if (std::string bad = first_not_finite(*it, path.empty() ? key : path + "." + key);
                !bad.empty())
                return bad;
        }
    }
    return "";
}

} // namespace

Report hydraulics_report(const HydraulicsRequest& o) {
    if (o.porosity > 0.0 && !o.bed.empty())
        throw InvalidInput(fmt::format("--porosity {} and --bed '{}' both given; allowed: one of "
                                       "them",
                                       o.porosity, o.bed));
    if (o.porosity <= 0.0 && o.bed.empty())
        throw InvalidInput("no porosity given; allowed: --porosity E (0 < E < 1) or --bed "
                           "SUMMARY.json");
    FluidAndParticles f = o.fluid;
    double aspect_ratio = o.aspect_ratio;
    std::string aspect_ratio_from = "given";
    const auto spec = parse_container(o.container);
    std::optional<Container> container;
    std::string container_from = fmt::format("--container {}", o.container);
    // A container from --bed is in the bed's length unit: a = D_h / the bed's size (a sphere's
    // diameter, a pellet's d_v), D_h in metres as the particle diameter's scale.
    std::optional<double> bed_diameter, bed_size;
    if (spec)
        container = spec;
    double e = o.porosity;
    std::string origin = "given";
    std::string diameter_from = o.diameter_given ? "given" : "the default";
    if (!o.bed.empty()) {
        // A bed's lengths are in the unit of its --diameter; hydraulics reads them as metres
        // unless --diameter is given (rather than a silent default of 1 mm).
        const BedFacts bed = bed_facts(o.bed);
        e = bed.porosity;
        origin = bed.porosity_from;
        if (!o.diameter_given && !bed.pellets.empty() && !bed.diameter)
            throw InvalidInput(fmt::format(
                "--bed {}: a bed of {} pellets of several sizes (--sizes), whose mean 6 V / S "
                "its summary does not hold; allowed: give --diameter in metres",
                bed.shown, bed.pellets));
        if (!o.diameter_given && !bed.pellets.empty() && bed.pellet_diameter == 1.0)
            throw InvalidInput(fmt::format(
                "--bed {}: shape {}, a pellet's D = 1 (lengths in pellet diameters, no unit); "
                "allowed: give --diameter in metres (a pellet's 6 V / S, Ergun's diameter)",
                bed.shown, bed.pellets));
        if (!o.diameter_given && bed.diameter) {
            if (*bed.diameter == 1.0) // generate's and lattice's default: no unit at all
                throw InvalidInput(fmt::format(
                    "--bed {}: diameter = 1, packbed's default (lengths in sphere diameters, "
                    "no unit); allowed: give --diameter in metres",
                    bed.shown));
            if (!(*bed.diameter >= limits::min_particle_diameter_m &&
                  *bed.diameter <= limits::max_particle_diameter_m))
                throw InvalidInput(fmt::format(
                    "--bed {}: diameter = {} is not allowed as metres; allowed: {:g} to {:g} m, "
                    "or give --diameter in metres",
                    bed.shown, *bed.diameter, limits::min_particle_diameter_m,
                    limits::max_particle_diameter_m));
            f.diameter = *bed.diameter;
            // Spheres of several sizes: their Sauter mean d32, the diameter of Ergun's equation
            // and of the correlations for mixtures (docs/sizes.md).
            diameter_from =
                bed.sauter_mean
                    ? fmt::format("the Sauter mean diameter d32 of the sizes of {}, read as "
                                  "metres (the diameter of Ergun's equation for mixtures)",
                                  bed.shown)
                : !bed.pellets.empty()
                    ? fmt::format("6 V / S of the {} pellets of {}, read as metres (the "
                                  "diameter of Ergun's equation for non-spheres)",
                                  bed.pellets, bed.shown)
                    : fmt::format("the diameter of {}, read as metres", bed.shown);
        }
        // The tube of a cylindrical bed gives the wall-corrected pressure drop.
        // An annulus or a periodic cell: its hydraulic diameter, or no wall.
        if (!o.aspect_ratio_given && !spec && bed.container && bed.diameter && bed.size) {
            container = bed.container;
            bed_diameter = bed.diameter;
            bed_size = bed.size;
            container_from = fmt::format("the {} of {}", bed.container->spec(), bed.shown);
        } else if (!o.aspect_ratio_given && !spec && bed.size && bed.container_radius) {
            const double a = 2.0 * *bed.container_radius / *bed.size;
            if (a > 1.0 && a <= limits::max_tube_aspect_ratio) {
                aspect_ratio = a;
                aspect_ratio_from =
                    fmt::format("2 container.radius / {} of {}",
                                bed.pellets.empty() ? "diameter" : "a pellet's d_v", bed.shown);
            }
        }
    }
    std::optional<double> hydraulic; // D_h = 4 A / P of a container other than a tube, metres
    std::string wall_correction;     // a container without a wall: why there is none
    const HydraulicDiameter dh = container ? container->hydraulic_diameter() : HydraulicDiameter{};
    if (const std::optional<double> tube = container ? container->tube_diameter() : std::nullopt) {
        // a = D / d, both in metres, once d is known (given, the default, or the bed's).
        aspect_ratio = *tube / f.diameter;
        if (!(aspect_ratio >= 1.0 && aspect_ratio <= limits::max_tube_aspect_ratio))
            throw InvalidInput(fmt::format(
                "--container {}: the tube's diameter over the particle diameter ({} m) is a = "
                "{:.6g}; allowed: a from 1 to {:g}",
                o.container, f.diameter, aspect_ratio, limits::max_tube_aspect_ratio));
        aspect_ratio_from = fmt::format("--container {} over the particle diameter", o.container);
    } else if (container && !dh.value) {
        aspect_ratio = 0.0;
        wall_correction =
            fmt::format("none: {} {} (Ergun, no wall correction)", container_from, dh.formula);
    } else if (container) {
        // Another container: a = D_h / d with the hydraulic diameter 4 A / P.
        hydraulic = dh.value;
        aspect_ratio = *hydraulic / bed_size.value_or(f.diameter);
        if (bed_diameter) // in metres, at the particle diameter used
            hydraulic = *hydraulic / *bed_diameter * f.diameter;
        const std::string_view formula = dh.formula;
        if (!(aspect_ratio >= 1.0 && aspect_ratio <= limits::max_tube_aspect_ratio))
            throw InvalidInput(fmt::format(
                "{}: the hydraulic diameter {} = {} m over the particle diameter ({} m) is a = "
                "{:.6g}; allowed: a from 1 to {:g}",
                container_from, formula, *hydraulic, f.diameter, aspect_ratio,
                limits::max_tube_aspect_ratio));
        aspect_ratio_from = fmt::format(
            "{}: the hydraulic diameter 4 A / P = {} = {} m over the particle diameter (exact "
            "for the wall term A_w, the wall-to-particle surface ratio; an assumption for B_w, "
            "fitted to tubes)",
            container_from, formula, *hydraulic);
    }
    const double ar = archimedes_number(f);
    const auto coefficients = fluidization_coefficients(e);
    const double re_c = critical_reynolds(ar, e);
    const double w = superficial_velocity(re_c, f);
    const double re_mf = wen_yu_reynolds(ar);
    const double u = o.velocity > 0.0 ? o.velocity : w;
    const double u_re = f.fluid_density * u * f.diameter / f.viscosity;
    const double u_mf = superficial_velocity(re_mf, f);
    const double ergun = ergun_pressure_gradient(e, u, f);
    const double k_carman_kozeny = carman_kozeny_permeability(e, f.diameter);
    const double k_ergun = ergun_permeability(e, f.diameter);
    nlohmann::json out;
    out["units"] = "SI: m, kg/m^3, Pa s, m/s, Pa/m, m^2";
    out["porosity"] = {{"value", e}, {"from", origin}};
    out["fluid_and_particles"] = {{"diameter_m", f.diameter},
                                  {"diameter_from", diameter_from},
                                  {"particle_density_kg_m3", f.particle_density},
                                  {"fluid_density_kg_m3", f.fluid_density},
                                  {"viscosity_Pa_s", f.viscosity},
                                  {"gravity_m_s2", f.gravity}};
    out["archimedes"] = ar;
    out["equation_1"] = {{"source", "Tsayger (2013) eq. (1), Goroshko, Rosenbaum & Todes (1958)"},
                         {"formula", "Ar = 150 (1-e)/e^3 Re + 1.75/e^3 Re^2"},
                         {"linear", coefficients.linear},
                         {"quadratic", coefficients.quadratic},
                         {"critical_reynolds", re_c},
                         {"superficial_velocity_m_s", w}};
    out["wen_yu_1966"] = {{"reynolds_mf", re_mf}, {"velocity_mf_m_s", u_mf}};
    out["pressure_gradient"] = {{"velocity_m_s", u}, {"reynolds", u_re}, {"ergun_Pa_m", ergun}};
    std::string warning;
    if (aspect_ratio > 0.0) {
        const CorrelationValue es = eisfeld_schnitzlein_pressure_gradient(e, u, aspect_ratio, f);
        out["pressure_gradient"]["eisfeld_schnitzlein_Pa_m"] = es.value;
        out["pressure_gradient"]["aspect_ratio"] = aspect_ratio;
        out["pressure_gradient"]["aspect_ratio_from"] = aspect_ratio_from;
        out["pressure_gradient"]["eisfeld_schnitzlein_in_range"] = es.warning.empty();
        if (hydraulic)
            out["pressure_gradient"]["hydraulic_diameter_m"] = *hydraulic;
        warning = es.warning;
    }
    if (!wall_correction.empty())
        out["pressure_gradient"]["wall_correction"] = wall_correction;
    // The band of published correlations at the same point (pressure_drop_band; none at rest,
    // a velocity that underflowed to 0).
    out["pressure_gradient"]["band"] = nlohmann::json::array();
    const double a = aspect_ratio > 0.0 ? aspect_ratio : std::numeric_limits<double>::infinity();
    for (const PressureDropBandValue& b :
         u > 0.0 ? pressure_drop_band(e, u, a, f) : std::vector<PressureDropBandValue>{})
        out["pressure_gradient"]["band"].push_back(
            {{"name", b.correlation->name},
             {"label", b.correlation->label},
             {"Pa_m", b.gradient.value},
             {"outside_range",
              b.gradient.warning.empty() ? nlohmann::json() : nlohmann::json(b.gradient.warning)}});
    out["permeability_m2"] = {{"carman_kozeny", k_carman_kozeny}, {"ergun", k_ergun}};
    // Eqs. (2)-(4): eq. (1) at the exact porosities of the three regular packings.
    const double hexagonal = fluidization_coefficients(unit_cell(LatticeType::fcc).porosity).linear;
    for (const auto& [name, type] : {std::pair{"hexagonal (fcc, hcp)", LatticeType::fcc},
                                     {"cubic (sc)", LatticeType::sc},
                                     {"tetrahedral (diamond)", LatticeType::diamond}}) {
        const double porosity = unit_cell(type).porosity;
        const auto c = fluidization_coefficients(porosity);
        out["regular_packings"].push_back({{"packing", name},
                                           {"porosity", porosity},
                                           {"linear", c.linear},
                                           {"quadratic", c.quadratic},
                                           {"permeability_over_hexagonal", hexagonal / c.linear},
                                           {"critical_reynolds", critical_reynolds(ar, porosity)}});
    }
    // The library refuses results that are not finite; this holds for what is computed here.
    if (const std::string bad = first_not_finite(out); !bad.empty())
        throw InvalidInput(fmt::format(
            "{} is not a finite number for porosity = {}, diameter = {}, particle-density = {}, "
            "fluid-density = {}, viscosity = {}, gravity = {}, velocity = {}; allowed: inputs "
            "that give one",
            bad, e, f.diameter, f.particle_density, f.fluid_density, f.viscosity, f.gravity, u));
    Report report{std::move(out), {}};
    if (!warning.empty())
        report.warnings.push_back(warning);
    return report;
}

Report correlations_report(const CorrelationsRequest& request) {
    const double a = request.aspect_ratio, profile_step = request.profile_step,
                 profile_to = request.profile_to;
    // A tube's radial profile ends at its axis, a / 2 from the wall.
    const double to = std::min(profile_to, 0.5 * a);
    if (to / profile_step > max_profile_steps)
        throw InvalidInput(fmt::format(
            "--profile-step {} to x = {:g} d ({}) is not allowed: {:.6g} steps; allowed: at "
            "most {:g} steps",
            profile_step, to, to < profile_to ? "the axis at a / 2" : "--profile-to",
            to / profile_step, max_profile_steps));
    const auto steps = static_cast<std::size_t>(std::floor(to / profile_step + 1e-9));
    nlohmann::json out;
    out["aspect_ratio"] = a;
    std::vector<std::string> warnings;
    for (const auto& c : mean_void_fraction_correlations()) {
        const auto v = c(a);
        out["mean_void_fraction"][std::string(c.name)] = {
            {"value", v.value},
            {"formula", c.formula},
            {"source", c.source},
            {"label", c.label},
            {"validity", validity_range(c.a_low, c.a_high)},
            {"in_range", v.warning.empty()}};
        if (!v.warning.empty())
            warnings.push_back(v.warning);
    }
    for (const auto& c : radial_void_fraction_correlations()) {
        auto& profile = out["radial_void_fraction"][std::string(c.name)];
        profile["formula"] = c.formula;
        profile["source"] = c.source;
        profile["label"] = c.label;
        profile["validity"] = validity_range(c.a_low, c.a_high);
        std::string warning;
        for (std::size_t k = 0; k <= steps; ++k) {
            const double z = static_cast<double>(k) * profile_step;
            const auto v = c(z, a);
            profile["x_from_wall_d"].push_back(z);
            profile["void_fraction"].push_back(v.value);
            warning = v.warning;
        }
        profile["in_range"] = warning.empty();
        if (!warning.empty())
            warnings.push_back(warning);
    }
    return {std::move(out), std::move(warnings)};
}

} // namespace packbed
