// The soft-sphere packing algorithm of Salvat, Mariani, Barreto & Martinez, "An algorithm to
// simulate packing structure in cylindrical containers", Catalysis Today 107-108 (2005) 513-519.
// Mono-sized spheres in a cylinder: generation, initial, intermediate and final stages (section 3).
#pragma once

#include <algorithm>
#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include <nlohmann/json.hpp>

#include "packbed/container.hpp"
#include "packbed/neighbor_list.hpp"
#include "packbed/packing.hpp"
#include "packbed/particle_shape.hpp"
#include "packbed/registry.hpp"

namespace packbed {

/// How one iteration of eq. (4) applies the displacements.
enum class UpdateOrder {
    simultaneous, ///< all spheres move at once from the old positions (Jacobi); parallel
    in_place,     ///< one sphere after another, each seeing the moves made before it
                  ///< (Gauss-Seidel); sequential
};

/// The names users pick an update order by ("in-place", "simultaneous"): the one registry.
const Registry<UpdateOrder>& update_orders();
/// \return the name of an update order in update_orders().
std::string to_string(UpdateOrder order);

/// How the bed is relaxed. Both minimise the same energy (overlap springs, gravity, rigid
/// floor, elastic wall) and end at the same overlap tolerance; docs/generate.md says when
/// to use which.
enum class Solver {
    paper, ///< Salvat et al. (2005): eq. (4) iterated, Cg by eq. (7), mass-centre rule
    fire,  ///< FIRE (Bitzek et al. 2006) through the paper's stages, under fire_schedule
};

/// The names users pick a solver by ("paper", "fire"): the one registry.
const Registry<Solver>& solvers();
/// \return the name of a solver in solvers().
std::string to_string(Solver solver);

/// Every parameter of the algorithm; defaults are the paper's values, but for the solver (fire)
/// and the settling schedule, which is the chosen solver's own unless given (schedule()). Lengths
/// marked "Dp" are in units of the sphere diameter. Plain value type.
struct SoftSphereParameters {
    std::uint64_t particles = 500; ///< Np, >= 1
    std::uint64_t seed = 1;        ///< seed of the generation stage's random numbers
    double diameter = 1.0;         ///< Dp in output length units, 1e-12 to 1e12
    double e0 = 0.47;              ///< initial overall void fraction for L0, eq. (6); (0, 1)
    double ck = 0.3;               ///< elasticity parameter Ck of eq. (4); (0, 1)
    double cg_step = 1.25e-7;      ///< Delta Cg of the control loop, eq. (7); (0, 5e-6]
    /// Lower bound delta_L of eq. (7), Dp; unset: the solver's (schedule()).
    std::optional<double> overlap_low;
    /// Upper bound delta_U of eq. (7), Dp, low < high < 0.5; unset: the solver's (schedule()).
    std::optional<double> overlap_high;
    double tolerance = 1e-4;       ///< largest allowed final overlap, pair and wall, Dp
    std::uint32_t mc_period = 100; ///< iterations between mass-centre records
    std::uint32_t mc_window = 10;  ///< successive records that must agree
    /// Their allowed spread, percent of the mean; unset: the solver's (schedule()).
    std::optional<double> mc_tolerance;
    UpdateOrder update = UpdateOrder::simultaneous; ///< see UpdateOrder; docs/performance.md
    /// see Solver. fire by default: the same energy, stages and tolerances as the
    /// paper's, under fire_schedule, the paper's beds in 50-70x fewer iterations;
    /// Solver::paper reproduces the article exactly.
    Solver solver = Solver::fire;
    /// Verlet-list skin, Dp; (0, 1]; unset: the solver's (list_skin()).
    std::optional<double> skin;
    /// Fire solver: a bed whose L0 (eq. 6) exceeds twice this is relaxed in layers of about
    /// this height, bottom first (relax_with_fire); 0: in one piece. Dp; 0 or [10, 1e6].
    double layer_height = 30.0;
    /// Coulomb's friction coefficient between spheres (docs/generate.md, "Friction"):
    /// tangential springs capped by mu F_n at every contact, the spheres' rotations. 0: the
    /// paper's frictionless beds, bit for bit. The fire solver only; 0 to 100.
    double friction = 0.0;
    /// The same between a sphere and the container's walls and floor.
    double wall_friction = 0.0;
    std::uint64_t max_iterations = 200'000'000; ///< give up (ConvergenceError) beyond this
    /// Spheres of many sizes: each sphere's diameter in units of `diameter`, the
    /// reference diameter Dp that a and every length marked Dp refer to (packbed generate
    /// --sizes makes it the Sauter mean d32), in generation order; `particles` of them, each
    /// in (0, 2a) and at most max_size_ratio times the smallest. Empty: every sphere Dp, the
    /// paper's mono-sized bed, with the same bits as before sizes existed. With sizes, the
    /// tolerance and the control band of eq. (7) are in units of the smallest diameter (so
    /// every pair's overlap ends below tolerance x the smaller diameter of the pair) and each
    /// sphere moves with its own step length (docs/sizes.md, "Both solvers").
    std::vector<double> sizes;
    static constexpr double max_size_ratio = 10.0; ///< largest over smallest diameter
    /// The container in units of Dp: by default the paper's tube of a = 2 Rt / Dp = 5
    /// (`Container::tube(a)`: the front ends' --aspect-ratio; a from 1 to 10000).
    Container container = Container::tube(5.0);

    /// The settling schedule: the control band of eq. (7) and the mass-centre rule's spread.
    struct Schedule {
        double overlap_low;  ///< Dp
        double overlap_high; ///< Dp
        double mc_tolerance; ///< percent
    };
    /// The paper's schedule (section 3.3): band 0.5-1 % of Dp, records within 1e-4 %.
    static constexpr Schedule paper_schedule{0.5e-2, 1e-2, 1e-4};
    /// The fire solver's schedule: band 1.5-3 % of Dp, records within 5e-2 %. FIRE's inertia
    /// keeps compacting the bed long after the paper's iteration would have stopped, so under
    /// the paper's schedule it spends 95-98 % of its steps on a creep that ends denser than
    /// the paper's beds (by 0.0017 at a = 10, 0.003 at a = 20). A heavier gravity (the wider
    /// band) compacts as far in fewer steps, and the looser rule stops where the paper's beds
    /// are: 50x (a = 5) to 70x (a = 20) fewer steps than the paper's solver, 1.4x to 2x fewer
    /// than the first version of this schedule (1-2 %, 1e-2 %; docs/validation.md, "The fire
    /// solver's own schedule against the paper's").
    static constexpr Schedule fire_schedule{1.5e-2, 3e-2, 5e-2};
    /// \return overlap_low, overlap_high and mc_tolerance, each unset one from the solver's
    /// schedule (paper_schedule or fire_schedule).
    Schedule schedule() const;

    /// The Verlet-list skin of each solver when none is given, Dp. Fire's 0.2 spends 11-14 %
    /// less time per step than 0.1 at 1e5 spheres (half the list builds for a few more pairs;
    /// docs/performance.md, "One step"). The paper's solver keeps 0.1: its in-place
    /// update's beds depend on the skin, and its tests pin the first implementation's bits.
    static constexpr double fire_skin = 0.2, paper_skin = 0.1;
    /// \return skin, or the solver's own when unset.
    double list_skin() const;

    /// \return the smallest diameter over Dp: 1 for a mono-sized bed.
    double smallest_size() const;
    /// \return the largest diameter over Dp: 1 for a mono-sized bed.
    double largest_size() const;
    /// \return true when a contact has friction (friction or wall_friction above 0).
    bool frictional() const { return friction > 0.0 || wall_friction > 0.0; }
    /// \return the friction options above 0 as a message names them ("--friction 0.3",
    /// "--wall-friction 0.2", or both joined by "and").
    std::string friction_options() const;
    /// \return a = 2 Rt / Dp where the container is a tube, else nothing.
    std::optional<double> aspect_ratio() const { return container.tube_diameter(); }

    /// Check every value and their combinations.
    /// \throws InvalidInput naming the parameter, its value and the allowed range.
    void validate() const;
    /// \throws InvalidInput when the container ends below the bed's initial height.
    void check_top() const;
};

/// The state at the end of one stage (section 3).
struct StageRecord {
    std::string name;                       ///< "initial", "intermediate" or "final"
    std::uint64_t iterations = 0;           ///< iterations spent in this stage
    std::uint32_t steps = 1;                ///< final stage: number of Cg halvings run; 1 otherwise
    double cg = 0.0;                        ///< gravity parameter Cg at the end of the stage
    double max_overlap_pair = 0;            ///< largest sphere-sphere overlap at the end, Dp
    double max_overlap_wall = 0;            ///< largest sphere-wall overlap at the end, Dp
    double mass_centre_z = 0;               ///< height of the mass centre at the end, Dp
    std::vector<double> mass_centre_window; ///< the last mass-centre records, Dp (oldest first)
};

/// Where a run stands, for progress displays.
struct Progress {
    std::string_view stage;   ///< stage name
    std::uint64_t iteration;  ///< total iterations so far
    double cg;                ///< current gravity parameter
    double max_overlap_pair;  ///< Dp, as seen in the last iteration
    double max_overlap_wall;  ///< Dp, as seen in the last iteration
    double mass_centre_z;     ///< Dp (fire solver in layers: above the free band's bottom)
    std::uint32_t layer = 0;  ///< fire solver: the layer being relaxed, from 0
    std::uint32_t layers = 1; ///< fire solver: number of layers (1: the bed in one piece)
    /// the run of a --target-void-fraction search this is ("calibration bed 2, friction
    /// 0.0147"); empty otherwise
    std::string_view run{};
};

/// A progress report as a record: its fields by name, in the order of Progress (what Python's
/// progress callback gets).
nlohmann::ordered_json progress_json(const Progress& progress);

/// The state of a fire run in layers (relax_with_fire) after `layers_done` whole layers:
/// enough to resume it and end with the same bits as a run that was never stopped.
struct LayerCheckpoint {
    std::uint32_t layers_done = 0;     ///< layers relaxed, from the bottom
    std::uint64_t iterations = 0;      ///< steps so far, all layers
    std::uint64_t neighbor_builds = 0; ///< Verlet-list builds so far
    double top = 0.0;                  ///< highest centre of the relaxed layers, Dp
    Packing packing;                   ///< every sphere in generation order, Dp (those of the
                                       ///< layers still to come where the generation put them)
    std::vector<StageRecord> stages;   ///< stage records so far (iterations summed over layers)
};

/// Hooks a caller may give a run, all optional. on_progress and should_stop are called every
/// mc_period iterations from the thread that called run().
struct RunControl {
    std::function<void(const Progress&)> on_progress; ///< progress report
    std::function<bool()> should_stop;                ///< return true to cancel (throws Cancelled)
    /// Fire solver in layers: called after each layer with the state to save.
    std::function<void(const LayerCheckpoint&)> on_layer;
    /// Fire solver in layers: continue from this state (of the same parameters) instead of
    /// from the generation stage.
    const LayerCheckpoint* resume = nullptr;
};

/// The outcome of a run. Lengths of `packing` and `container` are in output units (diameter).
struct SoftSphereResult {
    Packing packing;                            ///< final sphere positions and radii (in a periodic
                                                ///< cell, their copies in [0, LX) x [0, LY))
    Container container = Container::tube(2.0); ///< the container, in the bed's length units
    double initial_height = 0.0;                ///< L0 of eq. (6), output units
    std::uint64_t iterations = 0;               ///< all stages together
    double max_overlap_pair = 0.0;              ///< largest sphere-sphere overlap of the result, Dp
    double max_overlap_wall = 0.0;              ///< largest sphere-wall overlap of the result, Dp
    std::vector<StageRecord> stages;            ///< initial, intermediate, final
    std::uint64_t neighbor_builds = 0;          ///< Verlet-list rebuilds
    std::uint32_t layers = 1;                   ///< layers the fire solver built the bed in
    double seconds = 0.0;                       ///< wall time of run()
    /// With friction: the largest force (k Dp) and torque (k Dp^2) left on a sphere at the end,
    /// k the contact stiffness (of the layer relaxed last where the bed is built in layers:
    /// each layer's at its own end, the largest)
    std::optional<std::pair<double, double>> residuals;
};

/// Largest overlaps of a configuration, computed exactly (O(N) with a cell grid).
struct Overlaps {
    double pair = 0.0; ///< largest sphere-sphere overlap r_i + r_j - |x_i - x_j| (0 if none)
    double wall = 0.0; ///< largest sphere-wall overlap (0 if none)
};

/// \return the largest overlaps of a bed's particles in `container` (lengths in the bed's
/// units): each pair the neighbour list of their bounding radii finds (by the minimum image in a
/// periodic cell), its ParticleShape::pair_overlap, and each particle's wall_overlap.
template <ParticleShape S>
Overlaps measure_overlaps(const ShapedBed<S>& bed, const Container& container) {
    Overlaps out;
    NeighborList list;
    const std::optional<Periods> cell = container.periods();
    if (cell)
        list.wrap(*cell);
    const std::vector<double> bounding = bed.bounding_radii();
    const std::vector<Vec3>& centers = bed.particles().centers;
    list.build(centers, bounding, 0.0);
    for (std::size_t i = 0; i < bed.size(); ++i) {
        const S& shape = bed.shape(i);
        const Placement p = bed.placement(i);
        for (const auto j : list.neighbors_of(i)) {
            const Vec3 ij =
                cell ? cell->separation(centers[i], centers[j]) : centers[j] - centers[i];
            out.pair =
                std::max(out.pair, shape.pair_overlap(p, bed.shape(j), bed.placement(j), ij).depth);
        }
        out.wall = std::max(out.wall, shape.wall_overlap(container, p));
    }
    return out;
}

/// The largest overlaps of a packing of spheres (spheres(packing), sphere_shape.hpp).
Overlaps measure_overlaps(const Packing& packing, const Container& container);

/// Initial bed height, eq. (6): \f$L_0 = \frac{2}{3}\frac{D_p N_p}{a^2 (1 - \varepsilon_0)}\f$.
/// \param particles Np \param aspect_ratio a \param e0 initial void fraction in (0, 1)
/// \return L0 in units of Dp.
double initial_bed_height(std::uint64_t particles, double aspect_ratio, double e0);

/// Eq. (6) for spheres of many sizes, in any container: the height the solid volume fills at void
/// fraction e0, \f$L_0 = \sum_i \frac{\pi}{6} d_i^3 / (\frac{\pi}{4} a^2 D_p^2 (1 - \varepsilon_0))
/// = \frac{2}{3} \frac{\sum_i (d_i/D_p)^3}{a^2 (1 - \varepsilon_0)} D_p\f$: with every d_i = Dp,
/// the paper's eq. (6) (the same bits: the sum of Np ones is Np exactly). In another
/// container, \f$\frac{\pi}{4} a^2\f$ is its cross-section A in Dp^2:
/// \f$L_0 = \frac{\pi}{6} \sum_i (d_i/D_p)^3 / (A (1 - \varepsilon_0))\f$.
/// \return L0 in units of Dp.
double initial_bed_height(const SoftSphereParameters& parameters);

/// The paper's algorithm (Solver::paper), stage by stage; `parameters.solver` is not looked
/// at here (generate_soft_sphere dispatches on it). The constructor runs the generation stage
/// (section 3.1); run() runs the three relaxation stages, or call them one by one (for tests and
/// tools). Positions are kept in units of Dp internally. Not thread-safe; uses OpenMP inside (the
/// simultaneous update is parallel and gives the same bits for any number of threads).
class SoftSphereGenerator {
public:
    /// \param parameters validated here (InvalidInput when wrong)
    explicit SoftSphereGenerator(const SoftSphereParameters& parameters);
    ~SoftSphereGenerator();
    SoftSphereGenerator(const SoftSphereGenerator&) = delete;
    SoftSphereGenerator& operator=(const SoftSphereGenerator&) = delete;

    /// Section 3.2: Cg = 0, eq. (4) until both largest overlaps are below the tolerance.
    StageRecord run_initial_stage(const RunControl& control = {});
    /// Section 3.3: gravity on, Cg by eq. (7), until mc_window successive mass-centre records
    /// (every mc_period iterations) spread less than mc_tolerance percent.
    StageRecord run_intermediate_stage(const RunControl& control = {});
    /// Section 3.4: Cg halved at each step, each step ending on the mass-centre rule; the stage
    /// ends as soon as both largest overlaps are below the tolerance.
    StageRecord run_final_stage(const RunControl& control = {});

    /// One iteration of eq. (4) at gravity parameter `cg` (>= 0), outside any stage logic:
    /// for benchmarks and tools that drive the iteration themselves.
    /// \return the largest overlaps seen during the iteration, Dp.
    Overlaps iterate(double cg);

    /// All three stages, then the result in output units.
    /// \throws ConvergenceError on divergence or when max_iterations is exceeded
    /// \throws Cancelled when control.should_stop() returned true
    SoftSphereResult run(const RunControl& control = {});

    /// \return the current configuration in generation order, in units of Dp (radius 0.5);
    /// refreshed at each call, valid until the next call or the next iteration.
    const Packing& packing_dp() const;
    /// \return the parameters in use.
    const SoftSphereParameters& parameters() const;

private:
    struct State;
    std::unique_ptr<State> m_state;
};

/// Relax the generation stage's bed with FIRE (see Solver::fire and src/generate/fire.cpp): stages
/// "initial" (no gravity, overlaps removed), "intermediate" (gravity under the control of
/// eq. (7), mass-centre rule) and "final" (gravity halved until both largest overlaps are
/// below the tolerance). `iterations` counts force evaluations; `cg` in a StageRecord and in
/// Progress is the paper's Cg = Ck g, g being the gravity force per sphere in units of
/// contact stiffness x Dp (so the two solvers' values compare); `ck` enters only there and
/// in the gravity step cg_step / ck.
/// \throws ConvergenceError, Cancelled as SoftSphereGenerator::run
SoftSphereResult relax_with_fire(const SoftSphereParameters& parameters,
                                 const RunControl& control = {});

/// \return the number of layers relax_with_fire builds a bed in: floor(L0 / layer_height)
/// when L0 > 2 layer_height, else 1.
std::uint32_t fire_layers(const SoftSphereParameters& parameters);

/// Run the whole algorithm with the chosen solver: SoftSphereGenerator(parameters).run(control)
/// or relax_with_fire(parameters, control).
SoftSphereResult generate_soft_sphere(const SoftSphereParameters& parameters,
                                      const RunControl& control = {});

/// Every field of `parameters` as a JSON object (keys: the field names; the update order and
/// solver by name): the `parameters` of summary.json, and what a checkpoint must match.
nlohmann::json soft_sphere_parameters_json(const SoftSphereParameters& parameters);

/// Everything a user needs to know about a soft-sphere run: inputs, every parameter, the
/// container, the overall void fraction over the band clear of the ends, the largest overlaps,
/// the stages, the time and the version. Lengths in output units unless a key says "_dp".
/// \param parameters the parameters of the run
/// \param result what SoftSphereGenerator::run returned
/// \param band_clearance distance of the void-fraction band from the floor and the top, in Dp
/// (>= 0); when the bed is too short for it, `void_fraction` is null and a note says why
/// \param threads number of threads used (recorded only)
/// \return the JSON object.
nlohmann::json soft_sphere_summary(const SoftSphereParameters& parameters,
                                   const SoftSphereResult& result, double band_clearance,
                                   int threads);

} // namespace packbed
