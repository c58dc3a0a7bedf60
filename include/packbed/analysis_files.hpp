// The tables of a bed analysis in every container: what `packbed analyze` and `generate` write.
// A container of one wall (cylinder, box) gets io.hpp's analysis_tables as they are; an annulus
// gets each wall's profiles in tables of their own; a periodic cell no table against a wall.
#pragma once

#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include <nlohmann/json.hpp>

#include "packbed/analysis.hpp"
#include "packbed/container.hpp"

namespace packbed {

/// The tables of a bed analysis as CSV texts, by file name:
/// - `radial_void_fraction.csv`: `radial_position,x_from_wall_d,void_fraction`, the shell's
///   mid-radius (length), x_from_wall_d = (Rt - radial_position) / Dp as in Salvat et al.
///   (2005), wall first; in a box the first column is `wall_distance`, the shell's middle
///   distance from the nearest face (Container::profile_position);
/// - `axial_void_fraction.csv`: `z,z_d,void_fraction`, z the slab's mid-height;
/// - `radial_centre_distribution.csv`: `radial_position,x_from_wall_d,relative_density` (see
///   analyze_bed);
/// - `coordination.csv`: `contacts,spheres`, the histogram of sphere-sphere contacts;
/// - `pair_correlation.csv`: `distance,distance_d,g`;
/// - for a bed of more than one size (BedAnalysis::by_size), `size_classes.csv`:
///   `low,high,spheres,number_fraction,volume_fraction,spheres_in_band,mean_coordination`, and
///   `centre_distribution_by_size.csv`: the wall profiles' position columns, then one column
///   `d_D` (a discrete size) or `d_LOW_HIGH` (a bin) per class.
/// Positions are written to 12 significant digits (bin centres without floating-point noise),
/// values as computed (shortest round trip). `r` is never a column name here: in particles.csv
/// it is the sphere's radius.
/// \param analysis what analyze_bed returned \param container the bed's container
/// \return (file name, contents) pairs.
std::vector<std::pair<std::string, std::string>> analysis_tables(const BedAnalysis& analysis,
                                                                 const Container& container);

/// The names of the tables of one wall's profiles in a container of several walls:
/// "radial_void_fraction_NAME.csv" and "radial_centre_distribution_NAME.csv".
/// \param wall the wall's name (WallAnalysis::name: "outer", "inner")
std::pair<std::string, std::string> wall_table_names(const std::string& wall);

/// Every table of an analysis, as (file name, CSV text), in the order they are written.
/// - A container of one wall (cylinder, box): analysis_tables (io.hpp), unchanged.
/// - An annulus: instead of radial_void_fraction.csv and radial_centre_distribution.csv, a
///   pair of tables per wall (wall_table_names), columns radial_position (the distance from
///   the axis: R - d from the tube, Ri + d from the rod), x_from_wall_d (d / Dp) and the value;
///   no centre_distribution_by_size.csv (by_size's distributions are for one wall).
/// - A periodic cell: no table against a wall (axial profile, coordination, g(r), and the
///   size classes of a mixture).
/// \param analysis what analyze_bed measured in `container`
std::vector<std::pair<std::string, std::string>> analysis_files(const BedAnalysis& analysis,
                                                                const Container& container);

/// The tables of a pellet bed's analysis (analyze_pellet_bed), lengths over d_v where a column
/// ends in _d: radial_void_fraction.csv and axial_void_fraction.csv as a sphere bed's, and
/// orientation_profile.csv (the container's position and x_from_wall_d of each bin's middle,
/// pellets, mean_cos2, order) in a container of one wall.
std::vector<std::pair<std::string, std::string>> pellet_analysis_files(const PelletAnalysis& a,
                                                                       const Container& container);

/// The numbers of a pellet bed's analysis as `packbed analyze` writes them in summary.json
/// (the tables go to pellet_analysis_files): the pellets, their `shape` spec, d_v, the
/// container, band, void fraction, the axes' orientation and the contacts per pellet.
/// \param contact_tolerance the gap (d_v) the contacts were counted at
nlohmann::ordered_json pellet_analysis_summary(const PelletAnalysis& a, std::string_view shape,
                                               std::size_t pellets, const Container& container,
                                               double contact_tolerance);

/// The numbers of a bed analysis (the tables go to CSV files, see analysis_files): band,
/// overall void fraction, coordination (mean with and without rattlers, rattlers, wall contacts),
/// the reference diameter, the options used and the files. An annulus adds `walls`, each wall's
/// name, wall contacts and tables (wall_contacts counts the spheres touching either); a
/// periodic cell has `walls` empty, no wall_contacts, and `no_walls` saying why.
nlohmann::json analysis_summary(const BedAnalysis& analysis, const AnalysisOptions& options);

} // namespace packbed
