#include "packbed/random_array.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <numbers>
#include <random>
#include <vector>

#include <fmt/format.h>

#include "generate/random.hpp"
#include "packbed/container.hpp"
#include "packbed/error.hpp"
#include "packbed/limits.hpp"
#include "packbed/option_ranges.hpp"
#include "packbed/periodic.hpp"
#include "packbed/shape.hpp"
#include "packbed/version.hpp"

namespace packbed {

double RandomArrayParameters::cell() const {
    // To 9 significant digits, as the container's spec writes it: the cell is then exactly the
    // one the spec names, and the solid fraction (actual_solid_fraction) follows from it.
    const double edge =
        std::cbrt(static_cast<double>(count) * std::numbers::pi / 6.0 / solid_fraction) * diameter;
    return std::stod(fmt::format("{:.9g}", edge));
}

double RandomArrayParameters::actual_solid_fraction() const {
    const double edge = cell();
    return static_cast<double>(count) * std::numbers::pi / 6.0 * diameter * diameter * diameter /
           (edge * edge * edge);
}

double RandomArrayParameters::hard_sphere_fraction() const {
    return solid_fraction * std::pow(1.0 + gap, 3);
}

void RandomArrayParameters::validate() const {
    check_option("count",
                 static_cast<long long>(
                     std::min<std::uint64_t>(count, std::numeric_limits<long long>::max())),
                 option_range::random_array_count);
    check_option("solid-fraction", solid_fraction, option_range::random_array_solid_fraction);
    check_option("diameter", diameter, option_range::diameter);
    check_option("gap", gap, option_range::random_array_gap);
    check_option("sweeps",
                 static_cast<long long>(
                     std::min<std::uint64_t>(sweeps, std::numeric_limits<long long>::max())),
                 option_range::random_array_sweeps);
    if (!(hard_sphere_fraction() <= limits::max_hard_sphere_fraction))
        throw InvalidInput(fmt::format(
            "--solid-fraction {} with --gap {} is not allowed: its hard spheres of diameter "
            "(1 + gap) d fill {:.4g}; allowed: at most {} (hard spheres freeze at 0.494), a "
            "solid fraction up to {:.4g} with this gap",
            solid_fraction, gap, hard_sphere_fraction(), limits::max_hard_sphere_fraction,
            limits::max_hard_sphere_fraction / std::pow(1.0 + gap, 3)));
    if (static_cast<double>(count) * static_cast<double>(sweeps) > limits::max_random_array_moves)
        throw InvalidInput(fmt::format("--sweeps {} with --count {} is not allowed: {:.3g} trial "
                                       "moves; allowed: at most {:.0e} (spheres times sweeps)",
                                       sweeps, count,
                                       static_cast<double>(count) * static_cast<double>(sweeps),
                                       limits::max_random_array_moves));
    // The minimum image: each pair has one nearest copy when the cell is 2 sigma wide.
    const double sigma = (1.0 + gap) * diameter;
    if (!(cell() >= 2.0 * sigma))
        throw InvalidInput(fmt::format(
            "--count {} is not allowed at --solid-fraction {}: the cell's edge {:.4g} d is below "
            "twice the spheres' diameter (1 + gap) d; allowed: a count of at least {}",
            count, solid_fraction, cell() / diameter,
            static_cast<std::uint64_t>(std::ceil(8.0 * std::pow(1.0 + gap, 3) * solid_fraction *
                                                 6.0 / std::numbers::pi))));
}

namespace {

// How much the diameter a growth sweep keeps is raised each time no pair is closer than it:
// 4000 spheres at 0.45 took 1 647, 470 and 259 sweeps at 0.002, 0.01 and 0.03.
constexpr double growth = 0.03;

/// The spheres of a cubic periodic cell in a grid of cubic bins at least `width` wide (the
/// largest diameter a pair is tested at), each bin listing its spheres. Fewer than 3 bins a
/// side: every sphere is tested against every other one.
class HardSpheres {
public:
    HardSpheres(double edge, double width)
        : m_cell(edge, edge, edge)
        , m_edge(edge)
        , m_bins(std::max(1, static_cast<int>(std::floor(edge / width)))) {
        if (m_bins < 3)
            m_bins = 1;
        m_members.assign(static_cast<std::size_t>(m_bins) * m_bins * m_bins, {});
    }

    /// Add a sphere at p (inside the cell).
    void add(const Vec3& p) {
        m_bin_of.push_back(bin(p));
        m_members[m_bin_of.back()].push_back(static_cast<std::uint32_t>(x.size()));
        x.push_back(p);
    }

    /// \return whether a new sphere at p keeps every sphere at least `sigma` away.
    bool free(const Vec3& p, double sigma) const {
        const double s2 = sigma * sigma;
        bool clear = true;
        visit(p,
              [&](std::uint32_t j) { clear = clear && norm2(m_cell.separation(p, x[j])) >= s2; });
        return clear;
    }

    /// \return whether sphere i may move to p: every other sphere ends at least `sigma` away
    /// or, where it was closer, no closer than it was (an overlap of the start only shrinks).
    bool may_move(std::uint32_t i, const Vec3& p, double sigma) const {
        const double s2 = sigma * sigma;
        bool clear = true;
        visit(p, [&](std::uint32_t j) {
            if (j == i || !clear)
                return;
            const double now = norm2(m_cell.separation(p, x[j]));
            clear = now >= s2 || now >= norm2(m_cell.separation(x[i], x[j]));
        });
        return clear;
    }

    /// Move sphere i to p (inside the cell).
    void move(std::uint32_t i, const Vec3& p) {
        x[i] = p;
        const std::uint32_t b = bin(p);
        if (b == m_bin_of[i])
            return;
        std::vector<std::uint32_t>& from = m_members[m_bin_of[i]];
        from.erase(std::find(from.begin(), from.end(), i));
        m_members[b].push_back(i);
        m_bin_of[i] = b;
    }

    /// \return the smallest distance between two centres (their nearest copies) below `cut`,
    /// `cut` when none is closer.
    double closest(double cut) const {
        double best2 = cut * cut;
        for (std::uint32_t i = 0; i < x.size(); ++i)
            visit(x[i], [&](std::uint32_t j) {
                if (j > i)
                    best2 = std::min(best2, norm2(m_cell.separation(x[i], x[j])));
            });
        return std::sqrt(best2);
    }

    const Periods& cell() const { return m_cell; }

private:
    std::uint32_t bin(const Vec3& p) const {
        auto index = [&](double v) {
            return std::min(m_bins - 1, static_cast<int>(v / m_edge * m_bins));
        };
        return static_cast<std::uint32_t>((index(p.z) * m_bins + index(p.y)) * m_bins + index(p.x));
    }
    /// f(j) for every sphere j in p's bin and the 26 around it (every sphere with one bin).
    template <class F> void visit(const Vec3& p, F&& f) const {
        if (m_bins == 1) {
            for (const std::uint32_t j : m_members[0])
                f(j);
            return;
        }
        const std::uint32_t b = bin(p);
        const int bx = static_cast<int>(b % m_bins), by = static_cast<int>(b / m_bins % m_bins),
                  bz = static_cast<int>(b / m_bins / m_bins);
        for (int dz = -1; dz <= 1; ++dz)
            for (int dy = -1; dy <= 1; ++dy)
                for (int dx = -1; dx <= 1; ++dx) {
                    const int cx = (bx + dx + m_bins) % m_bins, cy = (by + dy + m_bins) % m_bins,
                              cz = (bz + dz + m_bins) % m_bins;
                    for (const std::uint32_t j :
                         m_members[static_cast<std::size_t>((cz * m_bins + cy) * m_bins + cx)])
                        f(j);
                }
    }

    Periods m_cell;
    double m_edge;
    int m_bins;
    std::vector<std::uint32_t> m_bin_of;
    std::vector<std::vector<std::uint32_t>> m_members;

public:
    std::vector<Vec3> x; ///< centres in [0, L)^3
};

/// One sweep: each sphere in index order tries a move uniform in the cube [-step, step]^3,
/// accepted when every other sphere stays `sigma` away. \return the moves accepted.
std::uint64_t sweep(HardSpheres& spheres, std::vector<Vec3>& travelled, double sigma, double step,
                    std::mt19937_64& rng) {
    std::uint64_t accepted = 0;
    for (std::uint32_t i = 0; i < spheres.x.size(); ++i) {
        Vec3 move;
        move.x = (2.0 * portable_random::uniform01(rng) - 1.0) * step;
        move.y = (2.0 * portable_random::uniform01(rng) - 1.0) * step;
        move.z = (2.0 * portable_random::uniform01(rng) - 1.0) * step;
        const Vec3 p = spheres.cell().wrapped(spheres.x[i] + move);
        if (spheres.may_move(i, p, sigma)) {
            spheres.move(i, p);
            travelled[i] += move;
            ++accepted;
        }
    }
    return accepted;
}

} // namespace

RandomArray random_array(const RandomArrayParameters& p, const RandomArrayProgress& progress) {
    p.validate();
    const double d = p.diameter;
    const double edge = p.cell();
    const double sigma = (1.0 + p.gap) * d;
    const std::size_t n = p.count;
    std::mt19937_64 rng(p.seed);

    // Random sequential addition at sigma_0: a quarter of the cell filled, far from RSA's
    // jamming at 0.384, so that a place is found in a few tries.
    const double sigma0 = sigma * std::min(1.0, std::cbrt(0.25 / p.hard_sphere_fraction()));
    HardSpheres spheres(edge, sigma);
    for (std::size_t i = 0; i < n; ++i)
        for (std::uint64_t tries = 0;; ++tries) {
            if (tries == 1'000'000)
                throw ConvergenceError("random-array: random sequential addition found no place "
                                       "for a sphere in 1e6 tries");
            const Vec3 c{portable_random::uniform01(rng) * edge,
                         portable_random::uniform01(rng) * edge,
                         portable_random::uniform01(rng) * edge};
            if (spheres.free(c, sigma0)) {
                spheres.add(c);
                break;
            }
        }

    RandomArray out;
    out.cell = edge;
    std::vector<Vec3> travelled(n, Vec3{});
    // The trial move: about 0.4 of the moves accepted (0.4 to 0.5 is the usual aim for hard
    // spheres), starting from a tenth of the mean distance between centres.
    double step = 0.1 * edge / std::cbrt(static_cast<double>(n));
    auto adapt = [&](std::uint64_t accepted) {
        const double rate = static_cast<double>(accepted) / static_cast<double>(n);
        step *= std::clamp(rate / 0.4, 0.5, 1.5);
        step = std::clamp(step, 1e-9 * d, 0.5 * edge);
        return rate;
    };

    // Growth: the diameter the sweeps keep, sigma_c, starts at the closest pair's distance and
    // is raised to (1 + growth) times it after each sweep that leaves no pair closer than
    // sigma_c, up to sigma. The pairs a raise puts below sigma_c are a growth's width apart,
    // and may_move only parts them.
    const std::uint64_t max_growth = 1'000'000;
    double closest = spheres.closest(sigma);
    double current = std::min(sigma, closest);
    for (;; closest = spheres.closest(sigma)) {
        if (closest >= current) {
            if (current == sigma)
                break;
            current = std::min(sigma, closest * (1.0 + growth));
        }
        if (out.growth_sweeps == max_growth)
            throw ConvergenceError(fmt::format(
                "random-array: after {} sweeps the spheres have grown to {:.6g} d of {:.6g} d; "
                "a lower --solid-fraction or --gap grows faster",
                max_growth, closest / d, sigma / d));
        adapt(sweep(spheres, travelled, current, step, rng));
        ++out.growth_sweeps;
        if (progress)
            progress(out.growth_sweeps, out.growth_sweeps + p.sweeps + 1);
    }

    std::uint64_t accepted = 0;
    for (std::uint64_t s = 0; s < p.sweeps; ++s) {
        const std::uint64_t a = sweep(spheres, travelled, sigma, step, rng);
        accepted += a;
        adapt(a);
        if (progress)
            progress(out.growth_sweeps + s + 1, out.growth_sweeps + p.sweeps);
    }
    out.acceptance = p.sweeps > 0 ? static_cast<double>(accepted) /
                                        (static_cast<double>(n) * static_cast<double>(p.sweeps))
                                  : 0.0;
    out.step = step / d;
    double moved = 0.0;
    for (const Vec3& t : travelled)
        moved += std::sqrt(norm2(t));
    out.mean_displacement = moved / static_cast<double>(n) / d;
    for (const Vec3& c : spheres.x)
        out.packing.add(c, 0.5 * d);
    return out;
}

nlohmann::json random_array_summary(const RandomArrayParameters& p, const RandomArray& array) {
    const Container container{Periodic(array.cell, array.cell)};
    const Periods cell(array.cell, array.cell, array.cell);
    const std::vector<Vec3>& x = array.packing.centers;
    double closest2 = std::numeric_limits<double>::infinity();
    if (x.size() <= 20'000) // a check that shares no code with the Monte Carlo's bins: O(N^2)
        for (std::size_t i = 0; i < x.size(); ++i)
            for (std::size_t j = i + 1; j < x.size(); ++j)
                closest2 = std::min(closest2, norm2(cell.separation(x[i], x[j])));
    nlohmann::json summary;
    summary["version"] = std::string(version);
    summary["generator"] = "random-array";
    summary["diameter"] = p.diameter;
    summary["count"] = p.count;
    summary["seed"] = p.seed;
    summary["solid_fraction"] = p.actual_solid_fraction();
    summary["void_fraction"] = 1.0 - p.actual_solid_fraction();
    summary["gap"] = p.gap;
    summary["hard_sphere_fraction"] = p.hard_sphere_fraction();
    summary["region"] = container.region_json(array.cell);
    summary["container"] = container.summary_json();
    summary["period_z"] = array.cell;
    summary["monte_carlo"] = {{"growth_sweeps", array.growth_sweeps},
                              {"sweeps", p.sweeps},
                              {"acceptance", array.acceptance},
                              {"step_d", array.step},
                              {"mean_displacement_d", array.mean_displacement}};
    summary["closest_distance_d"] =
        std::isfinite(closest2) ? nlohmann::json(std::sqrt(closest2) / p.diameter) : nullptr;
    return summary;
}

} // namespace packbed
