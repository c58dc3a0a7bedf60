// `packbed voxelize`: a bed as a voxel image for image-based tools (PoreSpy and the like).
#include <filesystem>
#include <memory>
#include <optional>

#include <fmt/format.h>
#include <omp.h>

#include "command.hpp"
#include "packbed/error.hpp"
#include "packbed/files.hpp"
#include "packbed/limits.hpp"
#include "packbed/output.hpp"
#include "packbed/pipeline.hpp"
#include "packbed/read.hpp"
#include "packbed/text.hpp"
#include "packbed/voxel.hpp"

namespace packbed::cli {

namespace {

struct VoxelizeOptions {
    std::string particles;
    std::string format = "auto";
    std::string container;
    double diameter = 0.0; // 0: from the file
    double voxel_size = 0.0;
    std::string region; // XLOW,YLOW,ZLOW,XHIGH,YHIGH,ZHIGH; "": the container, floor to top
    std::string kind = "binary";
    std::string dtype = "float64";
    std::string out;
    double outside_tolerance = 0.01;
    InputPlacement placement;
    unsigned long long threads = static_cast<unsigned long long>(omp_get_num_procs());
    bool quiet = false;
};

int run_voxelize(VoxelizeOptions& o) {
    const std::filesystem::path path(o.particles);
    const auto format = image_format(o.out);
    if (!format)
        throw InvalidInput(fmt::format("--out {}: the extension is not allowed; allowed: .npy, "
                                       ".tif (or .tiff) or .raw (with a .raw.json header)",
                                       printable(o.out)));
    ReadOptions read_options;
    if (o.diameter > 0.0)
        read_options.radius = 0.5 * o.diameter;
    read_options.format = particle_formats().at(o.format);
    o.placement.apply(read_options);
    // A bed of pellets (the shape its summary.json records) is drawn as its pellets; a bed of
    // spheres is checked to lie inside its container first.
    const BedInContainer bed =
        read_bed_or_pellets(path, read_options, o.container, 0.0, o.outside_tolerance);
    const std::optional<PelletSpec>& pellet = bed.pellet;
    if (!bed.container)
        throw InvalidInput(fmt::format("--container is needed: no summary.json with a container "
                                       "next to {}",
                                       printable(path.native())));
    const ParticleFile& file = bed.file;
    const Container& container = *bed.container;
    const PelletShape* shape = pellet ? &pellet->shape : nullptr;
    std::optional<std::array<double, 6>> region;
    if (!o.region.empty()) {
        const auto v = parse_finite_list(o.region);
        if (!v || v->size() != 6)
            throw InvalidInput(fmt::format("--region '{}' is not allowed; allowed: XLOW,YLOW,ZLOW,"
                                           "XHIGH,YHIGH,ZHIGH (six numbers, file units)",
                                           printable(o.region.substr(0, 80))));
        region = std::array<double, 6>{(*v)[0], (*v)[1], (*v)[2], (*v)[3], (*v)[4], (*v)[5]};
    }
    const VoxelType type = voxel_type(o.kind, o.dtype);
    const bool binary = type == VoxelType::boolean;
    // A random array's cube is periodic along z too (its summary.json's period_z).
    const std::optional<double> period_z = shape ? std::nullopt : period_z_beside(path);
    // Every check before the work: the grid's size, the output.
    voxelize_grid(file.packing, container, o.voxel_size, region, type, shape, period_z);
    const std::filesystem::path target(o.out);
    OutputDirectory out(target.parent_path().empty() ? "." : target.parent_path(), "--out",
                        OutputKind::files);
    use_threads(o.threads);
    const VoxelImage image =
        voxelize(file.packing, container, o.voxel_size, region, type, shape, period_z);
    stage_image(out, target.filename().string(), *format, image);
    out.commit();
    if (const std::string warning =
            untiled_cell_warning(image.grid, container, region.has_value(), period_z);
        !warning.empty() && !o.quiet)
        fmt::print(stderr, "packbed voxelize: warning: {}\n", warning);
    if (!o.quiet)
        fmt::print("packbed voxelize: {}{} x {} x {} voxels of {:g} ({}), porosity of the image "
                   "{:.5f}{}: {}\n",
                   pellet ? fmt::format("{} pellets {} in ", file.packing.size(), pellet->text)
                          : std::string(),
                   image.grid.count[0], image.grid.count[1], image.grid.count[2], image.grid.size,
                   binary ? "1 = pore, 0 = solid"
                          : fmt::format("solid fractions, exact, {}", o.dtype),
                   image.porosity(),
                   container.periods() ? ""
                   : binary            ? " (the container's outside counted as solid)"
                                       : " (the container's outside counted as pore)",
                   target.string());
    return 0;
}

} // namespace

Command register_voxelize(CLI::App& parent) {
    auto options = std::make_shared<VoxelizeOptions>();
    auto& o = *options;
    CLI::App* app = parent.add_subcommand(
        "voxelize", "A bed as a voxel image: binary (1 = pore space, as PoreSpy) or the exact "
                    "solid fraction of each voxel; .npy, .tif or .raw + .json (docs/voxels.md)");
    app->option_defaults()->always_capture_default();
    app->fallthrough();
    app->add_option("particles", o.particles,
                    "the bed: any file analyze reads (CSV, XYZ, LAMMPS/LIGGGHTS dump or data; "
                    "also .gz); a bed of pellets with the shape its summary.json records")
        ->required()
        ->check(path_text());
    app->add_option("--format", o.format, "file format; auto: from the extension or first line")
        ->check(one_of(particle_formats().names()));
    add_container_option(*app, o.container, "file units; default: summary.json next to the file");
    app->add_option("--voxel-size", o.voxel_size, "the voxels' edge h (file units)")
        ->required()
        ->check(real_in(option_range::voxel_size));
    app->add_option("--region", o.region,
                    "XLOW,YLOW,ZLOW,XHIGH,YHIGH,ZHIGH: the box imaged (file units); default: the "
                    "container across, the floor to the bed's top")
        ->check(path_text());
    app->add_option("--kind", o.kind,
                    "binary: 1 where a voxel's centre is pore space (inside the container, in no "
                    "sphere or pellet), 0 solid; fraction: each voxel's solid fraction, exact "
                    "(float64)")
        ->check(one_of({"binary", "fraction"}));
    app->add_option("--dtype", o.dtype,
                    "the fractions' type: float64, or float32 for half the memory and file "
                    "(each value rounded once; --kind fraction only)")
        ->check(one_of({"float64", "float32"}));
    app->add_option("-o,--out", o.out,
                    "the image file: .npy (numpy), .tif (tifffile, ImageJ) or .raw (and .raw.json "
                    "with its shape, type, voxel size and origin); replaced if it exists")
        ->required()
        ->check(path_text());
    app->add_option("-d,--diameter", o.diameter,
                    "the sphere size of files without a radius or diameter column")
        ->check(real_in(option_range::diameter));
    add_input_placement(*app, o.placement);
    app->add_option("--outside-tolerance", o.outside_tolerance,
                    "how far a sphere may stick out of the wall or floor, Dp")
        ->check(real_in(option_range::outside_tolerance));
    add_threads_option(*app, o.threads);
    app->add_flag("-q,--quiet", o.quiet, "no report on the terminal");
    return {app, [options] { return run_voxelize(*options); }};
}

} // namespace packbed::cli
