// An estimate of the time left in a stage of a soft-sphere run, from its progress reports.
#pragma once

#include <cstddef>
#include <cstdint>
#include <deque>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "packbed/soft_sphere.hpp"

namespace packbed {

/// Estimates how long the current stage of a run (either solver) still takes. Each stage ends
/// when one quantity q falls to 1:
///  - "initial": q = max(pair overlap, wall overlap) / tolerance;
///  - "final": the overlaps the current Cg leaves once the bed has settled, over the
///    tolerance: q = q0 Cg / Cg0 (q0 and Cg0 at the stage's first report; the overlaps of a
///    settled bed are proportional to Cg), fitted over the whole stage (it falls in steps);
///  - "intermediate": q = spread of the last mc_window mass-centre records / (mc_tolerance
///    percent of their mean), the paper's settling rule (section 3.3).
/// Both solvers converge roughly geometrically, so ln q falls roughly linearly in time. The
/// estimate is ln q / r, r being the least-squares rate of fall of ln q over the last half of
/// the stage's reports (at least `min_reports`). There is none while q does not fall (Cg still
/// ramping up, a rearranging bed), and it says nothing about the stages still to come.
///
/// One exception: the intermediate stage of the fire solver under its own schedule
/// (fire_schedule). There q falls fast while the bed lands and then creeps down a slow, noisy
/// tail that the rule ends where noise first takes q under 1, so a fit of q is up to half the
/// stage too short mid-stage (docs/notes/fire-schedule.md). That stage takes a nearly
/// fixed number of steps at every width (typical_intermediate_steps), so until it has run that
/// many the estimate is the steps still to go at the stage's own seconds per step; past them,
/// the fit.
class StageTimeLeft {
public:
    /// \param parameters the run's parameters (tolerance, mc_window, mc_tolerance)
    explicit StageTimeLeft(const SoftSphereParameters& parameters);

    /// Take one progress report made `seconds` after the start of the run (any monotone
    /// clock). \return the seconds left in the report's stage, or nothing when there is no
    /// estimate yet.
    std::optional<double> update(const Progress& progress, double seconds);

    /// Reports taken into the fit (fewer give no estimate).
    static constexpr std::size_t min_reports = 5;
    /// Steps of the fire solver's intermediate stage under fire_schedule: measured 7 500-9 200
    /// for beds of a = 20 and 30 (9 000 and 20 000 spheres, seeds 1-3), about 12 000 for a = 20,
    /// 1e4 spheres, seed 1, 5 300-10 800 for the layers of a = 20, 60 000 spheres, 4 700-8 800
    /// for smaller beds (docs/notes/fire-schedule.md; 9 500-10 200 with dt_max
    /// 0.2): near the upper end, so that the estimate is too long for a small bed (by a
    /// fraction of a second) rather than too short for a large one.
    static constexpr std::uint64_t typical_intermediate_steps = 10'000;
    /// Steps of a whole piece or layer of the fire solver under fire_schedule: the initial
    /// stage's 100-500, typical_intermediate_steps and the final stage's 900-1 800.
    static constexpr std::uint64_t typical_piece_steps = 11'300;

    /// \return true when `parameters` are the fire solver's under its own schedule (the
    /// measured stage lengths above hold).
    static bool typical_lengths_known(const SoftSphereParameters& parameters);

private:
    bool m_typical; // typical_lengths_known(parameters)
    std::uint32_t m_mc_period;
    std::uint64_t m_stage_first_iteration = 0; // of the stage's first report
    double m_stage_first_seconds = 0.0;
    double m_tolerance;
    std::size_t m_mc_window;
    double m_mc_fraction;
    std::string m_stage;
    double m_final_start_q = 0.0;  // q at the first report of the stage
    double m_final_start_cg = 0.0; // Cg at the first report of the stage
    std::deque<double> m_mass_centres;
    std::vector<std::pair<double, double>> m_history; // (seconds, ln q) in this stage
};

/// Estimates how long a fire run in layers (relax_with_fire) still takes. The bottom layer
/// (layer 0) is relaxed alone; every later one together with the layer under it, twice the
/// spheres: it takes later_layer_cost times as long. Later layers: the mean time of the later
/// layers seen (from their first report to the next layer's), times the layers still to come,
/// plus what the current layer has left of that mean; while none is over, later_layer_cost times
/// the bottom layer's time. Until a layer is over (a resumed run starts at a layer's beginning,
/// so its first layer counts too): under fire_schedule, the typical steps of the layers still
/// to go (StageTimeLeft::typical_piece_steps, less those the current layer has run; a later
/// layer's later_layer_cost times the bottom one's) at the run's seconds per step; otherwise
/// nothing.
class LayerTimeLeft {
public:
    /// No estimate before a layer is over.
    LayerTimeLeft() = default;
    /// \param parameters the run's: under fire_schedule the first layer has an estimate too
    explicit LayerTimeLeft(const SoftSphereParameters& parameters)
        : m_typical(StageTimeLeft::typical_lengths_known(parameters)) {}

    /// Take one progress report made `seconds` after the start of the run. \return the
    /// seconds left in the run, or nothing when there is no estimate yet.
    std::optional<double> update(const Progress& progress, double seconds);

    /// A later layer's time over the bottom layer's: 1.7-2.7, 2.0 on average (a = 20, 60 000
    /// spheres, seed 1, 2 threads; docs/notes/tall-beds.md; 2.1-2.8 with
    /// dt_max 0.2, whose longer creep weighed more in the taller parts).
    static constexpr double later_layer_cost = 2.0;

private:
    bool m_typical = false;
    bool m_started = false;
    double m_bottom_seconds = 0.0;       // the bottom layer's time, 0 until it is over
    std::uint64_t m_first_iteration = 0; // of the run's first report
    double m_first_seconds = 0.0;
    std::uint64_t m_layer_first_iteration = 0; // of the current layer's first report
    std::uint32_t m_layer = 0;
    double m_layer_start = 0.0;
    std::uint32_t m_timed = 0;
    double m_timed_seconds = 0.0;
};

} // namespace packbed
