// Reading beds made elsewhere: our CSV and other delimited tables (ParaView's CSV export,
// semicolon-, tab- or space-separated text), XYZ, LAMMPS/LIGGGHTS text dumps and data files,
// each also gzip-compressed; one frame of a file or all of them.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <functional>
#include <istream>
#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include <nlohmann/json_fwd.hpp>

#include "packbed/container.hpp"
#include "packbed/limits.hpp"
#include "packbed/packing.hpp"
#include "packbed/registry.hpp"

namespace packbed {

/// The file formats read_particles understands. Every one may also be gzip-compressed
/// (recognised by its first bytes; `.gz` after the extension: bed.dump.gz).
enum class ParticleFormat {
    /// A delimited table with a header row: the separator is the header's (`;`, else `,`,
    /// else a tab, else runs of spaces); fields may be quoted ("..."). Columns x, y, z (or
    /// ParaView's Points:0, Points:1, Points:2) and r, radius, d or diameter (or none when
    /// ReadOptions::radius is given); with the four columns qw, qx, qy, qz (what packbed writes
    /// for pellets), each particle's orientation, a quaternion of norm 1 within 1e-3 (made
    /// exactly 1); other columns are ignored. In a `;`-separated table a decimal comma (1,5) is
    /// read as a decimal point. One frame.
    csv,
    /// Frames of: a count line, a comment line, `name x y z [radius]` per sphere.
    xyz,
    /// LAMMPS/LIGGGHTS text dump (`dump atom`, `dump custom`): per snapshot ITEM: TIMESTEP,
    /// NUMBER OF ATOMS, BOX BOUNDS and ATOMS with x y z, xu yu zu, or the scaled xs ys zs or
    /// xsu ysu zsu (unscaled with the snapshot's box, orthogonal or triclinic), and radius or
    /// diameter (or none when ReadOptions::radius is given).
    lammps_dump,
    /// LAMMPS/LIGGGHTS data file (`read_data`; what `packbed export --format lammps-data`
    /// writes): the `N atoms` header line and the Atoms section of atom_style sphere or
    /// granular (`id type diameter density x y z [ix iy iz]`), or atomic (`id type x y z
    /// [ix iy iz]`, ReadOptions::radius needed). Without a style comment (`Atoms # sphere`)
    /// sphere is assumed; image flags are ignored (the positions in the box are read). One frame.
    lammps_data,
};

/// The names users pick a format by ("auto": from the extension or the first line, "csv",
/// "xyz", "lammps-dump", "lammps-data"): the one registry.
const Registry<std::optional<ParticleFormat>>& particle_formats();

/// What a file does not say itself, and which part of it to read.
struct ReadOptions {
    /// Radius of every sphere in files without a size column (XYZ `name x y z`, dumps, data
    /// files of atom_style atomic, tables without r/d); a size column wins where there is one.
    /// Length, from limits::min_diameter / 2 to limits::max_diameter / 2.
    std::optional<double> radius;
    std::optional<ParticleFormat> format; ///< the file's format; default: detect_particle_format
    /// The frame read_particles reads: 1 the first, 2 the second, ...; -1 the last, -2 the one
    /// before, ... (0 is refused). Files of one frame (CSV, data files) have frame 1 = -1.
    /// Frames after the one asked for are not read.
    long long frame = -1;
    /// The container's axis (x, y), subtracted from every centre: the bed is read in
    /// coordinates whose z axis is the container's axis. Length, each within
    /// limits::max_length.
    std::array<double, 2> axis{0.0, 0.0};
    /// The container's floor (z), subtracted from every centre's z. Length, within
    /// limits::max_length.
    double floor = 0.0;
    /// A gzip-compressed input is refused once it has unpacked to more than this many bytes
    /// (a "zip bomb"). Plain files have no such limit (their lines and spheres do).
    std::uint64_t max_bytes = limits::max_decompressed_bytes;
};

/// Spheres read from a file (one frame), with the line each came from (1-based) for later
/// messages.
struct ParticleFile {
    Packing packing;                ///< the spheres, in the file's length unit
    std::vector<std::size_t> lines; ///< line number of each sphere (of the decompressed text)
    ParticleFormat format = ParticleFormat::csv;
    std::size_t frame = 1;             ///< which frame of the file this is, from 1
    std::optional<long long> timestep; ///< the dump's ITEM: TIMESTEP, when it has one
};

/// The format of a file from its extension (.csv, .tsv, .xyz, .dump, .lammpstrj, .data; a
/// trailing .gz is looked through) or, failing that, its first lines: `ITEM:` (a dump), a
/// count (XYZ), an `N atoms` line (a data file), a header naming x, y and z (a table).
/// \throws InvalidInput naming the file when no format fits.
ParticleFormat detect_particle_format(const std::filesystem::path& path);

/// Read one frame of a file (ReadOptions::frame, default the last). Refuses, with InvalidInput
/// naming the file, the line and the reason: what is not a regular file (a directory, a FIFO,
/// a device: see open_regular_file), an empty file, a missing column, a missing or non-numeric
/// field, NaN or infinity, a radius <= 0, a line longer than limits::max_line_length, more than
/// limits::max_spheres spheres, a frame without spheres, a frame number 0 or past the end (the
/// message says how many frames the file has), a gzip file that is corrupt, cut short or
/// larger than ReadOptions::max_bytes once decompressed, options out of range.
ParticleFile read_particles(const std::filesystem::path& path, const ReadOptions& options = {});

/// Read from a stream (gzip-compressed or not); `name` is used in messages. A frame counted
/// from the end other than -1 reads the stream twice (it must be seekable).
ParticleFile read_particles(std::istream& input, std::string_view name, ParticleFormat format,
                            const ReadOptions& options = {});

/// Call `visit` with every frame of a file in order, as it is read (one frame in memory at a
/// time): frames without spheres too (a dump's frames before the particles were inserted),
/// with an empty packing. ReadOptions::frame is not used.
/// \throws InvalidInput as read_particles does, and when the file has no frame at all or more
/// than limits::max_frames; what `visit` throws goes through.
void for_each_particle_frame(const std::filesystem::path& path, const ReadOptions& options,
                             const std::function<void(ParticleFile&&)>& visit);
/// The same from a stream.
void for_each_particle_frame(std::istream& input, std::string_view name, ParticleFormat format,
                             const ReadOptions& options,
                             const std::function<void(ParticleFile&&)>& visit);

/// Every frame of a file (a time series), in order, as for_each_particle_frame reads them;
/// refused beyond limits::max_spheres spheres in all frames together (memory).
std::vector<ParticleFile> read_particle_frames(const std::filesystem::path& path,
                                               const ReadOptions& options = {});
/// The same from a stream.
std::vector<ParticleFile> read_particle_frames(std::istream& input, std::string_view name,
                                               ParticleFormat format,
                                               const ReadOptions& options = {});

/// What a bed's summary.json (written by `packbed generate`, `lattice` or `analyze`) tells a
/// later command about the bed.
struct BedSummary {
    /// container.radius (length), when present (an annulus's: its outer radius)
    std::optional<double> container_radius;
    /// the container, when the summary records one (container_from_record of its `container`,
    /// else of a lattice's `region`)
    std::optional<Container> container;
    std::optional<double> diameter; ///< the spheres' diameter (length), when present
    /// the bed has spheres of several sizes (a `sizes` record, packbed generate --sizes):
    /// `diameter` is their Sauter mean d32
    bool sauter_mean = false;
    std::optional<double> porosity; ///< a lattice's exact porosity or the void fraction
    /// "the porosity of the TYPE lattice", "the overall void fraction" or "the overall void
    /// fraction of its analysis" (analysis.void_fraction), when porosity is set
    std::string porosity_source;
    /// the friction the bed was generated with (parameters.friction; a pellet bed's friction
    /// beside its shape), when present
    std::optional<double> friction;
    /// the walls' and floor's friction (parameters.wall_friction; a pellet bed's beside its
    /// shape), when present
    std::optional<double> wall_friction;
    /// the period along z of a cell periodic on all six faces (`period_z`, packbed
    /// random-array), when present
    std::optional<double> period_z;
    /// the particles' shape as `generate --shape` wrote it (`shape.spec`: "cylinder:D,L"),
    /// when the bed is not of spheres
    std::optional<std::string> shape;
    /// the smallest and the largest drawn size (`sizes.statistics`: a sphere's diameter, a
    /// pellet's D), when the bed has sizes
    std::optional<std::pair<double, double>> size_range;
    /// a lattice kept by its centres (`keep: centres`, lattice --keep centres): its balls reach
    /// out of the region, its container, by up to their radius
    bool centres_kept = false;
};

/// Read a summary.json. Absent keys are left empty; present ones must be right.
/// \param name names the file in messages
/// \throws InvalidInput naming the file when it is not JSON, or when container.radius is not
/// a number in (0, limits::max_length], the diameter not one in (0, limits::max_diameter] or
/// the porosity not a number in (0, 1)
BedSummary read_bed_summary(std::istream& input, std::string_view name);

/// Read a summary already parsed (a Python bed's, kept in memory): the same checks as above.
/// \throws InvalidInput as above
BedSummary read_bed_summary(const nlohmann::json& json, std::string_view name);

/// Read a summary.json file (at most limits::max_small_file bytes; a regular file, see
/// open_regular_file). \throws InvalidInput as above
BedSummary read_bed_summary(const std::filesystem::path& path);

} // namespace packbed
