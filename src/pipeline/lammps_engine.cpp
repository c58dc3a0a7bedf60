// The LAMMPS engine's input and its result read back (lammps_engine.hpp, docs/lammps.md).
//
// The energy is fire.cpp's, in units of Dp, unit stiffness and a sphere of Dp of unit mass
// (`units lj`; atom_style sphere with density 6 / pi, so a sphere's mass is d^3):
//   E = 1/2 sum_pairs delta_ij^2 + 1/2 sum_walls delta_iw^2 + 1/2 sum_floor delta_i0^2
//       + g sum_i d_i^3 z_i.
// The pair term is `pair_style gran/hooke` with its normal spring only (F = kn (rc - r), kn = 1,
// rc = r_i + r_j from each atom's radius; granular styles tally no energy, which FIRE does not
// need) or `harmonic/cut` (E = k (rc - r)^2, k = 1/2, rc per pair of types). The walls are
// `fix wall/region ... harmonic` and `fix wall/harmonic` (E = eps (rc - r)^2, eps = 1/2, r the
// centre's distance from the surface, rc the sphere's radius); the fire solver's floor is rigid,
// LAMMPS's is this spring, whose overlaps the tolerance bounds as the walls'. Gravity is `fix
// addforce` per size, a constant force with its energy (minimize ignores fix gravity).
#include "packbed/lammps_engine.hpp"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <numbers>
#include <sstream>

#include <unistd.h>

#include <fmt/format.h>

#include "generate/soft_bed.hpp"
#include "packbed/error.hpp"
#include "packbed/files.hpp"
#include "packbed/io.hpp"
#include "packbed/limits.hpp"
#include "packbed/read.hpp"
#include "packbed/text.hpp"
#include "packbed/version.hpp"

namespace packbed {

const Registry<Engine>& engines() {
    static const Registry<Engine> names("engine",
                                        {{"packbed", Engine::packbed}, {"lammps", Engine::lammps}});
    return names;
}

std::string to_string(Engine engine) {
    return engines().name(engine);
}

std::string to_string(LammpsPairStyle style) {
    return style == LammpsPairStyle::gran_hooke ? "gran/hooke" : "harmonic/cut";
}

namespace {

/// A wall fix is set back by this much (Dp) with its reach as much longer: the same law inside
/// the container, and room for a centre pushed past the wall in the random start (LAMMPS stops
/// the run when a centre crosses a wall fix's surface).
constexpr double wall_setback = 1.0;

/// The distinct diameters of a bed (Dp) and each sphere's atom type, from 1.
struct SizeTypes {
    std::vector<double> diameters;
    std::vector<std::uint32_t> of_sphere;
};

SizeTypes size_types(const SoftSphereParameters& p) {
    SizeTypes t;
    if (p.sizes.empty()) {
        t.diameters = {1.0};
        t.of_sphere.assign(p.particles, 1);
        return t;
    }
    t.diameters = p.sizes;
    std::sort(t.diameters.begin(), t.diameters.end());
    t.diameters.erase(std::unique(t.diameters.begin(), t.diameters.end()), t.diameters.end());
    if (t.diameters.size() > max_lammps_types)
        throw InvalidInput(fmt::format(
            "--engine lammps with {} distinct sphere sizes is not allowed; allowed: at most {} "
            "(one atom type and one group of wall fixes each): a --sizes of discrete "
            "diameters",
            t.diameters.size(), max_lammps_types));
    t.of_sphere.reserve(p.sizes.size());
    for (const double d : p.sizes)
        t.of_sphere.push_back(static_cast<std::uint32_t>(
            std::lower_bound(t.diameters.begin(), t.diameters.end(), d) - t.diameters.begin() + 1));
    return t;
}

/// Shortest round-trip text of a number (as the data file's).
std::string num(double value) {
    return fmt::format("{}", value);
}

/// The container's part of the input: the boundary, the data file's box, the wall fixes (one
/// per size, each with its reach) and the atom variables of each wall's overlap.
struct ContainerScript {
    std::string boundary;
    AxisBox box;
    std::string walls;
    std::vector<std::string> overlaps; // atom-style formulas, r the radius
};

ContainerScript container_script(const Container& c, const std::vector<double>& diameters,
                                 double top) {
    ContainerScript s;
    const double m = 2.0 * wall_setback; // the box's margin beyond a wall
    const LammpsSide side = c.lammps_side(diameters, wall_setback);
    s.boundary = side.boundary + " m";
    s.box.lo = {side.box.x_low, side.box.y_low, -m};
    s.box.hi = {side.box.x_high, side.box.y_high, top + m};
    s.walls = side.walls;
    s.overlaps = side.overlaps;
    const auto per_type = [&](auto&& line) {
        for (std::size_t t = 0; t < diameters.size(); ++t)
            s.walls += line(t + 1, 0.5 * diameters[t] + wall_setback);
    };
    per_type([](std::size_t t, double reach) {
        return fmt::format("fix floor{0} size{0} wall/harmonic zlo {1} 0.5 1.0 {2} units box\n"
                           "fix_modify floor{0} energy yes\n",
                           t, num(-wall_setback), num(reach));
    });
    s.overlaps.push_back("v_r-z");
    return s;
}

void replace_all(std::string& text, std::string_view key, std::string_view value) {
    for (std::size_t at = text.find(key); at != std::string::npos;
         at = text.find(key, at + value.size()))
        text.replace(at, key.size(), value);
}

// The input. @NAME@ are filled in by lammps_job; LAMMPS's own ${name} and $(expression) are
// its variables, evaluated as the script runs.
constexpr std::string_view input_template =
    R"LAMMPS(# packbed @VERSION@: the relaxation of Salvat et al. (2005) with the fire solver's energy and
# schedule, run by LAMMPS (written by packbed generate --engine lammps; docs/lammps.md).
# @BED@
# Lengths in units of Dp, unit overlap stiffness, a sphere of Dp has unit mass (units lj).
# Run it in this folder:
#   @COMMAND@ -in in.packbed
# It writes the relaxed bed to bed.dump; `packbed import-lammps THIS-FOLDER --out OUT` reads it
# back, checks it (overlaps, every sphere inside) and writes what packbed generate writes.
# Any value below may be changed on the command line: -var settle 0.1

variable tol      index @TOL@   # largest overlap at the end (pair, wall, floor), Dp
variable low      index @LOW@   # the band of eq. (7) the settled bed's largest overlap
variable high     index @HIGH@   # must end in, Dp
variable settle   index @SETTLE@   # settled: the RMS force on a sphere below this x a Dp sphere's weight
variable maxsteps index @MAXSTEPS@   # give up beyond this many minimiser iterations in all
variable g        equal @G0@   # gravity: the weight of a sphere of Dp (rescaled below)

units           lj
atom_style      sphere
boundary        @BOUNDARY@
read_data       start.data
@PAIR@
neighbor        @SKIN@ bin
neigh_modify    delay 0 every 1 check yes
@GROUPS@
# The walls and the floor: harmonic, E = 1/2 overlap^2 as the contacts. Each is set back by
# 1 Dp with its reach 1 Dp longer (the same law inside the container), so that a centre pushed
# past a wall in the random start does not stop the run.
@WALLS@
# What the schedule measures: the largest overlaps (the pair force is the overlap, unit
# stiffness) and the mass centre (masses d^3).
compute pairs all pair/local force
compute pairmax all reduce max c_pairs
variable pair equal c_pairmax
variable r atom 0.5*mass^(1.0/3.0)
@OVERLAPS@
variable mc equal xcm(all,z)
variable below equal (v_pair<${tol})&&(v_wall<${tol})
thermo_style    custom step pe fmax v_pair v_wall v_mc v_g
thermo          1000
thermo_modify   norm no flush yes

# FIRE as packbed's (fire.cpp): dt 0.05 to 0.2 in units of 1/sqrt(k/m), 5 downhill steps before
# dt grows, alpha_0 0.5, a half step back on an uphill one, no sphere moving more than 0.01 Dp.
# A gravity value is settled when the forces' 2-norm is below settle x g x sqrt(N).
min_style       fire
min_modify      integrator eulerimplicit tmax 4 tmin 0.08 delaystep 5 dtgrow 1.1 dtshrink 0.5 alpha0 0.5 alphashrink 0.99 halfstepback yes initialdelay yes dmax 0.01 norm two
timestep        0.05

# 1. initial: no gravity, until both largest overlaps are below the tolerance.
fix stop all halt 10 v_below == 1 error continue message no
minimize 0.0 0.0 ${maxsteps} @MAXEVAL@
run 0 post no
print "PACKBED stage initial step $(step) g 0 pair $(v_pair:%.10g) wall $(v_wall:%.10g) mc $(v_mc:%.10g) rounds 1"
if "${below} == 0" then "print 'PACKBED FAILED the overlaps of the random start were not removed within ${maxsteps} iterations'" "quit 1"
unfix stop

# 2. intermediate: gravity on, each value held until the bed settles, then rescaled by the
# band's middle over the largest overlap (a settled bed's overlaps are proportional to g),
# until that overlap lies in the band.
variable mid equal 0.5*(${low}+${high})
variable round loop 40
label intermediate
@GRAVITY@
  minimize 0.0 $(v_settle*v_g*sqrt(count(all)):%.17g) ${maxsteps} @MAXEVAL@
  run 0 post no
  print "PACKBED round intermediate step $(step) g $(v_g:%.17g) pair $(v_pair:%.10g) wall $(v_wall:%.10g) mc $(v_mc:%.10g) rounds ${round}"
  if "$(step) >= ${maxsteps}" then "print 'PACKBED FAILED the bed did not settle within ${maxsteps} iterations'" "quit 1"
  if "$(v_pair) >= ${low} && $(v_pair) <= ${high}" then "jump SELF final"
  variable g equal $(v_g*v_mid/((v_pair>0.25*v_mid)*v_pair+(v_pair<=0.25*v_mid)*0.25*v_mid):%.17g)
  next round
  jump SELF intermediate
print "PACKBED FAILED the largest overlap did not reach the band ${low} to ${high} in 40 gravity values"
quit 1

# 3. final: gravity cut to what leaves half the tolerance, then halved, each value held until
# the bed settles, until both largest overlaps are below the tolerance. A bed whose overlaps
# do not follow gravity down is jammed: the stage has a budget of @JAMMED@ times the steps
# before it (at least @JAMMEDMIN@), and a run beyond it stops saying so.
label final
print "PACKBED stage intermediate step $(step) g $(v_g:%.17g) pair $(v_pair:%.10g) wall $(v_wall:%.10g) mc $(v_mc:%.10g) rounds ${round}"
fix stop all halt 10 v_below == 1 error continue message no
variable budget equal $((@JAMMED@*step>@JAMMEDMIN@)*@JAMMED@*step+(@JAMMED@*step<=@JAMMEDMIN@)*@JAMMEDMIN@:%.0f)
variable finalend equal $((step+v_budget<v_maxsteps)*(step+v_budget)+(step+v_budget>=v_maxsteps)*v_maxsteps:%.0f)
variable cut equal $(0.5*v_tol/((v_pair>v_wall)*v_pair+(v_pair<=v_wall)*v_wall):%.17g)
variable cut equal $((v_cut<0.5)*v_cut+(v_cut>=0.5)*0.5:%.17g)
variable halving loop 60
label halve
  variable g equal $(v_g*v_cut:%.17g)
@GRAVITY@
  minimize 0.0 $(v_settle*v_g*sqrt(count(all)):%.17g) $(v_finalend-step:%.0f) @MAXEVAL@
  run 0 post no
  if "${below} == 1" then "jump SELF done"
  if "$(step) >= ${maxsteps}" then "print 'PACKBED FAILED the final stage did not end within ${maxsteps} iterations'" "quit 1"
  if "$(step) >= ${finalend}" then "print 'PACKBED FAILED the bed is jammed: the largest overlaps stay at $(v_pair:%.3g) (pair) and $(v_wall:%.3g) (wall) Dp after ${budget} steps of the final stage (@JAMMED@ times the stages before it) while gravity fell to $(v_g:%.3g); another --seed gives another bed, and --engine packbed lifts spheres pressed flat on the floor'" "quit 1"
  variable cut equal 0.5
  next halving
  jump SELF halve
print "PACKBED FAILED the overlaps stayed above the tolerance ${tol} after 60 halvings of gravity"
quit 1

label done
print "PACKBED stage final step $(step) g $(v_g:%.17g) pair $(v_pair:%.10g) wall $(v_wall:%.10g) mc $(v_mc:%.10g) rounds ${halving}"
write_dump all custom bed.dump id type x y z radius modify sort id format float %.17g
print "PACKBED done step $(step)"
)LAMMPS";

/// A stage's PACKBED line: "PACKBED stage NAME step S g G pair P wall W mc M rounds K".
std::optional<StageRecord> stage_line(std::string_view line, double ck) {
    const std::vector<std::string_view> w = split_spaces(line);
    if (w.size() != 15 || w[0] != "PACKBED" || w[1] != "stage")
        return std::nullopt;
    const auto number = [&](std::size_t k) {
        const auto value = parse_finite(w[k]);
        if (!value)
            throw ConvergenceError(fmt::format("LAMMPS's log has a stage line that is not "
                                               "numbers: '{}'",
                                               printable(line.substr(0, 200))));
        return *value;
    };
    // A count: a whole number from 0 to `largest` (a log edited or cut short may hold any
    // number; converting one beyond the integer's range would be undefined).
    const auto count = [&](std::size_t k, std::string_view what, double largest) {
        const double value = number(k);
        if (!(value >= 0.0 && value <= largest && value == std::floor(value)))
            throw ConvergenceError(fmt::format("LAMMPS's log has a stage line whose {} is {}; "
                                               "allowed: a whole number from 0 to {:g}",
                                               what, printable(w[k]), largest));
        return value;
    };
    StageRecord r;
    r.name = std::string(w[2]);
    // the step, made a count by the caller; LAMMPS's steps are 64-bit, counted here exactly
    // up to 2^53
    r.iterations = static_cast<std::uint64_t>(count(4, "step", 9007199254740992.0));
    r.cg = number(6) * ck;
    r.max_overlap_pair = std::max(0.0, number(8));
    r.max_overlap_wall = std::max(0.0, number(10));
    r.mass_centre_z = number(12);
    r.steps = static_cast<std::uint32_t>(count(14, "rounds", 4294967295.0));
    return r;
}

/// Call `f` with each line of `text` (without its '\n'), in order, until it returns false; no
/// list of the lines is kept (a log of 6e7 empty lines made one of 1 GB).
template <class F> void each_line(std::string_view text, F&& f) {
    for (std::size_t start = 0; start < text.size();) {
        std::size_t end = text.find('\n', start);
        if (end == std::string_view::npos)
            end = text.size();
        if (!f(text.substr(start, end - start)))
            return;
        start = end + 1;
    }
}

/// LAMMPS's "Total wall time: H:MM:SS" in seconds; 0 when it is not three whole numbers.
double wall_time(std::string_view text) {
    double seconds = 0.0;
    int parts = 0;
    for (std::size_t start = 0; start <= text.size() && parts < 3; ++parts) {
        std::size_t end = text.find(':', start);
        if (end == std::string_view::npos)
            end = text.size();
        const auto value = parse_whole<unsigned long>(text.substr(start, end - start));
        if (!value || *value > 1000000000ul)
            return 0.0;
        seconds = seconds * 60.0 + static_cast<double>(*value);
        start = end + 1;
    }
    return parts == 3 ? seconds : 0.0;
}

/// A text file LAMMPS wrote, whole; "" when it is not there or not a regular file (a device or
/// a pipe in a folder from elsewhere is never read). \throws InvalidInput above
/// limits::max_small_file (a job's log is a few MB at most).
std::string read_text(const std::filesystem::path& path) {
    std::error_code error;
    if (!std::filesystem::is_regular_file(path, error))
        return {};
    const std::uintmax_t size = std::filesystem::file_size(path, error);
    if (!error && size > limits::max_small_file)
        throw InvalidInput(fmt::format("{} is {} bytes; allowed: at most {} (LAMMPS's log and "
                                       "screen output of a packbed job are far smaller)",
                                       printable(path.string()), size, limits::max_small_file));
    std::ifstream in(path, std::ios::binary);
    std::ostringstream text;
    text << in.rdbuf();
    return text.str();
}

} // namespace

SoftSphereParameters lammps_parameters(SoftSphereParameters parameters) {
    parameters.overlap_low = parameters.overlap_low.value_or(lammps_overlap_low);
    parameters.overlap_high = parameters.overlap_high.value_or(lammps_overlap_high);
    parameters.skin = parameters.skin.value_or(lammps_skin);
    return parameters;
}

LammpsJob lammps_job(const SoftSphereParameters& parameters, LammpsPairStyle style,
                     std::string_view command) {
    const SoftSphereParameters banded = lammps_parameters(parameters);
    banded.validate();
    const SoftSphereParameters p = detail::in_dp(banded);
    detail::SoftBed bed(p.container);
    bed.generate(parameters);
    const Packing& start = bed.packing_in_generation_order();
    const SizeTypes types = size_types(p);
    double top = 0.0;
    for (const Vec3& c : start.centers)
        top = std::max(top, c.z);
    const ContainerScript walls = container_script(p.container, types.diameters, top);

    LammpsJob job;
    job.types = static_cast<std::uint32_t>(types.diameters.size());
    const std::string bed_text = fmt::format(
        "{} spheres, {}, seed {}, L0 = {:.6g} Dp", p.particles,
        p.aspect_ratio() ? fmt::format("a = {}", *p.aspect_ratio()) : p.container.spec(), p.seed,
        bed.initial_height);
    job.data = lammps_data(start, 6.0 / std::numbers::pi, walls.box,
                           "packbed generate --engine lammps: the generation stage, Dp = 1",
                           {bed_text}, types.of_sphere);

    std::string pair, groups, gravity, overlaps;
    if (style == LammpsPairStyle::gran_hooke) {
        // F = kn overlap along the line of centres, each atom's own radius; no tangential
        // spring, no damping, no friction: the linear law alone.
        pair = "# The overlap law, F = overlap along the line of centres (unit stiffness, each "
               "sphere's\n# own radius), no tangential spring, damping or friction.\n"
               "pair_style      gran/hooke 1.0 0.0 0.0 0.0 0.0 0\npair_coeff      * *\n"
               "comm_modify     vel yes\n";
    } else {
        pair = "# The overlap law, E = 1/2 overlap^2 (unit stiffness), rc per pair of sizes.\n"
               "pair_style      harmonic/cut\n";
        for (std::size_t i = 0; i < types.diameters.size(); ++i)
            for (std::size_t j = i; j < types.diameters.size(); ++j)
                pair += fmt::format("pair_coeff      {} {} 0.5 {}\n", i + 1, j + 1,
                                    num(0.5 * (types.diameters[i] + types.diameters[j])));
    }
    for (std::size_t t = 0; t < types.diameters.size(); ++t) {
        const double d = types.diameters[t];
        groups += fmt::format("group           size{0} type {0}   # d = {1} Dp\n", t + 1, num(d));
        gravity += fmt::format("  fix grav{0} size{0} addforce 0.0 0.0 $(-v_g*{1}:%.17g)\n"
                               "  fix_modify grav{0} energy yes\n",
                               t + 1, num(d * d * d));
    }
    // The largest wall overlap: a chain of maxima over the walls (LAMMPS 2022's formulas have
    // no two-argument max).
    std::string reduce = "compute walls all reduce max";
    for (std::size_t k = 0; k < walls.overlaps.size(); ++k) {
        overlaps += fmt::format("variable w{} atom {}\n", k + 1, walls.overlaps[k]);
        reduce += fmt::format(" v_w{}", k + 1);
    }
    // one value (a periodic cell: the floor alone) makes compute reduce a scalar
    overlaps += reduce + (walls.overlaps.size() == 1 ? "\nvariable wall1 equal c_walls\n"
                                                     : "\nvariable wall1 equal c_walls[1]\n");
    for (std::size_t k = 2; k <= walls.overlaps.size(); ++k)
        overlaps += fmt::format(
            "variable wall{0} equal (c_walls[{0}]>v_wall{1})*c_walls[{0}]+(c_walls[{0}]<=v_wall{1})"
            "*v_wall{1}\n",
            k, k - 1);
    overlaps += fmt::format("variable wall equal v_wall{}", walls.overlaps.size());

    // Gravity's first value: the fire solver's beds end the intermediate stage at g L0 of
    // about 0.3 times the band's middle (a = 5 to 20).
    const double mid = 0.5 * (*p.overlap_low + *p.overlap_high);
    const double g0 = 0.3 * mid / bed.initial_height;
    const std::uint64_t maxsteps = std::min<std::uint64_t>(p.max_iterations, 200'000'000);
    std::string input(input_template);
    replace_all(input, "@VERSION@", version);
    replace_all(input, "@BED@", bed_text);
    replace_all(input, "@TOL@", num(p.tolerance));
    replace_all(input, "@LOW@", num(*p.overlap_low));
    replace_all(input, "@HIGH@", num(*p.overlap_high));
    replace_all(input, "@SETTLE@", num(lammps_settle));
    replace_all(input, "@MAXSTEPS@", std::to_string(maxsteps));
    replace_all(input, "@MAXEVAL@", "2000000000");
    replace_all(input, "@JAMMED@", std::to_string(lammps_final_budget));
    replace_all(input, "@JAMMEDMIN@", std::to_string(lammps_final_budget_min));
    replace_all(input, "@G0@", num(g0));
    replace_all(input, "@BOUNDARY@", walls.boundary);
    replace_all(input, "@PAIR@", pair);
    replace_all(input, "@SKIN@", num(p.list_skin()));
    replace_all(input, "@GROUPS@", groups);
    replace_all(input, "@WALLS@", walls.walls);
    replace_all(input, "@OVERLAPS@", overlaps);
    replace_all(input, "@GRAVITY@", gravity);
    // Last, so that no text of the user's (a launcher's words, in a comment) is read for keys;
    // lammps_launch refuses a newline in it.
    replace_all(input, "@COMMAND@", printable(command));
    job.input = std::move(input);
    return job;
}

std::string lammps_error(std::string_view text) {
    std::string error;
    each_line(text, [&](std::string_view line) {
        if (line.rfind("PACKBED FAILED ", 0) == 0)
            error = printable(line.substr(15, 1000));
        else if (line.rfind("ERROR", 0) == 0) {
            // "ERROR on proc 1: Lost atoms: ... (src/thermo.cpp:481)": without the position
            if (const auto open = line.rfind(" (src/"); open != std::string_view::npos)
                line = line.substr(0, open);
            error = printable(line.substr(0, 300));
        }
        return error.empty();
    });
    return error;
}

SoftSphereResult lammps_result(const SoftSphereParameters& parameters,
                               const std::filesystem::path& folder) {
    const SoftSphereParameters p = detail::in_dp(parameters);
    const std::string log = read_text(folder / lammps_files::log);
    SoftSphereResult result;
    std::uint64_t before = 0;
    bool done = false;
    each_line(log, [&](std::string_view line) {
        if (std::optional<StageRecord> stage = stage_line(line, p.ck)) {
            if (result.stages.size() == 3) // the job prints three
                throw ConvergenceError("LAMMPS's log has more than the job's 3 stage lines");
            const std::uint64_t step = stage->iterations;
            stage->iterations = step - std::min(step, before);
            before = step;
            result.iterations = step;
            result.stages.push_back(std::move(*stage));
        } else if (line.rfind("PACKBED done", 0) == 0) {
            done = true;
        } else if (line.rfind("Neighbor list builds = ", 0) == 0) {
            result.neighbor_builds +=
                parse_whole<std::uint64_t>(trim(std::string_view(line).substr(23))).value_or(0);
        } else if (line.rfind("Total wall time: ", 0) == 0) {
            result.seconds = wall_time(line.substr(17)); // LAMMPS's own, H:MM:SS
        }
        return true;
    });
    if (done && result.stages.size() == 3 &&
        !(result.stages[0].name == "initial" && result.stages[1].name == "intermediate" &&
          result.stages[2].name == "final"))
        throw ConvergenceError(fmt::format(
            "LAMMPS's log has the stages {}, {}, {}; the job prints initial, intermediate, final",
            printable(result.stages[0].name.substr(0, 40)),
            printable(result.stages[1].name.substr(0, 40)),
            printable(result.stages[2].name.substr(0, 40))));
    if (!done || result.stages.size() != 3) {
        const std::string screen = read_text(folder / lammps_files::screen);
        std::string why = lammps_error(screen);
        if (why.empty())
            why = lammps_error(log);
        if (!why.empty())
            throw ConvergenceError("LAMMPS: " + why);
        // No ERROR line (mpirun refusing to start, LAMMPS killed): the last words printed. The
        // folder is named only in words, not by its path: a run's staging folder is gone by
        // the time the message is read.
        const std::string& printed = screen.empty() ? log : screen;
        std::string_view last;
        each_line(printed, [&](std::string_view line) {
            if (line.find_first_not_of(" \t\r") != std::string_view::npos)
                last = line;
            return true;
        });
        throw ConvergenceError(fmt::format(
            "LAMMPS ended without writing the bed (no 'PACKBED done' in its {}){}",
            lammps_files::log,
            last.empty()
                ? std::string("; it printed nothing")
                : fmt::format("; the last it printed: '{}'", printable(last.substr(0, 200)))));
    }
    ReadOptions options;
    options.format = ParticleFormat::lammps_dump;
    Packing bed = read_particles(folder / lammps_files::dump, options).packing;
    if (bed.size() != p.particles)
        throw ConvergenceError(
            fmt::format("LAMMPS's bed has {} spheres; the job had {}", bed.size(), p.particles));
    // The bed checked here, with packbed's code: the dump's radii are the job's, the overlaps
    // (pairs, walls, floor) below the tolerance.
    const Container container = p.container;
    double floor = 0.0;
    for (std::size_t i = 0; i < bed.size(); ++i) {
        const double want = p.sizes.empty() ? 0.5 : 0.5 * p.sizes[i];
        if (!(std::abs(bed.radii[i] - want) <= 1e-12 * want) || !is_finite(bed.centers[i]))
            throw ConvergenceError(fmt::format(
                "LAMMPS's bed: sphere {} has radius {} and centre ({}, {}, {}); the job's radius "
                "is {}",
                i + 1, bed.radii[i], bed.centers[i].x, bed.centers[i].y, bed.centers[i].z, want));
        bed.radii[i] = want;
        floor = std::max(floor, want - bed.centers[i].z);
    }
    if (const std::optional<Periods> cell = container.periods())
        for (Vec3& c : bed.centers)
            c = cell->wrapped(c);
    const Overlaps overlaps = measure_overlaps(bed, container);
    result.max_overlap_pair = overlaps.pair;
    result.max_overlap_wall = std::max(overlaps.wall, floor);
    if (!(result.max_overlap_pair < p.tolerance && result.max_overlap_wall < p.tolerance))
        throw ConvergenceError(fmt::format(
            "LAMMPS's bed fails packbed's check: largest overlaps {:.3g} (pair) and {:.3g} (wall "
            "and floor) Dp against the tolerance {:.3g}",
            result.max_overlap_pair, result.max_overlap_wall, p.tolerance));
    result.stages.back().mass_centre_z = 0.0;
    double weighted = 0.0, total = 0.0;
    for (std::size_t i = 0; i < bed.size(); ++i) {
        const double m = bed.radii[i] * bed.radii[i] * bed.radii[i];
        weighted += m * bed.centers[i].z;
        total += m;
    }
    result.stages.back().mass_centre_z = weighted / total;
    result.initial_height = initial_bed_height(parameters) * parameters.diameter;
    bed.scale(parameters.diameter);
    result.packing = std::move(bed);
    result.container = container.scaled(parameters.diameter);
    return result;
}

std::vector<std::string> lammps_launch(const LammpsLauncher& launcher) {
    std::vector<std::string> words;
    if (!launcher.mpi_command.empty()) {
        if (launcher.mpi_command.find_first_of("\n\r") != std::string::npos)
            throw InvalidInput(fmt::format("--mpi-command '{}' is not allowed; allowed: one line "
                                           "of words (a launcher such as 'srun -n 64')",
                                           printable(launcher.mpi_command.substr(0, 80))));
        for (const std::string_view w : split_spaces(launcher.mpi_command))
            words.emplace_back(w);
        if (words.empty())
            throw InvalidInput("--mpi-command '' is not allowed; allowed: a launcher's words "
                               "such as 'srun -n 64'");
    } else if (launcher.ranks > 1) {
        words = {"mpirun", "-np", std::to_string(launcher.ranks)};
        if (geteuid() == 0) // Open MPI refuses root otherwise
            words.emplace_back("--allow-run-as-root");
    }
    if (launcher.lmp.empty() || launcher.lmp.find_first_of("\n\r") != std::string::npos)
        throw InvalidInput(fmt::format("--lmp '{}' is not allowed; allowed: a program's name or "
                                       "path (lmp, lmp_mpi, /opt/lammps/bin/lmp)",
                                       printable(launcher.lmp.substr(0, 80))));
    words.push_back(launcher.lmp);
    return words;
}

} // namespace packbed
