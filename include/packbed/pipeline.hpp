// What a front end runs for a whole job, from its inputs to its files: the command line
// (apps/packbed) and the Python module (python/) are thin callers of these, so neither gets
// less than the other nor a copy of this logic.
#pragma once

#include <filesystem>
#include <functional>
#include <optional>
#include <string>
#include <string_view>

#include <nlohmann/json.hpp>
#include <sys/types.h>

#include "packbed/analysis.hpp"
#include "packbed/container.hpp"
#include "packbed/output.hpp"
#include "packbed/packing.hpp"
#include "packbed/sizes.hpp"
#include "packbed/soft_sphere.hpp"
#include "packbed/voxel.hpp"

namespace packbed {

/// Run the library's parallel loops on at most `threads` OpenMP threads, fewer while the
/// machine is busy (OpenMP's dynamic adjustment, which in GCC's libgomp subtracts the load
/// average from the cores): a thread that waits for a core at every barrier turns seconds
/// into minutes, and the results do not depend on the number of threads anyway. Setting
/// OMP_DYNAMIC (e.g. false, for benchmarks) leaves the choice to OpenMP.
void use_threads(unsigned long long threads);

// ---------------------------------------------------------------------------------------------
// generate: the soft-sphere bed of Salvat et al. (2005)

/// What `packbed generate` is asked for, as its options give it.
struct GenerateRequest {
    /// The solver's parameters; `diameter` is --diameter (with `sizes`, what the distribution's
    /// `mono` means; the bed's Dp becomes the drawn sizes' Sauter mean d32).
    SoftSphereParameters params;
    std::string sizes = "mono";                      ///< a --sizes spec (docs/sizes.md)
    FractionBasis fractions = FractionBasis::volume; ///< what the sizes' fractions count
    std::string container;                           ///< a ContainerSpec text; "": aspect_ratio
    std::string checkpoint;                          ///< --checkpoint file; "": none
    double band_clearance = 1.0;                     ///< of the void-fraction band, Dp
};

/// A request with its sizes drawn and its container resolved into the solver's parameters,
/// every check made: what the run will do, before it starts (for a progress estimate).
struct PreparedGeneration {
    GenerateRequest request;
    SoftSphereParameters params;         ///< validated; lengths in Dp
    std::optional<SizeStatistics> drawn; ///< the drawn sizes' statistics (none for `mono`)
};

/// Draw the sizes (a stream of their own: seed XOR 0x9E3779B97F4A7C15), resolve the container
/// (a = D / Dp for a tube, any other shape in units of Dp) and check everything, the
/// checkpoint's compatibility included.
/// \throws InvalidInput naming the option, the value and what is allowed
PreparedGeneration prepare_generation(GenerateRequest request);

/// A generated bed and its record.
struct GeneratedBed {
    SoftSphereResult result;
    /// summary.json: soft_sphere_summary (with `threads`), the sizes, later the analysis
    nlohmann::json summary;
};

/// Run the solver on a prepared generation. With a checkpoint: `out` (when given) is told to
/// keep it, the file is checked for writing before the run, a run resumes from it when it
/// exists (`on_resume` is told after which layer) and it is written after every layer.
/// \param control on_progress, should_stop (on_layer and resume are set here for a checkpoint)
/// \param threads recorded in the summary
/// \throws ConvergenceError, Cancelled, InvalidInput (a bad checkpoint)
GeneratedBed run_generation(const PreparedGeneration& prepared, RunControl control, int threads,
                            OutputDirectory* out = nullptr,
                            const std::function<void(std::uint32_t layers_done)>& on_resume = {});

// ---------------------------------------------------------------------------------------------
// the outputs of a bed

/// Stage what `generate` and `lattice` write for a bed: particles.csv, particles.vtu, the
/// analysis (stage_analysis) when `analyse` (the caller's choice: a bed tall enough for the
/// band), and summary.json.
void stage_bed(OutputDirectory& out, const Packing& packing, const Container& container,
               double band_clearance, bool analyse, nlohmann::json& summary);

/// The analysis `generate` and `lattice` run on what they made: analyze_bed over the band
/// `band_clearance` (Dp) clear of the ends (in a periodic cell g(r) within the smaller period),
/// its tables and plots staged in `out`, its numbers in summary["analysis"].
void stage_analysis(OutputDirectory& out, const Packing& packing, const Container& container,
                    double band_clearance, nlohmann::json& summary);

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

/// Refuse spheres that stick out of the container by more than `tolerance` (length units;
/// Container::sticks_out: beyond a wall, or a centre outside a periodic cell) or below the floor.
/// \param name the file in messages, with each sphere's line \param lines each sphere's line
/// \param shifted the centres were moved by --axis and --floor (the message says so)
/// \throws InvalidInput naming the file, the line, the sphere and the allowed tolerance
void check_inside(const Packing& packing, const std::vector<std::size_t>& lines,
                  std::string_view name, const Container& container, double tolerance,
                  bool shifted);

// ---------------------------------------------------------------------------------------------
// voxel images

/// A voxel image of a bed: the pore image (binary) or the solid fraction image.
struct VoxelImage {
    VoxelGrid grid;
    bool binary = true;
    std::vector<std::uint8_t> pore; ///< binary: 1 pore, 0 solid (pore_image)
    std::vector<double> fraction;   ///< not binary: each voxel's solid fraction, exact
    /// \return the porosity of the image: the mean of the pore image, or 1 - the mean solid
    /// fraction (over every voxel of the grid, the container's outside included)
    double porosity() const;
};

/// Make the image `voxelize` makes: voxel_grid, then pore_image or solid_fraction_image.
/// \throws InvalidInput as voxel_grid
VoxelImage voxelize(const Packing& packing, const Container& container, double voxel_size,
                    const std::optional<std::array<double, 6>>& region, bool binary);

/// Stage an image as the file `name` of `out` in `format`, and a raw image's header as
/// name + ".json" (image_header).
void stage_image(OutputDirectory& out, const std::string& name, ImageFormat format,
                 const VoxelImage& image);

} // namespace packbed
