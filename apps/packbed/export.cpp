// `packbed export`: any bed (generated, lattice, read from elsewhere) as a DEM data file.
#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include <fmt/format.h>

#include "command.hpp"
#include "packbed/error.hpp"
#include "packbed/io.hpp"
#include "packbed/read.hpp"

namespace packbed::cli {

namespace {

namespace fs = std::filesystem;

/// The data files `export` writes: LAMMPS `atom_style sphere` and LIGGGHTS `atom_style
/// granular` read the same columns; the name sets the first-line comment and the hint.
enum class ExportFormat { lammps_data, liggghts_data };

const std::vector<std::pair<std::string, ExportFormat>>& export_formats() {
    static const std::vector<std::pair<std::string, ExportFormat>> formats{
        {"lammps-data", ExportFormat::lammps_data}, {"liggghts-data", ExportFormat::liggghts_data}};
    return formats;
}

struct ExportOptions {
    std::string particles;
    std::string format = "lammps-data";
    std::string out;
    double density = 2500.0;
    std::string box;            // empty: the bounding box of the spheres
    double fluid_velocity = -1; // < 0: none
    double diameter = 0.0;      // XYZ files without radii
    bool quiet = false;
};

AxisBox parse_box(const std::string& text) {
    const auto v = comma_numbers(text);
    if (!v || v->size() != 6 || !((*v)[0] < (*v)[1] && (*v)[2] < (*v)[3] && (*v)[4] < (*v)[5]))
        throw InvalidInput(
            fmt::format("--box '{}' is not allowed; allowed: xlo,xhi,ylo,yhi,zlo,zhi "
                        "with lo < hi",
                        text));
    return {{(*v)[0], (*v)[2], (*v)[4]}, {(*v)[1], (*v)[3], (*v)[5]}};
}

int run_export(const ExportOptions& o) {
    ExportFormat format = ExportFormat::lammps_data;
    for (const auto& [name, value] : export_formats())
        if (name == o.format)
            format = value;
    ReadOptions read;
    if (o.diameter > 0.0)
        read.radius = 0.5 * o.diameter;
    const ParticleFile file = read_particles(o.particles, read);
    const AxisBox box = o.box.empty() ? bounding_box(file.packing) : parse_box(o.box);
    const fs::path out_path =
        o.out.empty() ? fs::path(o.particles).replace_extension(".data") : fs::path(o.out);
    const std::string program = format == ExportFormat::lammps_data ? "LAMMPS" : "LIGGGHTS";
    std::string comment = fmt::format("{} spheres from {} (packbed export, {} atom_style {})",
                                      file.packing.size(), o.particles, program,
                                      format == ExportFormat::lammps_data ? "sphere" : "granular");
    if (o.fluid_velocity >= 0.0)
        comment +=
            fmt::format("; fluid superficial velocity {} (packbed hydraulics)", o.fluid_velocity);
    OutputDirectory out(out_path.has_parent_path() ? out_path.parent_path() : fs::path("."));
    out.stage(out_path.filename().string(), lammps_data(file.packing, o.density, box, comment));
    if (o.fluid_velocity >= 0.0)
        out.stage(out_path.filename().string() + ".fluid.in",
                  fmt::format("# for the coupling: include this file in the {} input\n"
                              "variable fluid_velocity equal {}\n",
                              program, o.fluid_velocity));
    out.commit();
    if (!o.quiet)
        fmt::print("packbed export: {} spheres to {} ({}: read_data {}{})\n", file.packing.size(),
                   out_path.string(), program, out_path.filename().string(),
                   o.fluid_velocity >= 0.0
                       ? fmt::format("; include {}.fluid.in", out_path.filename().string())
                       : "");
    return 0;
}

} // namespace

Command register_export(CLI::App& parent) {
    auto options = std::make_shared<ExportOptions>();
    auto& o = *options;
    CLI::App* app = parent.add_subcommand(
        "export", "Write a bed (ours, a lattice, or one read from CSV, XYZ or a dump) as a "
                  "LAMMPS or LIGGGHTS data file");
    app->option_defaults()->always_capture_default();
    const double inf = std::numeric_limits<double>::infinity();
    app->add_option("particles", o.particles, "particles.csv, .xyz or a LAMMPS/LIGGGHTS dump")
        ->required();
    std::vector<std::string> names;
    for (const auto& entry : export_formats())
        names.push_back(entry.first);
    app->add_option("-f,--format", o.format,
                    "lammps-data (atom_style sphere) or liggghts-data (atom_style granular)")
        ->check(CLI::IsMember(names));
    app->add_option("-o,--out", o.out, "the data file (default: the particle file with .data)");
    app->add_option("--density", o.density, "particle density written for every atom")
        ->check(real_in(0.0, inf, true, true));
    app->add_option("--box", o.box,
                    "xlo,xhi,ylo,yhi,zlo,zhi (default: the smallest box holding every sphere)");
    app->add_option("--fluid-velocity", o.fluid_velocity,
                    "record this fluid velocity (e.g. from packbed hydraulics) in the header and "
                    "in FILE.fluid.in as a LAMMPS variable")
        ->check(real_in(0.0, inf, false, true));
    app->add_option("-d,--diameter", o.diameter, "sphere diameter, for XYZ files without radii")
        ->check(real_in(0.0, inf, true, true));
    app->add_flag("-q,--quiet", o.quiet, "no report on the terminal");
    app->fallthrough();
    app->footer("Exit status: 0 success, 2 bad input (a corrupt file, a sphere outside --box).");
    return {app, [options] { return run_export(*options); }};
}

} // namespace packbed::cli
