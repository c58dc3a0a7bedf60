// The relaxation run by LAMMPS: the generation stage of Salvat et al. (2005) made
// here, then the energy the fire solver minimises (fire.cpp) and its gravity schedule written
// as a LAMMPS input, for Debian's LAMMPS (20220106) and newer, run with MPI on as many ranks as
// a machine or a cluster has; the relaxed bed read back and checked here (docs/lammps.md).
#pragma once

#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "packbed/soft_sphere.hpp"

namespace packbed {

/// Who relaxes a bed: packbed's own solvers, or LAMMPS.
enum class Engine {
    packbed, ///< the solver of --solver, in this process (OpenMP threads)
    lammps,  ///< LAMMPS, started as a program (MPI ranks): lammps_job
};

/// The names users pick an engine by ("packbed", "lammps"): the one registry.
const Registry<Engine>& engines();
/// \return the name of an engine in engines().
std::string to_string(Engine engine);

/// How LAMMPS is started.
struct LammpsLauncher {
    std::string lmp = "lmp"; ///< the LAMMPS program (looked up on PATH): lmp, lmp_mpi, a path
    std::uint32_t ranks = 1; ///< MPI ranks; 1 starts lmp alone, more `mpirun -np RANKS lmp`
    /// A launcher's words instead of `mpirun -np RANKS` (a cluster's `srun`), split at spaces;
    /// empty: mpirun.
    std::string mpi_command;
};

/// The largest number of distinct sphere sizes the LAMMPS engine takes: each size is an atom
/// type and a group with its own wall fixes (LAMMPS allows 32 groups).
constexpr std::size_t max_lammps_types = 16;

/// The overlap law in LAMMPS (docs/lammps.md, "The contact law"): `pair_style gran/hooke` with
/// only its normal spring (each atom's own radius: any sizes; GRANULAR package, in Debian's
/// and most builds), else `harmonic/cut` (17Feb2022 and later: one coefficient per pair of
/// types). `pair_style table` is not used: LAMMPS interpolates F/r in r^2, which near r = 0 is
/// off by orders of magnitude and threw spheres of a random start out of the box.
enum class LammpsPairStyle { gran_hooke, harmonic_cut };

/// \return the style's name in LAMMPS ("gran/hooke", "harmonic/cut").
std::string to_string(LammpsPairStyle style);

/// The files of one LAMMPS relaxation, as texts; lammps_job_files names them.
struct LammpsJob {
    std::string data;        ///< start.data: the generation stage's spheres, one type per size
    std::string input;       ///< in.packbed: the energy, the schedule, the result's dump
    std::string readme;      ///< README.md: how to run it (a cluster's Slurm script) and import it
    std::uint32_t types = 1; ///< atom types (distinct sizes)
};

/// The names of the job's files in its folder, in the order above, and what LAMMPS writes.
namespace lammps_files {
constexpr std::string_view data = "start.data";
constexpr std::string_view input = "in.packbed";
constexpr std::string_view readme = "README.md";
constexpr std::string_view job = "job.json"; ///< the request, for import_lammps
constexpr std::string_view slurm = "job.sh"; ///< a Slurm script that runs the job
constexpr std::string_view log = "log.lammps";
constexpr std::string_view screen = "screen.txt";
constexpr std::string_view dump = "bed.dump";
} // namespace lammps_files

/// A gravity value is settled in LAMMPS when the RMS force on a sphere is below this times the
/// weight of a sphere of Dp (`minimize 0 settle*g*sqrt(N)` with `min_modify norm two`):
/// LAMMPS's counterpart of the mass-centre rule, a measure of the whole bed as that rule is,
/// chosen so that its beds match the fire solver's (docs/lammps.md).
constexpr double lammps_settle = 0.1;

/// The band of eq. (7) LAMMPS settles to unless one is given: 1-2 % of Dp, the band with which
/// lammps_settle was chosen and the engine checked against the fire solver (docs/lammps.md).
/// The fire solver's own band, 1.5-3 % (SoftSphereParameters::fire_schedule), goes with its
/// mass-centre rule; LAMMPS's rule on the RMS force was not tuned for it.
constexpr double lammps_overlap_low = 1e-2, lammps_overlap_high = 2e-2;

/// LAMMPS's neighbour skin unless one is given, Dp: the 0.1 the engine was checked with. The fire
/// solver's own skin became 0.2 (cheaper list builds in packbed, 2026-11-25), which bought
/// LAMMPS nothing measured, and on a periodic 6 x 6 cell of 300 spheres (seed 2) its other
/// trajectory took 1 956 680 steps in 23 rounds of the final stage instead of 32 360
/// (docs/lammps.md).
constexpr double lammps_skin = 0.1;

/// The final stage's budget in LAMMPS: this many times the steps of the stages before it, and
/// at least lammps_final_budget_min. A bed whose overlaps do not fall with gravity is jammed
/// (the fire solver lifts spheres pressed flat on the floor; the engine has no such move), and
/// a run beyond the budget stops with exit status 1 and a line saying so. The jammed periodic
/// 6 x 6 bed above (--skin 0.2) stops after 68 830 final steps (10 x its first 6 883; 4.4 s)
/// instead of running 1 956 680 steps (78 s); the final stages of the beds measured that end
/// take 0.06-0.2 x the steps before them (a = 5 and 10, seeds 1-3) and 3.1 x (that periodic
/// bed at the skin of 0.1) (docs/lammps.md).
constexpr unsigned lammps_final_budget = 10;
constexpr unsigned lammps_final_budget_min = 50'000;

/// \return `parameters` with the band and skin LAMMPS runs: the ones given, else
/// lammps_overlap_low, lammps_overlap_high and lammps_skin (what summary.json reports for an
/// --engine lammps run).
SoftSphereParameters lammps_parameters(SoftSphereParameters parameters);

/// Write the relaxation of `parameters` for LAMMPS: the generation stage (section 3.1, the
/// same start as the fire solver's), the energy of fire.cpp in LAMMPS's styles (unit overlap
/// stiffness as a pair style, the walls and the floor as harmonic wall fixes of the same
/// stiffness, gravity as `fix addforce` with its energy), and the fire solver's schedule as a
/// loop of `minimize` calls with `min_style fire`: the overlaps of the random start removed;
/// gravity rescaled until the settled bed's largest overlap lies in the band of eq. (7); then
/// cut to the value that leaves half the tolerance and halved, each value held until the bed
/// settles, until both overlaps are below the tolerance. Lengths in Dp, `units lj`.
/// \param parameters validated; any container; sizes of at most max_lammps_types diameters
/// \param command how the input's comment says to run it (the words before `-in in.packbed`)
/// \throws InvalidInput when the sizes have more distinct diameters than max_lammps_types
LammpsJob lammps_job(const SoftSphereParameters& parameters, LammpsPairStyle style,
                     std::string_view command);

/// \return the words that start LAMMPS, up to the program: `lmp`, `mpirun -np N lmp` (as root
/// with --allow-run-as-root, which Open MPI asks for), or the --mpi-command's words and lmp;
/// the job's arguments (-in in.packbed -log log.lammps) come after them.
/// \throws InvalidInput naming --mpi-command or --lmp when not allowed (no words, a newline)
std::vector<std::string> lammps_launch(const LammpsLauncher& launcher);

/// The result of a relaxation LAMMPS ran in `folder` (the job's files, log.lammps and
/// bed.dump): the spheres read back in generation order, the stages from the log, and the
/// bed checked with packbed's own code: every sphere there, largest pair, wall and floor
/// overlaps below the tolerance.
/// \param parameters those the job was written with
/// \throws ConvergenceError with LAMMPS's own message when the run failed (an ERROR line, a
/// schedule that did not end, no bed written), when the log's stage lines are not the job's,
/// or when the bed fails a check; InvalidInput for a log or screen output above
/// limits::max_small_file
SoftSphereResult lammps_result(const SoftSphereParameters& parameters,
                               const std::filesystem::path& folder);

/// \return LAMMPS's first ERROR line (or packbed's FAILED line) in `text`, without its source
/// position; "" when there is none.
std::string lammps_error(std::string_view text);

} // namespace packbed
