// generate --engine lammps, --write-only and import-lammps (pipeline.hpp, docs/lammps.md).
#include <chrono>
#include <cmath>
#include <fstream>
#include <functional>

#include <fmt/format.h>
#include <fmt/ranges.h>

#include "base/json_input.hpp"
#include "child.hpp"
#include "packbed/error.hpp"
#include "packbed/files.hpp"
#include "packbed/json_text.hpp"
#include "packbed/limits.hpp"
#include "packbed/pipeline.hpp"
#include "packbed/text.hpp"
#include "packbed/version.hpp"

namespace packbed {

namespace {

namespace fs = std::filesystem;

/// The Slurm script of a job folder (job.sh). LAMMPS 20220106 is the version the input is
/// tested with (docs/lammps.md); FIRE 2.0's keywords are in LAMMPS since 2020.
std::string slurm_script() {
    return R"(#!/bin/bash
#SBATCH --job-name=packbed
#SBATCH --ntasks=64
#SBATCH --time=04:00:00
# LAMMPS with the GRANULAR package; tested with 20220106 (Debian 12), newer ones should run it
module load lammps
srun lmp -in in.packbed -log log.lammps
)";
}

/// `text` with every line indented by 4 spaces (a Markdown code block).
std::string indented(const std::string& text) {
    std::string out;
    for (std::size_t start = 0; start < text.size();) {
        std::size_t end = text.find('\n', start);
        if (end == std::string::npos)
            end = text.size();
        out += "    " + text.substr(start, end - start) + "\n";
        start = end + 1;
    }
    return out;
}

/// The README of a job folder: how to run it here or on a cluster, and bring the bed back.
std::string job_readme(const std::string& command, const LammpsJob& job,
                       const PreparedGeneration& prepared) {
    const SoftSphereParameters& p = prepared.params;
    return fmt::format(
        R"(# A packbed bed for LAMMPS to relax

Written by packbed {version} (`packbed generate --engine lammps`): {n} spheres, seed {seed},
the generation stage of Salvat et al. (2005) in `start.data` ({types} atom type(s), one per
sphere size), the fire solver's energy and gravity schedule in `in.packbed` (docs/lammps.md in
packbed's sources says how each term maps onto LAMMPS). Lengths are in units of Dp.

## Run it

Here, on this folder's machine:

    {command} -in in.packbed

On a cluster with Slurm, with the folder copied there: `sbatch job.sh`, this folder's script
(change its tasks, time and module line to the cluster's):

{slurm}
LAMMPS writes `log.lammps` and, at the end, the relaxed bed `bed.dump`. A run that fails says
why in the log, on a line starting with `ERROR` or `PACKBED FAILED`.

## Bring it back

    packbed import-lammps THIS-FOLDER --out bed

reads `bed.dump` and `log.lammps`, checks the bed with packbed's own code (every sphere there,
the largest overlaps of pairs, walls and floor below {tol} Dp) and writes what `packbed
generate` writes: particles.csv, particles.vtu, summary.json and the analysis. `job.json` holds
the options it needs; the bed's lengths come back in the unit of --diameter.
)",
        fmt::arg("slurm", indented(slurm_script())), fmt::arg("version", version),
        fmt::arg("n", p.particles), fmt::arg("seed", p.seed), fmt::arg("types", job.types),
        fmt::arg("command", command), fmt::arg("tol", p.tolerance * p.smallest_size()));
}

/// job.json: what import_lammps needs to rebuild the run's parameters: summary.json's
/// parameters (soft_sphere_parameters_json, the schedule's values resolved) and the request's
/// container, sizes and band.
nlohmann::json job_json(const GenerateRequest& r, const std::vector<std::string>& command,
                        LammpsPairStyle style) {
    nlohmann::json request = soft_sphere_parameters_json(r.params);
    request.erase("friction"); // the engine runs frictionless beds only
    request.erase("wall_friction");
    request["aspect_ratio"] = r.aspect_ratio; // the request's shorthand, as given
    request["container"] = r.container;
    request["sizes"] = r.sizes;
    request["fractions"] = to_string(r.fractions);
    request["band_clearance"] = r.band_clearance;
    return {{"packbed", std::string(version)},
            {"engine", "lammps"},
            {"command", command},
            {"pair_style", to_string(style)},
            {"request", std::move(request)}};
}

/// The words that run the job in its folder.
std::vector<std::string> lammps_command(const LammpsLauncher& launcher) {
    std::vector<std::string> words = lammps_launch(launcher);
    for (const char* w : {"-in", "in.packbed", "-log", "log.lammps"})
        words.emplace_back(w);
    return words;
}

/// Progress from LAMMPS's log as it grows: its thermo lines (step pe fmax pair wall mc g,
/// every 1 000 steps), in the stage the last PACKBED line began.
class LogProgress {
public:
    LogProgress(fs::path log, double ck)
        : m_log(std::move(log))
        , m_ck(ck) {}

    /// Read what the log gained and report each thermo line in it.
    void poll(const std::function<void(const Progress&)>& report) {
        if (!m_reader.is_open())
            m_reader.open(m_log, std::ios::binary);
        if (!m_reader.is_open())
            return;
        m_reader.clear(); // past the end of what was there last time
        char buffer[4096];
        while (m_reader.read(buffer, sizeof buffer) || m_reader.gcount() > 0)
            m_pending.append(buffer, static_cast<std::size_t>(m_reader.gcount()));
        for (std::size_t end; (end = m_pending.find('\n')) != std::string::npos;) {
            line(std::string_view(m_pending).substr(0, end), report);
            m_pending.erase(0, end + 1);
        }
    }

private:
    void line(std::string_view text, const std::function<void(const Progress&)>& report) {
        const std::vector<std::string_view> w = split_spaces(text);
        if (w.size() >= 3 && w[0] == "PACKBED" && w[1] == "stage")
            m_stage = w[2] == "initial" ? "intermediate" : "final";
        if (w.size() != 7)
            return;
        double v[7];
        for (std::size_t k = 0; k < 7; ++k) {
            const auto value = parse_finite(w[k]);
            if (!value)
                return;
            v[k] = *value;
        }
        if (!(v[0] >= 0.0 && v[0] <= 9007199254740992.0)) // a step, to convert without UB
            return;
        report(Progress{m_stage, static_cast<std::uint64_t>(v[0]), v[6] * m_ck, std::max(0.0, v[3]),
                        std::max(0.0, v[4]), v[5]});
    }

    fs::path m_log;
    double m_ck;
    std::ifstream m_reader;
    std::string m_pending;
    std::string m_stage = "initial";
};

/// The bed LAMMPS relaxed, with its summary: generate's, with the engine recorded.
GeneratedBed lammps_bed(const PreparedGeneration& prepared, SoftSphereResult result,
                        const nlohmann::json& engine) {
    GeneratedBed bed;
    bed.result = std::move(result);
    bed.summary = generation_summary(prepared, bed.result, 1);
    bed.summary["parameters"].erase("threads");
    bed.summary["parameters"].erase("layer_height");
    bed.summary["parameters"].erase("update");
    bed.summary["engine"] = engine;
    return bed;
}

} // namespace

LammpsPairStyle probe_lammps(const LammpsLauncher& launcher, OutputDirectory& out) {
    const fs::path help = out.reserve("lmp-help.txt");
    const int status = run_program({launcher.lmp, "-h"}, help.parent_path(), help);
    std::string text;
    {
        std::ifstream in(help, std::ios::binary);
        text.assign(std::istreambuf_iterator<char>(in), {});
    }
    out.discard("lmp-help.txt");
    if (status == 127) // a name is looked for on the PATH, a path is not
        throw InvalidInput(
            fmt::format("--lmp {}: no such program{}; allowed: an installed LAMMPS (Debian: "
                        "scripts/install-deps.sh --lammps installs lammps and openmpi-bin)",
                        printable(launcher.lmp),
                        launcher.lmp.find('/') == std::string::npos ? " on the PATH" : ""));
    if (status != 0 ||
        text.find("Large-scale Atomic/Molecular Massively Parallel") == std::string::npos)
        throw InvalidInput(fmt::format("--lmp {}: `{} -h` did not answer as LAMMPS does (exit "
                                       "status {}); allowed: a LAMMPS executable",
                                       printable(launcher.lmp), printable(launcher.lmp), status));
    // `lmp -h` lists the styles in columns: a name between spaces or at a line's ends
    const auto has = [&](std::string_view style) {
        for (std::size_t at = text.find(style); at != std::string::npos;
             at = text.find(style, at + 1)) {
            const char before = at == 0 ? ' ' : text[at - 1];
            const std::size_t end = at + style.size();
            const char after = end < text.size() ? text[end] : ' ';
            if ((before == ' ' || before == '\n') && (after == ' ' || after == '\n'))
                return true;
        }
        return false;
    };
    if (has("gran/hooke"))
        return LammpsPairStyle::gran_hooke;
    if (has("harmonic/cut"))
        return LammpsPairStyle::harmonic_cut;
    throw InvalidInput(fmt::format("--lmp {}: this LAMMPS has neither pair_style gran/hooke "
                                   "(GRANULAR package) nor harmonic/cut; allowed: a LAMMPS "
                                   "with either",
                                   printable(launcher.lmp)));
}

std::vector<std::string> stage_lammps_job(OutputDirectory& out, const std::string& folder,
                                          const PreparedGeneration& prepared,
                                          const LammpsLauncher& launcher, LammpsPairStyle style) {
    const std::vector<std::string> command = lammps_command(launcher);
    const std::string launch = shell_line(lammps_launch(launcher));
    const LammpsJob job = lammps_job(prepared.params, style, launch);
    const std::string at = folder.empty() ? "" : folder + "/";
    out.stage(at + std::string(lammps_files::data), job.data);
    out.stage(at + std::string(lammps_files::input), job.input);
    out.stage(at + std::string(lammps_files::readme), job_readme(launch, job, prepared));
    out.stage(at + std::string(lammps_files::slurm), slurm_script());
    out.stage(at + std::string(lammps_files::job),
              json_file_text(job_json(prepared.request, command, style), "job.json"));
    return command;
}

GeneratedBed run_lammps_generation(const PreparedGeneration& prepared,
                                   const LammpsLauncher& launcher, const RunControl& control,
                                   OutputDirectory& out) {
    const auto t0 = std::chrono::steady_clock::now();
    const LammpsPairStyle style = probe_lammps(launcher, out);
    const std::vector<std::string> command =
        stage_lammps_job(out, "lammps", prepared, launcher, style);
    const fs::path log = out.reserve("lammps/" + std::string(lammps_files::log));
    const fs::path folder = log.parent_path();
    const fs::path screen = out.reserve("lammps/" + std::string(lammps_files::screen));
    out.reserve("lammps/" + std::string(lammps_files::dump));

    LogProgress progress(log, prepared.params.ck);
    const auto keep_going = [&] {
        if (control.should_stop && control.should_stop())
            return false;
        if (control.on_progress)
            progress.poll(control.on_progress);
        return true;
    };
    const int status = run_program(command, folder, screen, keep_going);
    if (control.should_stop && control.should_stop())
        throw Cancelled();
    if (status == 127)
        throw InvalidInput(
            fmt::format("{}: no such program{}; allowed: an installed "
                        "launcher (Debian: openmpi-bin gives mpirun)",
                        printable(command.front()),
                        command.front().find('/') == std::string::npos ? " on the PATH" : ""));
    SoftSphereResult result;
    try {
        result = lammps_result(prepared.params, folder);
    } catch (const ConvergenceError& e) {
        throw ConvergenceError(fmt::format("{} (LAMMPS's exit status {}; command: {})", e.what(),
                                           status, printable(shell_line(command))));
    }
    if (status != 0)
        throw ConvergenceError(fmt::format("LAMMPS wrote the bed but ended with exit status {} "
                                           "(command: {})",
                                           status, printable(shell_line(command))));
    result.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    return lammps_bed(prepared, std::move(result),
                      {{"name", "lammps"},
                       {"command", command},
                       {"ranks", launcher.mpi_command.empty() ? launcher.ranks : 0},
                       {"pair_style", to_string(style)},
                       {"files", "lammps/: the job (start.data, in.packbed, ...) and LAMMPS's "
                                 "log.lammps, screen.txt, bed.dump"}});
}

LammpsJobFile read_lammps_job(std::string_view text, std::string_view folder) {
    const ParsedJson parsed = parse_json(text);
    if (!parsed.error.empty())
        throw InvalidInput(fmt::format("FOLDER {}: {} is not JSON ({}); allowed: the job.json "
                                       "packbed generate --engine lammps --write-only wrote",
                                       printable(folder), lammps_files::job, parsed.error));
    const nlohmann::json& json = parsed.value;
    const auto bad = [&](std::string_view what) {
        return InvalidInput(fmt::format("FOLDER {}: {} in {} is missing or not allowed; "
                                        "allowed: the job.json packbed generate --engine lammps "
                                        "--write-only wrote",
                                        printable(folder), what, lammps_files::job));
    };
    if (!json.is_object() || !json.contains("request") || !json["request"].is_object())
        throw bad("the request");
    const nlohmann::json& r = json["request"];
    LammpsJobFile job;
    GenerateRequest& request = job.request;
    SoftSphereParameters& p = request.params;
    const auto number = [&](const char* key) {
        if (!r.contains(key) || !r[key].is_number())
            throw bad(key);
        return r[key].get<double>();
    };
    const auto whole = [&](const char* key) {
        if (!r.contains(key) || !r[key].is_number_unsigned())
            throw bad(key);
        return r[key].get<std::uint64_t>();
    };
    const auto word = [&](const char* key) {
        if (!r.contains(key) || !r[key].is_string())
            throw bad(key);
        return r[key].get<std::string>();
    };
    request.aspect_ratio = number("aspect_ratio");
    p.particles = whole("particles");
    p.seed = whole("seed");
    p.diameter = number("diameter");
    p.e0 = number("e0");
    p.ck = number("ck");
    p.tolerance = number("tolerance");
    p.overlap_low = number("overlap_low");
    p.overlap_high = number("overlap_high");
    p.skin = number("skin");
    p.max_iterations = whole("max_iterations");
    request.container = word("container");
    request.sizes = word("sizes");
    request.band_clearance = number("band_clearance");
    const std::string fractions = word("fractions");
    const std::optional<FractionBasis> basis = fraction_bases().find(fractions);
    if (!basis)
        throw bad("fractions");
    request.fractions = *basis;
    request.engine = Engine::lammps;
    // What the summary records of the job: the words that ran it and the pair style, checked
    // (the job's own values, not copied whole: a job.json is a user's file).
    job.command = nlohmann::json::array();
    if (const auto words = json.find("command"); words != json.end()) {
        if (!words->is_array() || words->size() > 64)
            throw bad("command (a list of at most 64 words)");
        for (const nlohmann::json& w : *words) {
            if (!w.is_string() || w.get_ref<const std::string&>().size() > 4096)
                throw bad("command (a list of at most 64 words)");
            job.command.push_back(w);
        }
    }
    if (const auto given = json.find("pair_style"); given != json.end()) {
        for (const LammpsPairStyle s : {LammpsPairStyle::gran_hooke, LammpsPairStyle::harmonic_cut})
            if (given->is_string() && *given == to_string(s))
                job.pair_style = to_string(s);
        if (job.pair_style.empty())
            throw bad(fmt::format("pair_style ({} or {})", to_string(LammpsPairStyle::gran_hooke),
                                  to_string(LammpsPairStyle::harmonic_cut)));
    }
    return job;
}

ImportedLammps import_lammps(const fs::path& folder) {
    check_path("FOLDER", folder);
    std::error_code error;
    if (!fs::is_directory(folder, error))
        throw InvalidInput(fmt::format("FOLDER {} is not a directory; allowed: the folder of a job "
                                       "written by packbed generate --engine lammps --write-only",
                                       printable(folder.string())));
    record_input("FOLDER", folder); // read whole: no output may be it or hold it
    LammpsJobFile job = read_lammps_job(
        read_small_file("FOLDER", folder / lammps_files::job, limits::max_small_file),
        folder.native());
    for (const std::string_view file : {lammps_files::log, lammps_files::dump})
        if (!fs::is_regular_file(folder / file, error))
            throw InvalidInput(fmt::format("FOLDER {}: {} is missing; allowed: a job folder after "
                                           "LAMMPS ran in it (README.md there says how)",
                                           printable(folder.string()), file));
    ImportedLammps imported{prepare_generation(job.request), {}};
    imported.bed = lammps_bed(imported.prepared, lammps_result(imported.prepared.params, folder),
                              {{"name", "lammps"},
                               {"imported_from", printable(folder.string())},
                               {"command", std::move(job.command)},
                               {"pair_style", job.pair_style}});
    return imported;
}

} // namespace packbed
