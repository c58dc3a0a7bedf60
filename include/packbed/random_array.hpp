// Random arrays of equal spheres in a cell periodic along x, y and z: the hard-sphere fluid that
// the drag laws of random arrays are fitted to (van der Hoef, Beetstra & Kuipers 2005), and a
// bulk packing at any solid fraction up to hard spheres' freezing point.
#pragma once

#include <cstdint>
#include <functional>

#include <nlohmann/json.hpp>

#include "packbed/packing.hpp"

namespace packbed {

/// Everything `random_array` needs. Plain value type; lengths in output units.
struct RandomArrayParameters {
    std::uint64_t count = 0;     ///< N, the spheres in the cell (--count)
    double solid_fraction = 0.3; ///< phi = N (pi/6) d^3 / L^3, which sets the cubic cell's edge L
    double diameter = 1.0;       ///< d
    double gap = 0.0;            ///< least gap between two surfaces, in d: the Monte Carlo moves
                                 ///< hard spheres of diameter sigma = (1 + gap) d
    std::uint64_t sweeps = 1000; ///< Monte Carlo sweeps (N trial moves each) at sigma
    std::uint64_t seed = 1;      ///< the random start and every trial move

    /// \return the cubic cell's edge L = (N (pi/6) d^3 / phi)^(1/3), to 9 significant digits
    /// (the container's spec, periodic:L,L, names it exactly).
    double cell() const;
    /// \return the solid fraction of that cell, N (pi/6) d^3 / L^3 (phi within 2e-9).
    double actual_solid_fraction() const;
    /// \return the hard spheres' solid fraction phi (1 + gap)^3, at most
    /// limits::max_hard_sphere_fraction.
    double hard_sphere_fraction() const;
    /// Check every value: 2 to limits::max_random_array spheres, phi in (0, 0.49] for the hard
    /// spheres, a gap in [0, 0.5] d, at most limits::max_random_array_moves trial moves, a cell
    /// at least 2 sigma wide (each pair has one nearest copy). \throws InvalidInput naming the
    /// command line's option, its value and the range.
    void validate() const;
};

/// What random_array made and how.
struct RandomArray {
    Packing packing;                 ///< the N spheres, centres wrapped into [0, L)^3
    double cell = 0.0;               ///< the cubic cell's edge L
    std::uint64_t growth_sweeps = 0; ///< sweeps that grew the spheres from the random start
    double acceptance = 0.0;         ///< accepted share of the trial moves at sigma
    double step = 0.0;               ///< the largest trial move in the end, in d
    double mean_displacement = 0.0;  ///< mean distance moved from the random start (unwrapped), d
};

/// Progress of random_array: sweeps done and planned (the growth's count is an estimate).
using RandomArrayProgress = std::function<void(std::uint64_t done, std::uint64_t planned)>;

/// Fill a cubic periodic cell with N equal spheres at random, as hard spheres in equilibrium:
/// - random sequential addition (Feder 1980) of spheres of diameter
///   sigma_0 = sigma min(1, (0.25 / phi_h)^(1/3)), far below RSA's jamming limit 0.384;
/// - Monte Carlo sweeps of hard spheres (Metropolis et al. 1953: a trial move, uniform in a cube,
///   is accepted when it leaves every pair at least the current diameter apart), the diameter
///   raised after each sweep to the smallest centre distance, up to sigma;
/// - `sweeps` more sweeps at sigma, the trial move's size set after each sweep so that about
///   0.4 of the moves are accepted.
/// Spheres are moved in index order; one thread: the same seed gives the same bits.
/// \throws InvalidInput for invalid parameters (RandomArrayParameters::validate) and
/// ConvergenceError when the growth does not reach sigma within 1e6 sweeps.
RandomArray random_array(const RandomArrayParameters& p, const RandomArrayProgress& progress = {});

/// summary.json of a random array: the parameters, the cell (container periodic:L,L, whose
/// period along z, `period_z`, is L too), the Monte Carlo's record and the closest surfaces.
nlohmann::json random_array_summary(const RandomArrayParameters& p, const RandomArray& array);

} // namespace packbed
