// The machine-readable record of a generated bed (summary.json).
#pragma once

#include <nlohmann/json.hpp>

#include "packbed/analysis.hpp"
#include "packbed/json_text.hpp"
#include "packbed/lattice.hpp"
#include "packbed/sizes.hpp"
#include "packbed/soft_sphere.hpp"

namespace packbed {

/// Everything a user needs to know about a soft-sphere run: inputs, every parameter, the
/// container, the overall void fraction over the band clear of the ends, the largest overlaps,
/// the stages, the time and the version. Lengths in output units unless a key says "_dp".
/// \param parameters the parameters of the run
/// \param result what SoftSphereGenerator::run returned
/// \param band_clearance distance of the void-fraction band from the floor and the top, in Dp
/// (>= 0); when the bed is too short for it, `void_fraction` is null and a note says why
/// \param threads number of threads used (recorded only)
/// \return the JSON object.
nlohmann::json soft_sphere_summary(const SoftSphereParameters& parameters,
                                   const SoftSphereResult& result, double band_clearance,
                                   int threads);

/// The numbers of a bed analysis (the tables go to CSV files, see analysis_files): band,
/// overall void fraction, coordination (mean with and without rattlers, rattlers, wall contacts),
/// the reference diameter, the options used and the files. An annulus adds `walls`, each wall's
/// name, wall contacts and tables (wall_contacts counts the spheres touching either); a
/// periodic cell has `walls` empty, no wall_contacts, and `no_walls` saying why.
nlohmann::json analysis_summary(const BedAnalysis& analysis, const AnalysisOptions& options);

/// The statistics of a bed's sizes as summary.json records them: count, d10, d50, d90 (by
/// volume), the Sauter mean d32, d43, the number mean and standard deviation, the smallest
/// and largest diameter and their ratio, and each class's range, count and number and volume
/// fractions.
nlohmann::json size_statistics_summary(const SizeStatistics& statistics);

/// The record of a lattice (`packbed lattice`): its parameters, the number of balls, the
/// lattice's exact porosity and coordination, the porosity measured in the region (the balls'
/// volume inside it over its volume, balls cut by the walls included: sphere_volume_in_box,
/// sphere_volume_in_cylinder_slab) and the contacts found (within 1e-9 d).
/// Lengths in output units.
nlohmann::json lattice_summary(const LatticeParameters& parameters, const Packing& packing);

} // namespace packbed
