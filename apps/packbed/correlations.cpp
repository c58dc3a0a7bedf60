// `packbed correlations`: the published correlations at an aspect ratio.
#include <memory>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "command.hpp"
#include "packbed/correlations.hpp"
#include "packbed/json_text.hpp"
#include "packbed/pipeline.hpp"

namespace packbed::cli {

namespace {

/// `packbed correlations`'s options: the library's request and --json.
struct CorrelationOptions {
    CorrelationsRequest request;
    bool json = false;
};

int run_correlations(const CorrelationOptions& o) {
    const Report report = correlations_report(o.request);
    const nlohmann::json& out = report.values;
    const auto& warnings = report.warnings;
    for (const auto& w : warnings)
        fmt::print(stderr, "packbed correlations: warning: {}\n", w);
    if (o.json) {
        fmt::print("{}", json_file_text(out, "the report"));
        return 0;
    }
    fmt::print("mean void fraction at a = {}:\n", o.request.aspect_ratio);
    for (const auto& c : mean_void_fraction_correlations()) {
        const auto v = c(o.request.aspect_ratio);
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
    app->add_option("-a,--aspect-ratio", o.request.aspect_ratio, "a = D/d")
        ->check(real_in(option_range::aspect_ratio));
    app->add_option("--profile-step", o.request.profile_step, "step of the radial profiles, in d")
        ->check(real_in(option_range::profile_step));
    app->add_option("--profile-to", o.request.profile_to,
                    "radial profiles from the wall to this, in d")
        ->check(real_in(option_range::profile_to));
    app->add_flag("--json", o.json, "print everything, profiles included, as JSON");
    return {app, [options] { return run_correlations(*options); }};
}

} // namespace packbed::cli
