#include "packbed/time_left.hpp"

#include <algorithm>
#include <cmath>

namespace packbed {

namespace {

// Longer stage histories are thinned (every other report dropped) so memory stays bounded.
constexpr std::size_t max_history = 4096;
// Least fall of ln q over the fitted reports that counts as a trend.
constexpr double min_fall = 0.1;

} // namespace

bool StageTimeLeft::typical_lengths_known(const SoftSphereParameters& parameters) {
    const SoftSphereParameters::Schedule s = parameters.schedule();
    const SoftSphereParameters::Schedule f = SoftSphereParameters::fire_schedule;
    return parameters.solver == Solver::fire && s.overlap_low == f.overlap_low &&
           s.overlap_high == f.overlap_high && s.mc_tolerance == f.mc_tolerance;
}

StageTimeLeft::StageTimeLeft(const SoftSphereParameters& parameters)
    : m_typical(typical_lengths_known(parameters))
    , m_mc_period(parameters.mc_period)
    , m_tolerance(parameters.tolerance)
    , m_mc_window(parameters.mc_window)
    , m_mc_fraction(parameters.schedule().mc_tolerance / 100.0) {}

std::optional<double> StageTimeLeft::update(const Progress& progress, double seconds) {
    if (progress.stage != m_stage) {
        m_stage = progress.stage;
        m_mass_centres.clear();
        m_history.clear();
        m_final_start_q =
            std::max(progress.max_overlap_pair, progress.max_overlap_wall) / m_tolerance;
        m_final_start_cg = progress.cg;
        m_stage_first_iteration = progress.iteration;
        m_stage_first_seconds = seconds;
    }
    // Fire's intermediate stage, within its typical length: the steps still to go at the
    // stage's seconds per step (the class comment). The reports still feed the fit below.
    std::optional<double> typical_left;
    const std::uint64_t run = progress.iteration - m_stage_first_iteration; // since 1st report
    if (m_typical && m_stage == "intermediate" && run > 0 &&
        run + m_mc_period < typical_intermediate_steps) {
        const double per_step = (seconds - m_stage_first_seconds) / static_cast<double>(run);
        typical_left = static_cast<double>(typical_intermediate_steps - run - m_mc_period) *
                       std::max(0.0, per_step);
    }
    double q = 0.0;
    if (m_stage == "intermediate") {
        m_mass_centres.push_back(progress.mass_centre_z);
        if (m_mass_centres.size() > m_mc_window)
            m_mass_centres.pop_front();
        if (m_mass_centres.size() < m_mc_window)
            return typical_left;
        const auto [lo, hi] = std::minmax_element(m_mass_centres.begin(), m_mass_centres.end());
        double mean = 0.0;
        for (const double v : m_mass_centres)
            mean += v;
        mean /= static_cast<double>(m_mass_centres.size());
        q = (*hi - *lo) / (m_mc_fraction * std::abs(mean));
    } else if (m_stage == "final" && m_final_start_cg > 0.0) {
        // The overlaps of a settled bed are proportional to Cg: the overlaps this Cg leaves.
        q = m_final_start_q * progress.cg / m_final_start_cg;
        if (std::max(progress.max_overlap_pair, progress.max_overlap_wall) < m_tolerance)
            q = 1.0;
    } else {
        q = std::max(progress.max_overlap_pair, progress.max_overlap_wall) / m_tolerance;
    }
    if (!(q > 0.0) || !std::isfinite(q))
        return typical_left;
    if (m_history.size() == max_history) {
        std::size_t kept = 0;
        for (std::size_t i = 1; i < m_history.size(); i += 2)
            m_history[kept++] = m_history[i];
        m_history.resize(kept);
    }
    m_history.emplace_back(seconds, std::log(q));
    if (q <= 1.0)
        return 0.0;
    if (typical_left)
        return typical_left;

    // Least-squares slope of ln q against time over the last half of the stage's reports.
    const std::size_t n =
        std::max(min_reports, m_stage == "final" ? m_history.size() : m_history.size() / 2);
    if (m_history.size() < n)
        return std::nullopt;
    double st = 0.0, sy = 0.0;
    const auto first = m_history.end() - static_cast<std::ptrdiff_t>(n);
    for (auto it = first; it != m_history.end(); ++it) {
        st += it->first;
        sy += it->second;
    }
    const double mt = st / static_cast<double>(n), my = sy / static_cast<double>(n);
    double stt = 0.0, sty = 0.0;
    for (auto it = first; it != m_history.end(); ++it) {
        stt += (it->first - mt) * (it->first - mt);
        sty += (it->first - mt) * (it->second - my);
    }
    if (!(stt > 0.0))
        return std::nullopt;
    const double slope = sty / stt; // d ln q / dt
    // No estimate unless q has clearly fallen over the fit (a tenth in ln q), so noise on a
    // level q (a final-stage Cg held until the bed settles) does not read as a trend.
    const double span = m_history.back().first - first->first;
    if (!(-slope * span > min_fall))
        return std::nullopt;
    const double fitted_now = my + slope * (seconds - mt); // ln q on the fitted line
    return std::max(0.0, fitted_now / -slope);
}

std::optional<double> LayerTimeLeft::update(const Progress& progress, double seconds) {
    if (!m_started || progress.layer != m_layer) {
        if (m_started && progress.layer == m_layer + 1) {
            if (m_layer == 0) {
                m_bottom_seconds = seconds - m_layer_start;
            } else {
                ++m_timed;
                m_timed_seconds += seconds - m_layer_start;
            }
        }
        if (!m_started) {
            m_first_iteration = progress.iteration;
            m_first_seconds = seconds;
        }
        m_started = true;
        m_layer = progress.layer;
        m_layer_start = seconds;
        m_layer_first_iteration = progress.iteration;
    }
    const double to_come = progress.layers > progress.layer + 1
                               ? static_cast<double>(progress.layers - progress.layer - 1)
                               : 0.0;
    const bool bottom = progress.layer == 0;
    double later = 0.0; // a later layer's time
    if (m_timed > 0) {
        later = m_timed_seconds / m_timed;
    } else if (m_bottom_seconds > 0.0) {
        later = later_layer_cost * m_bottom_seconds;
    } else {
        // No layer over yet: the typical steps of the layers still to go (the class comment),
        // at this layer's seconds per step.
        const std::uint64_t run = progress.iteration - m_first_iteration;
        if (!m_typical || run == 0)
            return std::nullopt;
        const double per_step =
            std::max(0.0, (seconds - m_first_seconds) / static_cast<double>(run));
        const double in_layer = static_cast<double>(progress.iteration - m_layer_first_iteration);
        const double typical = static_cast<double>(StageTimeLeft::typical_piece_steps);
        const double later_per_step = bottom ? later_layer_cost * per_step : per_step;
        return per_step * std::max(0.0, typical - in_layer) + later_per_step * typical * to_come;
    }
    const double now = bottom ? later / later_layer_cost : later; // the current layer's time
    return later * to_come + std::max(0.0, now - (seconds - m_layer_start));
}

} // namespace packbed
