#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <string>
#include <string_view>

#include <fmt/format.h>
#include <fmt/ranges.h>
#include <nlohmann/json.hpp>
#include <omp.h>

#include "command.hpp"
#include "packbed/error.hpp"
#include "packbed/files.hpp"
#include "packbed/limits.hpp"
#include "packbed/read.hpp"
#include "packbed/text.hpp"

namespace packbed::cli {

CLI::Validator real_in(const NumberRange& range) {
    const std::string allowed = range.allowed();
    return CLI::Validator(
        [=](std::string& text) -> std::string {
            const auto value = parse_finite(text);
            if (!value)
                return fmt::format("'{}' is not allowed; allowed: {}", printable(text), allowed);
            if (!range.holds(*value))
                return fmt::format("{} is not allowed; allowed: {}", text, allowed);
            return {};
        },
        allowed);
}

CLI::Validator real_in(double low, double high, bool low_open, bool high_open) {
    return real_in(NumberRange{low, high, low_open, high_open});
}

CLI::Validator whole_in(const WholeRange& range) {
    return CLI::Validator([=](std::string& text) { return whole_problem(text, range); },
                          range.allowed());
}

CLI::Validator whole_in(unsigned long long low, unsigned long long high) {
    return whole_in(WholeRange{low, high});
}

CLI::Validator one_of(std::vector<std::string> names) {
    std::string allowed;
    for (const std::string& name : names)
        allowed += (allowed.empty() ? "" : ", ") + name;
    return CLI::Validator(
        [names, allowed](std::string& text) -> std::string {
            if (std::find(names.begin(), names.end(), text) != names.end())
                return {};
            return fmt::format("'{}' is not allowed; allowed: {}", printable(text.substr(0, 80)),
                               allowed);
        },
        "{" + fmt::format("{}", fmt::join(names, ",")) + "}");
}

CLI::Validator path_text() {
    return CLI::Validator(
        [](std::string& text) -> std::string {
            const std::string problem = path_problem(text);
            if (problem.empty())
                return {};
            return fmt::format("'{}' is not allowed ({}); allowed: a path of at most 4095 bytes "
                               "without control characters (newline, tab, ...)",
                               printable(text.substr(0, 200)), problem);
        },
        "PATH");
}

void add_output_directory(CLI::App& app, std::string& out, bool& force,
                          const std::string& default_text) {
    app.add_option("-o,--out", out,
                   "output directory: a new or empty one (created), or an existing one with "
                   "--force" +
                       (default_text.empty() ? std::string() : "; default: " + default_text))
        ->check(path_text());
    app.add_flag("--force", force,
                 "replace a non-empty output directory whole (its old files are deleted)");
}

namespace {

/// --frame: a whole number other than 0 (1 the first frame, -1 the last).
CLI::Validator frame_number() {
    const std::string allowed =
        "a whole number other than 0: 1 the first frame, 2 the second, ..., -1 the last, -2 the "
        "one before";
    return CLI::Validator(
        [allowed](std::string& text) -> std::string {
            const auto value = parse_whole<long long>(text);
            if (!value || *value == 0 || has_leading_zero(text))
                return fmt::format("'{}' is not allowed; allowed: {}",
                                   printable(text.substr(0, 80)), allowed);
            return {};
        },
        "N");
}

/// --axis: X,Y, two numbers within limits::max_length.
CLI::Validator axis_position() {
    const std::string allowed = fmt::format("X,Y: two numbers from {:g} to {:g} (file units)",
                                            -limits::max_length, limits::max_length);
    return CLI::Validator(
        [allowed](std::string& text) -> std::string {
            const auto v = parse_finite_list(text);
            if (!v || v->size() != 2 || !(std::abs((*v)[0]) <= limits::max_length) ||
                !(std::abs((*v)[1]) <= limits::max_length))
                return fmt::format("'{}' is not allowed; allowed: {}",
                                   printable(text.substr(0, 80)), allowed);
            return {};
        },
        "X,Y");
}

} // namespace

void InputPlacement::apply(ReadOptions& read) const {
    read.frame = frame;
    if (const auto xy = parse_finite_list(axis); xy && xy->size() == 2)
        read.axis = {(*xy)[0], (*xy)[1]};
    read.floor = floor;
}

void add_threads_option(CLI::App& app, unsigned long long& threads) {
    app.add_option("-j,--threads", threads,
                   "this many threads (results do not depend on it); default: every core")
        ->check(whole_in(option_range::threads));
}

CLI::Option* add_input_placement(CLI::App& app, InputPlacement& p) {
    CLI::Option* frame = app.add_option("--frame", p.frame,
                                        "which frame of a file of several (XYZ, dumps): 1 the "
                                        "first, -1 the last, -2 the one before")
                             ->check(frame_number());
    app.add_option("--axis", p.axis,
                   "X,Y: the container's axis, subtracted from every centre (file units); "
                   "default 0,0")
        ->check(axis_position());
    app.add_option("--floor", p.floor,
                   "the container's floor z, subtracted from every centre (file units)")
        ->check(real_in(option_range::floor_height));
    return frame;
}

CLI::Option* add_container_option(CLI::App& app, std::string& text, const std::string& meaning,
                                  const std::vector<std::string_view>& shapes) {
    const std::string allowed = allowed_containers(shapes);
    std::vector<std::string_view> names;
    for (const auto s : shapes)
        names.push_back(s);
    const std::string help = fmt::format("the container: {} ({})", fmt::join(names, ", "), meaning);
    return app.add_option("--container", text, help)
        ->check(CLI::Validator(
            [allowed, shapes](std::string& value) -> std::string {
                if (const auto spec = parse_container(value);
                    spec && std::find(shapes.begin(), shapes.end(), spec->name()) != shapes.end())
                    return {};
                return fmt::format("'{}' is not allowed; allowed: {}",
                                   printable(value.substr(0, 80)), allowed);
            },
            "SPEC"));
}

} // namespace packbed::cli
