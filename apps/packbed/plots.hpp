// Plots of a bed analysis, drawn by gnuplot (Debian: gnuplot-nox) when it is installed.
#pragma once

#include <string>

#include "packbed/analysis.hpp"
#include "packbed/io.hpp"

namespace packbed::cli {

/// Stage radial_void_fraction.svg (with the de Klerk and Mueller correlations) and
/// radial_centre_distribution.svg in `out`.
/// \return "" when drawn, or why not (gnuplot missing or failing): the run goes on without.
std::string stage_plots(OutputDirectory& out, const BedAnalysis& analysis, double container_radius);

} // namespace packbed::cli
