// `packbed analyze`: structure of a bed from any source (ours, LAMMPS, LIGGGHTS, XYZ).
#include <array>
#include <charconv>
#include <filesystem>
#include <memory>
#include <optional>

#include <fmt/format.h>
#include <nlohmann/json.hpp>
#include <omp.h>

#include "command.hpp"
#include "packbed/analysis.hpp"
#include "packbed/analysis_files.hpp"
#include "packbed/error.hpp"
#include "packbed/files.hpp"
#include "packbed/io.hpp"
#include "packbed/json_text.hpp"
#include "packbed/limits.hpp"
#include "packbed/output.hpp"
#include "packbed/pipeline.hpp"
#include "packbed/read.hpp"
#include "packbed/text.hpp"

namespace packbed::cli {

namespace {

namespace fs = std::filesystem;

struct AnalyzeOptions {
    std::string particles;
    std::string format = "auto";
    double container_radius = 0.0; // 0: from summary.json next to the file
    std::string container; // --container cylinder:D, box, annulus, periodic, or --container-radius
    std::string band;      // --band ZLOW,ZHIGH, instead of --band-clearance
    std::string out;       // default: analysis/ next to the file
    double diameter = 0.0; // 0: the mean sphere diameter
    double outside_tolerance = 0.01;
    InputPlacement placement; // --frame, --axis, --floor
    std::string frames;       // "all": every frame, and void_fraction_series.csv
    AnalysisOptions analysis;
    std::optional<double> friction; // none: the one summary.json beside the file records
    unsigned long long threads = static_cast<unsigned long long>(omp_get_num_procs());
    bool quiet = false;
    bool force = false;
    const CLI::App* app = nullptr; // which options were given (those a pellet bed refuses)
};

/// The spheres' options that a bed of pellets has no use for (Python's analyze refuses the
/// same).
constexpr std::array sphere_only_options{"--diameter", "--centre-bin", "--rdf-range", "--rdf-bin",
                                         "--friction"};

/// "N spheres touch the wall"; for an annulus each wall's count; in a periodic cell, that it
/// has no wall (nor wall profiles).
std::string wall_contacts_line(const BedAnalysis& a) {
    if (a.walls.size() == 1)
        return fmt::format("{} spheres touch the wall", a.coordination.wall_contacts);
    if (a.walls.empty())
        return "no side walls (periodic cell): no wall profile, centre distribution or wall "
               "contacts";
    std::string line;
    for (const WallAnalysis& wall : a.walls)
        line += fmt::format("{}{} spheres touch the {} wall", line.empty() ? "" : ", ",
                            wall.wall_contacts, wall.name);
    return line;
}

/// A bed of pellets (the shape summary.json beside it records): the exact void fractions and
/// the orientation of the axes (analyze_pellet_bed).
int run_pellet_analyze(const AnalyzeOptions& o, const fs::path& path, const ReadOptions& read,
                       const PelletSpec& pellet) {
    if (o.frames == "all")
        throw InvalidInput(fmt::format("--frames all is not allowed for a bed of {} pellets; "
                                       "allowed: one frame",
                                       pellet.text));
    for (const char* name : sphere_only_options)
        if (o.app && o.app->get_option(name)->count() > 0)
            throw InvalidInput(fmt::format(
                "{} is not allowed for a bed of {} pellets; allowed with pellets: --container, "
                "--band, --band-clearance, --shell-width, --slab-height, --contact-tolerance, "
                "--outside-tolerance (lengths in d_v), --format, --frame, --axis, --floor, "
                "--out, --force, --threads, --quiet",
                name, pellet.text));
    const ParticleFile file = read_particles(path, read);
    const std::optional<Container> found = find_container(path, o.container, o.container_radius);
    if (!found)
        throw InvalidInput(fmt::format("--container (or --container-radius) is needed: no "
                                       "summary.json with a container next to {}",
                                       printable(path.native())));
    check_pellets_inside(file.packing, file.lines, path.string(), *found, pellet,
                         o.outside_tolerance);
    const fs::path out_dir = o.out.empty() ? path.parent_path() / "analysis" : fs::path(o.out);
    OutputDirectory out(out_dir, "--out", OutputKind::directory, o.force);
    use_threads(o.threads);
    const PelletAnalysis a = analyze_pellet_bed(file.packing, pellet.shape, *found, o.analysis);
    nlohmann::ordered_json summary;
    summary["particles_file"] = path.string();
    summary.update(pellet_analysis_summary(a, pellet.text, file.packing.size(), *found,
                                           o.analysis.contact_tolerance));
    for (const auto& [name, text] : pellet_analysis_files(a, *found))
        out.stage(name, text);
    out.stage("summary.json", json_file_text(summary, "summary.json"));
    out.commit();
    if (!o.quiet) {
        const Coordination& c = a.coordination;
        fmt::print("packbed analyze: {} {} pellets in {}\n", file.packing.size(), pellet.text,
                   found->describe());
        fmt::print("void fraction: {:.4f} (between z = {:.4g} and z = {:.4g})\n", a.void_fraction,
                   a.band.z_low, a.band.z_high);
        fmt::print("orientation: <cos^2 theta> = {:.4f}, S = {:.4f} over {} pellets (1/3 and 0 at "
                   "random)\n",
                   a.overall.mean_cos2, a.overall.order, a.overall.pellets);
        fmt::print("contacts: {:.3f} per pellet ({:.3f} without {} rattlers, pellets touching "
                   "nothing); {} pellets touch the wall\n",
                   c.mean, c.mean_without_rattlers, c.rattlers, c.wall_contacts);
        fmt::print("results in {}/\n", out_dir.string());
    }
    return 0;
}

int run_analyze(AnalyzeOptions& o) {
    const fs::path path(o.particles);
    ReadOptions read_options;
    if (o.diameter > 0.0)
        read_options.radius = 0.5 * o.diameter;
    read_options.format = particle_formats().at(o.format);
    o.placement.apply(read_options);
    const bool series = o.frames == "all";
    if (const auto b = parse_finite_list(o.band); b && b->size() == 2)
        o.analysis.band = Band{(*b)[0], (*b)[1]};
    record_input("the particles file", path); // before its summary, as the reader would
    if (const std::optional<PelletSpec> pellet = shape_beside(path))
        return run_pellet_analyze(o, path, read_options, *pellet);
    // --container, then --container-radius, then the container summary.json records.
    std::optional<ParticleFile> read;
    std::optional<Container> given;
    if (series) {
        given = find_container(path, o.container, o.container_radius);
    } else {
        BedInContainer bed = read_bed_in_container(path, read_options, o.container,
                                                   o.container_radius, o.outside_tolerance);
        read = std::move(bed.file);
        given = std::move(bed.container);
    }
    if (!given)
        throw InvalidInput(fmt::format("--container (or --container-radius) is needed: no "
                                       "summary.json with a container next to {}",
                                       printable(path.native())));
    const Container container = *given;
    if (o.diameter > 0.0)
        o.analysis.diameter = o.diameter;
    o.analysis.rdf_range_given = o.app && o.app->get_option("--rdf-range")->count() > 0;
    // summary.json is read only when --friction is not given
    o.analysis.frictional = (o.friction ? *o.friction : friction_beside(path).value_or(0.0)) > 0.0;

    const fs::path out_dir = o.out.empty() ? path.parent_path() / "analysis" : fs::path(o.out);
    OutputDirectory out(out_dir, "--out", OutputKind::directory, o.force);
    use_threads(o.threads);
    std::size_t frames = 0;
    if (series) {
        // Every frame: its void fraction in the series; the last frame with spheres is the one
        // analysed in full below.
        FrameSeries frames_read =
            void_fraction_series(path, read_options, container, o.analysis, o.outside_tolerance);
        frames = frames_read.frames.size();
        out.stage("void_fraction_series.csv", frame_series_table(frames_read));
        read = std::move(frames_read.last);
    }
    const ParticleFile& file = *read;
    AnalyzeJob job = analyze_job(file.packing, container, o.analysis, &out);
    const BedAnalysis& analysis = job.analysis;
    nlohmann::json& summary = job.summary;
    summary["particles_file"] = path.string();
    summary["particles"] = file.packing.size();
    summary["frame"] = file.frame;
    if (file.timestep)
        summary["timestep"] = *file.timestep;
    if (series) {
        summary["frames"] = frames;
        summary["void_fraction_series"] = "void_fraction_series.csv";
    }
    summary["axis"] = {read_options.axis[0], read_options.axis[1]};
    summary["floor"] = read_options.floor;
    if (summary.contains("plots") && !o.quiet)
        fmt::print(stderr, "packbed analyze: {}\n", summary["plots"].get<std::string>());
    out.stage("summary.json", json_file_text(summary, "summary.json"));
    out.commit();
    if (!o.quiet)
        for (const auto& warning : job.warnings)
            fmt::print(stderr, "packbed analyze: warning: {}\n", warning);
    if (!o.quiet) {
        fmt::print("packbed analyze: {} spheres in {}{}\n", file.packing.size(),
                   container.describe(),
                   series ? fmt::format(" (frame {} of {}; the void fraction of every frame in "
                                        "void_fraction_series.csv)",
                                        file.frame, frames)
                          : "");
        fmt::print("void fraction: {:.4f} (between z = {:.4g} and z = {:.4g})\n",
                   analysis.void_fraction, analysis.band.z_low, analysis.band.z_high);
        fmt::print("coordination: {:.3f} ({:.3f} without {} rattlers, spheres with fewer than "
                   "{} contacts{}, a wall counted); {}\n",
                   analysis.coordination.mean, analysis.coordination.mean_without_rattlers,
                   analysis.coordination.rattlers, analysis.coordination.rattler_contacts,
                   o.analysis.frictional ? " in a frictional bed" : "",
                   wall_contacts_line(analysis));
        fmt::print("results in {}/\n", out_dir.string());
    }
    return 0;
}

} // namespace

Command register_analyze(CLI::App& parent) {
    auto options = std::make_shared<AnalyzeOptions>();
    auto& o = *options;
    auto& a = o.analysis;
    CLI::App* app = parent.add_subcommand(
        "analyze", "Measure a bed of spheres in a cylinder, a box, an annulus or a periodic cell: "
                   "overall, wall and axial void fraction, centre distribution, coordination, "
                   "wall contacts, g(r)");
    app->option_defaults()->always_capture_default();
    app->fallthrough();
    app->add_option("particles", o.particles,
                    "the bed: a table (CSV x,y,z,r or d; ParaView CSV; ;/tab/space separated), "
                    "XYZ, a LAMMPS/LIGGGHTS dump or data file; also .gz")
        ->required()
        ->check(path_text());
    app->add_option("--format", o.format, "file format; auto: from the extension or first line")
        ->check(one_of(particle_formats().names()));
    CLI::Option* radius =
        app->add_option("-R,--container-radius", o.container_radius,
                        "cylinder radius Rt (file units), shorthand of --container "
                        "cylinder:2Rt; default: summary.json next to the file")
            ->check(real_in(option_range::container_radius));
    add_container_option(*app, o.container, "file units; default: summary.json next to the file",
                         all_shapes)
        ->excludes(radius);
    add_output_directory(*app, o.out, o.force, "analysis/ next to the file");
    app->add_option("-d,--diameter", o.diameter,
                    "reference diameter Dp, and the sphere size of files without a radius or "
                    "diameter column; default: the mean sphere diameter")
        ->check(real_in(option_range::diameter));
    CLI::Option* clearance =
        app->add_option("--band-clearance", a.band_clearance,
                        "properties refer to the band this far from floor and top, Dp")
            ->check(real_in(option_range::band_clearance));
    app->add_option("--band", o.band,
                    "ZLOW,ZHIGH: the band the properties refer to (file units, 0 <= ZLOW < ZHIGH "
                    "<= the bed's top), instead of --band-clearance")
        ->check(CLI::Validator(
            [](std::string& text) -> std::string {
                const auto v = parse_finite_list(text);
                if (v && v->size() == 2 && (*v)[0] >= 0.0 && (*v)[0] < (*v)[1] &&
                    (*v)[1] <= limits::max_length)
                    return {};
                return fmt::format("'{}' is not allowed; allowed: ZLOW,ZHIGH, two numbers with 0 "
                                   "<= ZLOW < ZHIGH <= {:g}",
                                   printable(text.substr(0, 80)), limits::max_length);
            },
            "ZLOW,ZHIGH"))
        ->excludes(clearance);
    app->add_option("--shell-width", a.shell_width, "shell width of the radial profile, Dp")
        ->check(real_in(option_range::shell_width));
    app->add_option("--slab-height", a.slab_height, "slab height of the axial profile, Dp")
        ->check(real_in(option_range::slab_height));
    app->add_option("--centre-bin", a.centre_bin, "bin width of the centre distribution, Dp")
        ->check(real_in(option_range::centre_bin));
    app->add_option("--contact-tolerance", a.contact_tolerance, "a gap up to this is a contact, Dp")
        ->check(real_in(option_range::contact_tolerance));
    app->add_option("--friction", o.friction,
                    "friction between the spheres; above 0 a rattler has fewer than 2 contacts, "
                    "not 4 (default: summary.json's beside the file, else 0)")
        ->check(real_in(option_range::friction));
    app->add_option("--rdf-range", a.rdf_range, "largest distance of g(r), Dp")
        ->check(real_in(option_range::rdf_range));
    app->add_option("--rdf-bin", a.rdf_bin, "bin width of g(r), Dp")
        ->check(real_in(option_range::rdf_bin));
    CLI::Option* frame = add_input_placement(*app, o.placement);
    app->add_option("--frames", o.frames,
                    "all: the void fraction of every frame in void_fraction_series.csv (frame, "
                    "timestep, void_fraction, particles), the last frame analysed in full")
        ->check(one_of({"all"}))
        ->excludes(frame);
    app->add_option("--outside-tolerance", o.outside_tolerance,
                    "how far a sphere may stick out of the wall or floor, Dp (a pellet: d_v)")
        ->check(real_in(option_range::outside_tolerance));
    add_threads_option(*app, o.threads);
    app->add_flag("-q,--quiet", o.quiet, "no report on the terminal");
    o.app = app;
    return {app, [options] { return run_analyze(*options); }};
}

} // namespace packbed::cli
