#include "packbed/soft_sphere.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <numbers>
#include <optional>
#include <type_traits>

#include <fmt/format.h>

#include "base/parallel.hpp"
#include "base/require.hpp"
#include "generate/soft_bed.hpp"
#include "packbed/bed_volume.hpp"
#include "packbed/error.hpp"
#include "packbed/limits.hpp"
#include "packbed/neighbor_list.hpp"
#include "packbed/sphere_shape.hpp"
#include "packbed/version.hpp"

namespace packbed {

namespace {

using detail::require;

/// Largest values seen in one iteration.
struct SweepStats {
    double pair = 0.0;  ///< largest sphere-sphere overlap, Dp
    double wall = 0.0;  ///< largest sphere-wall overlap, Dp
    double top = 0.0;   ///< highest centre after the move, Dp
    bool finite = true; ///< every new position finite
};

} // namespace

void SoftSphereParameters::validate() const {
    if (const std::optional<double> a = aspect_ratio()) {
        require(std::isfinite(*a) && *a >= 1.0 && *a <= 1e4, "aspect-ratio", *a,
                "1 <= a <= 10000 (a < 1: one sphere does not fit)");
    } else {
        const std::string problem = container.fit_problem(largest_size());
        if (!problem.empty())
            throw InvalidInput(fmt::format("--container {} (in units of Dp) is not allowed; "
                                           "allowed: {}",
                                           container.spec(), problem));
    }
    require(particles >= 1 && particles <= 100'000'000, "particles", static_cast<double>(particles),
            "1 to 100000000");
    // Bounded so that lengths, and volumes (diameter^3), stay finite doubles in every unit.
    require(diameter >= 1e-12 && diameter <= 1e12, "diameter", diameter, "1e-12 to 1e12");
    require(e0 > 0.0 && e0 < 1.0, "e0", e0, "0 < e0 < 1");
    require(ck >= limits::min_ck && ck < 1.0, "ck", ck,
            fmt::format("{:g} <= ck < 1 (from ck = 1 on, even a single overlapping pair does not "
                        "converge; below {:g} the iterations grow past any useful number)",
                        limits::min_ck, limits::min_ck));
    require(cg_step > 0.0 && cg_step <= 5e-6, "cg-step", cg_step,
            "0 < cg-step <= 5e-6 (larger steps keep Cg from settling)");
    const Schedule s = schedule();
    require(s.overlap_low > 0.0 && s.overlap_low < 0.5, "overlap-low", s.overlap_low,
            "0 < overlap-low < 0.5 (Dp)");
    require(s.overlap_high > s.overlap_low && s.overlap_high < 0.5, "overlap-high", s.overlap_high,
            fmt::format("overlap-low ({}) < overlap-high < 0.5 (Dp)", s.overlap_low));
    require(tolerance >= limits::min_tolerance && tolerance <= 1e-2, "tolerance", tolerance,
            fmt::format("{:g} <= tolerance <= 0.01 (Dp; below {:g} the rounding of the positions "
                        "is not below the tolerance)",
                        limits::min_tolerance, limits::min_tolerance));
    require(mc_period >= 1 && mc_period <= 1'000'000, "mc-period", mc_period, "1 to 1000000");
    require(mc_window >= 2 && mc_window <= 10'000, "mc-window", mc_window, "2 to 10000");
    require(s.mc_tolerance > 0.0 && s.mc_tolerance <= 100.0, "mc-tolerance", s.mc_tolerance,
            "0 < mc-tolerance <= 100 (percent)");
    require(list_skin() > 0.0 && list_skin() <= 1.0, "skin", list_skin(), "0 < skin <= 1 (Dp)");
    require(layer_height == 0.0 || (layer_height >= 10.0 && layer_height <= 1e6), "layer-height",
            layer_height, "0 (one piece) or 10 to 1000000 (Dp)");
    require(friction >= 0.0 && friction <= 100.0, "friction", friction, "0 to 100");
    require(wall_friction >= 0.0 && wall_friction <= 100.0, "wall-friction", wall_friction,
            "0 to 100");
    if (frictional() && solver != Solver::fire)
        throw InvalidInput(fmt::format("--solver {} with {} is not allowed; allowed: friction "
                                       "with --solver fire (the paper's iteration has no "
                                       "rotations)",
                                       to_string(solver), friction_options()));
    require(max_iterations >= 1, "max-iterations", static_cast<double>(max_iterations), ">= 1");
    if (sizes.empty())
        return check_top();
    if (sizes.size() != particles)
        throw InvalidInput(fmt::format("--sizes gives {} diameters for {} particles; allowed: one "
                                       "per particle",
                                       sizes.size(), particles));
    const auto [smallest, largest] = std::minmax_element(sizes.begin(), sizes.end());
    const Container shape = container;
    const std::optional<double> tube = shape.tube_diameter();
    // Written to fail on NaN: every comparison with NaN is false. Another container's fit to
    // the largest sphere was checked above.
    for (const double d : sizes)
        if (!(d > 0.0 && (!tube || d < *tube)))
            throw InvalidInput(
                tube ? fmt::format("--sizes: a diameter of {:.6g} Dp is not allowed in a tube of "
                                   "a = {:.6g}; allowed: diameters > 0 and below the tube's (a "
                                   "Dp, Dp = {:.6g} the reference diameter)",
                                   d, *tube, diameter)
                     : fmt::format("--sizes: a diameter of {:.6g} Dp is not allowed; allowed: "
                                   "diameters > 0",
                                   d));
    if (!(*largest / *smallest <= max_size_ratio))
        throw InvalidInput(fmt::format(
            "--sizes: the largest diameter is {:.6g} times the smallest; allowed: at most {:g} "
            "(the size ratio the solvers are tested for)",
            *largest / *smallest, max_size_ratio));
    check_top();
}

/// A container that ends (a cone) holds the initial bed below its top: the paper's L0 and
/// the largest sphere.
void SoftSphereParameters::check_top() const {
    const Container shape = container;
    const std::optional<double> top = shape.top();
    if (!top)
        return;
    const double height = initial_bed_height(*this) + largest_size();
    if (!(height <= *top))
        throw InvalidInput(fmt::format(
            "--particles {} is not allowed in --container {} (in units of Dp): {}; allowed: a "
            "bed below the container's top at {:.6g} Dp (fewer particles or a taller "
            "container)",
            particles, shape.spec(),
            std::isfinite(height)
                ? fmt::format("the bed's initial height, eq. (6) at e0 = {:g}, is about {:.6g} "
                              "Dp with the largest sphere",
                              e0, height)
                : fmt::format("the container holds less than the bed's initial volume at e0 = "
                              "{:g}, eq. (6)",
                              e0),
            *top));
}

double initial_bed_height(std::uint64_t particles, double aspect_ratio, double e0) {
    return 2.0 / 3.0 * static_cast<double>(particles) / (aspect_ratio * aspect_ratio * (1.0 - e0));
}

double initial_bed_height(const SoftSphereParameters& p) {
    double solid = 0.0; // sum of (d_i / Dp)^3, in generation order
    if (p.sizes.empty())
        solid = static_cast<double>(p.particles);
    for (const double d : p.sizes)
        solid += d * d * d;
    return p.container.fill_height(solid, p.e0);
}

SoftSphereParameters::Schedule SoftSphereParameters::schedule() const {
    const Schedule& own = solver == Solver::paper ? paper_schedule : fire_schedule;
    return {overlap_low.value_or(own.overlap_low), overlap_high.value_or(own.overlap_high),
            mc_tolerance.value_or(own.mc_tolerance)};
}

double SoftSphereParameters::list_skin() const {
    return skin.value_or(solver == Solver::paper ? paper_skin : fire_skin);
}

double SoftSphereParameters::smallest_size() const {
    return sizes.empty() ? 1.0 : *std::min_element(sizes.begin(), sizes.end());
}

std::string SoftSphereParameters::friction_options() const {
    std::string named;
    if (friction > 0.0)
        named = fmt::format("--friction {}", friction);
    if (wall_friction > 0.0)
        named += fmt::format("{}--wall-friction {}", named.empty() ? "" : " and ", wall_friction);
    return named;
}

double SoftSphereParameters::largest_size() const {
    return sizes.empty() ? 1.0 : *std::max_element(sizes.begin(), sizes.end());
}

nlohmann::ordered_json progress_json(const Progress& p) {
    nlohmann::ordered_json out = {{"stage", p.stage},
                                  {"iteration", p.iteration},
                                  {"cg", p.cg},
                                  {"max_overlap_pair", p.max_overlap_pair},
                                  {"max_overlap_wall", p.max_overlap_wall},
                                  {"mass_centre_z", p.mass_centre_z},
                                  {"layer", p.layer},
                                  {"layers", p.layers}};
    if (!p.run.empty())
        out["run"] = p.run;
    return out;
}

Overlaps measure_overlaps(const Packing& packing, const Container& container) {
    return measure_overlaps(spheres(packing), container);
}

struct SoftSphereGenerator::State : detail::SoftBed {
    SoftSphereParameters params;
    double cg = 0.0;
    std::uint64_t iterations = 0;
    std::vector<StageRecord> stages;

    explicit State(const SoftSphereParameters& p)
        : SoftBed(p.container)
        , params(detail::in_dp(p)) {}

    void generate() { SoftBed::generate(params); }

    /// One iteration of eq. (4) with gravity parameter Cg = `gravity`, then the rigid floor z >=
    /// r_i.
    template <UpdateOrder update> SweepStats sweep(double gravity) {
        if (list_stale())
            rebuild_list(params.list_skin());
        const detail::LinearOverlapLaw law{params.ck};
        const std::size_t n = packing.size();
        Vec3* const x = packing.centers.data();
        const double* const radius = packing.radii.data();
        const Vec3* const reference = list.reference().data();
        double pair = 0.0, wall = 0.0, top = 0.0, drift = 0.0;
        bool finite = true;
        // Each sphere's step length and weight (SoftBed::mobility, weight; 1 when mono-sized).
        auto move_of = [&](std::size_t k, double& pair_k, double& wall_k) {
            Vec3 move = contact_move(k, law, pair_k, wall_k) * mobility(radius[k]);
            move.z -= gravity * weight(radius[k]);
            Vec3 moved = x[k] + move;
            moved.z = std::max(moved.z, radius[k]);
            return moved;
        };
        if constexpr (update == UpdateOrder::simultaneous) {
            // Two passes: the factor of each pair once, then the moves (contact_move's bits).
#pragma omp parallel if (n >= detail::parallel_min_spheres)
            {
                const std::size_t pairs = list.pairs();
                const std::size_t chunks = (pairs + pair_chunk - 1) / pair_chunk;
#pragma omp for schedule(static) reduction(max : pair)
                for (std::size_t c = 0; c < chunks; ++c)
                    pair = std::max(pair, pair_factors(c * pair_chunk,
                                                       std::min(pairs, (c + 1) * pair_chunk), law));
#pragma omp for schedule(static) reduction(max : wall, top, drift) reduction(&& : finite)
                for (std::size_t k = 0; k < n; ++k) {
                    Vec3 move = contact_move_from_factors(k, law, wall) * mobility(radius[k]);
                    move.z -= gravity * weight(radius[k]);
                    Vec3 moved = x[k] + move;
                    moved.z = std::max(moved.z, radius[k]);
                    finite = finite && is_finite(moved);
                    top = std::max(top, moved.z);
                    drift = std::max(drift, norm2(moved - reference[k]));
                    next[k] = moved;
                }
            }
            packing.centers.swap(next);
        } else {
            for (std::size_t i = 0; i < n; ++i) { // generation order
                const std::size_t k = slot[i];
                const Vec3 moved = move_of(k, pair, wall);
                finite = finite && is_finite(moved);
                top = std::max(top, moved.z);
                drift = std::max(drift, norm2(moved - reference[k]));
                x[k] = moved;
            }
        }
        drift2 = drift;
        ++iterations;
        return {pair, wall, top, finite};
    }

    SweepStats sweep(double gravity) {
        return params.update == UpdateOrder::simultaneous
                   ? sweep<UpdateOrder::simultaneous>(gravity)
                   : sweep<UpdateOrder::in_place>(gravity);
    }

    /// Stop with an error naming the stage, the iteration and what to lower, when the
    /// iteration has left the region where it converges.
    void check(const SweepStats& s, std::string_view stage, bool gravity_on) const {
        std::string what;
        if (!s.finite)
            what = "a position became NaN or infinite";
        else if (s.wall >= (gravity_on ? 0.5 : 2.5))
            // Centre beyond the wall; the random start may overshoot transiently, so the
            // initial stage only stops when the centre is 2 Dp out.
            what = fmt::format("a sphere left the container through the wall (overlap {:.3g} Dp)",
                               s.wall);
        else if (s.top > ceiling)
            what = fmt::format("a sphere was thrown to z = {:.3g} Dp, above {:.3g} Dp", s.top,
                               ceiling);
        else if (gravity_on && s.pair > 0.5)
            what = fmt::format("the largest overlap grew to {:.3g} Dp", s.pair);
        if (what.empty())
            return;
        throw ConvergenceError(
            fmt::format("diverged in the {} stage at iteration {}: {}; lower --ck (now {}){}",
                        stage, iterations, what, params.ck,
                        gravity_on ? fmt::format(" or --cg-step (now {})", params.cg_step) : ""));
    }

    void check_budget(std::string_view stage, const SweepStats& s) const {
        if (iterations >= params.max_iterations)
            throw ConvergenceError(fmt::format(
                "the {} stage did not finish within --max-iterations {} (largest overlap now "
                "{:.3g} Dp); raise --max-iterations, or lower --ck (now {}) or --cg-step (now {}) "
                "if the overlaps or the mass centre keep oscillating",
                stage, params.max_iterations, s.pair, params.ck, params.cg_step));
    }

    /// Every mc_period iterations: budget, cancellation and progress.
    void report(const RunControl& control, std::string_view stage, const SweepStats& s,
                double mass_centre) const {
        check_budget(stage, s);
        if (control.should_stop && control.should_stop())
            throw Cancelled();
        if (control.on_progress)
            control.on_progress({stage, iterations, cg, s.pair, s.wall, mass_centre});
    }

    /// \return the exact overlaps of the current configuration when both are below the
    /// tolerance; nothing otherwise.
    std::optional<Overlaps> converged(const SweepStats& s) const {
        if (s.pair >= params.tolerance || s.wall >= params.tolerance)
            return std::nullopt;
        // The iteration saw small overlaps; confirm them on the configuration it left.
        const Overlaps now = measure_overlaps(packing, container);
        if (now.pair < params.tolerance && now.wall < params.tolerance)
            return now;
        return std::nullopt;
    }

    StageRecord record(std::string name, std::uint64_t start, const SweepStats& s,
                       const detail::MassCentreWindow& window) {
        StageRecord r;
        r.name = std::move(name);
        r.iterations = iterations - start;
        r.cg = cg;
        r.max_overlap_pair = s.pair;
        r.max_overlap_wall = s.wall;
        r.mass_centre_z = mass_centre_z();
        r.mass_centre_window = window.values();
        return r;
    }
};

SoftSphereGenerator::SoftSphereGenerator(const SoftSphereParameters& parameters) {
    parameters.validate();
    m_state = std::make_unique<State>(parameters);
    m_state->generate();
}

SoftSphereGenerator::~SoftSphereGenerator() = default;

const Packing& SoftSphereGenerator::packing_dp() const {
    return m_state->packing_in_generation_order();
}
const SoftSphereParameters& SoftSphereGenerator::parameters() const {
    return m_state->params;
}

StageRecord SoftSphereGenerator::run_initial_stage(const RunControl& control) {
    State& st = *m_state;
    const std::uint64_t start = st.iterations;
    detail::MassCentreWindow window(st.params.mc_window, st.params.schedule().mc_tolerance);
    st.cg = 0.0;
    for (;;) {
        const SweepStats s = st.sweep(0.0);
        st.check(s, "initial", false);
        if (const auto now = st.converged(s))
            return st.record("initial", start, {now->pair, now->wall, s.top, true}, window);
        if ((st.iterations - start) % st.params.mc_period == 0)
            st.report(control, "initial", s, st.mass_centre_z());
    }
}

StageRecord SoftSphereGenerator::run_intermediate_stage(const RunControl& control) {
    State& st = *m_state;
    const SoftSphereParameters& p = st.params;
    const std::uint64_t start = st.iterations;
    const SoftSphereParameters::Schedule schedule = p.schedule();
    detail::MassCentreWindow window(p.mc_window, schedule.mc_tolerance);
    st.cg = 0.0; // "starting from a null initial value"
    for (;;) {
        const SweepStats s = st.sweep(st.cg);
        st.check(s, "intermediate", true);
        // Eq. (7): keep the largest pair overlap inside [delta_L, delta_U].
        if (s.pair < schedule.overlap_low)
            st.cg += p.cg_step;
        else if (s.pair > schedule.overlap_high)
            st.cg = std::max(st.cg - p.cg_step, 0.0);
        if ((st.iterations - start) % p.mc_period == 0) {
            const double mc = st.mass_centre_z();
            window.push(mc);
            st.report(control, "intermediate", s, mc);
            if (window.settled())
                return st.record("intermediate", start, s, window);
        }
    }
}

StageRecord SoftSphereGenerator::run_final_stage(const RunControl& control) {
    State& st = *m_state;
    const SoftSphereParameters& p = st.params;
    const std::uint64_t start = st.iterations;
    const double mc_tolerance = p.schedule().mc_tolerance;
    detail::MassCentreWindow window(p.mc_window, mc_tolerance);
    std::uint32_t steps = 0;
    // Below this Cg, gravity moves a sphere by less than 1e-8 of the tolerance per iteration.
    const double stalled_cg = 1e-8 * p.tolerance;
    detail::StallGuard guard(p.mc_window, p.mc_period);
    for (;;) {
        // A new step: Cg halved, held constant until the mass centre settles.
        st.cg *= 0.5;
        ++steps;
        window = detail::MassCentreWindow(p.mc_window, mc_tolerance);
        for (std::uint64_t k = 1;; ++k) {
            const SweepStats s = st.sweep(st.cg);
            st.check(s, "final", true);
            if (const auto now = st.converged(s)) {
                StageRecord r =
                    st.record("final", start, {now->pair, now->wall, s.top, true}, window);
                r.steps = steps;
                return r;
            }
            bool settled = false;
            if (k % p.mc_period == 0) {
                const double mc = st.mass_centre_z();
                window.push(mc);
                st.report(control, "final", s, mc);
                settled = window.settled();
            }
            // Gravity has become negligible, yet the overlaps stay above the tolerance: spheres
            // pressed flat on the floor are lifted and the iteration goes on, or the bed is
            // jammed or the iteration caught in a cycle (detail::StallGuard). The case once
            // taken for a cycle (in-place, Ck 0.45, a = 4) was such a floor layer.
            if (st.cg < stalled_cg && k % p.mc_period == 0) {
                const auto verdict =
                    guard.record(st, std::max(s.pair, s.wall), p.tolerance, 0, st.iterations);
                if (verdict == detail::StallGuard::Verdict::lifted) {
                    window = detail::MassCentreWindow(p.mc_window, mc_tolerance);
                    continue;
                }
                if (verdict == detail::StallGuard::Verdict::jammed)
                    throw ConvergenceError(fmt::format(
                        "diverged in the final stage at iteration {}: the largest overlaps stay "
                        "at {:.3g} (pair) and {:.3g} (wall) Dp while Cg fell to {:.3g}; {}",
                        st.iterations, s.pair, s.wall, st.cg,
                        p.update == UpdateOrder::in_place
                            ? fmt::format("lower --ck (now {}) or use --update simultaneous", p.ck)
                            : std::string("the bed is jammed; another --seed gives another bed")));
            }
            if (settled)
                break;
        }
    }
}

Overlaps SoftSphereGenerator::iterate(double cg) {
    const SweepStats s = m_state->sweep(cg);
    return {s.pair, s.wall};
}

SoftSphereResult SoftSphereGenerator::run(const RunControl& control) {
    const auto t0 = std::chrono::steady_clock::now();
    State& st = *m_state;
    st.stages.clear();
    st.stages.push_back(run_initial_stage(control));
    st.stages.push_back(run_intermediate_stage(control));
    st.stages.push_back(run_final_stage(control));

    SoftSphereResult result;
    st.fill_result(result, st.params.diameter);
    result.iterations = st.iterations;
    result.stages = st.stages;
    result.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    return result;
}

SoftSphereResult generate_soft_sphere(const SoftSphereParameters& parameters,
                                      const RunControl& control) {
    if (parameters.solver == Solver::fire)
        return relax_with_fire(parameters, control);
    return SoftSphereGenerator(parameters).run(control);
}

const Registry<Solver>& solvers() {
    static const Registry<Solver> names("solver",
                                        {{"paper", Solver::paper}, {"fire", Solver::fire}});
    return names;
}

std::string to_string(Solver solver) {
    return solvers().name(solver);
}

const Registry<UpdateOrder>& update_orders() {
    static const Registry<UpdateOrder> names(
        "update",
        {{"in-place", UpdateOrder::in_place}, {"simultaneous", UpdateOrder::simultaneous}});
    return names;
}

std::string to_string(UpdateOrder order) {
    return update_orders().name(order);
}

nlohmann::json soft_sphere_parameters_json(const SoftSphereParameters& p) {
    const SoftSphereParameters::Schedule schedule = p.schedule(); // the values the run used
    const std::optional<double> a = p.aspect_ratio();
    return {{"aspect_ratio", a ? nlohmann::json(*a) : nlohmann::json(nullptr)},
            {"particles", p.particles},
            {"seed", p.seed},
            {"diameter", p.diameter},
            {"e0", p.e0},
            {"ck", p.ck},
            {"cg_step", p.cg_step},
            {"overlap_low", schedule.overlap_low},
            {"overlap_high", schedule.overlap_high},
            {"tolerance", p.tolerance},
            {"mc_period", p.mc_period},
            {"mc_window", p.mc_window},
            {"mc_tolerance", schedule.mc_tolerance},
            {"update", to_string(p.update)},
            {"solver", to_string(p.solver)},
            {"skin", p.list_skin()},
            {"layer_height", p.layer_height},
            {"friction", p.friction},
            {"wall_friction", p.wall_friction},
            {"max_iterations", p.max_iterations}};
}

nlohmann::json soft_sphere_summary(const SoftSphereParameters& p, const SoftSphereResult& result,
                                   double band_clearance, int threads) {
    using nlohmann::json;
    const double d = p.diameter;
    json summary;
    summary["version"] = std::string(version);
    summary["generator"] = "soft-sphere (Salvat et al. 2005)";
    if (const std::optional<double> a = p.aspect_ratio())
        summary["aspect_ratio"] = *a; // another container has none: its spec
    summary["particles"] = p.particles;
    summary["seed"] = p.seed;
    summary["diameter"] = d;
    summary["container"] = result.container.summary_json();
    summary["container"]["height"] = bed_top(result.packing);
    summary["container"]["bottom"] = 0.0;
    if (const std::string_view axis = result.container.axis(); !axis.empty())
        summary["container"]["axis"] = axis;

    const auto band = band_clear_of_ends(result.packing, band_clearance * d);
    if (band) {
        summary["void_fraction"] =
            void_fraction(result.packing, result.container, band->z_low, band->z_high);
        summary["void_fraction_band"] = {band->z_low, band->z_high};
    } else {
        summary["void_fraction"] = nullptr;
        summary["void_fraction_band"] = nullptr;
        summary["void_fraction_note"] =
            "the bed is not taller than twice the band clearance; lower --band-clearance";
    }
    summary["band_clearance"] = band_clearance;
    summary["max_overlap_pair"] = result.max_overlap_pair;
    summary["max_overlap_wall"] = result.max_overlap_wall;
    if (result.residuals) {
        summary["force_residual"] = result.residuals->first;
        summary["torque_residual"] = result.residuals->second;
    }
    summary["iterations"] = result.iterations;
    summary["initial_height"] = result.initial_height;
    summary["neighbor_list_builds"] = result.neighbor_builds;
    summary["layers"] = result.layers;
    json stages = json::array();
    for (const auto& s : result.stages)
        stages.push_back({{"name", s.name},
                          {"iterations", s.iterations},
                          {"steps", s.steps},
                          {"cg", s.cg},
                          {"max_overlap_pair", s.max_overlap_pair},
                          {"max_overlap_wall", s.max_overlap_wall},
                          {"mass_centre_z", s.mass_centre_z * d}});
    summary["stages"] = stages;
    summary["parameters"] = soft_sphere_parameters_json(p);
    summary["parameters"].erase("aspect_ratio"); // these four are at the top level
    summary["parameters"].erase("particles");
    summary["parameters"].erase("seed");
    summary["parameters"].erase("diameter");
    summary["parameters"]["band_clearance"] = band_clearance;
    summary["parameters"]["threads"] = threads;
    summary["units"] = {{"length", "diameter units as given by --diameter"},
                        {"max_overlap_pair", "Dp"},
                        {"max_overlap_wall", "Dp"},
                        {"overlap_low", "Dp"},
                        {"overlap_high", "Dp"},
                        {"tolerance", "Dp"},
                        {"mc_tolerance", "percent"},
                        {"skin", "Dp"},
                        {"layer_height", "Dp"},
                        {"band_clearance", "Dp"}};
    if (result.residuals) {
        summary["units"]["force_residual"] = "k Dp (k the contact stiffness)";
        summary["units"]["torque_residual"] = "k Dp^2";
    }
    summary["seconds"] = result.seconds;
    return summary;
}

} // namespace packbed
