// `packbed hydraulics`: the fluid velocity that starts a DEM run of a fluidized bed (Tsayger
// 2013, eq. (1)), pressure drops, minimum fluidization and permeability, for a porosity given
// or read from a bed's summary.json.
#include <memory>
#include <string>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "command.hpp"
#include "packbed/json_text.hpp"
#include "packbed/limits.hpp"
#include "packbed/pipeline.hpp"

namespace packbed::cli {

namespace {

/// `packbed hydraulics`'s options, as the library's request.
using HydraulicsOptions = HydraulicsRequest;

int run_hydraulics(const HydraulicsOptions& o, bool json) {
    const Report report = hydraulics_report(o);
    const nlohmann::json& out = report.values;
    for (const auto& w : report.warnings)
        fmt::print(stderr, "packbed hydraulics: warning: {}\n", w);
    if (json) {
        fmt::print("{}", json_file_text(out, "the report"));
        return 0;
    }
    const auto& fluid = out["fluid_and_particles"];
    const auto& eq1 = out["equation_1"];
    const auto& drop = out["pressure_gradient"];
    fmt::print("porosity e = {:.5f} ({})\n", out["porosity"]["value"].get<double>(),
               out["porosity"]["from"].get<std::string>());
    fmt::print("particle diameter d = {:.6g} m ({})\n", fluid["diameter_m"].get<double>(),
               fluid["diameter_from"].get<std::string>());
    fmt::print("Archimedes number Ar = {:.6g}\n", out["archimedes"].get<double>());
    fmt::print("eq. (1) at e: Ar = {:.6g} Re + {:.6g} Re^2\n", eq1["linear"].get<double>(),
               eq1["quadratic"].get<double>());
    fmt::print("critical Re = {:.6g}; superficial velocity w = {:.6g} m/s (the initial fluid "
               "velocity for DEM)\n",
               eq1["critical_reynolds"].get<double>(),
               eq1["superficial_velocity_m_s"].get<double>());
    fmt::print("Wen & Yu (1966): Re_mf = {:.6g}, u_mf = {:.6g} m/s\n",
               out["wen_yu_1966"]["reynolds_mf"].get<double>(),
               out["wen_yu_1966"]["velocity_mf_m_s"].get<double>());
    fmt::print("at u = {:.6g} m/s (Re = {:.6g}): Ergun {:.6g} Pa/m",
               drop["velocity_m_s"].get<double>(), drop["reynolds"].get<double>(),
               drop["ergun_Pa_m"].get<double>());
    if (drop.contains("aspect_ratio"))
        fmt::print(", Eisfeld & Schnitzlein (a = {:.6g}) {:.6g} Pa/m",
                   drop["aspect_ratio"].get<double>(),
                   drop["eisfeld_schnitzlein_Pa_m"].get<double>());
    if (drop.contains("hydraulic_diameter_m"))
        fmt::print("\nwall correction: a = {}", drop["aspect_ratio_from"].get<std::string>());
    if (drop.contains("wall_correction"))
        fmt::print("\nwall correction: {}", drop["wall_correction"].get<std::string>());
    fmt::print("\nthe band of pressure-drop correlations at u (docs/hydraulics.md; * outside its "
               "stated range, --json says which):");
    for (const auto& b : drop["band"])
        fmt::print("\n  {:<30} {:>12.6g} Pa/m{}", b["label"].get<std::string>(),
                   b["Pa_m"].get<double>(), b["outside_range"].is_null() ? "" : " *");
    fmt::print("\npermeability: Carman-Kozeny {:.6g} m^2, Ergun {:.6g} m^2\n",
               out["permeability_m2"]["carman_kozeny"].get<double>(),
               out["permeability_m2"]["ergun"].get<double>());
    fmt::print("\nregular packings, eq. (1) at their exact porosities (Tsayger's eqs. 2-4):\n");
    fmt::print("{:<22} {:>9} {:>10} {:>9} {:>13} {:>12}\n", "packing", "porosity", "A", "B",
               "permeability", "critical Re");
    for (const auto& row : out["regular_packings"])
        fmt::print("{:<22} {:>9.5f} {:>10.6g} {:>9.5g} {:>13.4g} {:>12.6g}\n",
                   row["packing"].get<std::string>(), row["porosity"].get<double>(),
                   row["linear"].get<double>(), row["quadratic"].get<double>(),
                   row["permeability_over_hexagonal"].get<double>(),
                   row["critical_reynolds"].get<double>());
    return 0;
}

} // namespace

Command register_hydraulics(CLI::App& parent) {
    auto options = std::make_shared<HydraulicsOptions>();
    auto json = std::make_shared<bool>(false);
    auto& o = *options;
    CLI::App* app = parent.add_subcommand(
        "hydraulics", "Onset of fluidization (Tsayger 2013, eq. 1) and the fluid velocity for a "
                      "DEM start, pressure drops, Wen & Yu, permeability; SI units");
    app->option_defaults()->always_capture_default();
    // Physical ranges (limits.hpp): nanoparticles to boulders, gases to liquid metals,
    // microgravity to centrifuges.
    app->add_option("-e,--porosity", o.porosity,
                    "bed porosity (void fraction); one of --porosity and --bed is needed")
        ->check(real_in(option_range::porosity));
    app->add_option("--bed", o.bed,
                    "a bed's summary.json (or its directory): a lattice's exact porosity or a "
                    "generated bed's void fraction; also its diameter, read as metres, unless "
                    "--diameter, and a cylinder's aspect ratio unless --aspect-ratio")
        ->check(path_text());
    app->add_option("-d,--diameter", o.fluid.diameter, "particle diameter, m (1 nm to 10 m)")
        ->check(real_in(option_range::diameter_m));
    app->add_option("--particle-density", o.fluid.particle_density,
                    "kg/m^3, above the fluid's (aerogels to tungsten)")
        ->check(real_in(option_range::density_kg_m3));
    app->add_option("--fluid-density", o.fluid.fluid_density,
                    "kg/m^3 (default: water, 20 C; gases at low pressure to mercury)")
        ->check(real_in(option_range::density_kg_m3));
    app->add_option("--viscosity", o.fluid.viscosity,
                    "dynamic viscosity, Pa s (default: water; gases to heavy oils)")
        ->check(real_in(option_range::viscosity_pa_s));
    app->add_option("-g,--gravity", o.fluid.gravity, "m/s^2 (microgravity to centrifuges)")
        ->check(real_in(option_range::gravity_m_s2));
    app->add_option("-u,--velocity", o.velocity,
                    "superficial velocity for the pressure drops, m/s (default: the critical one)")
        ->check(real_in(option_range::velocity_m_s));
    CLI::Option* aspect =
        app->add_option("-a,--aspect-ratio", o.aspect_ratio,
                        "tube over particle diameter: adds Eisfeld & Schnitzlein's wall-corrected "
                        "pressure drop (shorthand of --container)")
            ->check(real_in(option_range::tube_aspect_ratio));
    add_container_option(*app, o.container,
                         fmt::format("metres: a = D_h / d with the hydraulic diameter D_h = "
                                     "4 A / P ({}); instead of --aspect-ratio",
                                     hydraulic_formulas()))
        ->excludes(aspect);
    app->add_flag("--json", *json, "print everything as JSON");
    app->fallthrough();
    app->footer("Exit status: 0 success, 2 bad input (e.g. a particle lighter than the fluid).");
    return {app, [options, json, app] {
                options->diameter_given = app->count("--diameter") > 0;
                options->aspect_ratio_given = app->count("--aspect-ratio") > 0;
                return run_hydraulics(*options, *json);
            }};
}

} // namespace packbed::cli
