#include "packbed/checkpoint.hpp"

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <fstream>
#include <iterator>
#include <limits>
#include <string>
#include <string_view>
#include <system_error>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "base/json_input.hpp"
#include "packbed/error.hpp"
#include "packbed/files.hpp"
#include "packbed/limits.hpp"
#include "packbed/output.hpp"

namespace packbed {

namespace {

using nlohmann::json;

static_assert(std::endian::native == std::endian::little,
              "checkpoint data are written as the host's doubles, little-endian");

// The first line: the format's name and number. Format 1 (commit 803e157 only) listed the
// parameters as [name, value] pairs; format 2 as an object (soft_sphere_parameters_json), its
// hash covering the data only; format 3 has the hash on a line of its own, covering the header
// line and the data.
constexpr std::string_view magic = "packbed-checkpoint ";
constexpr int format = 3;
constexpr std::string_view hash_label = "fnv1a64 ";

/// The parameters a checkpoint records and a resumed run must match: all but max_iterations,
/// which only bounds the run. Frictionless runs leave the friction out, as checkpoints written
/// before friction existed do.
json parameters_json(const SoftSphereParameters& p) {
    json all = soft_sphere_parameters_json(p);
    all.erase("max_iterations");
    if (!p.frictional()) {
        all.erase("friction");
        all.erase("wall_friction");
    }
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

/// FNV-1a, 64 bits, continued from `h`.
std::uint64_t fnv1a(std::string_view bytes, std::uint64_t h = 0xcbf29ce484222325ULL) {
    for (const char c : bytes) {
        h ^= static_cast<unsigned char>(c);
        h *= 0x100000001b3ULL;
    }
    return h;
}

/// The hash line of a header line and its data.
std::string hash_line(std::string_view header, std::string_view data) {
    return fmt::format("{}{:016x}", hash_label, fnv1a(data, fnv1a("\n", fnv1a(header))));
}

void append(std::string& bytes, double value) {
    char raw[sizeof value];
    std::memcpy(raw, &value, sizeof value);
    bytes.append(raw, sizeof value);
}

double take(std::string_view bytes, std::size_t at) {
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
    const std::string header = json{
        {"parameters", parameters_json(parameters)},
        {"layers_done", checkpoint.layers_done},
        {"iterations", checkpoint.iterations},
        {"neighbor_builds", checkpoint.neighbor_builds},
        {"top", checkpoint.top},
        {"stages", stages},
        {"spheres",
         packing.size()}}.dump();
    const std::string first = fmt::format("{}{}\n", magic, format);
    const std::string hash = hash_line(header, data) + "\n";
    replace_file(path, "--checkpoint", {first, header, "\n", hash, data});
}

namespace {

/// Reads the fields of a checkpoint's header, refusing any value out of its range with a
/// message naming the field.
class HeaderReader {
public:
    HeaderReader(std::string_view name)
        : m_name(printable(name)) {}

    [[noreturn]] void refuse(const std::string& what) const {
        throw InvalidInput(fmt::format("--checkpoint {}: {}; allowed: a checkpoint written by "
                                       "`packbed generate --checkpoint` with the same options",
                                       m_name, what));
    }

    /// `key` of `object`, which must be there.
    const json& at(const json& object, const char* key, std::string_view where) const {
        if (!object.is_object() || !object.contains(key))
            refuse(fmt::format("corrupt checkpoint: no field {}{}", where, key));
        return object[key];
    }

    std::uint64_t whole(const json& object, const char* key, std::uint64_t low, std::uint64_t high,
                        std::string_view where = "") const {
        const json& v = at(object, key, where);
        if (!v.is_number_unsigned() || v.get<std::uint64_t>() < low ||
            v.get<std::uint64_t>() > high)
            refuse(fmt::format("corrupt checkpoint: {}{} = {} is not allowed; allowed: a whole "
                               "number from {} to {}",
                               where, key, json_excerpt(v, 40), low, high));
        return v.get<std::uint64_t>();
    }

    double real(const json& object, const char* key, double low, double high,
                std::string_view where = "") const {
        const json& v = at(object, key, where);
        const double value = v.is_number() ? v.get<double>() : std::nan("");
        if (!(value >= low && value <= high))
            refuse(fmt::format("corrupt checkpoint: {}{} = {} is not allowed; allowed: a number "
                               "from {} to {}",
                               where, key, json_excerpt(v, 40), low, high));
        return value;
    }

private:
    std::string m_name;
};

} // namespace

LayerCheckpoint read_checkpoint(std::istream& in, std::string_view name,
                                const SoftSphereParameters& parameters) {
    const HeaderReader field(name);
    std::string line, header_text, hash;
    if (read_line(in, line, 64) != LineRead::line || !line.starts_with(magic))
        field.refuse(
            fmt::format("not a packbed checkpoint (its first line is not '{}{}')", magic, format));
    if (line != fmt::format("{}{}", magic, format))
        field.refuse(fmt::format("written in checkpoint format '{}', this packbed reads format "
                                 "{} (resume with the packbed that wrote it)",
                                 printable(line.substr(magic.size())), format));
    if (read_line(in, header_text, limits::max_line_length) != LineRead::line)
        field.refuse("corrupt checkpoint: no header line (cut short or too long)");
    if (read_line(in, hash, 64) != LineRead::line || !hash.starts_with(hash_label))
        field.refuse("corrupt checkpoint: no hash line");

    // The data: exactly the spheres of this run, then the end of the file.
    const std::uint64_t particles = parameters.particles;
    if (particles > limits::max_spheres)
        field.refuse(fmt::format("this run has {} spheres", particles));
    std::string data(particles * 4 * sizeof(double), '\0');
    in.read(data.data(), static_cast<std::streamsize>(data.size()));
    const auto got = static_cast<std::size_t>(in.gcount());
    if (got != data.size() || in.peek() != std::char_traits<char>::eof())
        field.refuse(fmt::format("corrupt checkpoint: {} bytes of data where {} spheres need {}",
                                 got == data.size() ? "more" : std::to_string(got), particles,
                                 data.size()));
    if (hash_line(header_text, data) != hash)
        field.refuse("corrupt checkpoint: the header and data do not match their hash");

    const ParsedJson parsed = parse_json(header_text);
    if (!parsed.error.empty())
        field.refuse(fmt::format("corrupt checkpoint: the header is not JSON ({})",
                                 std::string_view(parsed.error).substr(0, 120)));
    const json& header = parsed.value;
    const json& stored = field.at(header, "parameters", "");
    const json wanted = parameters_json(parameters);
    for (const auto& [key, value] : wanted.items()) {
        const auto found = stored.is_object() ? stored.find(key) : stored.end();
        if (!stored.is_object() || found == stored.end() || *found != value) {
            std::string option = key; // the command line's name
            std::replace(option.begin(), option.end(), '_', '-');
            field.refuse(fmt::format(
                "it was taken with {} = {}, this run has {}", option,
                !stored.is_object() || found == stored.end() ? "(none)" : json_excerpt(*found, 40),
                json_excerpt(value, 40)));
        }
    }

    // Every field within what this run can have produced.
    const std::uint32_t layers = fire_layers(parameters);
    // A checkpoint holds a bed in a tube (prepare_generation refuses any other container).
    const std::optional<double> tube = parameters.aspect_ratio();
    if (!tube)
        field.refuse(fmt::format("this run's container is {}; a checkpoint holds a bed in a tube",
                                 parameters.container.spec()));
    const double a = *tube;
    const double height = initial_bed_height(particles, a, parameters.e0);
    // Internal lengths are in Dp: centres inside the cylinder, the bed no taller than its
    // generated height or a single file of all its spheres, whichever is taller.
    const double z_high = std::max(height, static_cast<double>(particles)) + 2.0;
    LayerCheckpoint checkpoint;
    checkpoint.layers_done =
        static_cast<std::uint32_t>(field.whole(header, "layers_done", 1, layers));
    checkpoint.iterations =
        field.whole(header, "iterations", 0, std::numeric_limits<std::int64_t>::max());
    checkpoint.neighbor_builds =
        field.whole(header, "neighbor_builds", 0, std::numeric_limits<std::int64_t>::max());
    checkpoint.top = field.real(header, "top", 0.0, z_high);
    field.whole(header, "spheres", particles, particles);
    const json& stages = field.at(header, "stages", "");
    const char* names[] = {"initial", "intermediate", "final"};
    if (!stages.is_array() || stages.size() != 3)
        field.refuse("corrupt checkpoint: stages is not a list of the 3 stages");
    std::uint64_t stage_iterations = 0;
    for (std::size_t k = 0; k < 3; ++k) {
        const json& j = stages[k];
        const std::string where = fmt::format("stages[{}].", k);
        const json& stage_name = field.at(j, "name", where);
        if (stage_name != names[k])
            field.refuse(fmt::format("corrupt checkpoint: {}name = {} is not allowed; allowed: "
                                     "\"{}\"",
                                     where, json_excerpt(stage_name, 40), names[k]));
        StageRecord s;
        s.name = names[k];
        s.iterations = field.whole(j, "iterations", 0, checkpoint.iterations, where);
        s.steps = static_cast<std::uint32_t>(
            field.whole(j, "steps", 1, std::numeric_limits<std::uint32_t>::max(), where));
        s.cg = field.real(j, "cg", 0.0, 1.0, where);
        s.max_overlap_pair = field.real(j, "max_overlap_pair", 0.0, 1.0, where);
        s.max_overlap_wall = field.real(j, "max_overlap_wall", 0.0, 1.0, where);
        s.mass_centre_z = field.real(j, "mass_centre_z", -1.0, z_high, where);
        const json& window = field.at(j, "mass_centre_window", where);
        if (!window.is_array() || window.size() > parameters.mc_window)
            field.refuse(fmt::format("corrupt checkpoint: {}mass_centre_window is not a list of "
                                     "at most {} numbers",
                                     where, parameters.mc_window));
        for (const json& v : window) {
            const double z = v.is_number() ? v.get<double>() : std::nan("");
            if (!(z >= -1.0 && z <= z_high))
                field.refuse(fmt::format("corrupt checkpoint: {}mass_centre_window holds {}; "
                                         "allowed: numbers from -1 to {}",
                                         where, json_excerpt(v, 40), z_high));
            s.mass_centre_window.push_back(z);
        }
        stage_iterations += s.iterations;
        checkpoint.stages.push_back(std::move(s));
    }
    if (stage_iterations != checkpoint.iterations)
        field.refuse(fmt::format("corrupt checkpoint: the stages' iterations add up to {}, not "
                                 "iterations = {}",
                                 stage_iterations, checkpoint.iterations));

    checkpoint.packing.centers.reserve(particles);
    checkpoint.packing.radii.reserve(particles);
    const double reach = 0.5 * a + 1.0;
    for (std::size_t i = 0; i < particles; ++i) {
        const std::size_t at = i * 4 * sizeof(double);
        const Vec3 c{take(data, at), take(data, at + 8), take(data, at + 16)};
        const double r = take(data, at + 24);
        if (!(std::abs(c.x) <= reach && std::abs(c.y) <= reach && c.z >= -1.0 && c.z <= z_high &&
              r > 0.0 && r <= 0.5 * a))
            field.refuse(fmt::format("corrupt checkpoint: sphere {} is at ({}, {}, {}) with "
                                     "radius {}, outside the container",
                                     i, c.x, c.y, c.z, r));
        checkpoint.packing.add(c, r);
    }
    return checkpoint;
}

LayerCheckpoint read_checkpoint(const std::filesystem::path& path,
                                const SoftSphereParameters& parameters) {
    std::ifstream in = open_regular_file("--checkpoint", path);
    return read_checkpoint(in, path.native(), parameters);
}

} // namespace packbed
