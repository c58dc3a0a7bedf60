// `packbed correlations`: the published correlations at an aspect ratio.
#include <memory>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "command.hpp"
#include "packbed/correlations.hpp"

namespace packbed::cli {

namespace {

struct CorrelationOptions {
    double aspect_ratio = 5.0;
    double profile_step = 0.01;
    double profile_to = 5.0;
    bool json = false;
};

int run_correlations(const CorrelationOptions& o) {
    nlohmann::json out;
    out["aspect_ratio"] = o.aspect_ratio;
    std::vector<std::string> warnings;
    for (const auto& c : mean_void_fraction_correlations()) {
        const auto v = c(o.aspect_ratio);
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
        for (double z = 0.0; z <= o.profile_to + 1e-12; z += o.profile_step) {
            const auto v = c(z, o.aspect_ratio);
            profile["x_from_wall_d"].push_back(z);
            profile["void_fraction"].push_back(v.value);
            warning = v.warning;
        }
        profile["in_range"] = warning.empty();
        if (!warning.empty())
            warnings.push_back(warning);
    }
    for (const auto& w : warnings)
        fmt::print(stderr, "packbed correlations: warning: {}\n", w);
    if (o.json) {
        fmt::print("{}\n", out.dump(2));
        return 0;
    }
    fmt::print("mean void fraction at a = {}:\n", o.aspect_ratio);
    for (const auto& c : mean_void_fraction_correlations()) {
        const auto v = c(o.aspect_ratio);
        // A value outside (0, 1) is not printed as if it were one; the warning above says why.
        const std::string value =
            v.value > 0.0 && v.value < 1.0 ? fmt::format("{:.4f}", v.value) : "  --  ";
        fmt::print("  {:<26} {}  {}{}\n", c.label, value, validity_range(c.a_low, c.a_high),
                   v.warning.empty() ? "" : " (see the warning)");
    }
    fmt::print("formulas and publications: packbed correlations --json\n");
    return 0;
}

} // namespace

Command register_correlations(CLI::App& parent) {
    auto options = std::make_shared<CorrelationOptions>();
    auto& o = *options;
    CLI::App* app = parent.add_subcommand(
        "correlations", "Evaluate the published void-fraction correlations at an aspect ratio");
    app->option_defaults()->always_capture_default();
    app->fallthrough();
    app->add_option("-a,--aspect-ratio", o.aspect_ratio, "a = D/d")
        ->check(real_in(1.0, 1e4, false, false));
    app->add_option("--profile-step", o.profile_step, "step of the radial profiles, in d")
        ->check(real_in(1e-4, 1.0, false, false));
    app->add_option("--profile-to", o.profile_to, "radial profiles from the wall to this, in d")
        ->check(real_in(0.0, 1e3, false, false));
    app->add_flag("--json", o.json, "print everything, profiles included, as JSON");
    return {app, [options] { return run_correlations(*options); }};
}

} // namespace packbed::cli
