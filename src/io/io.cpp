#include "packbed/io.hpp"

#include <algorithm>
#include <cmath>
#include <iterator>
#include <limits>
#include <numbers>

#include <fmt/format.h>

#include "packbed/error.hpp"
#include "packbed/sphere_shape.hpp"

namespace packbed {

std::string particles_csv(const Packing& packing) {
    fmt::memory_buffer out;
    const bool turned = !packing.orientations.empty();
    fmt::format_to(std::back_inserter(out), "{}", turned ? "x,y,z,r,qw,qx,qy,qz\n" : "x,y,z,r\n");
    for (std::size_t i = 0; i < packing.size(); ++i) {
        const Vec3& c = packing.centers[i];
        // fmt's "{}" for double is the shortest representation that round-trips.
        fmt::format_to(std::back_inserter(out), "{},{},{},{}", c.x, c.y, c.z, packing.radii[i]);
        if (turned) {
            const Quaternion& q = packing.orientations[i];
            fmt::format_to(std::back_inserter(out), ",{},{},{},{}", q.w, q.x, q.y, q.z);
        }
        out.push_back('\n');
    }
    return fmt::to_string(out);
}

AxisBox bounding_box(const Packing& packing) {
    if (packing.size() == 0)
        return {{0.0, 0.0, 0.0}, {1.0, 1.0, 1.0}};
    const double inf = std::numeric_limits<double>::infinity();
    AxisBox box{{inf, inf, inf}, {-inf, -inf, -inf}};
    for (std::size_t i = 0; i < packing.size(); ++i) {
        const Vec3 c = packing.centers[i];
        const double r = packing.radii[i];
        box.lo = {std::min(box.lo.x, c.x - r), std::min(box.lo.y, c.y - r),
                  std::min(box.lo.z, c.z - r)};
        box.hi = {std::max(box.hi.x, c.x + r), std::max(box.hi.y, c.y + r),
                  std::max(box.hi.z, c.z + r)};
    }
    return box;
}

std::string lammps_data(const Packing& packing, double density, const AxisBox& box,
                        std::string_view comment, const std::vector<std::string>& notes,
                        const std::vector<std::uint32_t>& types, std::size_t clump_spheres,
                        std::uint32_t atom_types) {
    if (!(std::isfinite(density) && density > 0.0))
        throw InvalidInput(
            fmt::format("density = {} is not allowed; allowed: a number > 0", density));
    std::string header(comment);
    for (const std::string& note : notes)
        header += "\n# " + note;
    for (std::size_t start = 0, end = 0; start <= header.size(); start = end + 1) {
        end = std::min(header.find('\n', start), header.size());
        if (end - start > max_data_header_line)
            throw InvalidInput(fmt::format(
                "the data file's header line '{}...' ({} characters) is not allowed; allowed: "
                "up to {} characters (LAMMPS and LIGGGHTS read no more)",
                header.substr(start, 40), end - start, max_data_header_line));
    }
    for (const std::string& note : notes)
        if (note.find('\n') != std::string::npos)
            throw InvalidInput("a data file note with a newline is not allowed; allowed: one line");
    // Each particle as its DEM spheres (ParticleShape::dem_spheres: a sphere is one atom).
    const ShapedBed<SphereShape> bed = spheres(packing);
    std::size_t atoms = 0;
    for (std::size_t i = 0; i < bed.size(); ++i)
        bed.shape(i).dem_spheres(bed.placement(i), [&](const DemSphere& a) {
            const Vec3& c = a.centre;
            if (!(c.x >= box.lo.x && c.x <= box.hi.x && c.y >= box.lo.y && c.y <= box.hi.y &&
                  c.z >= box.lo.z && c.z <= box.hi.z))
                throw InvalidInput(fmt::format(
                    "sphere {} at ({}, {}, {}) lies outside the box [{}, {}] x [{}, {}] x [{}, "
                    "{}]; allowed: a box holding every centre",
                    i + 1, c.x, c.y, c.z, box.lo.x, box.hi.x, box.lo.y, box.hi.y, box.lo.z,
                    box.hi.z));
            ++atoms;
        });
    fmt::memory_buffer out;
    const std::uint32_t ntypes =
        std::max(atom_types, types.empty() ? 1u : *std::max_element(types.begin(), types.end()));
    fmt::format_to(std::back_inserter(out), "{}\n\n{} atoms\n{} atom types\n\n", header, atoms,
                   ntypes);
    fmt::format_to(std::back_inserter(out), "{} {} xlo xhi\n{} {} ylo yhi\n{} {} zlo zhi\n\n",
                   box.lo.x, box.hi.x, box.lo.y, box.hi.y, box.lo.z, box.hi.z);
    fmt::format_to(std::back_inserter(out), "Atoms # sphere\n\n");
    std::size_t id = 0;
    for (std::size_t i = 0; i < bed.size(); ++i)
        bed.shape(i).dem_spheres(bed.placement(i), [&](const DemSphere& a) {
            fmt::format_to(std::back_inserter(out), "{} {} {} {} {} {} {}\n", ++id,
                           types.empty() ? 1u : types[i], 2.0 * a.radius, density, a.centre.x,
                           a.centre.y, a.centre.z);
        });
    if (clump_spheres > 0) {
        fmt::format_to(std::back_inserter(out), "\nMolecules\n\n");
        for (std::size_t k = 1; k <= id; ++k)
            fmt::format_to(std::back_inserter(out), "{} {}\n", k, (k - 1) / clump_spheres + 1);
    }
    return fmt::to_string(out);
}

double container_box_margin(double diameter, double container_radius) {
    return std::max(0.5 * diameter, 0.01 * container_radius);
}

namespace {

/// Throw InvalidInput unless `value` is finite and > 0.
void require_positive(std::string_view name, double value) {
    if (!(std::isfinite(value) && value > 0.0))
        throw InvalidInput(
            fmt::format("{} = {} is not allowed; allowed: a number > 0", name, value));
}

} // namespace

AxisBox container_box(double container_radius, double height, double diameter) {
    require_positive("container radius", container_radius);
    require_positive("container height", height);
    require_positive("diameter", diameter);
    const double m = container_box_margin(diameter, container_radius);
    const double half = container_radius + m;
    return {{-half, -half, -m}, {half, half, height + m}};
}

namespace {

/// Throw InvalidInput unless the container has finite bounds and a depth > 0 (a periodic
/// cell, which has no wall and so no depth: an area > 0).
void require_container(const Container& container) {
    const Rectangle b = container.bounds();
    const bool sized = container.periods() ? container.cross_section_area(0.0, 0.0) > 0.0
                                           : container.depth(0.0, 0.0) > 0.0;
    if (!(std::isfinite(b.x_low) && std::isfinite(b.x_high) && std::isfinite(b.y_low) &&
          std::isfinite(b.y_high) && sized))
        throw InvalidInput(fmt::format("the container {} is not allowed; allowed: a container "
                                       "of finite size > 0",
                                       container.spec()));
}

} // namespace

double container_box_margin(const Container& container, double diameter) {
    return container_box_margin(diameter, container.box_margin().length);
}

AxisBox container_box(const Container& container, double height, double diameter) {
    require_container(container);
    require_positive("container height", height);
    require_positive("diameter", diameter);
    const double m = container_box_margin(container, diameter);
    const Rectangle b = container.bounds();
    if (container.periods()) // x and y: the cell itself, its periods
        return {{b.x_low, b.y_low, -m}, {b.x_high, b.y_high, height + m}};
    return {{b.x_low - m, b.y_low - m, -m}, {b.x_high + m, b.y_high + m, height + m}};
}

double rayleigh_time(double radius, double density, double youngs_modulus, double poisson_ratio) {
    require_positive("radius", radius);
    require_positive("density", density);
    require_positive("Young's modulus", youngs_modulus);
    if (!(poisson_ratio >= 0.0 && poisson_ratio < 0.5))
        throw InvalidInput(fmt::format(
            "Poisson's ratio = {} is not allowed; allowed: a number in [0, 0.5)", poisson_ratio));
    const double shear_modulus = youngs_modulus / (2.0 * (1.0 + poisson_ratio));
    return std::numbers::pi * radius * std::sqrt(density / shear_modulus) /
           (0.1631 * poisson_ratio + 0.8766);
}

namespace {

/// A file name a LAMMPS or LIGGGHTS input can hold as one word: letters, digits, '.', '_',
/// '-', '+' (no blanks, '#' comments, '$' variables, quotes).
void require_input_word(std::string_view what, const std::string& name) {
    const bool ok = !name.empty() && std::all_of(name.begin(), name.end(), [](char c) {
        return (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') ||
               c == '.' || c == '_' || c == '-' || c == '+';
    });
    if (!ok)
        throw InvalidInput(fmt::format("{} '{}' is not allowed in a DEM input; allowed: a file "
                                       "name of letters, digits, '.', '_', '-' and '+'",
                                       what, name));
}

/// The checks and the numbers both inputs share.
struct SettleNumbers {
    double rayleigh = 0.0;  // s, smallest sphere
    double time_step = 0.0; // s
    double skin = 0.0;      // neighbour skin
};

SettleNumbers settle_numbers(const DemSettle& s) {
    require_input_word("the data file", s.data_file);
    require_input_word("the dump file", s.dump);
    require_container(s.container);
    require_positive("container height", s.container_height);
    require_positive("diameter", s.diameter);
    const DemMaterial& m = s.material;
    if (!(m.restitution > 0.0 && m.restitution <= 1.0))
        throw InvalidInput(fmt::format(
            "restitution = {} is not allowed; allowed: a number in (0, 1]", m.restitution));
    if (!(m.friction >= 0.0 && std::isfinite(m.friction)))
        throw InvalidInput(
            fmt::format("friction = {} is not allowed; allowed: a number >= 0", m.friction));
    if (m.wall_friction && !(*m.wall_friction >= 0.0 && std::isfinite(*m.wall_friction)))
        throw InvalidInput(fmt::format("wall friction = {} is not allowed; allowed: a number >= 0",
                                       *m.wall_friction));
    if (!(s.steps >= 1))
        throw InvalidInput(fmt::format("steps = {} is not allowed; allowed: 1 or more", s.steps));
    if (!(s.time_step_fraction > 0.0 && s.time_step_fraction <= 1.0))
        throw InvalidInput(fmt::format("time step fraction = {} is not allowed; allowed: a "
                                       "number in (0, 1]",
                                       s.time_step_fraction));
    SettleNumbers n;
    n.rayleigh = rayleigh_time(s.smallest_radius, s.density, m.youngs_modulus, m.poisson_ratio);
    n.time_step = s.time_step_fraction * n.rayleigh;
    n.skin = 0.1 * s.diameter;
    return n;
}

DemSettleWall settle_wall(const DemSettle& s, std::string_view contact = "") {
    return s.container.settle_wall(s.container_height, contact);
}

/// The comment block and the variables both inputs start with.
std::string settle_head(const DemSettle& s, const SettleNumbers& n, std::string_view program,
                        std::string_view run) {
    const DemMaterial& m = s.material;
    return fmt::format(
        "# packbed export: a short DEM settle of the bed in {0} under gravity, in its container,\n"
        "# for {1}. Run it in the folder of {0}:  {2}\n"
        "# Lengths as in {0} with units si (metres); the container is the {3} (docs/dem.md).\n"
        "# Material: an example (a soft glass-like solid, E far below glass's 63 GPa as usual in\n"
        "# DEM), not calibrated; edit the variables below, the time step follows them.\n"
        "{15}"
        "# Time step: {4} x the Rayleigh time of the smallest sphere (radius R),\n"
        "#   t_R = pi R sqrt(rho / G) / (0.1631 nu + 0.8766), G = E / (2 (1 + nu))\n"
        "#   (Li, Xu & Thornton 2005, Powder Technol. 160: 219-228; LIGGGHTS fix "
        "check/timestep/gran)\n"
        "#   here: R = {5:.9g}, rho = {6:.9g}, E = {7:.9g}, nu = {8:.9g}: t_R = {9:.6g} s,\n"
        "#   dt = {10:.6g} s;"
        " {11} steps = {12:.6g} s of settling.\n\n"
        "variable        youngs equal {7}\n"
        "variable        poisson equal {8}\n"
        "variable        restitution equal {13}\n"
        "variable        friction equal {14}\n"
        "{16}"
        "variable        density equal {6}\n"
        "variable        radius equal {5}\n"
        "variable        shear equal v_youngs/(2*(1+v_poisson))\n"
        "variable        rayleigh equal "
        "PI*v_radius*sqrt(v_density/v_shear)/(0.1631*v_poisson+0.8766)\n"
        "variable        dt equal {4}*v_rayleigh\n\n",
        s.data_file, program, run, settle_wall(s).words, s.time_step_fraction, s.smallest_radius,
        s.density, m.youngs_modulus, m.poisson_ratio, n.rayleigh, n.time_step, s.steps,
        s.steps * n.time_step, m.restitution, m.friction,
        m.friction_of_bed ? "# Friction: the bed's own, as packbed generate --friction made it.\n"
                          : "",
        m.wall_friction ? fmt::format("variable        wall_friction equal {}\n", *m.wall_friction)
                        : std::string());
}

/// The run and its report, the same in both programs.
std::string settle_run(const DemSettle& s, const SettleNumbers& n) {
    return fmt::format(
        "fix             gravity all gravity 9.81 vector 0.0 0.0 -1.0\n"
        "{4}"
        "timestep        ${{dt}}\n\n"
        "thermo          {0}\n"
        "{5}"
        "# The spheres at the first and the last step (packbed analyze reads it: --frame -1).\n"
        "dump            settle all custom {1} {2} id type x y z radius\n"
        "variable        zc equal xcm(all,z)\n"
        "variable        zc0 equal ${{zc}}\n"
        "variable        atoms equal atoms\n"
        "run             {1}\n"
        "print           \"packbed settle: ${{atoms}} atoms after {1} steps of {3:.6g} s; mass "
        "centre z ${{zc0}} -> ${{zc}}\"\n",
        std::max(1, s.steps / 4), s.steps, s.dump, n.time_step,
        s.clump_spheres > 0
            ? "# Each clump one rigid body (its spheres' forces and torques summed).\n"
              "fix             integrate all rigid/small molecule\n"
            : "fix             integrate all nve/sphere\n",
        s.clump_spheres > 0 ? "# (No ke: the temperature compute counts the atoms' own degrees of "
                              "freedom, which the bodies remove.)\n"
                              "thermo_style    custom step atoms\n"
                            : "thermo_style    custom step atoms ke\n");
}

/// The box of a settle input: SI units, the atom style, the boundary, how velocities reach the
/// ghost atoms (the granular pair styles need them), the data file and the neighbour list.
std::string settle_box(std::string_view atom_style, std::string_view boundary,
                       std::string_view communication, const DemSettle& s, const SettleNumbers& n) {
    if (s.clump_spheres > 0)
        return fmt::format("units           si\n"
                           "atom_style      {}\n"
                           "atom_modify     map array\n"
                           "boundary        {}\n"
                           "{}"
                           "# The pellets' clumps: each sphere's molecule ID (the data file's "
                           "Molecules section).\n"
                           "fix             clumps all property/atom mol ghost yes\n"
                           "read_data       {} fix clumps NULL Molecules\n\n"
                           "neighbor        {} bin\n"
                           "neigh_modify    delay 0 exclude molecule/intra all\n",
                           atom_style, boundary, communication, s.data_file, n.skin);
    return fmt::format("units           si\n"
                       "atom_style      {}\n"
                       "atom_modify     map array\n"
                       "boundary        {}\n"
                       "{}"
                       "read_data       {}\n\n"
                       "neighbor        {} bin\n"
                       "neigh_modify    delay 0\n",
                       atom_style, boundary, communication, s.data_file, n.skin);
}

} // namespace

std::string lammps_settle_input(const DemSettle& s) {
    const SettleNumbers n = settle_numbers(s);
    const auto contact_with = [](std::string_view friction) {
        return fmt::format("hertz/material ${{youngs}} ${{restitution}} ${{poisson}} tangential "
                           "mindlin NULL 1.0 ${{{}}} damping tsuji",
                           friction);
    };
    const std::string contact = contact_with("friction");
    // The walls and the floor with the bed's own wall friction where it differs.
    const std::string wall_contact =
        s.material.wall_friction ? contact_with("wall_friction") : contact;
    const DemSettleWall wall = settle_wall(s, wall_contact);
    return settle_head(s, n, "LAMMPS (2022, GRANULAR package)",
                       fmt::format("lmp -in {}.lammps.in", s.data_file)) +
           settle_box("sphere", wall.boundary,
                      s.clump_spheres > 0
                          ? fmt::format("# Ghost atoms as far as a pellet's clump reaches, and "
                                        "the skin: LAMMPS needs a rigid body's atoms within "
                                        "them.\ncomm_modify     vel yes cutoff {:.9g}\n",
                                        2.0 * s.clump_reach + n.skin)
                          : std::string("comm_modify     vel yes\n"),
                      s, n) +
           fmt::format(
               "# Hertz contacts with the material's E, nu, restitution (Tsuji damping) and "
               "friction.\n"
               "pair_style      granular\n"
               "pair_coeff      * * {0}\n"
               "{1}"
               "fix             floor all wall/gran granular {2} zplane 0.0 NULL\n",
               contact, wall.lammps, wall_contact) +
           settle_run(s, n);
}

std::string liggghts_settle_input(const DemSettle& s) {
    if (s.clump_spheres > 0)
        throw InvalidInput("a LIGGGHTS settle of rigid clumps is not written; allowed: LAMMPS "
                           "(LIGGGHTS makes its multisphere clumps from its own templates as it "
                           "inserts them, not from a data file)");
    const SettleNumbers n = settle_numbers(s);
    const DemSettleWall wall = settle_wall(s);
    const bool stl = !wall.liggghts_stl.empty(); // a periodic cell: no STL, a plane floor
    if (stl) {
        require_input_word("the wall STL", s.wall_stl);
        require_input_word("the bottom STL", s.bottom_stl);
    }
    // The walls of their own atom type (2) where their friction is the bed's own and differs.
    const bool own = s.material.wall_friction.has_value();
    const int type = own ? 2 : 1;
    const std::string container =
        stl ? fmt::format(
                  "# The container from packbed's STL: its side ({2}) and floor.\n"
                  "fix             side all mesh/surface file {0} type {3}\n"
                  "fix             floor all mesh/surface file {1} type {3}\n"
                  "fix             container all wall/gran model hertz tangential history mesh "
                  "n_meshes 2 meshes side floor\n",
                  s.wall_stl, s.bottom_stl, wall.liggghts_stl, type)
            : fmt::format("# The container: periodic in x and y (boundary p p f), no side wall; "
                          "the floor as the plane z = 0.\n"
                          "fix             floor all wall/gran model hertz tangential history "
                          "primitive type {} zplane 0.0\n",
                          type);
    // Per atom type (and pair of types): the spheres 1, the walls 2 where they have their own.
    const std::string materials =
        own ? std::string(
                  "# Atom type 2: the walls and the floor, with the bed's own wall friction.\n"
                  "fix             m1 all property/global youngsModulus peratomtype ${youngs} "
                  "${youngs}\n"
                  "fix             m2 all property/global poissonsRatio peratomtype ${poisson} "
                  "${poisson}\n"
                  "fix             m3 all property/global coefficientRestitution peratomtypepair 2 "
                  "${restitution} ${restitution} ${restitution} ${restitution}\n"
                  "fix             m4 all property/global coefficientFriction peratomtypepair 2 "
                  "${friction} ${wall_friction} ${wall_friction} ${wall_friction}\n")
            : std::string(
                  "fix             m1 all property/global youngsModulus peratomtype ${youngs}\n"
                  "fix             m2 all property/global poissonsRatio peratomtype ${poisson}\n"
                  "fix             m3 all property/global coefficientRestitution peratomtypepair 1 "
                  "${restitution}\n"
                  "fix             m4 all property/global coefficientFriction peratomtypepair 1 "
                  "${friction}\n");
    return settle_head(s, n, "LIGGGHTS 3.8",
                       fmt::format("liggghts -in {}.liggghts.in", s.data_file)) +
           settle_box("granular", wall.boundary,
                      "newton          off\ncommunicate     single vel yes\n", s, n) +
           materials +
           fmt::format("pair_style      gran model hertz tangential history\n"
                       "pair_coeff      * *\n"
                       "{0}"
                       "# Warns if dt exceeds a quarter of the Rayleigh or Hertz time.\n"
                       "fix             dt_check all check/timestep/gran {1} 0.25 0.25\n",
                       container, std::max(1, s.steps / 2)) +
           settle_run(s, n);
}

std::string particles_vtu(const Packing& packing) {
    const std::size_t n = packing.size();
    fmt::memory_buffer out;
    auto put = [&]<class... Args>(fmt::format_string<Args...> format, Args&&... args) {
        fmt::format_to(std::back_inserter(out), format, std::forward<Args>(args)...);
    };
    put("<?xml version=\"1.0\"?>\n"
        "<VTKFile type=\"UnstructuredGrid\" version=\"1.0\" byte_order=\"LittleEndian\">\n"
        "  <UnstructuredGrid>\n"
        "    <Piece NumberOfPoints=\"{0}\" NumberOfCells=\"{0}\">\n"
        "      <PointData Scalars=\"radius\">\n"
        "        <DataArray type=\"Float64\" Name=\"radius\" format=\"ascii\">\n",
        n);
    for (const double r : packing.radii)
        put("{}\n", r);
    put("        </DataArray>\n"
        "        <DataArray type=\"Float64\" Name=\"diameter\" format=\"ascii\">\n");
    for (const double r : packing.radii)
        put("{}\n", 2.0 * r);
    put("        </DataArray>\n");
    if (!packing.orientations.empty()) {
        // Oriented particles (pellets): the unit quaternion, and the body z axis it turns
        // into the particle's (what glyphs are oriented by).
        put("        <DataArray type=\"Float64\" Name=\"orientation\" NumberOfComponents=\"4\" "
            "format=\"ascii\">\n");
        for (const Quaternion& q : packing.orientations)
            put("{} {} {} {}\n", q.w, q.x, q.y, q.z);
        put("        </DataArray>\n"
            "        <DataArray type=\"Float64\" Name=\"axis\" NumberOfComponents=\"3\" "
            "format=\"ascii\">\n");
        for (const Quaternion& q : packing.orientations) {
            const Vec3 a = rotate(q, Vec3{0.0, 0.0, 1.0});
            put("{} {} {}\n", a.x, a.y, a.z);
        }
        put("        </DataArray>\n");
    }
    put("      </PointData>\n"
        "      <Points>\n"
        "        <DataArray type=\"Float64\" NumberOfComponents=\"3\" format=\"ascii\">\n");
    for (const Vec3& c : packing.centers)
        put("{} {} {}\n", c.x, c.y, c.z);
    put("        </DataArray>\n"
        "      </Points>\n"
        "      <Cells>\n"
        "        <DataArray type=\"Int64\" Name=\"connectivity\" format=\"ascii\">\n");
    for (std::size_t i = 0; i < n; ++i)
        put("{}\n", i);
    put("        </DataArray>\n"
        "        <DataArray type=\"Int64\" Name=\"offsets\" format=\"ascii\">\n");
    for (std::size_t i = 1; i <= n; ++i)
        put("{}\n", i);
    put("        </DataArray>\n"
        "        <DataArray type=\"UInt8\" Name=\"types\" format=\"ascii\">\n");
    for (std::size_t i = 0; i < n; ++i)
        put("1\n"); // VTK_VERTEX
    put("        </DataArray>\n"
        "      </Cells>\n"
        "    </Piece>\n"
        "  </UnstructuredGrid>\n"
        "</VTKFile>\n");
    return fmt::to_string(out);
}

} // namespace packbed
