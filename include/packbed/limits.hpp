// The ranges packbed accepts, in one place: the command line's validators, the readers and the
// library's own checks all read them, so that a value one accepts the others can handle.
#pragma once

#include <cstddef>
#include <cstdint>

namespace packbed::limits {

/// A sphere diameter, in any length unit (the unit of the outputs).
inline constexpr double min_diameter = 1e-12;
inline constexpr double max_diameter = 1e12;

/// Any other length (a container, a region, a coordinate), in the same units: far inside the
/// range where a double still resolves a sphere of the smallest diameter.
inline constexpr double max_length = 1e15;

/// The most spheres a bed may hold: what packbed generates, reads or fills a region with.
inline constexpr std::uint64_t max_spheres = 100'000'000;

/// A random array (random_array.hpp): at most this solid fraction of its hard spheres, the
/// freezing point of hard spheres, 0.494 (Hoover & Ree 1968): an equilibrium hard-sphere
/// system above it is partly a crystal, not a random array.
inline constexpr double max_hard_sphere_fraction = 0.49;
/// The most spheres of a random array, and the most trial moves (spheres times sweeps) of its
/// Monte Carlo: about 10 000 s at 1e6 moves a second.
inline constexpr std::uint64_t max_random_array = 10'000'000;
inline constexpr double max_random_array_moves = 1e10;

/// The most ball positions `fill_lattice` tries (the cells of the lattice that overlap the
/// region's bounding box, times the balls of a cell): 10 times those of the largest lattice
/// allowed (max_spheres balls), which leaves room for the bounding box of a turned region;
/// about 10 s. A thin region far longer than the rest would otherwise try ~1e12.
inline constexpr double max_lattice_positions = 1e9;

/// How far the lattice origin may lie from the region, in ball diameters: the positions are
/// origin + offset, so an origin x from the region costs x 1.1e-16 of their precision; 1e6
/// diameters keep it within 1.1e-10 d, under the 1e-9 d that decides whether a ball touching
/// a wall is inside.
inline constexpr double max_lattice_origin_offset = 1e6;

/// The bins of one profile of `analyze` (radial shells, axial slabs, centre bins, g(r) bins):
/// at most max(min_profile_bins, profile_bins_per_sphere N) for N spheres. A real bed needs
/// far fewer: 25 a shells for aspect ratio a at the default 0.02 Dp, and 20 slabs per Dp of
/// height at 0.05 Dp, about 20 per sphere in a single-file column (a = 1), 5 per sphere at
/// a = 2. The floor lets a small bed be measured finely (1e6 bins: 24 MB, a 50 MB table); the
/// bins are refused beyond it where the bins would outnumber what the spheres can fill: a
/// sphere far above the rest, a container far wider than the bed, a tiny bin.
inline constexpr double min_profile_bins = 1e6;
inline constexpr double profile_bins_per_sphere = 100.0;

/// The distance checks of the pair searches of `analyze` (contacts, g(r)): at most
/// max(min_pair_checks, pair_checks_per_sphere N max(1, (c / D)^3)), c the search distance,
/// D the mean sphere diameter. A bed at the densest packing (0.74 x 6 / pi = 1.41 centres per
/// D^3) costs 27 x 1.41 (c / D)^3 = 38 (c / D)^3 checks per sphere in a grid of cells of edge
/// c; the factor 1000 leaves room for overlaps, size ratios and clustering. Beyond it the
/// spheres are piled on each other (all pairs neighbours: N^2 checks, hours for 1e6 spheres).
inline constexpr double min_pair_checks = 1e8;
inline constexpr double pair_checks_per_sphere = 1000.0;

/// The reference diameter of `analyze` (--diameter) may differ from the spheres' mean
/// diameter by at most this factor: bins and search distances are set in reference diameters,
/// so one far from the spheres' size measures nothing and multiplies the work.
inline constexpr double max_reference_diameter_ratio = 10.0;

/// The physical ranges of `packbed hydraulics` (SI): nanoparticles to boulders, gases at low
/// pressure to liquid metals, microgravity to centrifuges. Within them, at porosities from
/// 1e-3, every quantity it prints stays below 1e38 (an Ergun gradient at 1e4 m/s); a result
/// that is still not a finite number (a porosity near 0) is refused, never printed.
inline constexpr double min_particle_diameter_m = 1e-9;
inline constexpr double max_particle_diameter_m = 10.0;
inline constexpr double min_density_kg_m3 = 1e-3; ///< particle and fluid
inline constexpr double max_density_kg_m3 = 3e4;
inline constexpr double min_viscosity_pa_s = 1e-7;
inline constexpr double max_viscosity_pa_s = 1e4;
inline constexpr double min_gravity_m_s2 = 1e-6;
inline constexpr double max_gravity_m_s2 = 1e6;
inline constexpr double max_velocity_m_s = 1e4; ///< superficial velocity, > 0
inline constexpr double max_tube_aspect_ratio = 1e4;

/// The smallest final overlap tolerance of generate (Dp): a position of a bed 1000 Dp tall is
/// rounded to about 1e-13 Dp, so a tolerance below this may never be reached (with 1e-16 a run
/// went on until --max-iterations). The paper's solver reaches about 1e-7 at most; below, it
/// stops with exit status 1 and says so.
inline constexpr double min_tolerance = 1e-12;

/// The smallest elasticity parameter Ck of eq. (4): the iterations grow as 1/Ck (0.3 is the
/// paper's; 1e-300 moved nothing and ran until --max-iterations).
inline constexpr double min_ck = 0.01;

/// The longest line a text reader accepts (bytes): far above any real line, and it bounds the
/// memory a file without newlines can take.
inline constexpr std::size_t max_line_length = 1 << 20;

/// How far from the origin, in mean sphere diameters, a sphere of an exported bed may reach:
/// surfaces (STL, OBJ) and the walls of a LIGGGHTS input store single precision, which at
/// 1e6 Dp resolves 0.06 Dp; a sphere 1e14 Dp up put the container's STL outside its box.
inline constexpr double max_export_reach = 1e6;

/// The largest small text file read whole (summary.json, job.json, packbed.json), bytes.
inline constexpr std::size_t max_small_file = 64u << 20;

/// The largest --config file, bytes: a TOML parser keeps about 60 bytes per value it reads (a
/// 60 MB array took 3.8 GB), and a config of every option of a subcommand is under 4 KB.
inline constexpr std::size_t max_config_file = 1u << 20;

/// How deep the JSON and TOML a user gives may nest (arrays, objects, tables, the parts of a
/// dotted key): the parsers' trees are copied, printed and destroyed by recursion, so 1e5
/// nested brackets or a key of 5e4 parts overflowed the stack. packbed's own files nest 4
/// deep.
inline constexpr std::size_t max_json_nesting = 64;
inline constexpr std::size_t max_toml_nesting = 64;

/// The most frames read_particle_frames and for_each_particle_frame read from one file (the
/// frames of a time series: `packbed analyze --frames all`).
inline constexpr std::size_t max_frames = 100'000;

/// The most bytes a gzip-compressed file may hold once decompressed (ReadOptions::max_bytes'
/// default): 16 GiB, above the largest bed allowed (limits::max_spheres lines of about 100
/// bytes), far below what a small "zip bomb" (compressed 1000 to 1) unpacks to.
inline constexpr std::uint64_t max_decompressed_bytes = std::uint64_t{16} << 30;

/// How many times its size a gzip file may expand to (what a reader keeps stays in proportion
/// to the file): a bed's text compresses about 2 times (a random bed's CSV), 8 (a simple cubic
/// lattice), 17 (fcc); 1e8 identical rows compress about 400 times.
inline constexpr double max_gzip_ratio = 100.0;

/// The bytes of one voxel image (voxelize) in memory and in its file: 16 GiB, 2^34 voxels of a
/// binary image, 2^31 of a fraction image (8 bytes each).
inline constexpr double max_image_bytes = 17179869184.0;

} // namespace packbed::limits
