// Beds and their analysis as file contents: CSV, VTK XML (ParaView), LAMMPS data. Where the
// files go, whole or not at all: output.hpp.
#pragma once

#include <filesystem>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "packbed/analysis.hpp"
#include "packbed/packing.hpp"

namespace packbed {

/// The spheres as CSV: header `x,y,z,r`, one row per sphere, each number in the shortest form
/// that reads back to the same double (round-trip precision).
/// \return the file's text.
std::string particles_csv(const Packing& packing);

/// The spheres as a VTK XML unstructured grid (.vtu): one vertex cell per sphere, point data
/// `radius` and `diameter`. ParaView shows it with the Point Gaussian representation or glyphs.
/// \return the file's text.
std::string particles_vtu(const Packing& packing);

/// An axis-aligned box (lengths in the packing's units), lo < hi on every axis.
struct AxisBox {
    Vec3 lo, hi;
};

/// \return the smallest box holding every sphere whole (centre -/+ radius): the default box of
/// a DEM data file. An empty packing gives the unit cube.
AxisBox bounding_box(const Packing& packing);

/// The spheres as a LAMMPS data file for `atom_style sphere` (LIGGGHTS: `atom_style
/// granular`, the same columns): header with the atom count, one atom type and the box
/// bounds, then `Atoms # sphere` rows `id type diameter density x y z` (ids from 1 in packing
/// order, type 1). Numbers in shortest round-trip form.
/// \param density particle density (mass per volume, in the units the DEM run uses; > 0)
/// \param box must hold every centre (LAMMPS drops atoms outside a fixed box)
/// \param comment first line of the file (no newline)
/// \throws InvalidInput when the density is not > 0 or a centre is outside the box
std::string lammps_data(const Packing& packing, double density, const AxisBox& box,
                        std::string_view comment);

/// The tables of a bed analysis as CSV texts, by file name:
/// - `radial_void_fraction.csv`: `radial_position,x_from_wall_d,void_fraction`, the shell's
///   mid-radius (length), x_from_wall_d = (Rt - radial_position) / Dp as in Salvat et al.
///   (2005), wall first;
/// - `axial_void_fraction.csv`: `z,z_d,void_fraction`, z the slab's mid-height;
/// - `radial_centre_distribution.csv`: `radial_position,x_from_wall_d,relative_density` (see
///   analyze_bed);
/// - `coordination.csv`: `contacts,spheres`, the histogram of sphere-sphere contacts;
/// - `pair_correlation.csv`: `distance,distance_d,g`.
/// Positions are written to 12 significant digits (bin centres without floating-point noise),
/// values as computed (shortest round trip). `r` is never a column name here: in particles.csv
/// it is the sphere's radius.
/// \param analysis what analyze_bed returned \param container_radius Rt (length)
/// \return (file name, contents) pairs.
std::vector<std::pair<std::string, std::string>> analysis_tables(const BedAnalysis& analysis,
                                                                 double container_radius);

} // namespace packbed
