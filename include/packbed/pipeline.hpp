// What a front end runs for a whole job, from its inputs to its files: the command line
// (apps/packbed) and the Python module (python/) are thin callers of these, so neither gets
// less than the other nor a copy of this logic.
#pragma once

#include <array>
#include <filesystem>
#include <functional>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include <nlohmann/json.hpp>
#include <sys/types.h>

#include "packbed/analysis.hpp"
#include "packbed/container.hpp"
#include "packbed/hydraulics.hpp"
#include "packbed/lammps_engine.hpp"
#include "packbed/lattice.hpp"
#include "packbed/openfoam.hpp"
#include "packbed/output.hpp"
#include "packbed/packing.hpp"
#include "packbed/pellet_bed.hpp"
#include "packbed/pellet_shape.hpp"
#include "packbed/read.hpp"
#include "packbed/sizes.hpp"
#include "packbed/soft_sphere.hpp"
#include "packbed/voxel.hpp"

namespace packbed {

/// Run the library's parallel loops on `threads` OpenMP threads, for the whole run (the
/// results do not depend on the number). OpenMP's dynamic adjustment stays as OpenMP sets it:
/// off, unless OMP_DYNAMIC says otherwise (it took threads away by the load average, which a
/// user's previous run had raised). \return the threads a parallel region gets now
/// (threads_in_use).
int use_threads(unsigned long long threads);

/// The threads a parallel region of this thread gets now: what summary.json records and the
/// progress line shows.
int threads_in_use();

// ---------------------------------------------------------------------------------------------
// generate: the soft-sphere bed of Salvat et al. (2005)

/// What `packbed generate` is asked for, as its options give it.
struct GenerateRequest {
    /// The solver's parameters; `diameter` is --diameter (with `sizes`, what the distribution's
    /// `mono` means; the bed's Dp becomes the drawn sizes' Sauter mean d32). Its `container` is
    /// not read: prepare_generation sets it from `container` or `aspect_ratio`.
    SoftSphereParameters params;
    std::string sizes = "mono";                      ///< a --sizes spec (docs/sizes.md)
    FractionBasis fractions = FractionBasis::volume; ///< what the sizes' fractions count
    double aspect_ratio = 5.0;       ///< --aspect-ratio: a tube of a Dp, where `container` is ""
    std::string container;           ///< a --container SPEC (parse_container); "": aspect_ratio
    std::string checkpoint;          ///< --checkpoint file; "": none
    double band_clearance = 1.0;     ///< of the void-fraction band, Dp
    Engine engine = Engine::packbed; ///< who relaxes the bed (Engine::lammps: the fire solver's)
    LammpsLauncher launcher;         ///< Engine::lammps: how LAMMPS is started
    bool write_only = false; ///< Engine::lammps: the job only staged (stage_lammps_job), not run
    /// --target-void-fraction: the bed's void fraction (summary.json's, over the band clear of
    /// the ends) to reach within target_tolerance by the friction of spheres and walls alike
    /// (run_generation; docs/generate.md, "A target void fraction"); none: params' friction.
    std::optional<double> target_void_fraction;
    static constexpr double target_tolerance = 0.005;
};

/// A request with its sizes drawn and its container resolved into the solver's parameters,
/// every check made: what the run will do, before it starts (for a progress estimate).
struct PreparedGeneration {
    GenerateRequest request;
    SoftSphereParameters params;         ///< validated; lengths in Dp
    std::optional<SizeStatistics> drawn; ///< the drawn sizes' statistics (none for `mono`)
    std::uint64_t memory = 0;            ///< the run's estimated memory (generation_memory)
};

/// Draw the sizes (a stream of their own: seed XOR 0x9E3779B97F4A7C15), resolve the container
/// (a = D / Dp for a tube, any other shape in units of Dp) and check everything: the launcher
/// only with the LAMMPS engine (and its words, lammps_launch), the checkpoint's compatibility
/// and the memory the run will need (check_memory) included.
/// \throws InvalidInput naming the option, the value and what is allowed
PreparedGeneration prepare_generation(GenerateRequest request);

/// A generated bed and its record.
struct GeneratedBed {
    SoftSphereResult result;
    /// summary.json: soft_sphere_summary (with `threads`), the sizes, later the analysis
    nlohmann::json summary;
};

/// Run the solver on a prepared generation. With a checkpoint: the file is checked for writing
/// before the run (and becomes an output of the job, JobScope), a run resumes from it when it
/// exists (`on_resume` is told after which layer) and it is written after every layer.
/// \param control on_progress, should_stop (on_layer and resume are set here for a checkpoint)
/// \param threads recorded in the summary
/// \throws ConvergenceError, Cancelled, InvalidInput (a bad checkpoint)
GeneratedBed run_generation(const PreparedGeneration& prepared, RunControl control, int threads,
                            const std::function<void(std::uint32_t layers_done)>& on_resume = {});

/// The generate job of every front end: the prepared bed relaxed by its engine, here
/// (run_generation) or by LAMMPS (run_lammps_generation).
/// \param threads Engine::packbed: recorded in the summary (use_threads set them)
/// \param folder Engine::lammps: the output in whose lammps/ folder LAMMPS runs (required)
/// \param on_resume Engine::packbed with a checkpoint: told after which layer the run resumes
/// \throws ConvergenceError, Cancelled, InvalidInput
GeneratedBed generate_bed(const PreparedGeneration& prepared, RunControl control, int threads,
                          OutputDirectory* folder,
                          const std::function<void(std::uint32_t layers_done)>& on_resume = {});

/// summary.json of a generated bed: soft_sphere_summary (with `threads`) and, for drawn sizes,
/// their spec and statistics.
nlohmann::json generation_summary(const PreparedGeneration& prepared,
                                  const SoftSphereResult& result, int threads);

// ---------------------------------------------------------------------------------------------
// generate --shape: a bed of pellets (pellet_bed.hpp, docs/generate.md "Pellets")

/// A pellet as users write it (--shape), in length units, each length in (0,
/// limits::max_length]: "cylinder:D,L" (L / D from 0.1 to 10), "ring:D,DI,L" (a hollow
/// cylinder, its bore DI < D, DI / D at most 0.9, L / D from 0.1 to 10), "trilobe:DL,DC,L" (three
/// lobes of diameter DL on a circle of diameter DC, 0 < DC <= DL, L / DL from 0.1 to 10), or
/// "multilobe:N,DL,DC,L" (N from 2 to 8 lobes, the same ranges), or "spherocylinder:D,L" (L the
/// cylindrical part, the caps' centres L apart; L / D from 0 to 10).
struct PelletSpec {
    /// At the volume-equivalent size: MultilobeShape::cylinder(CylinderShape::of_aspect(L / D)),
    /// MultilobeShape::cylinder(CylinderShape::ring(D, DI, L)), MultilobeShape::of or
    /// SpherocylinderShape::of_aspect(L / D).
    PelletShape shape;
    std::string kind;      ///< "cylinder", "ring", "trilobe", "multilobe" or "spherocylinder"
    double diameter = 0.0; ///< D, or DL for a multilobe
    double circle_diameter = 0.0; ///< DC (0 for a cylinder or a ring)
    double inner_diameter = 0.0;  ///< a ring's DI (0 for the others)
    double length = 0.0;          ///< L
    double volume_diameter = 0.0; ///< d_v = (6 V / pi)^(1/3), the bed's unit
    std::string text;             ///< as given
    /// A bed's pellets are the shape scaled by factors from the first to the second (a bed
    /// generated with --sizes: its drawn D's over the shape's, shape_beside); 1 and 1: all
    /// the shape's size.
    std::pair<double, double> scales{1.0, 1.0};

    /// The same pellet, its lengths within 1e-9 of each other's (however they were written).
    bool same_as(const PelletSpec& other) const;
};
/// \return the pellet of `text`, or nothing when it is not one ("sphere" is not a pellet).
std::optional<PelletSpec> parse_pellet_shape(std::string_view text);
/// What --shape allows, in the command line's words.
std::string allowed_shapes();
/// \return the surface-volume equivalent diameter 6 V / S of one pellet of `pellet`'s own size
/// (its lengths' unit): the diameter of Ergun's equation for non-spheres, the one cfd-report's
/// correlations take (D for a cylinder of L = D).
double surface_volume_diameter(const PelletSpec& pellet);

/// What `packbed generate --shape` is asked for.
struct PelletRequest {
    std::string shape;             ///< --shape SPEC (parse_pellet_shape)
    std::uint64_t particles = 100; ///< --particles
    std::uint64_t seed = 1;        ///< --seed
    double aspect_ratio = 5.0;     ///< a tube of a d_v, where `container` is ""
    std::string container;         ///< --container SPEC in length units; "": aspect_ratio
    double band_clearance = 1.0;   ///< of the void-fraction band, d_v
    double friction = 0.0;         ///< --friction, between pellets
    double wall_friction = 0.0;    ///< --wall-friction, at the walls and the floor
    /// --max-iterations: the solver's steps before it gives up (ConvergenceError, exit 1).
    std::uint64_t max_steps = PelletBedParameters{}.max_steps;
    /// --sizes on the pellet's D (a multilobe's DL; parse_sizes, mono: the --shape's D): each
    /// pellet is the --shape scaled by its D over the shape's.
    std::string sizes = "mono";
    FractionBasis fractions = FractionBasis::volume; ///< --fractions
    /// --layer-height, d_v: a tall bed relaxed in layers (PelletBedParameters::layer_height);
    /// 0: in one piece.
    double layer_height = 0.0;
    /// --checkpoint file of a bed in layers (write_pellet_checkpoint); "": none
    std::string checkpoint;
};

/// A pellet request checked and resolved: the solver's parameters (lengths in d_v).
struct PreparedPellets {
    PelletRequest request;
    PelletSpec pellet;
    PelletBedParameters params;
    /// The drawn D's statistics (none for `mono`): the reference pellet is the --shape scaled
    /// to their Sauter mean d32, each pellet's scale its D over d32.
    std::optional<SizeStatistics> drawn;
    /// The bed's unit, the reference pellet's volume-equivalent diameter d_v (the --shape's,
    /// times d32 / D with sizes): a = D_tube / d_v.
    double unit = 0.0;
    /// With a checkpoint: the column and layers of the bed (pellet_column).
    PelletColumn column;
};
/// \throws InvalidInput naming the option, the value and what is allowed (a checkpoint only
/// for a bed in layers, its path checked)
PreparedPellets prepare_pellets(const PelletRequest& request);

/// A generated pellet bed in length units and its record.
struct GeneratedPellets {
    PelletBed bed;   ///< as the solver returns it (lengths in d_v)
    Packing packing; ///< centroids and sizes (d_v / 2) in length units, orientations
    Container container = Container::tube(1.0); ///< in length units
    nlohmann::json summary;                     ///< summary.json
};
/// Run the pellet solver (generate_pellet_bed) and measure the bed: summary.json has the shape,
/// the container, the stages, the exact depths and residuals, and the void fraction over the
/// band clear of the floor and the top in a tube (the exact volumes, MultilobeShape::volume_in).
/// With a checkpoint: the file is checked for writing first; where it exists the run resumes
/// from it (on_resume told the layers done and the bed's layers), and it is replaced after each
/// layer.
/// \throws ConvergenceError, Cancelled, InvalidInput (a bad checkpoint)
GeneratedPellets
run_pellets(const PreparedPellets& prepared, const RunControl& control, int threads,
            const std::function<void(std::uint32_t, std::uint32_t)>& on_resume = {});
/// particles.csv (with the orientations) and summary.json staged in `out`.
void stage_pellet_bed(OutputDirectory& out, const GeneratedPellets& pellets);
/// summary.json's warning where `touching_nothing` of a bed's `pellets` overlap no neighbour and
/// no wall at the end: more than one in a hundred (more than one below 200 pellets).
std::optional<std::string> unsettled_pellets_warning(std::size_t touching_nothing,
                                                     std::size_t pellets);
/// summary.json's `shape` of a bed of `pellet`s: its kind, spec and lengths, d_v, and what
/// particles.csv's r and quaternion mean.
nlohmann::json pellet_shape_summary(const PelletSpec& pellet);

// ---------------------------------------------------------------------------------------------
// generate --engine lammps (lammps_engine.hpp, docs/lammps.md)

/// Which pair style the LAMMPS of `launcher` has, from `lmp -h` (run in `out`'s staging
/// folder): gran/hooke where listed, else harmonic/cut.
/// \throws InvalidInput naming --lmp when it cannot be started or is not LAMMPS
LammpsPairStyle probe_lammps(const LammpsLauncher& launcher, OutputDirectory& out);

/// Stage a LAMMPS job for `prepared` in `out`, in `folder` ("": at the top): start.data,
/// in.packbed, README.md and job.json (the request, for
/// import_lammps). \return the words that run it in that folder.
std::vector<std::string> stage_lammps_job(OutputDirectory& out, const std::string& folder,
                                          const PreparedGeneration& prepared,
                                          const LammpsLauncher& launcher, LammpsPairStyle style);

/// generate --engine lammps: the job staged in `out`'s lammps/ folder, LAMMPS run there
/// (without a shell; progress from its log, stopped when control.should_stop() says so),
/// the bed read back and checked (lammps_result), its summary with the engine recorded.
/// \throws InvalidInput (LAMMPS or the launcher missing), ConvergenceError (LAMMPS failed: its
/// own message), Cancelled
GeneratedBed run_lammps_generation(const PreparedGeneration& prepared,
                                   const LammpsLauncher& launcher, const RunControl& control,
                                   OutputDirectory& out);

/// What the job.json of a LAMMPS job holds (stage_lammps_job wrote it), every value checked.
struct LammpsJobFile {
    GenerateRequest request; ///< as the job was asked for (not yet prepare_generation's checks)
    nlohmann::json command;  ///< the words that run it: at most 64 strings of 4 KiB each
    std::string pair_style;  ///< "gran/hooke", "harmonic/cut" or "" (not recorded)
};

/// job.json's `text`, read (its nesting bounded) and checked.
/// \param folder the job's folder, for messages
/// \throws InvalidInput naming the folder and the field that is missing or not allowed
LammpsJobFile read_lammps_job(std::string_view text, std::string_view folder);

/// A bed LAMMPS relaxed in a job folder, brought back.
struct ImportedLammps {
    PreparedGeneration prepared; ///< the request of the folder's job.json
    GeneratedBed bed;
};

/// import-lammps FOLDER: the folder of a job written by --write-only (job.json) after LAMMPS
/// ran in it (log.lammps, bed.dump), read back and checked as generate --engine lammps does.
/// \throws InvalidInput naming the folder when a file is missing or job.json is not one;
/// ConvergenceError when the run failed or the bed fails a check
ImportedLammps import_lammps(const std::filesystem::path& folder);

// ---------------------------------------------------------------------------------------------
// the outputs of a bed

/// Stage what `generate` and `lattice` write for a bed: particles.csv, particles.vtu, the
/// analysis (stage_analysis) when `analyse` (the caller's choice: a bed tall enough for the
/// band), and summary.json.
void stage_bed(OutputDirectory& out, const Packing& packing, const Container& container,
               double band_clearance, bool analyse, nlohmann::json& summary);

/// Stage what `lattice` writes for the balls `packing` of `lattice`: stage_bed, analysed when
/// `analysis` and the region is taller than twice `band_clearance` (d); a region too short for
/// the band gets summary["analysis_note"] saying so instead.
void stage_lattice(OutputDirectory& out, const LatticeParameters& lattice, const Packing& packing,
                   double band_clearance, bool analysis, nlohmann::json& summary);

/// The analysis `generate` and `lattice` run on what they made: analyze_bed over the band
/// `band_clearance` (Dp) clear of the ends (in a periodic cell g(r) within the smaller period),
/// its tables and plots staged in `out`, its numbers in summary["analysis"].
void stage_analysis(OutputDirectory& out, const Packing& packing, const Container& container,
                    double band_clearance, nlohmann::json& summary);

/// What the analyze job gives: the analysis, the warnings about the bed (analysis_warnings) and
/// its summary: analysis_summary, `warnings`, `container` (Container::summary_json) and, when the
/// plots were not drawn, `plots` saying why.
struct AnalyzeJob {
    BedAnalysis analysis;
    std::vector<std::string> warnings;
    nlohmann::json summary;
};

/// The analyze job of both front ends (`packbed analyze`, `packbed.analyze`): analyze_bed (the
/// default g(r) range no farther than a periodic cell's smaller period), the
/// warnings, the summary, and with an output its tables and plots staged (stage_analysis_files).
/// The caller adds its own keys to the summary, stages summary.json and commits.
AnalyzeJob analyze_job(const Packing& packing, const Container& container,
                       const AnalysisOptions& options, OutputDirectory* out);

/// Stage the files of an analysis in `out`: its tables (analysis_files) and its plots
/// (stage_plots). \return "" when the plots were drawn, or why not.
std::string stage_analysis_files(OutputDirectory& out, const BedAnalysis& analysis,
                                 const Container& container);

/// Stage the plots of an analysis, drawn by gnuplot (Debian: gnuplot-nox) when it is installed:
/// the wall profile (in a cylinder with the de Klerk and Mueller correlations), the centre
/// distribution (by size class too), the axial profile and g(r), SVG and PNG, in `out`.
/// \return "" when drawn, or why not (gnuplot missing or failing): the run goes on without.
std::string stage_plots(OutputDirectory& out, const BedAnalysis& analysis,
                        const Container& container);

/// A front end's hook for the child programs the pipeline runs (gnuplot): called with the
/// child's process id (in a process group of its own) when it starts and with 0 when it has
/// ended, so that an interrupt handler can stop it. Process-wide; empty by default.
void set_child_watcher(std::function<void(pid_t)> watcher);

// ---------------------------------------------------------------------------------------------
// reading a bed

/// The container recorded in `summary.json` beside a particle file (written by
/// `packbed generate`, `lattice`, `analyze`): any of the four shapes (read_bed_summary).
/// \return nothing when there is no such file or it names no container.
/// \throws InvalidInput naming the file when it exists but is not a regular file, not a
/// summary, or has a container outside the limits
std::optional<Container> container_beside(const std::filesystem::path& particles);

/// The friction between spheres recorded in `summary.json` beside a particle file (packbed
/// generate's parameters.friction). \return nothing when there is no such file or it records
/// none. \throws InvalidInput as container_beside
std::optional<double> friction_beside(const std::filesystem::path& particles);
/// The walls' and floor's friction recorded beside a particle file (parameters.wall_friction,
/// a pellet bed's wall_friction), as friction_beside.
std::optional<double> wall_friction_beside(const std::filesystem::path& particles);

/// The period along z recorded in `summary.json` beside a particle file (a random array's
/// period_z). \return nothing when there is no such file or it records none.
/// \throws InvalidInput as container_beside
std::optional<double> period_z_beside(const std::filesystem::path& particles);

/// The pellet recorded in `summary.json` beside a particle file (`shape.spec`, what `generate
/// --shape` wrote). \return nothing when there is no such file or it records no shape (a bed of
/// spheres). \throws InvalidInput as container_beside, and when the spec is not a pellet
/// (parse_pellet_shape)
std::optional<PelletSpec> shape_beside(const std::filesystem::path& particles);

/// The container a spec text names (parse_container). \throws InvalidInput naming `option`,
/// the text and the four forms when it names none
Container container_from_spec(std::string_view option, const std::string& spec);

/// The container of the bed file `particles`: the spec `container` when given, else a
/// cylinder of radius `cylinder_radius` when > 0, else the one summary.json beside the file
/// records (container_beside). \return nothing when none of these gives one.
/// \throws InvalidInput for a spec that is not one (never skipped for the next source) or a bad
/// summary.json
std::optional<Container> find_container(const std::filesystem::path& particles,
                                        const std::string& container, double cylinder_radius = 0.0);

/// A bed read from a file, with its container when one is known.
struct BedInContainer {
    ParticleFile file;
    std::optional<Container> container;
    /// the pellets' shape (shape_beside) where read_bed_or_pellets read a bed of pellets
    std::optional<PelletSpec> pellet;
};

/// Read a bed file as `analyze`, `voxelize` and `packbed.read` do: read_particles, its
/// container (find_container), and, where there is one, the check that no sphere sticks out
/// by more than `outside_tolerance` Dp (Dp: the given diameter, else the spheres' mean;
/// check_inside).
/// \throws InvalidInput naming the file (and line) and what is allowed
BedInContainer read_bed_in_container(const std::filesystem::path& particles,
                                     const ReadOptions& options, const std::string& container,
                                     double cylinder_radius, double outside_tolerance);

/// read_bed_in_container, or, where summary.json beside the file records a pellet
/// (shape_beside), the pellets (their orientations) in their container with `pellet` set,
/// checked by their exact shapes (check_pellets_inside at `outside_tolerance` d_v) instead of
/// the spheres' check: r is a pellet's d_v / 2, not its extent.
BedInContainer read_bed_or_pellets(const std::filesystem::path& particles,
                                   const ReadOptions& options, const std::string& container,
                                   double cylinder_radius, double outside_tolerance);

/// Refuse pellets that reach beyond the container's walls or below its floor by more than
/// `outside_tolerance` d_v (the shape's exact wall_overlap, its lowest point), or whose
/// centroid lies outside a periodic cell by more than that.
/// \throws InvalidInput naming the file, the line, the pellet and the allowed tolerance
void check_pellets_inside(const Packing& packing, const std::vector<std::size_t>& lines,
                          std::string_view name, const Container& container,
                          const PelletSpec& pellet, double outside_tolerance);

/// check_inside for a file read with `options`, at `outside_tolerance` Dp (Dp: the file's
/// given diameter, else the spheres' mean), saying whether --axis and --floor moved it; with
/// `period_z` (period_z_beside: a random array's cube) periodic along z too.
void check_file_inside(const ParticleFile& file, const ReadOptions& options, std::string_view name,
                       const Container& container, double outside_tolerance,
                       std::optional<double> period_z);

/// One frame of a trajectory in a void-fraction series (`analyze --frames all`).
struct FrameVoidFraction {
    std::size_t frame = 0;               ///< from 1
    std::optional<long long> timestep;   ///< the dump's, when it has one
    std::optional<double> void_fraction; ///< none: no spheres, or not tall enough for the band
    std::size_t particles = 0;
};

/// Every frame of a trajectory, its void fraction in the band of `analysis` (a fixed band, or
/// band_clearance Dp clear of the frame's ends), and the last frame with spheres, for the full
/// analysis.
struct FrameSeries {
    std::vector<FrameVoidFraction> frames;
    ParticleFile last;
};

/// Read every frame of `particles` (for_each_particle_frame), each checked inside `container`
/// (check_file_inside at `outside_tolerance` Dp), and measure its void fraction.
/// \throws InvalidInput naming the frame (and timestep), or when no frame has spheres
FrameSeries void_fraction_series(const std::filesystem::path& particles, const ReadOptions& options,
                                 const Container& container, const AnalysisOptions& analysis,
                                 double outside_tolerance);

/// void_fraction_series.csv: frame,timestep,void_fraction,particles (empty where none).
std::string frame_series_table(const FrameSeries& series);

/// Refuse spheres that stick out of the container by more than `tolerance` (length units;
/// Container::sticks_out: beyond a wall, or a centre outside a periodic cell) or below the floor;
/// in a cell periodic along z too (`period_z`: random_array's cube), whose spheres cross its
/// floor and top, a centre below the floor or above the top.
/// \param name the file in messages, with each sphere's line \param lines each sphere's line
/// \param shifted the centres were moved by --axis and --floor (the message says so)
/// \throws InvalidInput naming the file, the line, the sphere and the allowed tolerance
void check_inside(const Packing& packing, const std::vector<std::size_t>& lines,
                  std::string_view name, const Container& container, double tolerance, bool shifted,
                  std::optional<double> period_z = std::nullopt);

// ---------------------------------------------------------------------------------------------
// export

/// What `packbed export` is asked for, once the bed is read and its container known.
struct ExportRequest {
    std::string format = "lammps-data"; ///< one of export_format_names()
    /// the file (data file, STL, OBJ: its `.json` report and the example DEM input beside it)
    /// or the case directory (openfoam: new or empty, or any with `force`)
    std::filesystem::path out;
    bool force = false;
    std::string source; ///< the bed's name in headers, reports and messages (its file)
    /// the bed's file: an input of the job (record_input), and the summary.json beside it;
    /// "": none
    std::filesystem::path keep;
    /// the friction the bed was generated with; none: the one summary.json beside `keep`
    /// records (friction_beside). Above 0, the example DEM input's friction.
    std::optional<double> friction;
    /// the walls' and floor's friction; none: the one summary.json beside `keep` records
    /// (wall_friction_beside). Where it differs from the bed's friction, the example DEM
    /// input's walls have it.
    std::optional<double> wall_friction;
    std::optional<Container> container; ///< the bed's; none: no wall treatment, no example
    /// the particles' shape (shape_beside, or export --shape); none: spheres. Pellets are
    /// written as surfaces (STL, OBJ, openfoam) with the contacts none or shrink:F
    std::optional<PelletSpec> pellet;
    double container_height = 0.0; ///< 0: the bed's top + 1 Dp
    bool no_container = false;     ///< surfaces: no container solids; data files: ignore it
    // data files
    double density = 2500.0;    ///< written for every atom
    std::string box;            ///< "xlo,xhi,ylo,yhi,zlo,zhi"; "": the container's or the bed's
    double fluid_velocity = -1; ///< >= 0: recorded in the header and FILE.fluid.in
    // surfaces
    std::string contacts = "none"; ///< a contact treatment (surface.hpp, docs/surfaces.md)
    int refine = 3;                ///< icosphere level
    /// a name of facet_modes(): where a sphere's facets lie; "": the format's default (auto
    /// for openfoam, inscribed for stl, stl-ascii and obj)
    std::string facets;
    double edge = 0.0; ///< > 0: the largest mean triangle edge, instead of refine
    OpenFoamMeshOptions mesh;
    OpenFoamFlowOptions flow;           ///< openfoam: the flow of the runnable case
    std::string turbulence = "laminar"; ///< openfoam: a name of turbulence_models() (flow's)
};

/// The formats of export: lammps-data, liggghts-data, stl, stl-ascii, obj, openfoam.
std::vector<std::string> export_format_names();

/// export's format where none is given, from the output's name: stl for a .stl file, obj for
/// a .obj one (either case), else lammps-data.
std::string export_format_for(const std::filesystem::path& out);

/// Where `export` writes by default for the bed file `particles`: the file with .data, .stl or
/// .obj, or the directory openfoam/ beside it.
std::filesystem::path default_export_path(const std::filesystem::path& particles,
                                          const std::string& format);

/// Whether export_bed uses the request's container: always for surfaces (cutting, walls), for
/// data files unless `no_container` (then they ignore it; the caller need not look for one).
/// \throws InvalidInput for an unknown format
bool export_uses_container(const ExportRequest& request);

/// Write a bed as `request` says (every check before the work; nothing half-written).
/// \param lines each sphere's line in its file, for messages (empty: the sphere's number)
/// \return the report line (what was written where)
/// \throws InvalidInput naming the option, the value and what is allowed
std::string export_bed(const Packing& packing, const std::vector<std::size_t>& lines,
                       const ExportRequest& request);

// ---------------------------------------------------------------------------------------------
// hydraulics and correlations

/// A computed report: its numbers as `--json` prints them, and the warnings to show with them
/// (a correlation used outside its validity range).
struct Report {
    nlohmann::json values;
    std::vector<std::string> warnings;
};

/// What `packbed hydraulics` is asked for (SI units).
struct HydraulicsRequest {
    FluidAndParticles fluid{1e-3, 2500.0, 998.2, 1.002e-3, 9.80665}; ///< glass in water, 20 C
    double porosity = 0.0;                                           ///< 0: from `bed`
    std::string bed;                 ///< a summary.json or its directory; "": `porosity`
    double velocity = 0.0;           ///< 0: the critical velocity of eq. (1)
    double aspect_ratio = 0.0;       ///< 0: no wall-corrected pressure drop (or from `bed`)
    bool diameter_given = false;     ///< fluid.diameter was given (not the default)
    bool aspect_ratio_given = false; ///< aspect_ratio was given
    std::string container;           ///< a --container SPEC in metres, instead of aspect_ratio
};

/// The onset of fluidization (Tsayger 2013, eq. (1)) and the fluid velocity for a DEM start,
/// Wen & Yu, Ergun's and Eisfeld & Schnitzlein's pressure gradients, permeabilities and the
/// regular packings' eqs. (2)-(4), for a porosity given or read from a bed's summary.json.
/// \throws InvalidInput naming the input, the value and what is allowed (also when a result
/// would not be a finite number)
Report hydraulics_report(const HydraulicsRequest& request);

/// What `packbed correlations` is asked for.
struct CorrelationsRequest {
    double aspect_ratio = 5.0;  ///< a = D/d
    double profile_step = 0.01; ///< of the radial profiles, d
    double profile_to = 5.0;    ///< the radial profiles from the wall to this, d
};

/// At most this many steps in a radial profile (--profile-to over --profile-step).
inline constexpr double max_profile_steps = 1e5;

/// The published void-fraction correlations at an aspect ratio: the mean void fractions and
/// the radial profiles, each with its formula, source and validity range. The profiles at
/// x = k profile_step from the wall, up to profile_to or the axis (a / 2), whichever is nearer.
/// \throws InvalidInput when that is more than max_profile_steps steps
Report correlations_report(const CorrelationsRequest& request);

// ---------------------------------------------------------------------------------------------
// cfd-report: a run OpenFOAM case's pressure drop against the correlations

/// A straight line p = intercept + slope z fitted by least squares.
struct PressureFit {
    double slope = 0.0;
    double intercept = 0.0;
    double standard_error = 0.0; ///< of the slope; 0 for two points
};

/// The least-squares line through the planes' (z, p).
/// \throws InvalidInput for fewer than 2 points, lists of different lengths or one height
PressureFit fit_pressure(const std::vector<double>& z, const std::vector<double>& p);

/// Check that CASE is a directory, and record it as an input of the job (JobScope): the front
/// ends call this before they claim cfd-report's output, so that an output that is the case or
/// holds it is refused before anything is read. \throws InvalidInput naming CASE
void check_cfd_case(const std::filesystem::path& case_dir);

/// The pressure drop of a case written by export --format openfoam and run by its Allrun:
/// the planes' area-averaged pressures (postProcessing/pN, times rho: Pa), the gradient -dp/dz
/// of the straight line fitted to them, Ergun's and Eisfeld & Schnitzlein's gradients at the
/// bed's own void fraction between the first and the last plane and the wall's aspect ratio
/// (both recorded in packbed.json by the export), the inlet's and outlet's fluxes, whether
/// simpleFoam converged (log.simpleFoam) and the mesh's void fraction (log.checkMesh's total
/// volume over the container's). A correlation outside its range gives a warning.
/// \throws InvalidInput naming CASE when a file is missing or not what Allrun writes
Report cfd_report(const std::filesystem::path& case_dir);

/// Stage `report` (cfd_report) in `out`: pressure.csv (the planes), cfd_report.json and the
/// plot pressure.svg/.png (the planes, the fit and the correlations' lines through the planes'
/// mean). \return "" or why there is no plot (gnuplot missing or failed)
std::string stage_cfd_report(OutputDirectory& out, const Report& report);

/// A mesh series' answer by Celik et al. (2008, J. Fluids Eng. 130, 078001, "Procedure for
/// estimation and reporting of uncertainty due to discretization in CFD applications", steps
/// 1-5) from its three finest levels.
struct GridConvergence {
    double order = 0.0;              ///< apparent order p
    double extrapolated = 0.0;       ///< Richardson's phi_ext^21
    double approximate_error = 0.0;  ///< e_a^21 = |(phi_1 - phi_2) / phi_1|
    double extrapolated_error = 0.0; ///< e_ext^21 = |(phi_ext - phi_1) / phi_ext|
    double gci_fine = 0.0;           ///< GCI_fine^21 = 1.25 e_a^21 / (r_21^p - 1)
    bool oscillating = false;        ///< the two differences of opposite signs (s = -1)
};

/// Celik et al.'s steps: h_1 < h_2 < h_3 the representative cell sizes (finest first), phi
/// the values; r_21 = h_2 / h_1, r_32 = h_3 / h_2, e_21 = phi_2 - phi_1, e_32 = phi_3 - phi_2,
/// s = sign(e_32 / e_21); the order solves p = |ln|e_32 / e_21| + q(p)| / ln r_21 with
/// q(p) = ln((r_21^p - s) / (r_32^p - s)) by fixed-point iteration from p = 2 (eqs. 3a-3c);
/// phi_ext = (r_21^p phi_1 - phi_2) / (r_21^p - 1) (eq. 4). \throws InvalidInput when the
/// sizes are not increasing, two levels give the same value, or the iteration finds no order
GridConvergence grid_convergence(const std::array<double, 3>& h, const std::array<double, 3>& phi);

/// A mesh series of cases of one bed (each as cfd_report reads it), coarse to fine by their
/// cells: each level's cells, representative size h = (mesh volume / cells)^(1/3) over the
/// spheres' diameter, the mesh's and the exact void fraction and the answer (a periodic
/// cell's K, else the pressure gradient), and grid_convergence of the three finest with the
/// reference where there is one (Zick & Homsy's K); a warning when the apparent order lies
/// outside 1 to 3 (the schemes' formal order is 2). \throws InvalidInput for fewer than 3
/// cases, cases of different kinds, or two with the same number of cells
Report cfd_series(const std::vector<std::filesystem::path>& cases);

/// Stage `report` (cfd_series) in `out`: series.csv and series.json.
void stage_cfd_series(OutputDirectory& out, const Report& report);

// ---------------------------------------------------------------------------------------------
// voxel images

/// A voxel image of a bed: the pore image (binary) or the solid fraction image.
struct VoxelImage {
    VoxelGrid grid;
    VoxelType type = VoxelType::boolean;
    Voxels<std::uint8_t> pore; ///< boolean: 1 pore, 0 solid (pore_image)
    Voxels<double> fraction;   ///< float64: each voxel's solid fraction, exact
    Voxels<float> fraction32;  ///< float32: the same, each rounded to single precision
    /// \return whether this is the pore image
    bool binary() const { return type == VoxelType::boolean; }
    /// \return the voxels of its type, in C order (VoxelGrid)
    const void* data() const;
    /// \return the porosity of the image: the mean of the pore image, or 1 - the mean solid
    /// fraction (over every voxel of the grid, the container's outside included)
    double porosity() const;
};

/// The type of voxelize's image from its --kind (binary, fraction) and --dtype (float64,
/// float32; fractions only).
/// \throws InvalidInput naming the option for any other text, and for a --dtype other than
/// float64 with --kind binary (a bool image)
VoxelType voxel_type(std::string_view kind, std::string_view dtype);

/// The grid `voxelize` draws on (voxel_grid): the default region's top the spheres' top, the
/// pellets' highest point (pellet_bed_top) given `pellet`, or the cell's top `period_z` of a
/// bed periodic along z too (random_array's cube, its summary.json's period_z). Called
/// before the work to check the image's size. \throws InvalidInput as voxel_grid
VoxelGrid voxelize_grid(const Packing& packing, const Container& container, double voxel_size,
                        const std::optional<std::array<double, 6>>& region, VoxelType type,
                        const PelletShape* pellet = nullptr,
                        std::optional<double> period_z = std::nullopt);

/// Make the image `voxelize` makes: voxelize_grid, then pore_image (type boolean) or
/// solid_fraction_image (float64 or float32), of spheres or, given `pellet`, of pellets of that
/// shape. With `period_z` (spheres), each sphere that crosses the cell's floor or top is drawn
/// again a period above or below, so the image of the cube wraps along z as across x and y.
/// \throws InvalidInput as voxel_grid
VoxelImage voxelize(const Packing& packing, const Container& container, double voxel_size,
                    const std::optional<std::array<double, 6>>& region, VoxelType type,
                    const PelletShape* pellet = nullptr,
                    std::optional<double> period_z = std::nullopt);

/// \return a warning where the image of a periodic cell drawn over its default region (the
/// cell, `region` not given) does not tile: a period (x, y, or z with `period_z`) that is not a
/// whole number of voxels (within 1e-9, as voxel_grid counts them), so that the whole voxels
/// covering it reach past the cell; else "". It names a voxel size that divides the period.
std::string untiled_cell_warning(const VoxelGrid& grid, const Container& container,
                                 bool region_given, std::optional<double> period_z);

/// Stage an image as the file `name` of `out` in `format`, and a raw image's header as
/// name + ".json" (image_header).
void stage_image(OutputDirectory& out, const std::string& name, ImageFormat format,
                 const VoxelImage& image);

} // namespace packbed
