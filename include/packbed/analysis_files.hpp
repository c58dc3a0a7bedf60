// The tables of a bed analysis in every container: what `packbed analyze` and `generate` write.
// A container of one wall (cylinder, box) gets io.hpp's analysis_tables as they are; an annulus
// gets each wall's profiles in tables of their own; a periodic cell no table against a wall.
#pragma once

#include <string>
#include <utility>
#include <vector>

#include "packbed/analysis.hpp"
#include "packbed/container.hpp"

namespace packbed {

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

} // namespace packbed
