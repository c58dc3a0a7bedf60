// Writing beds to files: CSV, VTK XML (ParaView), and all-or-nothing output directories.
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
/// - `radial_void_fraction.csv`: `r,x_from_wall_d,void_fraction`, r the shell's mid-radius
///   (length), x_from_wall_d = (Rt - r) / Dp as in Salvat et al. (2005), wall first;
/// - `axial_void_fraction.csv`: `z,z_d,void_fraction`, z the slab's mid-height;
/// - `radial_centre_distribution.csv`: `r,x_from_wall_d,relative_density` (see analyze_bed);
/// - `coordination.csv`: `contacts,spheres`, the histogram of sphere-sphere contacts;
/// - `pair_correlation.csv`: `r,r_d,g`.
/// \param analysis what analyze_bed returned \param container_radius Rt (length)
/// \return (file name, contents) pairs.
std::vector<std::pair<std::string, std::string>> analysis_tables(const BedAnalysis& analysis,
                                                                 double container_radius);

/// A set of files written all or nothing. Each file is first written under a temporary name
/// in the target directory; commit() renames them all into place. If the object is destroyed
/// without commit() (an error, an interruption), the temporary files are removed and no
/// target file is touched. Not thread-safe.
class OutputDirectory {
public:
    /// Create the directory if needed and check that it is writable.
    /// \param directory the output directory
    /// \throws InvalidInput naming the directory when it cannot be created or written
    explicit OutputDirectory(std::filesystem::path directory);
    ~OutputDirectory();
    OutputDirectory(const OutputDirectory&) = delete;
    OutputDirectory& operator=(const OutputDirectory&) = delete;

    /// Write `contents` to a temporary file for `name` (a file name inside the directory, or a
    /// relative path whose folders are then created: "system/controlDict").
    /// \throws std::runtime_error naming the file when writing fails
    void stage(const std::string& name, const std::string& contents);

    /// Reserve the temporary path of `name` for a file another program writes (e.g. a plot);
    /// it is renamed into place by commit() like staged files, and removed if not committed.
    /// \return the temporary path to write to.
    std::filesystem::path reserve(const std::string& name);

    /// Forget a staged or reserved file and remove its temporary (e.g. a plot that failed).
    void discard(const std::string& name);

    /// Rename every staged file to its final name, after checking that all of them exist.
    /// \throws std::runtime_error naming the file when one is missing or a rename fails
    void commit();

    /// \return the directory.
    const std::filesystem::path& path() const { return m_directory; }

private:
    std::filesystem::path m_directory;
    std::vector<std::pair<std::filesystem::path, std::filesystem::path>> m_staged; // tmp, final
};

} // namespace packbed
