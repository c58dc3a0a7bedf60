// What `packbed export` writes for a bed (pipeline.hpp): a LAMMPS or LIGGGHTS data file with an
// example settle, or surfaces (STL, OBJ, an OpenFOAM case) with the contacts treated.
#include <algorithm>
#include <cctype>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <memory>
#include <numbers>
#include <optional>
#include <stdexcept>
#include <string>
#include <variant>
#include <vector>

#include <fmt/format.h>
#include <fmt/ranges.h>
#include <nlohmann/json.hpp>

#include "packbed/bed_volume.hpp"
#include "packbed/error.hpp"
#include "packbed/files.hpp"
#include "packbed/io.hpp"
#include "packbed/json_text.hpp"
#include "packbed/limits.hpp"
#include "packbed/openfoam.hpp"
#include "packbed/option_ranges.hpp"
#include "packbed/output.hpp"
#include "packbed/pipeline.hpp"
#include "packbed/surface.hpp"
#include "packbed/text.hpp"
#include "packbed/volume.hpp"

namespace packbed {

namespace {

namespace fs = std::filesystem;

/// What `export` writes. The data files: LAMMPS `atom_style sphere` and LIGGGHTS `atom_style
/// granular` read the same columns; the name sets the first-line comment and the hint. The
/// surfaces: see packbed/surface.hpp.
enum class ExportFormat { lammps_data, liggghts_data, stl, stl_ascii, obj, openfoam };

const Registry<ExportFormat>& export_formats() {
    static const Registry<ExportFormat> formats("format",
                                                {{"lammps-data", ExportFormat::lammps_data},
                                                 {"liggghts-data", ExportFormat::liggghts_data},
                                                 {"stl", ExportFormat::stl},
                                                 {"stl-ascii", ExportFormat::stl_ascii},
                                                 {"obj", ExportFormat::obj},
                                                 {"openfoam", ExportFormat::openfoam}});
    return formats;
}

AxisBox parse_box(const std::string& text) {
    const auto v = parse_finite_list(text);
    if (!v || v->size() != 6 || !((*v)[0] < (*v)[1] && (*v)[2] < (*v)[3] && (*v)[4] < (*v)[5]))
        throw InvalidInput(
            fmt::format("--box '{}' is not allowed; allowed: xlo,xhi,ylo,yhi,zlo,zhi "
                        "with lo < hi",
                        printable(text)));
    return {{(*v)[0], (*v)[2], (*v)[4]}, {(*v)[1], (*v)[3], (*v)[5]}};
}

/// The output file `out_path` and the files `sidecars` beside it, reserved before any work:
/// the folder is checked, and no output may be the input.
std::unique_ptr<OutputDirectory> file_output(const fs::path& out_path,
                                             const std::vector<std::string>& sidecars) {
    if (!out_path.has_filename() || out_path.filename() == "." || out_path.filename() == "..")
        throw InvalidInput(fmt::format("--out {} is not allowed; allowed: a file name",
                                       printable(out_path.native())));
    auto out = std::make_unique<OutputDirectory>(out_path.has_parent_path() ? out_path.parent_path()
                                                                            : fs::path("."),
                                                 "--out", OutputKind::files);
    const std::string name = out_path.filename().string();
    out->reserve(name);
    for (const std::string& sidecar : sidecars)
        out->reserve(name + sidecar);
    return out;
}

/// The bed's container (ExportRequest::container), its height from --container-height or the
/// bed's top + 1 Dp.
/// \return nothing when there is none. \throws InvalidInput when the height is not above the bed
/// or a centre lies outside the container
std::optional<SurfaceContainer> bed_container(const ExportRequest& o, const Packing& packing,
                                              const std::vector<std::size_t>& lines) {
    if (!o.container)
        return std::nullopt;
    const Container& given = *o.container;
    const double top = bed_top(packing);
    const bool periodic_z = o.mesh.periodic_z;
    if (periodic_z && !given.periods())
        throw InvalidInput(fmt::format("--flow periodic is not allowed with --container {}; "
                                       "allowed: a periodic cell (periodic:LX,LY), whose sides "
                                       "repeat across",
                                       given.spec()));
    if (periodic_z && !(o.container_height > 0.0))
        throw InvalidInput("--flow periodic needs --container-height: the cell's period along z "
                           "(a lattice's region height; a random array's summary.json gives "
                           "its own); allowed: a height above every centre");
    const double height =
        o.container_height > 0.0 ? o.container_height : top + packing.mean_diameter();
    if (periodic_z) {
        // Every centre within the period: a sphere may cross the bottom or the top (its copy
        // comes in across the other), as it crosses the sides.
        for (std::size_t i = 0; i < packing.size(); ++i) {
            const double z = packing.centers[i].z;
            if (!(z >= 0.0 && z < height))
                throw InvalidInput(fmt::format(
                    "{}:{}: the sphere centre at z = {} is outside the cell periodic along z "
                    "with period {}; allowed with --flow periodic: centres from z = 0 to below "
                    "--container-height",
                    printable(o.source), i < lines.size() ? lines[i] : i + 1, z, height));
        }
    } else if (!(height > top)) {
        throw InvalidInput(fmt::format(
            "--container-height {} is not allowed; allowed: above the bed's top, {}", height, top));
    }
    for (std::size_t i = 0; i < packing.size(); ++i) {
        const Vec3& c = packing.centers[i];
        if (!(given.wall_distance(c) > 0.0) || (c.z <= 0.0 && !periodic_z))
            throw InvalidInput(
                fmt::format("{}:{}: the sphere centre ({}, {}, {}) is outside the container ({}, "
                            "floor z = 0); allowed: centres inside it",
                            printable(o.source), i < lines.size() ? lines[i] : i + 1, c.x, c.y, c.z,
                            describe(given)));
    }
    // A cone narrowing to its apex below the height would end in a point.
    if (!(given.cross_section_area(height, height) > 0.0))
        throw InvalidInput(fmt::format("--container-height {} is not allowed with --container {}: "
                                       "the container has no cross-section there; allowed: a "
                                       "height where it has one",
                                       height, given.spec()));
    return SurfaceContainer{given, height, periodic_z};
}

/// The container in packbed.json: its shape, size and height.
nlohmann::ordered_json container_json(const SurfaceContainer& container) {
    return container.container.export_json(container.height);
}

/// The container and the volumes in a surface export's report.
/// \return the change of void fraction, as the report line says it
std::string record_volumes(nlohmann::ordered_json& report, const SurfaceContainer& container,
                           const TreatmentVolumes& v) {
    report["container"] = container_json(container);
    report["volumes"] = {
        {"container", v.container_volume},
        {"untouched_solid", v.untouched_solid},
        {"treated_solid", v.treated_solid},
        {"fluid", v.container_volume - v.treated_solid},
        {"untouched_void_fraction", v.untouched_void_fraction},
        {"treated_void_fraction", v.treated_void_fraction},
        {"void_fraction_change", v.treated_void_fraction - v.untouched_void_fraction}};
    return fmt::format("; void fraction in the container (z 0 to {:.6g}) {:.6f} -> {:.6f} "
                       "({:+.6f})",
                       container.height, v.untouched_void_fraction, v.treated_void_fraction,
                       v.treated_void_fraction - v.untouched_void_fraction);
}

/// The flow of the runnable case: the request's, the inlet's velocity where given instead of
/// the Reynolds number's, and the turbulence model by name.
OpenFoamFlowOptions case_flow(const ExportRequest& o) {
    OpenFoamFlowOptions flow = o.flow;
    if (o.fluid_velocity == 0.0)
        throw InvalidInput("--fluid-velocity 0 is not allowed with --format openfoam; "
                           "allowed: the inlet's velocity > 0 m/s, or --reynolds");
    if (o.fluid_velocity > 0.0) // the inlet's, instead of the Reynolds number's
        flow.velocity = o.fluid_velocity;
    const std::optional<Turbulence> model = turbulence_models().find(o.turbulence);
    if (!model)
        throw InvalidInput(fmt::format("--turbulence '{}' is not allowed; allowed: {}",
                                       printable(o.turbulence.substr(0, 80)),
                                       turbulence_models().allowed()));
    flow.turbulence = *model;
    return flow;
}

/// packbed.json's record of a case: its mesh, its flow, and what cfd-report compares with
/// (`band_void_fraction`, and the wall's aspect ratio D_h / d).
nlohmann::ordered_json case_record(const ExportRequest& o, const OpenFoamCase& foam,
                                   const OpenFoamFlowOptions& flow,
                                   const SurfaceContainer& container, double band_void_fraction,
                                   double diameter) {
    const std::optional<double> hydraulic = hydraulic_diameter(container.container);
    return {
        {"cell_size", foam.cell_size},
        {"particle_level", o.mesh.particle_level},
        {"wall_level", o.mesh.wall_level},
        {"layers", o.mesh.layers},
        {"location_in_mesh",
         {foam.location_in_mesh.x, foam.location_in_mesh.y, foam.location_in_mesh.z}},
        {"clearance", foam.clearance},
        {"flow",
         {{"ranks", flow.ranks},
          {"metres_per_unit", foam.scale},
          {"fluid_density", flow.fluid_density},
          {"viscosity", flow.viscosity},
          {"velocity", foam.velocity},
          {"reynolds", foam.reynolds},
          {"turbulence", o.turbulence},
          {"pressure_planes", foam.planes},
          {"band_void_fraction", band_void_fraction},
          {"aspect_ratio", hydraulic ? nlohmann::json(*hydraulic / diameter) : nlohmann::json()}}}};
}

/// A case's files, Allrun executable, its surfaces and packbed.json staged, and the case
/// committed.
void stage_case(OutputDirectory& out, const OpenFoamCase& foam,
                const nlohmann::ordered_json& report) {
    for (const auto& [path, text] : foam.files)
        out.stage(path, text);
    out.stage("Allrun", foam.allrun);
    const fs::path allrun = out.reserve("Allrun");
    fs::permissions(allrun, fs::perms::owner_exec | fs::perms::group_exec | fs::perms::others_exec,
                    fs::perm_options::add);
    write_surface(foam.particles, SurfaceFormat::stl_binary,
                  out.reserve("constant/triSurface/particles.stl"));
    if (!foam.wall.empty()) // a cylinder's wall; a box's is the background's faces
        write_surface(foam.wall, SurfaceFormat::stl_binary,
                      out.reserve("constant/triSurface/wall.stl"));
    if (!foam.rod.empty()) // an annulus' rod
        write_surface(foam.rod, SurfaceFormat::stl_binary,
                      out.reserve("constant/triSurface/rod.stl"));
    out.stage("packbed.json", json_file_text(report, "packbed.json"));
    out.commit();
}

/// An STL or OBJ file of `solids` at `out_path`, the report (with each solid's triangles) as
/// its `.json` beside it, committed. \return the triangles written
std::size_t write_surface_file(OutputDirectory& out, const fs::path& out_path, ExportFormat format,
                               const std::vector<Solid>& solids, nlohmann::ordered_json& report) {
    std::size_t triangles = 0;
    report["solids"] = nlohmann::ordered_json::array();
    for (const Solid& s : solids) {
        triangles += s.mesh.triangles.size();
        report["solids"].push_back({{"name", s.name}, {"triangles", s.mesh.triangles.size()}});
    }
    const std::string name = out_path.filename().string();
    write_surface(solids,
                  format == ExportFormat::stl         ? SurfaceFormat::stl_binary
                  : format == ExportFormat::stl_ascii ? SurfaceFormat::stl_ascii
                                                      : SurfaceFormat::obj,
                  out.reserve(name));
    out.stage(name + ".json", json_file_text(report, name + ".json"));
    out.commit();
    return triangles;
}

/// The facets asked for: request.facets, or where it is "" the format's default (auto for an
/// OpenFOAM case, whose drag follows the solid's volume; inscribed for STL and OBJ).
Facets asked_facets(const ExportRequest& o, ExportFormat format) {
    if (o.facets.empty())
        return format == ExportFormat::openfoam ? Facets::automatic : Facets::inscribed;
    return facet_modes().at(o.facets);
}

/// STL, OBJ or an OpenFOAM case: treat the contacts, tessellate, write the surfaces and the
/// volumes.
std::string surface_export(const ExportRequest& o, ExportFormat format, const Packing& packing,
                           const std::vector<std::size_t>& lines) {
    // The output first, so that everything that can refuse it does before the work.
    const fs::path& out_path = o.out;
    std::unique_ptr<OutputDirectory> out;
    if (format == ExportFormat::openfoam) {
        out = std::make_unique<OutputDirectory>(out_path, "--out", OutputKind::directory, o.force);
    } else {
        out = file_output(out_path, {".json"});
    }
    const Contacts contacts = parse_contacts(o.contacts);
    const double dp = packing.mean_diameter();
    const std::optional<SurfaceContainer> container = bed_container(o, packing, lines);
    if (container && container->container.periods() && format != ExportFormat::openfoam)
        throw InvalidInput(fmt::format(
            "--container {} is not allowed with --format {}; allowed: {} (a periodic cell has no "
            "closed surface: it is exported as an openfoam case with cyclic sides, or by "
            "lammps-data and liggghts-data)",
            container->container.spec(), o.format, forms_but(container->container.name())));
    SurfaceOptions options;
    double largest = 0.0;
    for (const double r : packing.radii)
        largest = std::max(largest, r);
    options.level = o.edge > 0.0 ? icosphere_level_for_edge(largest, o.edge) : o.refine;
    if (o.edge > 0.0 && largest * icosphere_edge(options.level) > o.edge)
        throw InvalidInput(fmt::format(
            "--edge {:g} is not allowed for spheres up to radius {:g}: it needs more than "
            "icosphere level {}; allowed: at least {:.6g} (that level's edge)",
            o.edge, largest, options.level, largest * icosphere_edge(options.level)));
    options.facets = asked_facets(o, format);
    options.container = container;
    options.write_container = !o.no_container;
    const TreatedBed bed = treat_contacts(packing, contacts, container);
    options.facets = facets_for(bed, options);
    if (container && !container->periodic_z) // periodic along z: checked by bed_container
        for (std::size_t i = 0; i < bed.bodies.size(); ++i) {
            const TreatedBody& b = bed.bodies[i];
            if (!(b.center.z + b.radius < container->height))
                throw InvalidInput(fmt::format(
                    "--container-height {} is not allowed; allowed: above the top of every "
                    "treated sphere (sphere {} reaches {})",
                    container->height, i + 1, b.center.z + b.radius));
        }
    if (format == ExportFormat::openfoam && !container)
        throw InvalidInput(
            fmt::format("--format openfoam needs the container: give --container (no "
                        "summary.json with a container next to {})",
                        printable(o.source)));

    // What every surface export reports (printed, and written as JSON beside the output).
    nlohmann::ordered_json report;
    report["particles"] = o.source;
    report["spheres"] = packing.size();
    report["contacts"] = o.contacts;
    report["diameter"] = dp;
    report["icosphere_level"] = options.level;
    report["facets"] = facet_modes().name(options.facets);
    std::optional<TreatmentVolumes> volumes;
    std::string change;
    if (container) {
        change = record_volumes(report, *container,
                                volumes.emplace(treatment_volumes(packing, bed, *container)));
    }

    if (format == ExportFormat::openfoam) {
        const OpenFoamFlowOptions flow = case_flow(o);
        const OpenFoamCase foam =
            openfoam_case(bed, *container, *volumes, o.contacts, dp, options, o.mesh, flow);
        report["openfoam"] =
            case_record(o, foam, flow, *container,
                        // what cfd-report compares with: the bed's void fraction between the first
                        // and the last plane (exact, untreated; a cell periodic along z: the whole
                        // cell's, treated)
                        container->periodic_z ? volumes->treated_void_fraction
                                              : void_fraction(packing, container->container,
                                                              foam.planes.front() / foam.scale,
                                                              foam.planes.back() / foam.scale),
                        dp);
        if (container->periodic_z) {
            // What cfd-report needs for the drag per sphere (F = rho G V / N) and its
            // dimensionless forms: the cell, the spheres in it and their mean radius after the
            // treatment (a shrunk array's spheres are the smaller ones).
            double radius = 0.0;
            for (const TreatedBody& b : bed.bodies)
                radius += b.radius / static_cast<double>(bed.bodies.size());
            report["openfoam"]["flow"]["periodic"] = {
                {"period_z", container->height},
                {"cell_volume", volumes->container_volume},
                {"spheres", bed.bodies.size()},
                {"sphere_radius", radius},
                {"solid_fraction", 1.0 - volumes->treated_void_fraction},
                {"interstitial_velocity", foam.interstitial_velocity}};
        }
        stage_case(*out, foam, report);
        return fmt::format("OpenFOAM case in {} ({} spheres, contacts {}{}); run ./Allrun "
                           "there",
                           out_path.string(), packing.size(), o.contacts, change);
    }

    const std::size_t triangles =
        write_surface_file(*out, out_path, format, bed_surface(bed, options), report);
    return fmt::format("{} spheres to {} ({} triangles, icosphere level {}, contacts {}){}",
                       packing.size(), out_path.string(), triangles, options.level, o.contacts,
                       change);
}

/// The names of the example DEM run written beside a data file `name` when the container is
/// known (docs/dem.md).
struct DemFiles {
    std::string input, dump, wall, bottom; // wall, bottom: LIGGGHTS only
};

DemFiles dem_files(const std::string& name, ExportFormat format, bool periodic) {
    if (format == ExportFormat::lammps_data)
        return {name + ".lammps.in", name + ".lammps.dump", "", ""};
    if (periodic) // no side wall, the floor a plane: no STL
        return {name + ".liggghts.in", name + ".liggghts.dump", "", ""};
    return {name + ".liggghts.in", name + ".liggghts.dump", name + ".wall.stl",
            name + ".bottom.stl"};
}

/// A bed of pellets as DEM clumps (data_export): the packing holds the spheres of each pellet's
/// clump, `spheres` per pellet, each of a density `density_scale` times the pellets' so that a
/// clump weighs what its pellet does.
struct ClumpExport {
    std::size_t spheres = 0, pellets = 0;
    std::string shape;
    double density_scale = 1.0;
    double reach = 0.0; ///< the farthest a sphere's surface lies from its pellet's centroid
};

/// A LAMMPS or LIGGGHTS data file; where the container is known, its box holds the container
/// and an example settle (input, and for LIGGGHTS the wall STL files) is written beside it.
/// With `clumps` (LAMMPS only), each pellet's spheres one rigid body.
std::string data_export(const ExportRequest& o, ExportFormat format, const Packing& packing,
                        const std::vector<std::size_t>& lines,
                        const ClumpExport* clumps = nullptr) {
    const bool lammps = format == ExportFormat::lammps_data;
    const double density = clumps ? o.density * clumps->density_scale : o.density;
    const std::optional<AxisBox> given_box =
        o.box.empty() ? std::nullopt : std::optional<AxisBox>(parse_box(o.box));
    const fs::path& out_path = o.out;
    const std::string name = out_path.filename().string();
    const std::optional<SurfaceContainer> container =
        o.no_container ? std::nullopt : bed_container(o, packing, lines);
    const double dp = packing.mean_diameter();
    std::vector<std::string> sidecars;
    if (o.fluid_velocity >= 0.0)
        sidecars.push_back(".fluid.in");
    if (given_box && container && container->container.periods())
        throw InvalidInput(fmt::format("--box {} is not allowed with the periodic cell {}; "
                                       "allowed: no --box (the data file's box is the cell, its "
                                       "periods), or --no-container",
                                       printable(o.box), container->container.spec()));
    const DemFiles dem = dem_files(name, format, container && container->container.periods());
    if (container) {
        // The inputs name the files as single words.
        const bool word = !name.empty() && std::all_of(name.begin(), name.end(), [](char c) {
            return std::isalnum(static_cast<unsigned char>(c)) || c == '.' || c == '_' ||
                   c == '-' || c == '+';
        });
        if (!word)
            throw InvalidInput(fmt::format(
                "--out {}: the file name '{}' is not allowed with the example DEM input, which "
                "names it; allowed: letters, digits, '.', '_', '-' and '+' (or --no-container: "
                "no example)",
                printable(out_path.native()), printable(name)));
        for (const std::string& f : {dem.input, dem.wall, dem.bottom})
            if (!f.empty())
                sidecars.push_back(f.substr(name.size()));
    }
    const auto out = file_output(out_path, sidecars);
    const std::string program = lammps ? "LAMMPS" : "LIGGGHTS";
    // The title: where the spheres came from, shortened to the file's name (then cut) where
    // the path would make it longer than LAMMPS and LIGGGHTS read.
    const auto title = [&](std::string_view source) {
        std::string t =
            clumps ? fmt::format("{} {} pellets as rigid clumps of {} spheres from {} (packbed "
                                 "export, LAMMPS atom_style sphere, molecules)",
                                 clumps->pellets, clumps->shape, clumps->spheres, source)
                   : fmt::format("{} spheres from {} (packbed export, {} atom_style {})",
                                 packing.size(), source, program, lammps ? "sphere" : "granular");
        if (o.fluid_velocity >= 0.0)
            t += fmt::format("; fluid superficial velocity {} (packbed hydraulics)",
                             o.fluid_velocity);
        return t;
    };
    std::string comment = title(o.source);
    if (comment.size() > max_data_header_line) {
        const std::string base = fs::path(o.source).filename().string();
        const std::size_t room = max_data_header_line - (title("").size() + 3);
        comment = title(base.size() <= room ? base : "..." + base.substr(base.size() - room));
    }
    // The box: --box, else the container and a margin where it is known, else the spheres'
    // bounding box (the header says which where the container is known).
    // A periodic cell: every centre moved by whole periods into the cell (the data file's box).
    Packing wrapped = packing;
    if (container)
        if (const std::optional<Periods> cell = container->container.periods())
            for (Vec3& c : wrapped.centers)
                c = cell->wrapped(c);
    AxisBox box = bounding_box(wrapped);
    std::string box_note;
    if (given_box) {
        box = *given_box;
        if (container)
            box_note = "box from --box";
    } else if (container) {
        const Container& c = container->container;
        box = container_box(c, container->height, dp);
        // The cylinder's margin rule in Rt; a box's in its depth, half the narrower width; an
        // annulus' in its tube's radius; a periodic cell's box is the cell in x and y.
        const BoxMargin margin = c.box_margin();
        if (c.periods())
            box_note = fmt::format("box: the periodic cell {0} (boundary p p f), z from -{2:.9g} "
                                   "to the height {1:.9g} + {2:.9g} (Dp/2)",
                                   c.spec(), container->height, container_box_margin(c, dp));
        else
            box_note = fmt::format("box: the container ({}, height {:.9g}) and a margin of {:.9g} "
                                   "(the larger of Dp/2 and {}) on every side",
                                   margin.container, container->height, container_box_margin(c, dp),
                                   margin.words);
    }
    std::vector<std::string> notes;
    if (!box_note.empty())
        notes.push_back(box_note);
    if (clumps)
        notes.push_back(fmt::format("each sphere of density {:.9g}: a clump weighs what its "
                                    "pellet of density {:.9g} does",
                                    density, o.density));
    // The bed's own friction (the example input's), and the walls' where it differs: in
    // LIGGGHTS of their own atom type, which the data file declares.
    const std::optional<double> friction =
        o.friction ? o.friction : (o.keep.empty() ? std::nullopt : friction_beside(o.keep));
    const std::optional<double> wall_friction =
        o.wall_friction ? o.wall_friction
                        : (o.keep.empty() ? std::nullopt : wall_friction_beside(o.keep));
    // As plain numbers (0 where none is known): GCC 12 takes an optional read further down
    // for one that may be uninitialised.
    const double mu = friction.value_or(0.0), wall_mu = wall_friction.value_or(0.0);
    const bool of_bed = mu > 0.0 || wall_mu > 0.0;
    const bool own_walls = of_bed && container && wall_friction && wall_mu != mu;
    out->stage(name, lammps_data(wrapped, density, box, comment, notes, {},
                                 clumps ? clumps->spheres : 0, own_walls && !lammps ? 2 : 1));
    if (o.fluid_velocity >= 0.0)
        out->stage(name + ".fluid.in",
                   fmt::format("# for the coupling: include this file in the {} input\n"
                               "variable fluid_velocity equal {}\n",
                               program, o.fluid_velocity));
    std::string note;
    if (container) {
        DemSettle settle;
        settle.data_file = name;
        settle.wall_stl = dem.wall;
        settle.bottom_stl = dem.bottom;
        settle.dump = dem.dump;
        settle.container = container->container;
        settle.container_height = container->height;
        settle.smallest_radius =
            packing.radii.empty() ? 0.5 * dp
                                  : *std::min_element(packing.radii.begin(), packing.radii.end());
        settle.diameter = dp;
        settle.density = density;
        settle.clump_spheres = clumps ? clumps->spheres : 0;
        settle.clump_reach = clumps ? clumps->reach : 0.0;
        if (of_bed) {
            settle.material.friction = mu;
            settle.material.friction_of_bed = true;
            if (own_walls)
                settle.material.wall_friction = wall_mu;
        }
        // The container's side (every solid but the floor and the top: an annulus' tube and
        // rod in one) and floor as LIGGGHTS walls, triangles about 1 Dp wide.
        const std::vector<Solid> solids = container->container.solids(0.0, container->height, dp);
        Solid side{"wall", {}}, bottom{"bottom", {}};
        for (const Solid& solid : solids)
            if (solid.name == "bottom")
                bottom.mesh.append(solid.mesh);
            else if (solid.name != "top")
                side.mesh.append(solid.mesh);
        bool inside = true;
        // (A periodic cell writes no STL: its box is the cell, the floor a plane.)
        if (container->container.periods())
            side.mesh = bottom.mesh = {};
        for (const Solid* k : {&side, &bottom})
            for (const Vec3& v : k->mesh.vertices) {
                // As the STL stores it: single precision.
                const auto f = [](double x) { return static_cast<double>(static_cast<float>(x)); };
                inside = inside && f(v.x) >= box.lo.x && f(v.x) <= box.hi.x && f(v.y) >= box.lo.y &&
                         f(v.y) <= box.hi.y && f(v.z) >= box.lo.z && f(v.z) <= box.hi.z;
            }
        if (lammps) {
            out->stage(dem.input, lammps_settle_input(settle));
        } else {
            out->stage(dem.input, liggghts_settle_input(settle));
            if (!dem.wall.empty()) {
                write_surface({side}, SurfaceFormat::stl_ascii, out->reserve(dem.wall));
                write_surface({bottom}, SurfaceFormat::stl_ascii, out->reserve(dem.bottom));
            }
        }
        if (!given_box && !inside)
            throw std::logic_error("the container's STL lies outside the default box");
        note = fmt::format("; {}; example settle: {} -in {}{}", box_note,
                           lammps ? "lmp" : "liggghts", dem.input,
                           inside   ? ""
                           : lammps ? " (note: the container reaches outside --box: spheres "
                                      "that leave the box are lost)"
                                    : " (note: the container's STL reaches outside --box: "
                                      "LIGGGHTS refuses mesh elements outside the box)");
    }
    out->commit();
    return fmt::format("{} to {} ({}: read_data {}{}{})",
                       clumps ? fmt::format("{} pellets as rigid clumps of {} spheres",
                                            clumps->pellets, clumps->spheres)
                              : fmt::format("{} spheres", packing.size()),
                       out_path.string(), program, name,
                       o.fluid_velocity >= 0.0 ? fmt::format("; include {}.fluid.in", name) : "",
                       note);
}

} // namespace

std::vector<std::string> export_format_names() {
    return export_formats().names();
}

namespace {

/// The format `name`. \throws InvalidInput naming every format
ExportFormat export_format(const std::string& name) {
    const std::optional<ExportFormat> format = export_formats().find(name);
    if (!format)
        throw InvalidInput(fmt::format("--format '{}' is not allowed; allowed: {}",
                                       printable(name.substr(0, 80)), export_formats().allowed()));
    return *format;
}

bool is_surface(ExportFormat format) {
    return format == ExportFormat::stl || format == ExportFormat::stl_ascii ||
           format == ExportFormat::obj || format == ExportFormat::openfoam;
}

/// The radius of a pellet's rims (a lobe's, a spherocylinder's), at size 1: what its surface's
/// segments about the axis are counted on.
double rim_radius(const MultilobeShape& shape) {
    return shape.lobe.radius;
}
double rim_radius(const SpherocylinderShape& shape) {
    return shape.radius;
}

/// The surface-volume equivalent diameter 6 V / S at `size`: a cylinder's in closed form,
/// 6 R h / (R + 2 h) for radius R and half-length h (D when L = D).
double surface_volume_diameter(const MultilobeShape& shape, double size) {
    if (shape.lobes == 1 && shape.lobe.bore == 0.0) {
        const double r = shape.lobe.radius * size, h = shape.lobe.half_length * size;
        return 6.0 * r * h / (r + 2.0 * h);
    }
    return 6.0 * shape.volume(size) / shape.surface_area(size);
}
double surface_volume_diameter(const SpherocylinderShape& shape, double size) {
    return 6.0 * shape.volume(size) / shape.surface_area(size);
}

/// A bed of pellets for LAMMPS: each pellet as its clump of spheres (the shape's dem_spheres,
/// inside the pellet, the outermost touching its surface), one rigid body in the example
/// settle (docs/dem.md, "Pellets").
template <class S>
std::string clump_export(const ExportRequest& request, const Packing& packing,
                         const std::vector<std::size_t>& lines, const PelletSpec& pellet,
                         const S& shape) {
    if (request.contacts != "none" && !request.contacts.empty())
        throw InvalidInput(fmt::format("--contacts {} is not allowed with --format lammps-data; "
                                       "allowed: none (the clumps are the pellets' own)",
                                       printable(request.contacts)));
    const ShapedBed<S> bed(packing, {shape});
    Packing spheres;
    std::vector<std::size_t> sphere_lines;
    double sphere_volume = 0.0, pellet_volume = 0.0;
    ClumpExport clumps{0, bed.size(), pellet.text, 1.0};
    for (std::size_t i = 0; i < bed.size(); ++i) {
        std::size_t count = 0;
        bed.shape(i).dem_spheres(bed.placement(i), [&](const DemSphere& a) {
            spheres.add(a.centre, a.radius);
            clumps.reach = std::max(clumps.reach, norm(a.centre - packing.centers[i]) + a.radius);
            sphere_lines.push_back(i < lines.size() ? lines[i] : i + 1);
            sphere_volume += 4.0 / 3.0 * std::numbers::pi * a.radius * a.radius * a.radius;
            ++count;
        });
        clumps.spheres = count; // the shape's, whatever the size
        pellet_volume += bed.shape(i).volume(packing.radii[i]);
    }
    clumps.density_scale = pellet_volume / sphere_volume;
    return data_export(request, ExportFormat::lammps_data, spheres, sphere_lines, &clumps);
}

/// A bed of pellets as surfaces (STL, OBJ, an OpenFOAM case): each pellet's exact shape
/// tessellated (ParticleShape::unit_surface, its vertices on the surface, so that the
/// polyhedron lies inside the convex pellet), for shrink:F scaled by 1 - F about its centroid,
/// which leaves a gap wherever the exact shapes shrunk so are apart (checked pair by pair by
/// the exact penetration depth, and at the walls and the floor); the exact volumes.
template <class S>
std::string pellet_export(const ExportRequest& request, ExportFormat format, const Packing& packing,
                          const std::vector<std::size_t>& lines, const PelletSpec& pellet,
                          const S& shape) {
    const std::string shown = printable(request.source);
    if (!is_surface(format) && format != ExportFormat::lammps_data)
        throw InvalidInput(fmt::format("--format {} is not allowed for a bed of {} pellets; "
                                       "allowed: stl, stl-ascii, obj, openfoam, lammps-data "
                                       "(LIGGGHTS makes its multisphere clumps from its own "
                                       "templates as it inserts them)",
                                       request.format, pellet.text));
    if (packing.orientations.size() != packing.size())
        throw InvalidInput(fmt::format("{}: a bed of {} pellets needs each pellet's orientation; "
                                       "allowed: a table with the columns qw, qx, qy, qz (what "
                                       "packbed generate --shape writes)",
                                       shown, pellet.text));
    if (request.container && request.container->periods())
        throw InvalidInput(fmt::format("--container {} is not allowed for a bed of pellets; "
                                       "allowed: {}",
                                       request.container->spec(),
                                       forms_but(request.container->name())));
    if (format == ExportFormat::lammps_data)
        return clump_export(request, packing, lines, pellet, shape);
    const fs::path& out_path = request.out;
    std::unique_ptr<OutputDirectory> out =
        format == ExportFormat::openfoam
            ? std::make_unique<OutputDirectory>(out_path, "--out", OutputKind::directory,
                                                request.force)
            : file_output(out_path, {".json"});
    const Contacts contacts = parse_contacts(request.contacts);
    if (contacts.treatment != ContactTreatment::none &&
        contacts.treatment != ContactTreatment::shrink)
        throw InvalidInput(fmt::format("--contacts {} is not allowed for a bed of pellets; "
                                       "allowed: none, or shrink:F (each pellet scaled by 1 - F "
                                       "about its centroid, F in (0, 0.5))",
                                       printable(request.contacts)));
    if (asked_facets(request, format) == Facets::volume)
        throw InvalidInput(fmt::format("--facets {} is not allowed for a bed of pellets; "
                                       "allowed: inscribed or auto (the pellets' vertices lie on "
                                       "their surfaces)",
                                       printable(request.facets)));
    const double scale =
        contacts.treatment == ContactTreatment::shrink ? 1.0 - contacts.parameter : 1.0;
    const ShapedBed<S> bed(packing, {shape});
    const double dv = packing.mean_diameter(); // r is d_v / 2
    const double largest = *std::max_element(packing.radii.begin(), packing.radii.end());
    const double top = bed_top(bed);
    // The container's height: given, or the pellets' top + 1 d_v.
    ExportRequest o = request;
    if (!(o.container_height > 0.0))
        o.container_height = top + dv;
    else if (!(o.container_height > top))
        throw InvalidInput(fmt::format("--container-height {} is not allowed; allowed: above "
                                       "the top of every pellet, {}",
                                       o.container_height, top));
    const std::optional<SurfaceContainer> container = bed_container(o, packing, lines);
    if (format == ExportFormat::openfoam && !container)
        throw InvalidInput(
            fmt::format("--format openfoam needs the container: give --container (no "
                        "summary.json with a container next to {})",
                        shown));
    // Each pellet shrunk so: placed at its size times the scale.
    const auto placed = [&](std::size_t i) {
        Placement p = bed.placement(i);
        p.size *= scale;
        return p;
    };
    const auto line = [&](std::size_t i) { return i < lines.size() ? lines[i] : i + 1; };
    if (scale < 1.0) {
        // Pairs whose bounding spheres meet, swept along z.
        std::vector<std::size_t> by_z(bed.size());
        for (std::size_t i = 0; i < by_z.size(); ++i)
            by_z[i] = i;
        std::sort(by_z.begin(), by_z.end(), [&](std::size_t a, std::size_t b) {
            return packing.centers[a].z < packing.centers[b].z;
        });
        const double reach = 2.0 * shape.bounding_radius(largest * scale) * 1.0001;
        for (std::size_t k = 0; k < by_z.size(); ++k) {
            const std::size_t i = by_z[k];
            const Placement a = placed(i);
            for (std::size_t m = k + 1; m < by_z.size(); ++m) {
                const std::size_t j = by_z[m];
                const Placement b = placed(j);
                if (b.position.z - a.position.z > reach)
                    break;
                const Vec3 ab = b.position - a.position;
                if (norm(ab) > shape.bounding_radius(a.size) + shape.bounding_radius(b.size))
                    continue;
                const PairOverlap overlap = shape.pair_overlap(a, shape, b, ab);
                if (overlap.depth > 0.0)
                    throw InvalidInput(fmt::format(
                        "--contacts {}: the pellets of lines {} and {} of {} still overlap by "
                        "{:.3g} after shrinking; allowed: a larger F",
                        request.contacts, line(i), line(j), shown, overlap.depth));
            }
        }
        if (container)
            for (std::size_t i = 0; i < bed.size(); ++i) {
                const Placement p = placed(i);
                const double wall = shape.wall_overlap(container->container, p);
                const double floor = -shape.support(p, Vec3{0.0, 0.0, -1.0}).z;
                if (wall > 0.0 || floor >= 0.0)
                    throw InvalidInput(fmt::format(
                        "--contacts {}: the pellet of line {} of {} still reaches {:.3g} into "
                        "the {} after shrinking; allowed: a larger F",
                        request.contacts, line(i), shown, std::max(wall, floor),
                        wall > 0.0 ? "wall" : "floor"));
            }
    }
    // Segments about the rim: --refine, or the level whose chord is at most --edge (on the
    // largest pellet).
    const double rim = rim_radius(shape) * largest * scale;
    int level = o.refine;
    if (o.edge > 0.0) {
        level = 0;
        while (level < static_cast<int>(option_range::refine.high) &&
               2.0 * std::numbers::pi * rim / static_cast<double>(12 << level) > o.edge)
            ++level;
        const double chord = 2.0 * std::numbers::pi * rim / static_cast<double>(12 << level);
        if (chord > o.edge)
            throw InvalidInput(fmt::format(
                "--edge {:g} is not allowed for pellets of radius {:g}: it needs more than "
                "level {}; allowed: at least {:.6g} (that level's edge about the rim)",
                o.edge, rim, level, chord));
    }
    const int segments = 12 << level;
    Solid particles{"particles", particle_surfaces(bed, level, scale)};

    nlohmann::ordered_json report;
    report["particles"] = o.source;
    report["pellets"] = packing.size();
    report["shape"] = pellet.text;
    report["contacts"] = o.contacts;
    report["volume_equivalent_diameter"] = dv;
    report["diameter"] = surface_volume_diameter(shape, 0.5 * dv);
    report["diameter_note"] = "the surface-volume equivalent diameter 6 V / S (Ergun's for "
                              "non-spheres), which cfd-report's correlations use; the mesh's "
                              "cells per diameter, the Reynolds number of --reynolds and the "
                              "aspect ratio are on volume_equivalent_diameter";
    report["segments"] = segments;
    // An inscribed polygon of n sides: R (1 - cos(pi / n)) from the circle at most.
    report["chord_error"] = rim * (1.0 - std::cos(std::numbers::pi / segments));
    std::optional<TreatmentVolumes> volumes;
    std::string change;
    if (container) {
        TreatmentVolumes& v = volumes.emplace();
        const double height = container->height;
        v.container_volume = container->container.cross_section_area(0.0, height) * height;
        v.untouched_solid = solid_volume(bed, container->container, 0.0, height);
        // Shrunk pellets lie inside the container (checked above): their whole volumes.
        v.treated_solid = v.untouched_solid;
        if (scale < 1.0) {
            v.treated_solid = 0.0;
            for (std::size_t i = 0; i < bed.size(); ++i)
                v.treated_solid += shape.volume(placed(i).size);
        }
        v.untouched_void_fraction = 1.0 - v.untouched_solid / v.container_volume;
        v.treated_void_fraction = 1.0 - v.treated_solid / v.container_volume;
        change = record_volumes(report, *container, v);
        report["volumes"]["note"] = "exact volumes of the shapes inside the container (overlaps "
                                    "between pellets, each below the generator's tolerance, are "
                                    "not subtracted)";
    }

    if (format == ExportFormat::openfoam) {
        const OpenFoamFlowOptions flow = case_flow(o);
        CaseParticles cp;
        cp.surface.push_back(std::move(particles));
        for (std::size_t i = 0; i < bed.size(); ++i) {
            const Placement p = placed(i);
            cp.bounds.push_back({p.position, shape.bounding_radius(p.size), {}});
            cp.top = std::max(cp.top, shape.support(p, Vec3{0.0, 0.0, 1.0}).z);
        }
        cp.count = bed.size();
        cp.wall_edge = 2.0 * std::numbers::pi * rim / segments;
        const OpenFoamCase foam =
            openfoam_case(cp, *container, *volumes, o.contacts, dv, o.mesh, flow);
        report["openfoam"] =
            case_record(o, foam, flow, *container,
                        void_fraction(bed, container->container, foam.planes.front() / foam.scale,
                                      foam.planes.back() / foam.scale),
                        dv);
        stage_case(*out, foam, report);
        return fmt::format("OpenFOAM case in {} ({} {} pellets, contacts {}{}); run ./Allrun "
                           "there",
                           out_path.string(), packing.size(), pellet.text, o.contacts, change);
    }

    std::vector<Solid> solids;
    solids.push_back(std::move(particles));
    if (container && !o.no_container)
        for (Solid& solid : container->container.solids(0.0, container->height,
                                                        2.0 * std::numbers::pi * rim / segments))
            solids.push_back(std::move(solid));
    const std::size_t triangles = write_surface_file(*out, out_path, format, solids, report);
    return fmt::format("{} {} pellets to {} ({} triangles, {} segments about the rim, contacts "
                       "{}){}",
                       packing.size(), pellet.text, out_path.string(), triangles, segments,
                       o.contacts, change);
}

} // namespace

double surface_volume_diameter(const PelletSpec& pellet) {
    return std::visit(
        [&](const auto& shape) {
            return surface_volume_diameter(shape, 0.5 * pellet.volume_diameter);
        },
        pellet.shape);
}

std::string export_format_for(const std::filesystem::path& out) {
    std::string extension = out.extension().string();
    std::transform(extension.begin(), extension.end(), extension.begin(),
                   [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
    if (extension == ".stl")
        return "stl";
    if (extension == ".obj")
        return "obj";
    return ExportRequest{}.format;
}

std::filesystem::path default_export_path(const std::filesystem::path& particles,
                                          const std::string& format) {
    switch (export_format(format)) {
    case ExportFormat::openfoam:
        return particles.parent_path() / "openfoam";
    case ExportFormat::stl:
    case ExportFormat::stl_ascii:
        return fs::path(particles).replace_extension(".stl");
    case ExportFormat::obj:
        return fs::path(particles).replace_extension(".obj");
    default:
        return fs::path(particles).replace_extension(".data");
    }
}

bool export_uses_container(const ExportRequest& request) {
    return is_surface(export_format(request.format)) || !request.no_container;
}

std::string export_bed(const Packing& packing, const std::vector<std::size_t>& lines,
                       const ExportRequest& request) {
    const ExportFormat format = export_format(request.format);
    if (request.mesh.periodic_z && format != ExportFormat::openfoam)
        throw InvalidInput(fmt::format("--flow periodic is not allowed with --format {}; "
                                       "allowed: --format openfoam",
                                       request.format));
    if (!request.keep.empty()) { // the bed's file and the summary.json that gives its container
        record_input("the particles file", request.keep);
        std::error_code ec;
        const fs::path summary = request.keep.parent_path() / "summary.json";
        if (fs::is_regular_file(summary, ec))
            record_input("the bed's summary", summary);
    }
    if (packing.size() == 0)
        throw InvalidInput(fmt::format("{}: no spheres to export; allowed: a bed with at least "
                                       "one sphere",
                                       printable(request.source)));
    // Surfaces and LIGGGHTS's walls are written in single precision (7 digits): a sphere far
    // from the origin, in sphere diameters, would lose its shape and the container its box.
    const double dp = packing.mean_diameter();
    for (std::size_t i = 0; i < packing.size(); ++i) {
        const Vec3& c = packing.centers[i];
        const double reach =
            std::max({std::abs(c.x), std::abs(c.y), std::abs(c.z)}) + packing.radii[i];
        if (!(reach <= limits::max_export_reach * dp))
            throw InvalidInput(fmt::format(
                "{}:{}: the sphere at ({}, {}, {}) reaches {:.6g} mean diameters from the "
                "origin; allowed: at most {:g} (the surfaces and walls are written in single "
                "precision)",
                printable(request.source), i < lines.size() ? lines[i] : i + 1, c.x, c.y, c.z,
                reach / dp, limits::max_export_reach));
    }
    if (!request.pellet && !packing.orientations.empty())
        throw InvalidInput(fmt::format(
            "{}: its particles have orientations (qw, qx, qy, qz: a bed of pellets) but no "
            "pellet shape is given; allowed: --shape SPEC naming its pellets (a bed from generate "
            "--shape has it in the summary.json beside it)",
            printable(request.source)));
    // A pellet's size is its table's r, d_v / 2: a shape of another size (beyond the digits a
    // table written by hand keeps; with sizes, outside their range) is not its shape. (A table
    // without orientations is refused as such by pellet_export.)
    if (request.pellet && !packing.orientations.empty()) {
        const double half = 0.5 * request.pellet->volume_diameter;
        const auto [low, high] = request.pellet->scales;
        for (std::size_t i = 0; i < packing.size(); ++i) {
            const double r = packing.radii[i];
            if (!(r >= (1.0 - 1e-3) * low * half && r <= (1.0 + 1e-3) * high * half))
                throw InvalidInput(fmt::format(
                    "{}:{}: r = {} is not allowed for {} pellets; allowed: {} within 0.1 % (a "
                    "pellet's size in the table: give the shape's lengths in the table's units)",
                    printable(request.source), i < lines.size() ? lines[i] : i + 1, r,
                    printable(request.pellet->text),
                    low == high ? fmt::format("r = d_v / 2 = {}", half * low)
                                : fmt::format("r from {} to {} (d_v / 2 of the sizes recorded "
                                              "beside it)",
                                              half * low, half * high)));
        }
    }
    if (request.pellet)
        return std::visit(
            [&](const auto& shape) {
                return pellet_export(request, format, packing, lines, *request.pellet, shape);
            },
            request.pellet->shape);
    if (is_surface(format))
        return surface_export(request, format, packing, lines);
    return data_export(request, format, packing, lines);
}

} // namespace packbed
