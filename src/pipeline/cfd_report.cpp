// `packbed cfd-report`: the pressure gradient of a run OpenFOAM case next to the correlations
// (pipeline.hpp).
#include <algorithm>
#include <array>
#include <cmath>
#include <filesystem>
#include <limits>
#include <map>
#include <numbers>
#include <optional>
#include <set>
#include <string>
#include <vector>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "base/json_input.hpp"
#include "gnuplot.hpp"
#include "packbed/error.hpp"
#include "packbed/files.hpp"
#include "packbed/hydraulics.hpp"
#include "packbed/json_text.hpp"
#include "packbed/limits.hpp"
#include "packbed/pipeline.hpp"
#include "packbed/text.hpp"

namespace packbed {

namespace {

namespace fs = std::filesystem;

/// The longest line read from a log or a table (OpenFOAM's are far shorter).
constexpr std::size_t line_limit = 1 << 16;

/// The case's path as messages show it.
std::string shown(const fs::path& path) {
    return printable(path.native());
}

/// A function object's tables, the newest first. OpenFOAM writes
/// postProcessing/NAME/START/surfaceFieldValue.dat, START the time the run started from; a run
/// restarted from a START whose folder has that table already writes surfaceFieldValue_START.dat
/// beside it (a third run from the same START writes over that one). So: the latest START
/// first, and in it the suffixed table before the plain one.
std::vector<fs::path> tables_newest_first(const fs::path& folder) {
    std::vector<std::pair<double, fs::path>> starts;
    std::error_code error;
    if (fs::is_directory(folder, error))
        for (const auto& entry : fs::directory_iterator(folder, error))
            if (const auto t = parse_finite(entry.path().filename().string()))
                starts.emplace_back(*t, entry.path());
    std::sort(starts.begin(), starts.end(), [](const auto& a, const auto& b) {
        return a.first != b.first ? a.first > b.first : a.second > b.second;
    });
    std::vector<fs::path> tables;
    for (const auto& [t, start] : starts) {
        const std::string name = start.filename().string();
        for (const auto& file :
             {"surfaceFieldValue_" + name + ".dat", std::string("surfaceFieldValue.dat")})
            if (fs::is_regular_file(start / file, error))
                tables.push_back(start / file);
    }
    return tables;
}

/// The last row of `table` under its last header line ("# Time <tab> area <tab>
/// areaAverage(p)"), as column name -> value; none where it has no row (a run stopped before
/// its first write).
std::optional<std::map<std::string, double>> table_last_row(const fs::path& case_dir,
                                                            const fs::path& table) {
    std::ifstream in = open_regular_file("CASE", table);
    std::vector<std::string> header, row;
    std::string line;
    for (LineRead r; (r = read_line(in, line, line_limit)) != LineRead::end;) {
        if (r != LineRead::line)
            throw InvalidInput(fmt::format("CASE {}: {} cannot be read (a line longer than {} "
                                           "bytes, or an I/O error)",
                                           shown(case_dir), shown(table), line_limit));
        const auto fields = split_spaces(line);
        std::vector<std::string> w(fields.begin(), fields.end());
        if (w.empty())
            continue;
        if (w.front() == "#") {
            w.erase(w.begin());
            if (!w.empty() && w.front() == "Time")
                header = std::move(w);
        } else {
            row = std::move(w);
        }
    }
    if (row.empty())
        return std::nullopt;
    if (header.empty() || row.size() != header.size())
        throw InvalidInput(fmt::format("CASE {}: {}: its last row does not match a '# Time ...' "
                                       "header; allowed: a table as OpenFOAM writes it",
                                       shown(case_dir), shown(table)));
    std::map<std::string, double> out;
    for (std::size_t k = 0; k < row.size(); ++k) {
        const auto v = parse_finite(row[k]);
        if (!v)
            throw InvalidInput(fmt::format("CASE {}: {}: '{}' in column {} is not a finite number",
                                           shown(case_dir), shown(table), printable(row[k]),
                                           header[k]));
        out[header[k]] = *v;
    }
    return out;
}

/// The last row of a function object's newest table that has one
/// (postProcessing/NAME/START/surfaceFieldValue*.dat, tables_newest_first): a run restarted
/// and stopped again before its first write leaves an empty table, and the rows before it
/// are the latest there are.
std::map<std::string, double> last_row(const fs::path& case_dir, const std::string& name) {
    const auto tables = tables_newest_first(case_dir / "postProcessing" / name);
    if (tables.empty())
        throw InvalidInput(fmt::format("CASE {}: no postProcessing/{}/TIME/surfaceFieldValue.dat; "
                                       "allowed: a case exported by packbed export --format "
                                       "openfoam and run by its Allrun",
                                       shown(case_dir), name));
    for (const auto& table : tables)
        if (auto row = table_last_row(case_dir, table))
            return *std::move(row);
    throw InvalidInput(fmt::format("CASE {}: {} has no rows under a '# Time ...' header; "
                                   "allowed: a case whose solver ran at least one iteration",
                                   shown(case_dir), shown(tables.front())));
}

/// A column of `row` (last_row) that must be there.
double column(const std::map<std::string, double>& row, const std::string& name,
              const fs::path& case_dir, const std::string& table) {
    const auto it = row.find(name);
    if (it == row.end())
        throw InvalidInput(fmt::format("CASE {}: postProcessing/{} has no column {}",
                                       shown(case_dir), table, name));
    return it->second;
}

/// What a solver's log says about its end: simpleFoam's "SIMPLE solution converged in N
/// iterations" (residualControl), or the case's runTimeControl "pressureDropSteady condition
/// satisfied" (a laminar run above Re_p 10), and each field's initial residual in the last
/// iteration.
struct SolverLog {
    std::string stopped_by = "endTime"; ///< "residuals", "steady pressure drop" or "endTime"
    long iterations = 0;                ///< the last "Time = N"
    std::map<std::string, double> residuals;
    /// meanVelocityForce's last "pressure gradient = G" (kinematic, m/s^2; a periodic cell)
    std::optional<double> pressure_gradient;
};

SolverLog read_solver_log(const fs::path& case_dir) {
    SolverLog out;
    const fs::path path = case_dir / "log.simpleFoam";
    std::error_code error;
    if (!fs::exists(path, error))
        return out;
    std::ifstream in = open_regular_file("CASE", path);
    std::string line;
    // A field solved twice in an iteration (p, with a non-orthogonal corrector): its first
    // initial residual is the iteration's, the one residualControl compares.
    std::set<std::string> solved;
    for (LineRead r; (r = read_line(in, line, line_limit)) != LineRead::end;) {
        if (r != LineRead::line)
            continue; // a long line is nothing we look for
        if (line.starts_with("Time = ")) {
            solved.clear();
            if (const auto t = parse_finite(line.substr(7)))
                out.iterations = std::lround(*t);
        } else if (line.find("SIMPLE solution converged") != std::string::npos) {
            out.stopped_by = "residuals";
        } else if (line.find("pressureDropSteady condition satisfied") != std::string::npos) {
            out.stopped_by = "steady pressure drop";
        } else if (const auto g = line.find("pressure gradient = "); g != std::string::npos) {
            // "Pressure gradient source: uncorrected Ubar = 1e-05, pressure gradient = 0.0005"
            const auto fields = split_spaces(std::string_view(line).substr(g + 20));
            if (!fields.empty())
                if (const auto v = parse_finite(fields.front()))
                    out.pressure_gradient = *v;
        } else if (const auto at = line.find("Solving for "); at != std::string::npos) {
            // "smoothSolver:  Solving for Ux, Initial residual = 1e-07, Final residual = ..."
            const auto comma = line.find(',', at);
            const auto equals = line.find("Initial residual = ", at);
            if (comma == std::string::npos || equals == std::string::npos)
                continue;
            const std::string field = line.substr(at + 12, comma - at - 12);
            if (!solved.insert(field).second)
                continue;
            const auto end = line.find(',', equals);
            if (const auto v = parse_finite(line.substr(equals + 19, end - equals - 19)))
                out.residuals[field] = *v;
        }
    }
    return out;
}

bool converged(const SolverLog& log) {
    return log.stopped_by != "endTime";
}

/// The report's "solver" block.
nlohmann::ordered_json solver_json(const SolverLog& log) {
    return {{"log", "log.simpleFoam"},
            {"converged", converged(log)},
            {"stopped_by", log.stopped_by},
            {"iterations", log.iterations},
            {"last_initial_residuals", log.residuals}};
}

/// What log.checkMesh says of the mesh: its "cells: N" and "Total volume = V." (m^3 after
/// Allrun's transformPoints), each nothing when absent (or no log), and the checks it failed
/// ("Failed N mesh checks.", the first "***" line), in one pass. checkMesh prints no total
/// volume when a cell's volume is zero or negative.
struct MeshLog {
    std::optional<double> cells;
    std::optional<double> volume;
    int failed_checks = 0;
    std::string first_failure;
};

/// "the mesh failed N of checkMesh's checks (log.checkMesh: FIRST)".
std::string failed_checks(const MeshLog& mesh) {
    return fmt::format("the mesh failed {} of checkMesh's checks (log.checkMesh: \"{}\")",
                       mesh.failed_checks, mesh.first_failure);
}

MeshLog read_mesh_log(const fs::path& case_dir) {
    const fs::path path = case_dir / "log.checkMesh";
    std::error_code error;
    MeshLog out;
    if (!fs::exists(path, error))
        return out;
    std::ifstream in = open_regular_file("CASE", path);
    std::string line;
    for (LineRead r; (r = read_line(in, line, line_limit)) != LineRead::end;) {
        if (r != LineRead::line)
            continue;
        const auto fields = split_spaces(line);
        if (fields.size() == 2 && fields[0] == "cells:")
            out.cells = parse_finite(fields[1]);
        if (fields.size() == 4 && fields[0] == "Failed" && fields[2] == "mesh")
            out.failed_checks = static_cast<int>(parse_finite(fields[1]).value_or(1.0));
        if (out.first_failure.empty() && !fields.empty() && fields[0].starts_with("***"))
            out.first_failure = printable(std::string_view(line).substr(line.find("***") + 3));
        const auto at = line.find("Total volume = ");
        if (at == std::string::npos)
            continue;
        const auto rest = split_spaces(std::string_view(line).substr(at + 15));
        if (rest.empty())
            continue;
        std::string value(rest.front());
        if (value.back() == '.')
            value.pop_back();
        out.volume = parse_finite(value);
    }
    return out;
}

/// A number in packbed.json that must be there.
double recorded(const nlohmann::json& json, const nlohmann::json::json_pointer& at,
                const fs::path& case_dir) {
    if (!json.contains(at) || !json.at(at).is_number())
        throw InvalidInput(fmt::format("CASE {}: packbed.json has no number at {}; allowed: a "
                                       "case exported by this version of packbed export --format "
                                       "openfoam",
                                       shown(case_dir), at.to_string()));
    const double v = json.at(at).get<double>();
    if (!std::isfinite(v))
        throw InvalidInput(fmt::format("CASE {}: packbed.json {} = {} is not allowed; allowed: a "
                                       "finite number",
                                       shown(case_dir), at.to_string(), v));
    return v;
}

/// The references of a periodic cell's drag are Stokes flow (Re -> 0); above this particle
/// Reynolds number inertia adds to the drag (Beetstra et al.'s 2007 correction is about 1 % of
/// it at Re_p = 1 for phi = 0.2-0.6), so the comparison is flagged.
constexpr double stokes_reynolds = 0.1;

std::string stokes_warning(const fs::path& case_dir, double reynolds) {
    return fmt::format("{}: Re_p = {:.4g}: Zick & Homsy's and van der Hoef's drags are for "
                       "Stokes flow, and inertia adds to this one; export with --reynolds 0.01 "
                       "to compare with them",
                       shown(case_dir), reynolds);
}

/// The report of a cell periodic along z (packbed.json's openfoam.flow.periodic): the pressure
/// gradient that meanVelocityForce found, the drag per sphere it balances and its
/// dimensionless forms beside Zick & Homsy's simple cubic arrays and van der Hoef et al.'s
/// random ones. The superficial velocity is the mesh's: the mean velocity in its fluid (held at
/// the recorded one) times its void fraction (checkMesh's volume over the cell's), so that the
/// drag is that of the flow the mesh carries.
Report periodic_report(const fs::path& case_dir, const nlohmann::json& json) {
    using ptr = nlohmann::json::json_pointer;
    const ptr flow("/openfoam/flow"), cell = flow / "periodic";
    const double rho = recorded(json, flow / "fluid_density", case_dir);
    const double mu = recorded(json, flow / "viscosity", case_dir);
    const double scale = recorded(json, flow / "metres_per_unit", case_dir);
    const double volume = recorded(json, cell / "cell_volume", case_dir) * scale * scale * scale;
    const double spheres = recorded(json, cell / "spheres", case_dir);
    const double radius = recorded(json, cell / "sphere_radius", case_dir) * scale;
    const double phi = recorded(json, cell / "solid_fraction", case_dir);
    const double held = recorded(json, cell / "interstitial_velocity", case_dir);
    if (!(spheres >= 1.0 && radius > 0.0 && volume > 0.0 && phi > 0.0 && phi < 1.0))
        throw InvalidInput(fmt::format("CASE {}: packbed.json's openfoam.flow.periodic is not a "
                                       "cell with spheres in it; allowed: a case exported by "
                                       "packbed export --flow periodic",
                                       shown(case_dir)));
    std::error_code error;
    if (!fs::exists(case_dir / "log.simpleFoam", error))
        throw InvalidInput(fmt::format("CASE {}: no log.simpleFoam; allowed: a case run by its "
                                       "Allrun (./Allrun there)",
                                       shown(case_dir)));
    const SolverLog log = read_solver_log(case_dir);
    if (!log.pressure_gradient)
        throw InvalidInput(fmt::format("CASE {}: log.simpleFoam has no \"pressure gradient = \" "
                                       "line; allowed: a periodic case run by its Allrun",
                                       shown(case_dir)));
    const MeshLog mesh = read_mesh_log(case_dir);
    const std::optional<double> meshed = mesh.volume;
    if (!meshed && mesh.failed_checks > 0)
        throw InvalidInput(fmt::format("CASE {}: {}, and its volume is unknown; allowed: a mesh "
                                       "that passes (a finer mesh, or wider gaps between the "
                                       "spheres)",
                                       shown(case_dir), failed_checks(mesh)));
    if (!meshed)
        throw InvalidInput(fmt::format("CASE {}: log.checkMesh has no \"Total volume\"; allowed: "
                                       "a case run by its Allrun",
                                       shown(case_dir)));
    const double mesh_void = *meshed / volume;
    const double gradient = rho * *log.pressure_gradient; // Pa/m
    const double superficial = held * mesh_void;          // m/s, the mesh's flow
    const double force = gradient * volume / spheres;     // N, on each sphere
    const double k = force / (6.0 * std::numbers::pi * mu * radius * superficial);
    nlohmann::ordered_json references;
    if (const auto zh = zick_homsy_simple_cubic(phi)) {
        references["zick_homsy_solid_fraction"] = zh->first;
        references["zick_homsy_simple_cubic_K"] = zh->second;
        references["K_over_zick_homsy"] = k / zh->second;
    }
    const double vdh = van_der_hoef_drag(phi);
    references["van_der_hoef_random_F"] = vdh;
    references["F_over_van_der_hoef"] = (1.0 - phi) * k / vdh;

    Report report;
    const double reynolds = rho * superficial * 2.0 * radius / mu;
    if (mesh.failed_checks > 0)
        report.warnings.push_back(fmt::format("{}: {}", shown(case_dir), failed_checks(mesh)));
    if (reynolds > stokes_reynolds)
        report.warnings.push_back(stokes_warning(case_dir, reynolds));
    nlohmann::ordered_json out;
    out["case"] = case_dir.string();
    out["flow"] = {{"superficial_velocity_m_s", superficial},
                   {"interstitial_velocity_m_s", held},
                   {"reynolds", reynolds},
                   {"fluid_density_kg_m3", rho},
                   {"viscosity_Pa_s", mu},
                   {"diameter_m", 2.0 * radius}};
    out["solver"] = solver_json(log);
    out["periodic"] = {{"pressure_gradient_Pa_m", gradient},
                       {"cell_volume_m3", volume},
                       {"spheres", std::llround(spheres)},
                       {"drag_per_sphere_N", force},
                       {"K", k},
                       {"F", (1.0 - phi) * k},
                       {"references", references}};
    out["void_fraction"] = {{"exact", 1.0 - phi}, {"mesh", mesh_void}};
    if (mesh.cells)
        out["mesh"] = {{"cells", std::llround(*mesh.cells)}, {"volume_m3", *meshed}};
    if (!converged(log))
        report.warnings.push_back(fmt::format("{}: no \"SIMPLE solution converged\" nor a steady "
                                              "pressure drop in log.simpleFoam: the gradient is "
                                              "the last iteration's",
                                              shown(case_dir)));
    if (const std::string at = non_finite_at(out); !at.empty())
        throw InvalidInput(fmt::format("CASE {}: the report's {} is not a finite number; "
                                       "allowed: a case as its Allrun ran it",
                                       shown(case_dir), at));
    report.values = out;
    return report;
}

} // namespace

/// The least-squares line through (z_k, p_k): slope \f$b = \sum (z - \bar z)(p - \bar p) /
/// \sum (z - \bar z)^2\f$ and its standard error \f$\sqrt{\sum r^2 / ((n - 2) \sum (z - \bar
/// z)^2)}\f$ (residuals r; 0 for two points).
PressureFit fit_pressure(const std::vector<double>& z, const std::vector<double>& p) {
    const std::size_t n = z.size();
    if (n < 2 || p.size() != n)
        throw InvalidInput(fmt::format("pressure planes: {} heights and {} pressures; allowed: "
                                       "at least 2 of each, as many of one as of the other",
                                       n, p.size()));
    double mz = 0.0, mp = 0.0;
    for (std::size_t k = 0; k < n; ++k) {
        mz += z[k] / static_cast<double>(n);
        mp += p[k] / static_cast<double>(n);
    }
    double szz = 0.0, szp = 0.0;
    for (std::size_t k = 0; k < n; ++k) {
        szz += (z[k] - mz) * (z[k] - mz);
        szp += (z[k] - mz) * (p[k] - mp);
    }
    if (!(szz > 0.0))
        throw InvalidInput("pressure planes: all at one height; allowed: two heights or more");
    PressureFit fit;
    fit.slope = szp / szz;
    fit.intercept = mp - fit.slope * mz;
    double rr = 0.0;
    for (std::size_t k = 0; k < n; ++k) {
        const double r = p[k] - (fit.intercept + fit.slope * z[k]);
        rr += r * r;
    }
    fit.standard_error = n > 2 ? std::sqrt(rr / (static_cast<double>(n - 2) * szz)) : 0.0;
    return fit;
}

void check_cfd_case(const std::filesystem::path& case_dir) {
    check_path("CASE", case_dir);
    std::error_code error;
    if (!fs::is_directory(case_dir, error))
        throw InvalidInput(fmt::format("CASE {} is not a directory; allowed: the directory of a "
                                       "case written by packbed export --format openfoam",
                                       shown(case_dir)));
    record_input("CASE", case_dir); // read whole: no output may be it or hold it
}

Report cfd_report(const std::filesystem::path& case_dir) {
    check_cfd_case(case_dir);
    nlohmann::json json;
    {
        const std::string text =
            read_small_file("CASE", case_dir / "packbed.json", limits::max_small_file);
        json = parse_json(text).value; // discarded when not JSON or nested too deep
        if (json.is_discarded() || !json.is_object())
            throw InvalidInput(
                fmt::format("CASE {}: packbed.json is not a JSON object", shown(case_dir)));
    }
    using ptr = nlohmann::json::json_pointer;
    const ptr flow("/openfoam/flow");
    if (json.contains(flow / "periodic"))
        return periodic_report(case_dir, json);
    const double rho = recorded(json, flow / "fluid_density", case_dir);
    const double mu = recorded(json, flow / "viscosity", case_dir);
    const double u = recorded(json, flow / "velocity", case_dir);
    const double scale = recorded(json, flow / "metres_per_unit", case_dir);
    const double band_void = recorded(json, flow / "band_void_fraction", case_dir);
    const double diameter = recorded(json, ptr("/diameter"), case_dir) * scale; // m
    const ptr planes_at = flow / "pressure_planes";
    if (!json.contains(planes_at) || !json.at(planes_at).is_array() ||
        json.at(planes_at).size() < 2)
        throw InvalidInput(fmt::format("CASE {}: packbed.json's openfoam.flow.pressure_planes is "
                                       "not a list of heights; allowed: 2 heights or more, as "
                                       "packbed export --format openfoam writes",
                                       shown(case_dir)));
    const nlohmann::json& planes_json = json.at(planes_at);

    Report report;
    nlohmann::ordered_json out;
    out["case"] = case_dir.string();
    // The planes: the area-averaged kinematic pressure (m^2/s^2) times rho, in Pa.
    std::vector<double> z, p;
    nlohmann::ordered_json planes = nlohmann::ordered_json::array();
    std::optional<double> plane_time; // every plane's row must be of one iteration
    for (std::size_t k = 0; k < planes_json.size(); ++k) {
        const std::string name = fmt::format("p{}", k);
        const auto row = last_row(case_dir, name);
        const double time = column(row, "Time", case_dir, name);
        if (plane_time && time != *plane_time)
            throw InvalidInput(fmt::format("CASE {}: the last row of postProcessing/{} is of "
                                           "iteration {}, p0's of {}; allowed: planes' tables "
                                           "that end at one iteration, as a run writes them",
                                           shown(case_dir), name, time, *plane_time));
        plane_time = time;
        const double zk = recorded(json, flow / "pressure_planes" / k, case_dir);
        const double pk = rho * column(row, "areaAverage(p)", case_dir, name);
        z.push_back(zk);
        p.push_back(pk);
        planes.push_back({{"z_m", zk},
                          {"pressure_Pa", pk},
                          {"fluid_area_m2", column(row, "Area", case_dir, name)}});
    }
    const PressureFit fit = fit_pressure(z, p);
    const double gradient = -fit.slope;

    const double inlet = column(last_row(case_dir, "inletFlux"), "sum(phi)", case_dir, "inletFlux");
    const double outlet =
        column(last_row(case_dir, "outletFlux"), "sum(phi)", case_dir, "outletFlux");
    if (!(inlet != 0.0))
        throw InvalidInput(fmt::format("CASE {}: postProcessing/inletFlux: the inlet's flux "
                                       "sum(phi) is 0; allowed: a case whose flow ran (a flux "
                                       "through the inlet)",
                                       shown(case_dir)));
    const SolverLog log = read_solver_log(case_dir);

    // The correlations at the bed's own void fraction between the planes; the particle
    // density does not enter a pressure drop (FluidAndParticles wants one above the fluid's:
    // the densest allowed).
    FluidAndParticles fluid;
    fluid.diameter = diameter;
    fluid.fluid_density = rho;
    fluid.viscosity = mu;
    fluid.particle_density = limits::max_density_kg_m3;
    nlohmann::ordered_json correlations;
    try { // the correlations' ranges, for values that come from the case's packbed.json
        const double ergun = ergun_pressure_gradient(band_void, u, fluid);
        correlations = {{"ergun_Pa_m", ergun}, {"cfd_over_ergun", gradient / ergun}};
        const ptr aspect = flow / "aspect_ratio";
        if (json.contains(aspect) && json.at(aspect).is_number()) {
            const double a = recorded(json, aspect, case_dir);
            const CorrelationValue es =
                eisfeld_schnitzlein_pressure_gradient(band_void, u, a, fluid);
            correlations["aspect_ratio"] = a;
            correlations["eisfeld_schnitzlein_Pa_m"] = es.value;
            correlations["cfd_over_eisfeld_schnitzlein"] = gradient / es.value;
            if (!es.warning.empty())
                report.warnings.push_back(es.warning);
        } else {
            correlations["eisfeld_schnitzlein"] = "no wall (a periodic cell): Ergun only";
            // A bed periodic across: van der Hoef et al.'s random arrays. The gradient
            // balances the whole force on the spheres, phi / (pi d^3 / 6) of them a unit of
            // volume: F = G (pi d^3 / 6) / phi on each, K = F / (3 pi mu d U), and (1 - phi) K
            // is their F.
            const double phi = 1.0 - band_void;
            if (phi > 0.0 && phi < 1.0) {
                const double k = gradient * std::numbers::pi * diameter * diameter * diameter /
                                 6.0 / phi / (3.0 * std::numbers::pi * mu * diameter * u);
                const double vdh = van_der_hoef_drag(phi);
                correlations["K"] = k;
                correlations["F"] = (1.0 - phi) * k;
                correlations["van_der_hoef_random_F"] = vdh;
                correlations["F_over_van_der_hoef"] = (1.0 - phi) * k / vdh;
                const double re = rho * u * diameter / mu;
                if (re > stokes_reynolds)
                    report.warnings.push_back(stokes_warning(case_dir, re));
            }
        }
        // The band of published correlations (pressure_drop_band).
        const double a = correlations.contains("aspect_ratio")
                             ? correlations["aspect_ratio"].get<double>()
                             : std::numeric_limits<double>::infinity();
        nlohmann::ordered_json band = nlohmann::ordered_json::array();
        double low = std::numeric_limits<double>::infinity(), high = 0.0;
        for (const PressureDropBandValue& b : pressure_drop_band(band_void, u, a, fluid)) {
            const CorrelationValue& v = b.gradient;
            band.push_back(
                {{"name", b.correlation->name},
                 {"label", b.correlation->label},
                 {"wall", b.correlation->wall},
                 {"Pa_m", v.value},
                 {"cfd_over", gradient / v.value},
                 {"outside_range", v.warning.empty() ? nlohmann::ordered_json()
                                                     : nlohmann::ordered_json(v.warning)}});
            low = std::min(low, v.value);
            high = std::max(high, v.value);
        }
        correlations["band"] = band;
        correlations["band_Pa_m"] = {low, high};
        correlations["cfd_in_band"] = gradient >= low && gradient <= high;
    } catch (const InvalidInput& e) {
        throw InvalidInput(
            fmt::format("CASE {}: packbed.json's flow: {}", shown(case_dir), e.what()));
    }

    out["flow"] = {{"superficial_velocity_m_s", u},
                   {"reynolds", rho * u * diameter / mu},
                   {"fluid_density_kg_m3", rho},
                   {"viscosity_Pa_s", mu},
                   {"diameter_m", diameter}};
    out["solver"] = solver_json(log);
    out["fluxes_m3_s"] = {{"inlet", inlet},
                          {"outlet", outlet},
                          {"imbalance", std::abs(inlet + outlet) / std::abs(inlet)}};
    out["planes"] = planes;
    out["pressure_gradient_Pa_m"] = {{"cfd", gradient},
                                     {"standard_error", fit.standard_error},
                                     {"from_m", z.front()},
                                     {"to_m", z.back()},
                                     {"fit_intercept_Pa", fit.intercept}};
    out["correlations"] = correlations;
    // The void fractions: the bed's between the planes (what the correlations use), the
    // container's before and after the contact treatment, and the mesh's (checkMesh's volume).
    nlohmann::ordered_json voids = {{"band", band_void}};
    const MeshLog mesh = read_mesh_log(case_dir);
    const ptr untouched("/volumes/untouched_void_fraction"),
        treated("/volumes/treated_void_fraction");
    if (json.contains(untouched) && json.contains(treated)) {
        voids["container_untouched"] = recorded(json, untouched, case_dir);
        voids["container_treated"] = recorded(json, treated, case_dir);
        if (mesh.volume && json.contains(ptr("/volumes/container"))) {
            const double container =
                recorded(json, ptr("/volumes/container"), case_dir) * scale * scale * scale;
            voids["mesh"] = *mesh.volume / container;
        }
    }
    out["void_fraction"] = voids;
    if (mesh.volume && mesh.cells)
        out["mesh"] = {{"cells", std::llround(*mesh.cells)}, {"volume_m3", *mesh.volume}};
    if (mesh.failed_checks > 0)
        report.warnings.push_back(fmt::format("{}: {}", shown(case_dir), failed_checks(mesh)));
    if (!converged(log))
        report.warnings.push_back(fmt::format("{}: no \"SIMPLE solution converged\" nor a steady "
                                              "pressure drop in log.simpleFoam: the pressures "
                                              "are those of the last iteration written",
                                              shown(case_dir)));
    // Every value finite, or the case refused: finite numbers read from it can still overflow
    // in a product (a pressure of -1e308 times the density).
    if (const std::string at = non_finite_at(out); !at.empty())
        throw InvalidInput(fmt::format("CASE {}: the report's {} is not a finite number: the "
                                       "case's pressures, fluxes or packbed.json values are out "
                                       "of range; allowed: a case as its Allrun ran it",
                                       shown(case_dir), at));
    report.values = out;
    return report;
}

std::string stage_cfd_report(OutputDirectory& out, const Report& report) {
    const nlohmann::json& v = report.values;
    if (v.contains("periodic")) { // no planes to draw
        out.stage("cfd_report.json", json_file_text(v, "cfd_report.json"));
        return {};
    }
    std::string table = "z_m,pressure_Pa,fluid_area_m2\n";
    for (const auto& plane : v["planes"])
        table +=
            fmt::format("{},{},{}\n", plane["z_m"].get<double>(),
                        plane["pressure_Pa"].get<double>(), plane["fluid_area_m2"].get<double>());
    out.stage("pressure.csv", table);
    out.stage("cfd_report.json", json_file_text(v, "cfd_report.json"));

    // The plot: the planes' pressures, the fitted line and the correlations' lines through
    // the planes' mean, against the height in mm.
    const auto& g = v["pressure_gradient_Pa_m"];
    const auto& c = v["correlations"];
    double mz = 0.0, mp = 0.0;
    std::string points = "$planes << EOD\n";
    const double n = static_cast<double>(v["planes"].size());
    for (const auto& plane : v["planes"]) {
        const double z = plane["z_m"].get<double>(), p = plane["pressure_Pa"].get<double>();
        points += fmt::format("{} {}\n", 1e3 * z, p);
        mz += 1e3 * z / n;
        mp += p / n;
    }
    points += "EOD\n";
    // A line of gradient G (Pa/m) through the mean point, z in mm.
    const auto line = [&](double gradient) {
        return fmt::format("({:.17g} - {:.17g} * (x - {:.17g}) * 1e-3)", mp, gradient, mz);
    };
    std::string curves = fmt::format(
        "$planes using 1:2 with points pt 7 ps 1.2 lc rgb 'black' title 'CFD, planes', {} with "
        "lines lw 2 lc rgb 'black' title 'CFD fit: {:.4g} Pa/m', {} with lines dt 2 lw 2 title "
        "'Ergun: {:.4g} Pa/m'",
        line(g["cfd"].get<double>()), g["cfd"].get<double>(), line(c["ergun_Pa_m"].get<double>()),
        c["ergun_Pa_m"].get<double>());
    if (c.contains("eisfeld_schnitzlein_Pa_m"))
        curves += fmt::format(", {} with lines dt 4 lw 2 title 'Eisfeld & Schnitzlein: {:.4g} "
                              "Pa/m' noenhanced",
                              line(c["eisfeld_schnitzlein_Pa_m"].get<double>()),
                              c["eisfeld_schnitzlein_Pa_m"].get<double>());
    std::string script = points;
    for (const auto& [extension, terminal] : plot_terminals)
        script += fmt::format(
            "{}\nset output 'pressure.{}'\nset xlabel 'height z (mm)'\nset ylabel 'pressure "
            "(Pa)'\nset key top right\nset title 'Pressure across the bed, Re_p = {:.3g}, void "
            "fraction {:.4f}'\nplot [{:.17g}:{:.17g}] {}\n",
            terminal, extension, v["flow"]["reynolds"].get<double>(),
            v["void_fraction"]["band"].get<double>(), 1e3 * g["from_m"].get<double>(),
            1e3 * g["to_m"].get<double>(), curves);
    return draw_plots(out, {"pressure"}, {script});
}

} // namespace packbed

namespace packbed {

GridConvergence grid_convergence(const std::array<double, 3>& h, const std::array<double, 3>& phi) {
    const auto [h1, h2, h3] = h;
    const auto [f1, f2, f3] = phi;
    if (!(h1 > 0.0 && h2 > h1 && h3 > h2))
        throw InvalidInput(fmt::format("mesh series: cell sizes {}, {}, {} are not allowed; "
                                       "allowed: three sizes > 0, finest first, each larger",
                                       h1, h2, h3));
    const double e21 = f2 - f1, e32 = f3 - f2;
    if (!(e21 != 0.0 && e32 != 0.0 && std::isfinite(e32 / e21)))
        throw InvalidInput(fmt::format("mesh series: the values {}, {}, {} have two equal "
                                       "neighbours; allowed: values that change from level to "
                                       "level",
                                       f1, f2, f3));
    const double r21 = h2 / h1, r32 = h3 / h2;
    const double s = e32 / e21 > 0.0 ? 1.0 : -1.0;
    // Celik et al.'s eqs. (3a)-(3c) by fixed-point iteration; with r21 = r32, q = 0 and the
    // first step is exact.
    double p = 2.0;
    for (int k = 0; k < 500; ++k) {
        const double q = std::log((std::pow(r21, p) - s) / (std::pow(r32, p) - s));
        const double next = std::abs(std::log(std::abs(e32 / e21)) + q) / std::log(r21);
        if (!std::isfinite(next))
            break;
        const bool settled = std::abs(next - p) <= 1e-12 * std::max(1.0, p);
        p = next;
        if (settled)
            break;
    }
    if (!(std::isfinite(p) && p > 0.0 && std::pow(r21, p) > 1.0))
        throw InvalidInput(fmt::format("mesh series: no apparent order from the values {}, {}, "
                                       "{}; allowed: a series in its asymptotic range",
                                       f1, f2, f3));
    GridConvergence g;
    g.order = p;
    const double rp = std::pow(r21, p);
    g.extrapolated = (rp * f1 - f2) / (rp - 1.0);
    g.approximate_error = std::abs((f1 - f2) / f1);
    g.extrapolated_error = std::abs((g.extrapolated - f1) / g.extrapolated);
    g.gci_fine = 1.25 * g.approximate_error / (rp - 1.0);
    g.oscillating = s < 0.0;
    return g;
}

Report cfd_series(const std::vector<std::filesystem::path>& cases) {
    if (cases.size() < 3)
        throw InvalidInput(fmt::format("{} case(s) given for a mesh series; allowed: 3 or more "
                                       "cases of one bed, meshed at different resolutions",
                                       cases.size()));
    struct Level {
        std::filesystem::path path;
        nlohmann::json report;
        double cells, h, value;
    };
    std::vector<Level> levels;
    std::optional<bool> periodic;
    for (const std::filesystem::path& c : cases) {
        const Report r = cfd_report(c);
        const nlohmann::json& v = r.values;
        const bool is_periodic = v.contains("periodic");
        if (periodic && *periodic != is_periodic)
            throw InvalidInput(fmt::format("CASE {}: a {} case among {} ones; allowed: cases of "
                                           "one kind (export --flow)",
                                           shown(c), is_periodic ? "periodic" : "inlet",
                                           *periodic ? "periodic" : "inlet"));
        periodic = is_periodic;
        if (!v.contains("mesh"))
            throw InvalidInput(fmt::format("CASE {}: log.checkMesh has no cells or volume; "
                                           "allowed: a case run by its Allrun",
                                           shown(c)));
        // One bed, one flow: the exact void fraction, the spheres' diameter and the velocity
        // the case holds (a periodic cell's mean in the fluid, else the superficial one) of
        // the first case given; the meshes' own void fractions, and so their superficial
        // velocities, differ.
        const auto signature = [](const nlohmann::json& values) {
            const bool cell = values.contains("periodic");
            return std::array<double, 3>{
                cell ? values["void_fraction"]["exact"].get<double>()
                     : values["void_fraction"]["band"].get<double>(),
                values["flow"]["diameter_m"].get<double>(),
                cell ? values["flow"]["interstitial_velocity_m_s"].get<double>()
                     : values["flow"]["superficial_velocity_m_s"].get<double>()};
        };
        if (!levels.empty()) {
            const auto a = signature(v), b = signature(levels.front().report);
            for (std::size_t k = 0; k < 3; ++k)
                if (std::abs(a[k] - b[k]) > 1e-9 * std::max(std::abs(a[k]), std::abs(b[k])))
                    throw InvalidInput(fmt::format(
                        "CASE {}: void fraction {:.6g}, diameter {:.6g} m, velocity {:.6g} m/s "
                        "where CASE {} has {:.6g}, {:.6g} m, {:.6g} m/s; allowed: cases of one "
                        "bed and one flow, meshed at different resolutions",
                        shown(c), a[0], a[1], a[2], shown(levels.front().path), b[0], b[1], b[2]));
        }
        const double cells = v["mesh"]["cells"].get<double>();
        const double volume = v["mesh"]["volume_m3"].get<double>();
        const double d = v["flow"]["diameter_m"].get<double>();
        const double value = is_periodic ? v["periodic"]["K"].get<double>()
                                         : v["pressure_gradient_Pa_m"]["cfd"].get<double>();
        levels.push_back({c, v, cells, std::cbrt(volume / cells) / d, value});
    }
    std::sort(levels.begin(), levels.end(),
              [](const Level& a, const Level& b) { return a.cells < b.cells; });
    for (std::size_t k = 1; k < levels.size(); ++k) {
        if (levels[k].cells == levels[k - 1].cells)
            throw InvalidInput(fmt::format("CASE {} and CASE {} have the same {} cells; allowed: "
                                           "meshes of different resolutions",
                                           shown(levels[k - 1].path), shown(levels[k].path),
                                           levels[k].cells));
        if (!(levels[k].h < levels[k - 1].h))
            throw InvalidInput(fmt::format(
                "CASE {} has more cells than CASE {} ({} against {}) but no smaller ones (h / d "
                "{:.4g} against {:.4g}); allowed: meshes of one bed, finer with more cells",
                shown(levels[k].path), shown(levels[k - 1].path), levels[k].cells,
                levels[k - 1].cells, levels[k].h, levels[k - 1].h));
    }
    const std::string quantity = *periodic ? "K" : "pressure_gradient_Pa_m";
    std::optional<double> reference;
    if (*periodic) {
        const nlohmann::json& r = levels.back().report["periodic"]["references"];
        if (r.contains("zick_homsy_simple_cubic_K"))
            reference = r["zick_homsy_simple_cubic_K"].get<double>();
    }
    nlohmann::ordered_json rows = nlohmann::ordered_json::array();
    for (const Level& l : levels) {
        nlohmann::ordered_json row = {
            {"case", l.path.string()}, {"cells", std::llround(l.cells)},
            {"h_over_d", l.h},         {"mesh_void_fraction", l.report["void_fraction"]["mesh"]},
            {quantity, l.value},       {"converged", l.report["solver"]["converged"]}};
        if (reference)
            row["over_reference"] = l.value / *reference;
        rows.push_back(row);
    }
    const std::size_t n = levels.size();
    const GridConvergence g =
        grid_convergence({levels[n - 1].h, levels[n - 2].h, levels[n - 3].h},
                         {levels[n - 1].value, levels[n - 2].value, levels[n - 3].value});
    nlohmann::ordered_json celik = {{"order", g.order},
                                    {"extrapolated", g.extrapolated},
                                    {"approximate_error", g.approximate_error},
                                    {"extrapolated_error", g.extrapolated_error},
                                    {"gci_fine", g.gci_fine},
                                    {"oscillating", g.oscillating},
                                    // the cases' schemes are second order (Gauss linear,
                                    // linearUpwind): an apparent order far from 2 says the
                                    // series is not in its asymptotic range
                                    {"formal_order", 2},
                                    {"near_formal_order", g.order >= 1.0 && g.order <= 3.0}};
    if (reference) {
        celik["reference"] = *reference;
        celik["extrapolated_over_reference"] = g.extrapolated / *reference;
    }
    Report report;
    if (!(g.order >= 1.0 && g.order <= 3.0))
        report.warnings.push_back(fmt::format(
            "the apparent order {:.3g} is far from the schemes' 2: the three finest levels are "
            "not in the asymptotic range, and the extrapolation and the GCI are not reliable",
            g.order));
    nlohmann::ordered_json out;
    out["quantity"] = quantity;
    out["levels"] = rows;
    out["celik"] = celik;
    if (const std::string at = non_finite_at(out); !at.empty())
        throw InvalidInput(fmt::format("mesh series: the report's {} is not a finite number; "
                                       "allowed: cases as their Allrun ran them",
                                       at));
    report.values = out;
    return report;
}

void stage_cfd_series(OutputDirectory& out, const Report& report) {
    const nlohmann::json& v = report.values;
    // A path as one CSV field (RFC 4180): quoted, its quotes doubled, where it holds a comma
    // or a quote.
    const auto csv_field = [](const std::string& text) {
        if (text.find_first_of(",\"") == std::string::npos)
            return text;
        std::string quoted = "\"";
        for (const char c : text)
            quoted += c == '"' ? std::string("\"\"") : std::string(1, c);
        return quoted + "\"";
    };
    const std::string quantity = v["quantity"].get<std::string>();
    std::string table = fmt::format("case,cells,h_over_d,mesh_void_fraction,{}\n", quantity);
    for (const auto& row : v["levels"])
        table += fmt::format("{},{},{},{},{}\n", csv_field(row["case"].get<std::string>()),
                             row["cells"].get<long long>(), row["h_over_d"].get<double>(),
                             row["mesh_void_fraction"].get<double>(), row[quantity].get<double>());
    out.stage("series.csv", table);
    out.stage("series.json", json_file_text(v, "series.json"));
}

} // namespace packbed
