// The allowed values of the numeric options, one table for both front ends: the command line's
// validators (apps/packbed/validators.cpp) and the Python module's keyword checks
// (python/module.cpp) take their ranges and their wording from here, so a value is refused
// with the same one-line message wherever it is given.
#pragma once

#include <cstdint>
#include <limits>
#include <string>
#include <string_view>

#include "packbed/limits.hpp"

namespace packbed {

/// A real number option's range: from low to high, either end open or closed (high infinite:
/// no upper end).
struct NumberRange {
    double low = 0.0;
    double high = std::numeric_limits<double>::infinity();
    bool low_open = false;
    bool high_open = false;

    /// \return whether `value` is finite and in the range
    bool holds(double value) const;
    /// \return what is allowed, e.g. "a number in (0, 1)" or "a number >= 0"
    std::string allowed() const;
};

/// A whole number option's range, both ends included.
struct WholeRange {
    std::uint64_t low = 0;
    std::uint64_t high = std::numeric_limits<std::uint64_t>::max();

    /// \return "a whole number from LOW to HIGH"
    std::string allowed() const;
};

/// \return `value` when it is in `range`. \throws InvalidInput "--OPTION: VALUE is not allowed;
/// allowed: ..." (the command line's message; `option` without its dashes)
double check_option(std::string_view option, double value, const NumberRange& range);
/// \copydoc check_option
std::uint64_t check_option(std::string_view option, long long value, const WholeRange& range);

/// Why `text`, a whole-number option as typed (digits only: no sign, point or exponent), is not
/// allowed in `range`: "'TEXT' is not allowed; allowed: ..." (quoted: not a whole number from
/// 0 to 2^64 - 1, or written with a leading zero, which the command line's parser would read
/// as octal) or "TEXT is not allowed; allowed: ..." (outside the range); "" when it is.
std::string whole_problem(std::string_view text, const WholeRange& range);
/// \return the value of `text` (whole_problem). \throws InvalidInput "--OPTION: " and the
/// problem: the command line's message, for a value the Python module takes as text (a seed up
/// to 2^64 - 1, which no C++ integer type of the binding holds signed)
std::uint64_t check_whole(std::string_view option, std::string_view text, const WholeRange& range);

namespace option_range {

constexpr double inf = std::numeric_limits<double>::infinity();

// generate (Salvat et al. 2005 and fire's schedule, docs/generate.md)
inline constexpr NumberRange aspect_ratio{1.0, 1e4};
inline constexpr WholeRange particles{1, limits::max_spheres};
inline constexpr WholeRange seed{};
inline constexpr NumberRange diameter{limits::min_diameter, limits::max_diameter};
inline constexpr NumberRange e0{0.0, 1.0, true, true};
inline constexpr NumberRange ck{limits::min_ck, 1.0, false, true};
inline constexpr NumberRange cg_step{0.0, 5e-6, true, false};
inline constexpr NumberRange overlap_bound{0.0, 0.5, true, true}; ///< --overlap-low, -high
inline constexpr NumberRange tolerance{limits::min_tolerance, 1e-2};
inline constexpr WholeRange mc_period{1, 1'000'000};
inline constexpr WholeRange mc_window{2, 10'000};
inline constexpr NumberRange mc_tolerance{0.0, 100.0, true, false};
inline constexpr NumberRange skin{0.0, 1.0, true, false};
inline constexpr NumberRange layer_height{0.0, 1e6};
inline constexpr NumberRange friction{0.0, 100.0}; ///< --friction, --wall-friction
inline constexpr NumberRange void_fraction_target{0.0, 1.0, true, true};
inline constexpr WholeRange max_iterations{1, std::numeric_limits<std::uint64_t>::max()};
inline constexpr NumberRange band_clearance{0.0, inf, false, true};
inline constexpr WholeRange threads{1, 1024};

// lattice
inline constexpr NumberRange lattice_band_clearance{0.0, 1e6, false, true};

// random-array (hard spheres' freezing point, limits.hpp)
inline constexpr WholeRange random_array_count{2, limits::max_random_array};
inline constexpr NumberRange random_array_solid_fraction{0.0, limits::max_hard_sphere_fraction,
                                                         true, false};
inline constexpr NumberRange random_array_gap{0.0, 0.5};
inline constexpr WholeRange random_array_sweeps{0, 1'000'000};

// reading a bed, analyze, voxelize
inline constexpr NumberRange floor_height{-limits::max_length, limits::max_length};
inline constexpr NumberRange outside_tolerance{0.0, 1.0};
inline constexpr NumberRange container_radius{0.0, limits::max_length, true, false};
inline constexpr NumberRange shell_width{1e-4, 10.0};
inline constexpr NumberRange slab_height{1e-4, 10.0};
inline constexpr NumberRange centre_bin{1e-4, 10.0};
inline constexpr NumberRange contact_tolerance{0.0, 0.5};
inline constexpr NumberRange rdf_range{0.1, 20.0};
inline constexpr NumberRange rdf_bin{1e-4, 1.0};
inline constexpr NumberRange voxel_size{0.0, limits::max_length, true, false};

// export
inline constexpr WholeRange refine{0, 7};
inline constexpr NumberRange edge{0.0, inf, true, true};
inline constexpr NumberRange export_container_radius{0.0, inf, true, true};
inline constexpr NumberRange container_height{0.0, inf, true, true};
inline constexpr WholeRange cells_per_diameter{1, 100};
inline constexpr WholeRange refinement_level{0, 8}; ///< --particle-level, --wall-level
inline constexpr WholeRange surface_layers{0, 10};  ///< --layers
inline constexpr NumberRange density{0.0, inf, true, true};
inline constexpr NumberRange fluid_velocity{0.0, inf, false, true};
inline constexpr NumberRange export_diameter{0.0, inf, true, true};
// export --format openfoam's flow (SI): ranks of Allrun, the particle Reynolds number (steady
// laminar flow to a few hundred, RANS beyond), metres per unit of the bed's lengths
inline constexpr WholeRange ranks{1, 1024};
/// generate --engine lammps: mpirun's ranks (a cluster's launcher: --mpi-command).
inline constexpr WholeRange lammps_ranks{1, 1'000'000};
inline constexpr NumberRange reynolds{0.0, 1e5, true, false};
inline constexpr NumberRange metres_per_unit{0.0, 1e3, true, false};

// hydraulics (SI; limits.hpp: nanoparticles to boulders, gases to liquid metals, microgravity
// to centrifuges)
inline constexpr NumberRange porosity{0.0, 1.0, true, true};
inline constexpr NumberRange diameter_m{limits::min_particle_diameter_m,
                                        limits::max_particle_diameter_m};
inline constexpr NumberRange density_kg_m3{limits::min_density_kg_m3, limits::max_density_kg_m3};
inline constexpr NumberRange viscosity_pa_s{limits::min_viscosity_pa_s, limits::max_viscosity_pa_s};
inline constexpr NumberRange gravity_m_s2{limits::min_gravity_m_s2, limits::max_gravity_m_s2};
inline constexpr NumberRange velocity_m_s{0.0, limits::max_velocity_m_s, true, false};
inline constexpr NumberRange tube_aspect_ratio{1.0, limits::max_tube_aspect_ratio};

// correlations
inline constexpr NumberRange profile_step{1e-4, 1.0};
inline constexpr NumberRange profile_to{0.0, 1e3};

} // namespace option_range

} // namespace packbed
