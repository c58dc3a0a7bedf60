#include "packbed/checkpoint.hpp"

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <fstream>
#include <iterator>
#include <string>
#include <string_view>
#include <system_error>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "packbed/error.hpp"
#include "packbed/summary.hpp"

namespace packbed {

namespace {

using nlohmann::json;

static_assert(std::endian::native == std::endian::little,
              "checkpoint data are written as the host's doubles, little-endian");

// The first line: the format's name and number. Format 1 (commit 803e157 only) listed the
// parameters as [name, value] pairs; format 2 as an object (soft_sphere_parameters_json).
constexpr std::string_view magic = "packbed-checkpoint ";
constexpr int format = 2;

/// The parameters a checkpoint records and a resumed run must match: all but max_iterations,
/// which only bounds the run.
json parameters_json(const SoftSphereParameters& p) {
    json all = soft_sphere_parameters_json(p);
    all.erase("max_iterations");
    return all;
}

json stage_json(const StageRecord& s) {
    return {{"name", s.name},
            {"iterations", s.iterations},
            {"steps", s.steps},
            {"cg", s.cg},
            {"max_overlap_pair", s.max_overlap_pair},
            {"max_overlap_wall", s.max_overlap_wall},
            {"mass_centre_z", s.mass_centre_z},
            {"mass_centre_window", s.mass_centre_window}};
}

StageRecord stage_from_json(const json& j) {
    StageRecord s;
    s.name = j.at("name").get<std::string>();
    s.iterations = j.at("iterations").get<std::uint64_t>();
    s.steps = j.at("steps").get<std::uint32_t>();
    s.cg = j.at("cg").get<double>();
    s.max_overlap_pair = j.at("max_overlap_pair").get<double>();
    s.max_overlap_wall = j.at("max_overlap_wall").get<double>();
    s.mass_centre_z = j.at("mass_centre_z").get<double>();
    s.mass_centre_window = j.at("mass_centre_window").get<std::vector<double>>();
    return s;
}

/// FNV-1a, 64 bits.
std::uint64_t fnv1a(const std::string& bytes) {
    std::uint64_t h = 0xcbf29ce484222325ULL;
    for (const char c : bytes) {
        h ^= static_cast<unsigned char>(c);
        h *= 0x100000001b3ULL;
    }
    return h;
}

void append(std::string& bytes, double value) {
    char raw[sizeof value];
    std::memcpy(raw, &value, sizeof value);
    bytes.append(raw, sizeof value);
}

double take(const std::string& bytes, std::size_t at) {
    double value;
    std::memcpy(&value, bytes.data() + at, sizeof value);
    return value;
}

} // namespace

void write_checkpoint(const std::filesystem::path& path, const SoftSphereParameters& parameters,
                      const LayerCheckpoint& checkpoint) {
    const Packing& packing = checkpoint.packing;
    std::string data;
    data.reserve(packing.size() * 4 * sizeof(double));
    for (std::size_t i = 0; i < packing.size(); ++i) {
        append(data, packing.centers[i].x);
        append(data, packing.centers[i].y);
        append(data, packing.centers[i].z);
        append(data, packing.radii[i]);
    }
    json stages = json::array();
    for (const StageRecord& s : checkpoint.stages)
        stages.push_back(stage_json(s));
    const json header = {{"parameters", parameters_json(parameters)},
                         {"layers_done", checkpoint.layers_done},
                         {"iterations", checkpoint.iterations},
                         {"neighbor_builds", checkpoint.neighbor_builds},
                         {"top", checkpoint.top},
                         {"stages", stages},
                         {"spheres", packing.size()},
                         {"fnv1a64", fmt::format("{:016x}", fnv1a(data))}};

    std::filesystem::path temporary = path;
    temporary += ".partial";
    {
        std::ofstream out(temporary, std::ios::binary | std::ios::trunc);
        out << magic << format << '\n' << header.dump() << '\n';
        out.write(data.data(), static_cast<std::streamsize>(data.size()));
        out.close();
        if (!out)
            throw InvalidInput(
                fmt::format("--checkpoint {}: cannot be written; allowed: a file in a "
                            "writable folder with room for {} bytes",
                            path.string(), data.size()));
    }
    std::error_code error;
    std::filesystem::rename(temporary, path, error);
    if (error)
        throw InvalidInput(fmt::format("--checkpoint {}: cannot be written ({}); allowed: a "
                                       "file in a writable folder",
                                       path.string(), error.message()));
}

LayerCheckpoint read_checkpoint(const std::filesystem::path& path,
                                const SoftSphereParameters& parameters) {
    const auto refuse = [&](const std::string& what) {
        return InvalidInput(fmt::format("--checkpoint {}: {}; allowed: a checkpoint written by "
                                        "`packbed generate --checkpoint` with the same options",
                                        path.string(), what));
    };
    std::ifstream in(path, std::ios::binary);
    if (!in)
        throw refuse("cannot be read");
    std::string line;
    if (!std::getline(in, line) || !line.starts_with(magic))
        throw refuse(
            fmt::format("not a packbed checkpoint (its first line is not '{}{}')", magic, format));
    if (line != fmt::format("{}{}", magic, format))
        throw refuse(fmt::format("written in checkpoint format '{}', this packbed reads format "
                                 "{} (resume with the packbed that wrote it)",
                                 line.substr(magic.size()), format));
    std::string header_text;
    if (!std::getline(in, header_text))
        throw refuse("cut short (no header)");
    const std::string data((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());

    LayerCheckpoint checkpoint;
    std::size_t spheres = 0;
    std::string hash;
    json stored;
    try {
        const json header = json::parse(header_text);
        stored = header.at("parameters");
        checkpoint.layers_done = header.at("layers_done").get<std::uint32_t>();
        checkpoint.iterations = header.at("iterations").get<std::uint64_t>();
        checkpoint.neighbor_builds = header.at("neighbor_builds").get<std::uint64_t>();
        checkpoint.top = header.at("top").get<double>();
        for (const json& s : header.at("stages"))
            checkpoint.stages.push_back(stage_from_json(s));
        spheres = header.at("spheres").get<std::size_t>();
        hash = header.at("fnv1a64").get<std::string>();
    } catch (const json::exception& e) {
        throw refuse(fmt::format("corrupt header ({})", e.what()));
    }

    const json wanted = parameters_json(parameters);
    for (const auto& [key, value] : wanted.items()) {
        const auto found = stored.find(key);
        if (found == stored.end() || *found != value) {
            std::string option = key; // the command line's name
            std::replace(option.begin(), option.end(), '_', '-');
            throw refuse(fmt::format("it was taken with {} = {}, this run has {}", option,
                                     found == stored.end() ? "(none)" : found->dump(),
                                     value.dump()));
        }
    }
    if (data.size() != spheres * 4 * sizeof(double))
        throw refuse(fmt::format("cut short or padded ({} bytes of data for {} spheres, "
                                 "expected {})",
                                 data.size(), spheres, spheres * 4 * sizeof(double)));
    if (fmt::format("{:016x}", fnv1a(data)) != hash)
        throw refuse("corrupt (the data do not match their hash)");
    checkpoint.packing.centers.reserve(spheres);
    checkpoint.packing.radii.reserve(spheres);
    for (std::size_t i = 0; i < spheres; ++i) {
        const std::size_t at = i * 4 * sizeof(double);
        const Vec3 c{take(data, at), take(data, at + 8), take(data, at + 16)};
        const double r = take(data, at + 24);
        if (!is_finite(c) || !(r > 0.0) || !std::isfinite(r))
            throw refuse(fmt::format("corrupt (sphere {} is at ({}, {}, {}) with radius {})", i,
                                     c.x, c.y, c.z, r));
        checkpoint.packing.add(c, r);
    }
    return checkpoint;
}

} // namespace packbed
