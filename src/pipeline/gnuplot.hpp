// Drawing plots with gnuplot, for the pipeline's stages (plots.cpp): the analysis' profiles
// and cfd-report's pressures.
#pragma once

#include <string>
#include <utility>
#include <vector>

#include "packbed/output.hpp"

namespace packbed {

/// The terminals every plot is drawn for, as (extension, gnuplot's `set terminal`): SVG for
/// documents, PNG (cairo) for everything else.
inline constexpr std::pair<const char*, const char*> plot_terminals[] = {
    {"svg", "set terminal svg size 800,450 background '#ffffff'"},
    {"png", "set terminal pngcairo size 1000,560 background '#ffffff'"}};

/// Run the gnuplot `scripts` in `out`'s staging folder, each in a gnuplot of its own and all at
/// once (run_programs), where together they write NAME.svg and NAME.png for each of `names`
/// (and nothing named by the user: every name is ours). When gnuplot is missing or fails, or a
/// plot is missing or empty, every plot is discarded and the rest of `out` stands.
/// \return "" when every plot was drawn, else why there are no plots
std::string draw_plots(OutputDirectory& out, const std::vector<std::string>& names,
                       const std::vector<std::string>& scripts);

} // namespace packbed
