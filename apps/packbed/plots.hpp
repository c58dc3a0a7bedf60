// Plots of a bed analysis, drawn by gnuplot (Debian: gnuplot-nox) when it is installed.
#pragma once

#include <string>

#include <nlohmann/json.hpp>

#include "packbed/analysis.hpp"
#include "packbed/container.hpp"
#include "packbed/output.hpp"

namespace packbed::cli {

/// Stage radial_void_fraction.svg (with the de Klerk and Mueller correlations) and
/// radial_centre_distribution.svg in `out`.
/// \return "" when drawn, or why not (gnuplot missing or failing): the run goes on without.
std::string stage_plots(OutputDirectory& out, const BedAnalysis& analysis, double container_radius);

/// The analysis `packbed generate` and `packbed lattice` run on what they made: analyze_bed
/// over the band `band_clearance` (Dp) clear of the ends, its tables and plots staged in
/// `out`, its numbers in summary["analysis"]. Does nothing when the bed is too short for the
/// band (the caller's summary says so).
void stage_analysis(OutputDirectory& out, const Packing& packing, const Cylinder& container,
                    double band_clearance, nlohmann::json& summary);

} // namespace packbed::cli
