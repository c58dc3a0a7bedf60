// Reading beds made elsewhere: our CSV, XYZ, LAMMPS/LIGGGHTS text dumps.
#pragma once

#include <cstddef>
#include <filesystem>
#include <istream>
#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "packbed/packing.hpp"

namespace packbed {

/// The file formats read_particles understands.
enum class ParticleFormat {
    csv, ///< header row naming x, y, z and r, radius, d or diameter; optional id, others ignored
    xyz, ///< count line, comment line, then `name x y z [radius]` per sphere
    lammps_dump, ///< LAMMPS/LIGGGHTS text dump: `ITEM: ATOMS` with x y z (or xu yu zu) and
                 ///< radius or diameter; the last snapshot of the file is read
};

/// The names users pick a format by ("csv", "xyz", "lammps-dump"): the one registry.
const std::vector<std::pair<std::string, ParticleFormat>>& particle_formats();

/// What a file does not say itself.
struct ReadOptions {
    std::optional<double> radius; ///< radius for XYZ files without a radius column (length, > 0)
    std::optional<ParticleFormat> format; ///< the file's format; default: detect_particle_format
};

/// Spheres read from a file, with the line each came from (1-based) for later messages.
struct ParticleFile {
    Packing packing;                ///< the spheres, in the file's length unit
    std::vector<std::size_t> lines; ///< line number of each sphere
    ParticleFormat format = ParticleFormat::csv;
};

/// The format of a file from its extension (.csv, .xyz, .dump, .lammpstrj) or, failing that,
/// its first line. \throws InvalidInput naming the file when no format fits.
ParticleFormat detect_particle_format(const std::filesystem::path& path);

/// Read a file. Refuses, with InvalidInput naming the file, the line and the reason: what is
/// not a regular file (a directory, a FIFO, a device: see open_regular_file), an empty file, a
/// missing column, a missing or non-numeric field, NaN or infinity, a radius <= 0, a line
/// longer than limits::max_line_length, more than limits::max_spheres spheres.
ParticleFile read_particles(const std::filesystem::path& path, const ReadOptions& options = {});

/// Read from a stream; `name` is used in messages.
ParticleFile read_particles(std::istream& input, std::string_view name, ParticleFormat format,
                            const ReadOptions& options = {});

/// What a bed's summary.json (written by `packbed generate`, `lattice` or `analyze`) tells a
/// later command about the bed.
struct BedSummary {
    std::optional<double> container_radius; ///< container.radius (length), when present
    std::optional<double> diameter;         ///< the spheres' diameter (length), when present
    std::optional<double> porosity;         ///< a lattice's exact porosity or the void fraction
    /// "the porosity of the TYPE lattice" or "the overall void fraction", when porosity is set
    std::string porosity_source;
};

/// Read a summary.json. Absent keys are left empty; present ones must be right.
/// \param name names the file in messages
/// 	hrows InvalidInput naming the file when it is not JSON, or when container.radius is not
/// a number in (0, limits::max_length], the diameter not one in (0, limits::max_diameter] or
/// the porosity not a number in (0, 1)
BedSummary read_bed_summary(std::istream& input, std::string_view name);

/// Read a summary.json file (at most limits::max_small_file bytes; a regular file, see
/// open_regular_file). 	hrows InvalidInput as above
BedSummary read_bed_summary(const std::filesystem::path& path);

} // namespace packbed
