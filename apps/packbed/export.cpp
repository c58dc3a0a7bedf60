// `packbed export`: any bed (generated, lattice, read from elsewhere) as a DEM data file or as
// a surface for meshers (STL, OBJ) with the contacts treated: the options, the bed read and its
// container found; the library's export_bed (src/pipeline/export.cpp) writes.
#include <filesystem>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <fmt/format.h>

#include "command.hpp"
#include "packbed/error.hpp"
#include "packbed/openfoam.hpp"
#include "packbed/pipeline.hpp"
#include "packbed/read.hpp"
#include "packbed/text.hpp"

namespace packbed::cli {

namespace {

namespace fs = std::filesystem;

/// `packbed export`'s options: the library's request and how to read the bed.
struct ExportOptions {
    std::string particles;
    ExportRequest request;         // --out empty: default_export_path
    std::string out;               // --out
    double diameter = 0.0;         // files without radii
    InputPlacement placement;      // --frame, --axis, --floor
    double container_radius = 0.0; // 0: from summary.json beside the file, if any
    std::string container;         // --container SPEC (any shape), instead of -R
    std::string flow = "inlet";    // --flow: inlet, or periodic (request.mesh.periodic_z)
    std::string shape;             // --shape SPEC; "": summary.json beside the file, or spheres
    std::string mesh;              // --mesh NAME (mesh_presets()); "": none
    /// the mesh options and their fields: those given replace the preset's values
    std::vector<std::pair<const CLI::Option*, int OpenFoamMeshOptions::*>> mesh_options;
    bool quiet = false;
    const CLI::Option* format_option = nullptr; // --format, to know whether it was given
};

/// --mesh's values, then the mesh options given beside it again on top.
void apply_mesh_preset(const ExportOptions& o, OpenFoamMeshOptions& mesh) {
    if (o.mesh.empty())
        return;
    const OpenFoamMeshOptions given = mesh;
    mesh = mesh_presets().at(o.mesh);
    for (const auto& [option, field] : o.mesh_options)
        if (option->count() > 0)
            mesh.*field = given.*field;
}

int run_export(ExportOptions& o) {
    ExportRequest& request = o.request;
    // No --format: the one the output's name says (x.stl an STL, not a data file named so).
    if (o.format_option->count() == 0 && !o.out.empty())
        request.format = export_format_for(o.out);
    request.out =
        o.out.empty() ? default_export_path(o.particles, request.format) : fs::path(o.out);
    request.source = o.particles;
    request.keep = o.particles;
    apply_mesh_preset(o, request.mesh);
    request.mesh.periodic_z = o.flow == "periodic";
    ReadOptions read;
    if (o.diameter > 0.0)
        read.radius = 0.5 * o.diameter;
    o.placement.apply(read);
    const ParticleFile file = read_particles(o.particles, read);
    // The particles' shape: --shape, else the one summary.json beside the file records.
    if (!o.shape.empty() && o.shape != "sphere") {
        request.pellet = parse_pellet_shape(o.shape);
        if (!request.pellet)
            throw InvalidInput(fmt::format("--shape '{}' is not allowed; allowed: {}",
                                           printable(o.shape), allowed_shapes()));
        if (const std::optional<PelletSpec> recorded = shape_beside(o.particles);
            recorded && !recorded->same_as(*request.pellet))
            throw InvalidInput(fmt::format(
                "--shape '{}' is not allowed for {}: the summary.json beside it records its "
                "pellets as '{}'; allowed: that shape, or no --shape",
                printable(o.shape), printable(o.particles), printable(recorded->text)));
        else if (recorded)
            request.pellet->scales = recorded->scales; // its sizes
    } else if (o.shape.empty()) {
        request.pellet = shape_beside(o.particles);
    } else if (const std::optional<PelletSpec> recorded = shape_beside(o.particles)) {
        throw InvalidInput(fmt::format("--shape sphere is not allowed for {}: the summary.json "
                                       "beside it records its pellets as '{}'; allowed: that "
                                       "shape, or no --shape",
                                       printable(o.particles), printable(recorded->text)));
    }
    // The container: --container, --container-radius or summary.json beside the file.
    if (export_uses_container(request))
        request.container = find_container(o.particles, o.container, o.container_radius);
    // A random array's cell repeats along z with the period its summary.json records.
    if (request.mesh.periodic_z && !(request.container_height > 0.0) && o.container.empty())
        request.container_height = period_z_beside(o.particles).value_or(0.0);
    const std::string report = export_bed(file.packing, file.lines, request);
    if (!o.quiet)
        fmt::print("packbed export: {}\n", report);
    return 0;
}

} // namespace

Command register_export(CLI::App& parent) {
    auto options = std::make_shared<ExportOptions>();
    auto& o = *options;
    CLI::App* app = parent.add_subcommand(
        "export", "Write a bed (ours, a lattice, or one read from CSV, XYZ or a dump) as a "
                  "LAMMPS or LIGGGHTS data file, as a surface (STL, OBJ) for meshers, or as an "
                  "OpenFOAM case (blockMesh + snappyHexMesh + simpleFoam)");
    app->option_defaults()->always_capture_default();
    app->add_option("particles", o.particles,
                    "the bed: a table (CSV, ParaView CSV, ;/tab/space separated), XYZ, a "
                    "LAMMPS/LIGGGHTS dump or data file; also .gz")
        ->required()
        ->check(path_text());
    const std::vector<std::string> names = export_format_names();
    o.format_option =
        app->add_option("-f,--format", o.request.format,
                        "lammps-data (atom_style sphere), liggghts-data (atom_style granular), stl "
                        "(binary), stl-ascii (one named solid per part), obj, or openfoam (a case "
                        "directory for blockMesh + snappyHexMesh); default: stl for an --out "
                        "ending in .stl, obj for .obj, else lammps-data")
            ->check(one_of(names));
    app->add_option("-o,--out", o.out,
                    "the output file (default: the particle file with .data, .stl or .obj), or "
                    "the case directory for openfoam (default: openfoam/ beside the file; a new "
                    "or empty one, or an existing one with --force)")
        ->check(path_text());
    app->add_flag("--force", o.request.force,
                  "openfoam: replace a non-empty case directory whole (its old files are "
                  "deleted); files are replaced without it");
    app->add_option("--shape", o.shape,
                    "the particles' shape: sphere, or a pellet (cylinder:D,L, ring:D,DI,L, "
                    "trilobe:DL,DC,L, multilobe:N,DL,DC,L, spherocylinder:D,L: the table's r is "
                    "d_v / 2 and its qw, qx, qy, qz each pellet's orientation; default: the "
                    "shape summary.json beside the file records, else spheres)");
    app->add_option("--contacts", o.request.contacts,
                    "surfaces: none; shrink:F (radii times 1 - F, gaps); enlarge:F (radii times "
                    "1 + F, united); caps:H (flat faces H Dp apart at every contact closer than "
                    "H Dp, and H Dp from the walls); bridges:D (a cylinder of diameter D Dp "
                    "along each contact, united); F, H, D in (0, 0.5) (docs/surfaces.md)");
    app->add_option("--refine", o.request.refine,
                    "surfaces: icosphere level of each sphere (20 x 4^level triangles)")
        ->check(whole_in(option_range::refine));
    app->add_option("--facets", o.request.facets,
                    "surfaces of spheres: inscribed (vertices on the sphere, the polyhedron "
                    "inside it: 0.86 % short of its volume at --refine 3), volume (scaled to "
                    "hold the sphere's volume; needs gaps between the bodies) or auto (volume "
                    "where every gap allows it, else inscribed; the report says which); default: "
                    "auto for openfoam, inscribed otherwise")
        ->check(one_of(facet_modes().names()));
    app->add_option("--edge", o.request.edge,
                    "surfaces: largest mean triangle edge instead of --refine (file units)")
        ->check(real_in(option_range::edge));
    CLI::Option* radius =
        app->add_option("-R,--container-radius", o.container_radius,
                        "cylinder radius, shorthand of --container cylinder:2R (default: "
                        "summary.json beside the file; none if absent: surfaces without wall "
                        "treatment or container solids, data files in the spheres' bounding box "
                        "without an example DEM input)")
            ->check(real_in(option_range::export_container_radius));
    add_container_option(*app, o.container, "file units; default: summary.json beside the file")
        ->excludes(radius);
    app->add_option(
           "--container-height", o.request.container_height,
           "container height from the floor z = 0 (default: the bed's top + 1 Dp); with --flow "
           "periodic the period along z (default: a random array's, from summary.json beside "
           "the file)")
        ->check(real_in(option_range::container_height));
    app->add_flag("--no-container", o.request.no_container,
                  "surfaces: cut against the container but do not write its solids; data "
                  "files: ignore it (the spheres' bounding box, no example DEM input)");
    app->add_option(
           "--mesh", o.mesh,
           "openfoam: a named mesh: quick (the defaults: d/16 at the particles, no layers) or "
           "accurate (d/32 and three prism layers: the pressure drop within 2 % of the "
           "converged one on the tube beds measured, for about 9 times the cells); the four "
           "options below replace its values (docs/validation.md)")
        ->check(one_of(mesh_presets().names()));
    const auto mesh_option = [&](const std::string& name, int OpenFoamMeshOptions::*field,
                                 const std::string& help, const WholeRange& range) {
        o.mesh_options.emplace_back(
            app->add_option(name, o.request.mesh.*field, help)->check(whole_in(range)), field);
    };
    mesh_option("--cells-per-diameter", &OpenFoamMeshOptions::cells_per_diameter,
                "openfoam: background (blockMesh) cells per particle diameter",
                option_range::cells_per_diameter);
    mesh_option("--particle-level", &OpenFoamMeshOptions::particle_level,
                "openfoam: snappyHexMesh refinement level at the particles",
                option_range::refinement_level);
    mesh_option("--wall-level", &OpenFoamMeshOptions::wall_level,
                "openfoam: snappyHexMesh refinement level at the wall",
                option_range::refinement_level);
    mesh_option("--layers", &OpenFoamMeshOptions::layers,
                "openfoam: snappyHexMesh's prism layers on the particles and the wall, 0 (none) "
                "to 10 (docs/surfaces.md)",
                option_range::surface_layers);
    app->add_option("--flow", o.flow,
                    "openfoam: inlet (a flow rate in at z = 0, p = 0 at the top), or periodic (a "
                    "periodic cell repeating along z too, --container-height its period: cyclic "
                    "on all six faces, the mean velocity held by a uniform pressure gradient; "
                    "docs/surfaces.md)")
        ->check(one_of({"inlet", "periodic"}));
    app->add_option("--ranks", o.request.flow.ranks,
                    "openfoam: MPI ranks of the case's Allrun (decomposeParDict)")
        ->check(whole_in(option_range::ranks));
    app->add_option("--reynolds", o.request.flow.reynolds,
                    "openfoam: the particle Reynolds number rho u d / mu of the superficial "
                    "velocity u, the inlet's or a periodic cell's mean (unless --fluid-velocity; d "
                    "the bed's mean diameter before a treatment)")
        ->check(real_in(option_range::reynolds));
    app->add_option("--turbulence", o.request.turbulence,
                    "openfoam: laminar, or a RANS model with wall functions (kEpsilon, "
                    "kOmegaSST; 5 % turbulence intensity at the inlet; laminar only with --flow "
                    "periodic)")
        ->check(one_of(turbulence_models().names()));
    app->add_option("--fluid-density", o.request.flow.fluid_density,
                    "openfoam: the fluid's density, kg/m^3 (default: water at 20 C)")
        ->check(real_in(option_range::density_kg_m3));
    app->add_option("--viscosity", o.request.flow.viscosity,
                    "openfoam: the fluid's dynamic viscosity, Pa s (default: water at 20 C)")
        ->check(real_in(option_range::viscosity_pa_s));
    app->add_option("--scale", o.request.flow.scale,
                    "openfoam: metres per unit of the bed's lengths (Allrun scales the mesh; "
                    "default: particles of 1 mm)")
        ->check(real_in(option_range::metres_per_unit));
    app->add_option("--density", o.request.density, "particle density written for every atom")
        ->check(real_in(option_range::density));
    app->add_option("--box", o.request.box,
                    "xlo,xhi,ylo,yhi,zlo,zhi (default: the container and a margin of "
                    "max(Dp/2, Rt/100), a box's half narrower width for Rt, where the container "
                    "is known, else the smallest box holding every sphere)");
    app->add_option("--fluid-velocity,--velocity", o.request.fluid_velocity,
                    "data files: record this fluid velocity (e.g. from packbed hydraulics) in the "
                    "header and in FILE.fluid.in as a LAMMPS variable; openfoam: the superficial "
                    "velocity, m/s, the inlet's or a periodic cell's mean (instead of --reynolds)")
        ->check(real_in(option_range::fluid_velocity));
    app->add_option("-d,--diameter", o.diameter,
                    "sphere diameter, for files without a radius or diameter column (XYZ, "
                    "dumps, tables, data files of atom_style atomic)")
        ->check(real_in(option_range::export_diameter));
    add_input_placement(*app, o.placement);
    app->add_flag("-q,--quiet", o.quiet, "no report on the terminal");
    app->fallthrough();
    app->footer("Exit status: 0 success, 2 bad input (a corrupt file, a sphere outside --box or "
                "the container, a treatment that cannot separate the spheres).");
    return {app, [options] { return run_export(*options); }};
}

} // namespace packbed::cli
