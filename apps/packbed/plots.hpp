// Plots of a bed analysis, drawn by gnuplot (Debian: gnuplot-nox) when it is installed.
#pragma once

#include <string>

#include <nlohmann/json.hpp>

#include "packbed/analysis.hpp"
#include "packbed/container.hpp"
#include "packbed/output.hpp"

namespace packbed::cli {

/// Stage the plots of the wall profile (in a cylinder with the de Klerk and Mueller
/// correlations), the centre distribution, the axial profile and g(r), SVG and PNG, in `out`.
/// \return "" when drawn, or why not (gnuplot missing or failing): the run goes on without.
std::string stage_plots(OutputDirectory& out, const BedAnalysis& analysis,
                        const Container& container);

/// The analysis `packbed generate` and `packbed lattice` run on what they made: analyze_bed
/// over the band `band_clearance` (Dp) clear of the ends, its tables and plots staged in
/// `out`, its numbers in summary["analysis"]. Does nothing when the bed is too short for the
/// band (the caller's summary says so).
void stage_analysis(OutputDirectory& out, const Packing& packing, const Container& container,
                    double band_clearance, nlohmann::json& summary);

} // namespace packbed::cli
