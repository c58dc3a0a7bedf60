// Particle-size distributions: chosen by name (`--sizes SPEC`), drawn reproducibly
// so that the drawn sizes hold the asked fractions up to the rounding a finite number of
// spheres forces, and the statistics of a set of diameters (fractions per class, d10, d50, d90,
// Sauter mean). docs/sizes.md states every definition and its source.
//
// Notation (ISO 9276-1): q0(d) is the number density of the diameters, q3(d) the volume (mass)
// density, \f$q_0(d) \propto q_3(d) / d^3\f$; Q0 and Q3 their cumulative fractions.
#pragma once

#include <cstddef>
#include <cstdint>
#include <memory>
#include <span>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include <nlohmann/json.hpp>

#include "packbed/registry.hpp"

namespace packbed {

/// The largest over the smallest diameter a distribution may have: what the solvers support
/// (neighbour searches stay O(Np) up to a size ratio of 10).
inline constexpr double max_size_ratio = 10.0;

/// How far the fractions of `discrete:` may add up away from 1, and the first and last
/// cumulative fractions of a sieve file (`file:`) away from 0 and 1. Within it they are
/// rescaled to add up to 1 exactly.
inline constexpr double fraction_tolerance = 1e-6;

/// The most sizes of `discrete:` and the most rows of a sieve file (`file:`).
inline constexpr std::size_t max_size_rows = 100'000;

/// The kinds of size distribution (`--sizes NAME:...`).
enum class SizeKind {
    mono,      ///< every sphere the same diameter (`--diameter`)
    discrete,  ///< a mixture of given diameters, each with its fraction
    uniform,   ///< a density constant between MIN and MAX
    normal,    ///< a normal density truncated at MIN and MAX
    lognormal, ///< a lognormal density truncated at MIN and MAX
    file,      ///< a sieve analysis: cumulative fraction passing against diameter
};

/// The names users pick a size distribution by ("mono", "discrete", "uniform", "normal",
/// "lognormal", "file"): the one registry.
const Registry<SizeKind>& size_kinds();
/// \return the name of a kind in size_kinds().
std::string to_string(SizeKind kind);
/// \return how a spec of `kind` is written, e.g. "uniform:MIN,MAX" (for messages and help).
std::string_view size_syntax(SizeKind kind);

/// What the fractions (and the densities of the continuous distributions) of a spec count.
enum class FractionBasis {
    volume, ///< by volume, i.e. by mass for spheres of one material: what engineers specify
            ///< and sieve analyses measure (q3); the default
    number, ///< by number of spheres (q0)
};

/// The names users pick a basis by ("volume", "number"; `--fractions`): the one registry.
const Registry<FractionBasis>& fraction_bases();
/// \return the name of a basis in fraction_bases().
std::string to_string(FractionBasis basis);

/// A size distribution as parsed from a spec, in output length units. Whether its fractions
/// and density count volume or number is said when it is used (FractionBasis). Plain value
/// type; parse_sizes makes valid ones.
struct SizeDistribution {
    SizeKind kind = SizeKind::mono;
    std::string spec = "mono"; ///< the spec it was parsed from
    /// mono: the one diameter; discrete: the sizes, ascending; uniform: {MIN, MAX}; file: the
    /// sieve diameters, ascending (from the last row at 0 to the first at 1); else empty
    std::vector<double> diameters;
    /// discrete: the fraction of each size (adding up to 1); uniform: {0, 1}; file: the
    /// cumulative fraction at each diameter (0 first, 1 last, not decreasing); else empty
    std::vector<double> fractions;
    double location = 0.0; ///< normal: MEAN; lognormal: MEDIAN (the distribution's own median)
    double spread = 0.0;   ///< normal: SD (> 0); lognormal: GSD (> 1)
    double low = 0.0;      ///< the smallest diameter that can be drawn (the lower bound)
    double high = 0.0;     ///< the largest diameter that can be drawn (the upper bound)

    /// \return high / low, at most max_size_ratio.
    double size_ratio() const { return high / low; }
};

/// Parse a `--sizes` spec:
/// - `mono`: every sphere `mono_diameter`;
/// - `discrete:D1:F1,D2:F2,...`: diameters Dk > 0, each once, with fractions Fk >= 0 adding up
///   to 1 within fraction_tolerance;
/// - `uniform:MIN,MAX`: a constant density on [MIN, MAX];
/// - `normal:MEAN,SD[,MIN,MAX]`: truncated at MIN and MAX; by default MEAN - 3 SD and
///   MEAN + 3 SD, the lower one raised to MAX / max_size_ratio where it is below;
/// - `lognormal:MEDIAN,GSD[,MIN,MAX]`: ln d normal with median MEDIAN and geometric standard
///   deviation GSD > 1, truncated at MIN and MAX; by default MEDIAN / GSD^3 and MEDIAN GSD^3,
///   narrowed about MEDIAN (in ln d) to a ratio of max_size_ratio where they are wider;
/// - `file:PATH`: a sieve analysis, a CSV of `diameter,cumulative_fraction` rows (docs/sizes.md),
///   read with the safe file functions of files.hpp.
/// Every diameter must be within limits::min_diameter to limits::max_diameter and the largest
/// over the smallest at most max_size_ratio.
/// \param spec the spec, as the user gave it
/// \param mono_diameter the diameter of `mono` (`--diameter`), output length units
/// \throws InvalidInput with one line naming `--sizes`, the spec and what is allowed
SizeDistribution parse_sizes(std::string_view spec, double mono_diameter);

/// A `--sizes` spec as messages show it: control characters escaped, cut after 100 bytes.
std::string shown_sizes(std::string_view spec);

/// Q0, the cumulative distribution by number that draw_diameters draws from, of a distribution
/// whose fractions (or density) count `basis`, and its inverse. Exact for every kind: closed
/// forms (`uniform` and `file` by volume: Q3 linear between the rows makes Q0 linear in d^-2;
/// `lognormal` by volume: Hatch & Choate's median shift), except `normal` by volume, whose
/// q3 / d^3 is integrated by Gauss-Legendre quadrature on a table (within 5e-15 of an adaptive
/// Gauss-Kronrod reference). Immutable once made: may be shared between threads.
class NumberDistribution {
public:
    /// \param sizes a distribution from parse_sizes
    /// \param basis what its fractions (or density) count
    NumberDistribution(const SizeDistribution& sizes, FractionBasis basis);

    /// \return Q0(d), the fraction by number of the spheres with a diameter at most `diameter`.
    double cumulative(double diameter) const;

    /// \return the smallest d with Q0(d) >= `fraction` (continuous kinds: the d with
    /// Q0(d) = fraction; cumulative(quantile(t)) is t within 1e-13), within [low, high].
    /// \param fraction in [0, 1] (clamped)
    double quantile(double fraction) const;

private:
    struct Impl;
    std::shared_ptr<const Impl> m_impl;
};

/// \return the fraction by number of each size of a `discrete` (or `mono`) distribution
/// whose fractions count `basis`: \f$x_k = (F_k / D_k^3) / \sum_j F_j / D_j^3\f$ by volume,
/// F_k by number; empty for the continuous kinds.
std::vector<double> number_fractions(const SizeDistribution& sizes, FractionBasis basis);

/// \return how many spheres of each size of a `discrete` (or `mono`) distribution
/// draw_diameters gives among `count`: the largest-remainder rounding of count x_k (each floor,
/// then one more to the largest remainders, ties to the smaller size), adding up to `count`;
/// empty for the continuous kinds.
std::vector<std::size_t> discrete_counts(const SizeDistribution& sizes, FractionBasis basis,
                                         std::size_t count);

/// Draw `count` diameters from `sizes`, whose fractions (or density) count `basis`.
/// - mono: `count` copies of the diameter; no random numbers.
/// - discrete: exactly discrete_counts of each size, in an order shuffled by `seed`.
/// - continuous (uniform, normal, lognormal, file): stratified inverse transform, sphere i of
///   count gets \f$Q_0^{-1}((i + u_i) / n)\f$ with u_i uniform in [0, 1), then the order is
///   shuffled: for every d, the number of drawn diameters <= d differs from n Q0(d) by less
///   than 1.
/// The random numbers are std::mt19937_64(seed) turned into doubles by bit arithmetic and the
/// transforms use only IEEE-exact operations and our own exp, log and erfc: the same bits on
/// every platform (built with -ffp-contract=off, as the library is).
/// \return the diameters, output length units
std::vector<double> draw_diameters(const SizeDistribution& sizes, std::size_t count,
                                   FractionBasis basis, std::uint64_t seed);

/// The seed of a bed's sizes (draw_diameters) from its --seed: the seed XOR the golden-ratio
/// constant 0x9E3779B97F4A7C15, a stream of its own, so that the positions are drawn from the
/// same numbers whatever the sizes.
constexpr std::uint64_t sizes_seed(std::uint64_t seed) {
    return seed ^ 0x9E3779B97F4A7C15ull;
}

/// One size class of a set of diameters.
struct SizeClass {
    double low = 0.0;           ///< smallest diameter of the class (discrete: the size)
    double high = 0.0;          ///< largest (discrete: the size; else the next class's low)
    std::uint64_t count = 0;    ///< spheres in the class
    double number_fraction = 0; ///< count over all spheres
    double volume_fraction = 0; ///< sum of d^3 in the class over the sum of all d^3
};

/// At most this many distinct diameters make one class each (a discrete mixture); more are
/// binned (size_classes).
inline constexpr std::size_t max_discrete_classes = 32;
/// The classes of a set of more than max_discrete_classes distinct diameters by default.
inline constexpr std::size_t default_size_bins = 20;

/// \return the classes of `diameters` (counts and fractions zero): one per distinct diameter
/// when there are at most max_discrete_classes of them; otherwise `bins` classes of equal
/// width in ln d (a geometric series, as sieve series are) from the smallest to the largest
/// diameter, each [low, high) and the last [low, high]. Empty for no diameters.
/// \param diameters > 0, finite, any order
/// \param bins >= 1
std::vector<SizeClass> size_classes(std::span<const double> diameters,
                                    std::size_t bins = default_size_bins);

/// \return the index of the class of `diameter` in `classes` (of size_classes): the last class
/// whose low is at most `diameter` (0 below the first).
std::size_t size_class_of(std::span<const SizeClass> classes, double diameter);

/// The statistics of a set of diameters (ISO 9276-2's moment ratios; docs/sizes.md).
struct SizeStatistics {
    std::uint64_t count = 0;        ///< number of diameters
    std::vector<SizeClass> classes; ///< size_classes, with counts and fractions
    /// d10, d50, d90 by volume: where Q3 reaches 0.1, 0.5, 0.9, with Q3 known at each distinct
    /// diameter (the volume of the spheres at most that size over all; 0 at the smallest) and
    /// linear in d between them, as between the sieves of a sieve analysis
    double d10 = 0.0;
    double d50 = 0.0;
    double d90 = 0.0;
    double sauter_mean = 0.0; ///< d32 = sum d^3 / sum d^2
    double volume_mean = 0.0; ///< d43 = sum d^4 / sum d^3 (De Brouckere)
    double number_mean = 0.0; ///< the arithmetic mean diameter, sum d / n
    double number_sd = 0.0;   ///< standard deviation of the diameters by number (over n)
    double smallest = 0.0;    ///< smallest diameter
    double largest = 0.0;     ///< largest diameter
    double size_ratio = 0.0;  ///< largest / smallest
};

/// \return the statistics of `diameters` (all zero, no classes, for none). Sums are
/// compensated (Neumaier) over the sorted diameters: the same result for any order.
/// \param diameters > 0 and finite, any order, any unit (the results are in the same)
/// \param bins the classes of a continuous set (size_classes)
/// \throws InvalidInput when a diameter is not a finite number > 0
SizeStatistics size_statistics(std::span<const double> diameters,
                               std::size_t bins = default_size_bins);

/// The statistics of a bed's sizes as summary.json records them: count, d10, d50, d90 (by
/// volume), the Sauter mean d32, d43, the number mean and standard deviation, the smallest
/// and largest diameter and their ratio, and each class's range, count and number and volume
/// fractions.
nlohmann::json size_statistics_summary(const SizeStatistics& statistics);

} // namespace packbed
