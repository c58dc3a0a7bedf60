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

#include "base/fnv1a.hpp"
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
// A pellet bed's checkpoint (write_pellet_checkpoint): the same parts, its own first line.
constexpr std::string_view pellet_magic = "packbed-pellet-checkpoint ";
constexpr int pellet_format = 1;

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

using detail::fnv1a;

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

    bool flag(const json& object, const char* key) const {
        const json& v = at(object, key, "");
        if (!v.is_boolean())
            refuse(fmt::format("corrupt checkpoint: {} = {} is not allowed; allowed: true or false",
                               key, json_excerpt(v, 40)));
        return v.get<bool>();
    }

private:
    std::string m_name;
};

/// A checkpoint file's header (parsed) and data, read and checked against their hash: the
/// first line `first_line`, then exactly `bytes` of data (`what` names them in a refusal).
struct CheckedFile {
    json header;
    std::string data;
};

CheckedFile read_checked(std::istream& in, const HeaderReader& field, std::string_view kind,
                         int version, std::size_t bytes, std::string_view what) {
    std::string line, header_text, hash;
    if (read_line(in, line, 64) != LineRead::line || !line.starts_with(kind)) {
        if (line.starts_with(magic) || line.starts_with(pellet_magic))
            field.refuse(fmt::format("a checkpoint of a {} bed, this run is of {}",
                                     line.starts_with(magic) ? "sphere" : "pellet",
                                     kind == magic ? "spheres" : "pellets"));
        field.refuse(
            fmt::format("not a packbed checkpoint (its first line is not '{}{}')", kind, version));
    }
    if (line != fmt::format("{}{}", kind, version))
        field.refuse(fmt::format("written in checkpoint format '{}', this packbed reads format "
                                 "{} (resume with the packbed that wrote it)",
                                 printable(line.substr(kind.size())), version));
    if (read_line(in, header_text, limits::max_line_length) != LineRead::line)
        field.refuse("corrupt checkpoint: no header line (cut short or too long)");
    if (read_line(in, hash, 64) != LineRead::line || !hash.starts_with(hash_label))
        field.refuse("corrupt checkpoint: no hash line");
    CheckedFile out;
    out.data.assign(bytes, '\0');
    in.read(out.data.data(), static_cast<std::streamsize>(bytes));
    const auto got = static_cast<std::size_t>(in.gcount());
    if (got != bytes || in.peek() != std::char_traits<char>::eof())
        field.refuse(fmt::format("corrupt checkpoint: {} bytes of data where {} need {}",
                                 got == bytes ? "more" : std::to_string(got), what, bytes));
    if (hash_line(header_text, out.data) != hash)
        field.refuse("corrupt checkpoint: the header and data do not match their hash");
    const ParsedJson parsed = parse_json(header_text);
    if (!parsed.error.empty())
        field.refuse(fmt::format("corrupt checkpoint: the header is not JSON ({})",
                                 std::string_view(parsed.error).substr(0, 120)));
    out.header = parsed.value;
    return out;
}

/// Refuses a header whose parameters differ from `wanted`, naming the first that does.
void check_parameters(const HeaderReader& field, const json& header, const json& wanted) {
    const json& stored = field.at(header, "parameters", "");
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
}

/// Writes a checkpoint: the first line, the header, the hash line, the data.
void write_checked(const std::filesystem::path& path, std::string_view kind, int version,
                   const std::string& header, const std::string& data) {
    const std::string first = fmt::format("{}{}\n", kind, version);
    const std::string hash = hash_line(header, data) + "\n";
    replace_file(path, "--checkpoint", {first, header, "\n", hash, data});
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
    write_checked(path, magic, format, header, data);
}

LayerCheckpoint read_checkpoint(std::istream& in, std::string_view name,
                                const SoftSphereParameters& parameters) {
    const HeaderReader field(name);
    // The data: exactly the spheres of this run, then the end of the file.
    const std::uint64_t particles = parameters.particles;
    if (particles > limits::max_spheres)
        field.refuse(fmt::format("this run has {} spheres", particles));
    const CheckedFile file = read_checked(in, field, magic, format, particles * 4 * sizeof(double),
                                          fmt::format("{} spheres", particles));
    const json& header = file.header;
    const std::string& data = file.data;
    check_parameters(field, header, parameters_json(parameters));

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

// Seven doubles a pellet: its centroid and its orientation.
constexpr std::size_t pellet_doubles = 7;

void write_pellet_checkpoint(const std::filesystem::path& path,
                             const PelletBedParameters& parameters,
                             const PelletCheckpoint& checkpoint) {
    std::string data;
    data.reserve(checkpoint.centre.size() * pellet_doubles * sizeof(double));
    for (std::size_t i = 0; i < checkpoint.centre.size(); ++i) {
        const Vec3& c = checkpoint.centre[i];
        const Quaternion& q = checkpoint.turn[i];
        for (const double v : {c.x, c.y, c.z, q.w, q.x, q.y, q.z})
            append(data, v);
    }
    json stages = json::array();
    for (const PelletStage& s : checkpoint.stages)
        stages.push_back({{"name", s.name},
                          {"steps", s.steps},
                          {"gravity", s.gravity},
                          {"max_depth", s.max_depth},
                          {"mass_centre_z", s.mass_centre_z},
                          {"layer", s.layer}});
    const std::string header = json{
        {"parameters", pellet_bed_parameters_json(parameters)},
        {"layers_done", checkpoint.layers_done},
        {"steps", checkpoint.steps},
        {"neighbor_builds", checkpoint.neighbor_builds},
        {"top", checkpoint.top},
        {"on_floor", checkpoint.on_floor},
        {"nodes", checkpoint.nodes},
        {"sliding_pairs", checkpoint.sliding_pairs},
        {"sliding_walls", checkpoint.sliding_walls},
        {"friction_kept", checkpoint.friction_kept},
        {"residual_force", checkpoint.residual_force},
        {"residual_torque", checkpoint.residual_torque},
        {"kicks", checkpoint.kicks},
        {"stages", stages},
        {"pellets",
         checkpoint.centre.size()}}.dump();
    write_checked(path, pellet_magic, pellet_format, header, data);
}

PelletCheckpoint read_pellet_checkpoint(std::istream& in, std::string_view name,
                                        const PelletBedParameters& parameters,
                                        const PelletColumn& column) {
    const HeaderReader field(name);
    const std::uint64_t n = parameters.particles;
    if (n > limits::max_spheres)
        field.refuse(fmt::format("this run has {} pellets", n));
    const CheckedFile file =
        read_checked(in, field, pellet_magic, pellet_format, n * pellet_doubles * sizeof(double),
                     fmt::format("{} pellets", n));
    const json& header = file.header;
    check_parameters(field, header, pellet_bed_parameters_json(parameters));

    // Every field within what this run can have produced: the settled bed no higher than the
    // inserted column, give or take a few pellets.
    constexpr auto most = static_cast<std::uint64_t>(std::numeric_limits<std::int64_t>::max());
    const double reach = column.largest_reach, z_high = column.height + 10.0 * reach;
    PelletCheckpoint c;
    c.layers_done =
        static_cast<std::uint32_t>(field.whole(header, "layers_done", 1, column.layers));
    c.steps = field.whole(header, "steps", 0, most);
    c.neighbor_builds = field.whole(header, "neighbor_builds", 0, most);
    c.top = field.real(header, "top", 0.0, z_high);
    c.on_floor = field.flag(header, "on_floor");
    c.nodes = field.whole(header, "nodes", 0, most);
    c.sliding_pairs = field.whole(header, "sliding_pairs", 0, most);
    c.sliding_walls = field.whole(header, "sliding_walls", 0, most);
    c.friction_kept = field.flag(header, "friction_kept");
    c.residual_force = field.real(header, "residual_force", 0.0, 1e12);
    c.residual_torque = field.real(header, "residual_torque", 0.0, 1e12);
    c.kicks = static_cast<std::uint32_t>(
        field.whole(header, "kicks", 0, std::min<std::uint64_t>(c.steps, 1U << 30)));
    field.whole(header, "pellets", n, n);
    const json& stages = field.at(header, "stages", "");
    if (!stages.is_array() || stages.size() > 2 * std::size_t{c.layers_done})
        field.refuse(fmt::format("corrupt checkpoint: stages is not a list of at most {} stages",
                                 2 * std::size_t{c.layers_done}));
    for (std::size_t k = 0; k < stages.size(); ++k) {
        const json& j = stages[k];
        const std::string where = fmt::format("stages[{}].", k);
        const json& stage_name = field.at(j, "name", where);
        if (stage_name != "settle" && stage_name != "final")
            field.refuse(fmt::format("corrupt checkpoint: {}name = {} is not allowed; allowed: "
                                     "\"settle\" or \"final\"",
                                     where, json_excerpt(stage_name, 40)));
        PelletStage s;
        s.name = stage_name.get<std::string>();
        s.steps = field.whole(j, "steps", 0, c.steps, where);
        s.gravity = field.real(j, "gravity", 0.0, 1.0, where);
        s.max_depth = field.real(j, "max_depth", 0.0, 2.0 * reach, where);
        s.mass_centre_z = field.real(j, "mass_centre_z", -z_high, z_high, where);
        s.layer = static_cast<std::uint32_t>(field.whole(j, "layer", 0, c.layers_done - 1, where));
        c.stages.push_back(std::move(s));
    }

    const Rectangle box = parameters.container.bounds();
    const double margin = 2.0 * reach;
    c.centre.reserve(n);
    c.turn.reserve(n);
    for (std::size_t i = 0; i < n; ++i) {
        const std::size_t at = i * pellet_doubles * sizeof(double);
        const auto value = [&](std::size_t k) { return take(file.data, at + k * sizeof(double)); };
        const Vec3 p{value(0), value(1), value(2)};
        const Quaternion q{value(3), value(4), value(5), value(6)};
        if (!(p.x >= box.x_low - margin && p.x <= box.x_high + margin &&
              p.y >= box.y_low - margin && p.y <= box.y_high + margin && p.z >= -margin &&
              p.z <= z_high))
            field.refuse(fmt::format("corrupt checkpoint: pellet {} is at ({}, {}, {}), outside "
                                     "the container",
                                     i, p.x, p.y, p.z));
        const double norm = q.w * q.w + q.x * q.x + q.y * q.y + q.z * q.z;
        if (!(std::abs(norm - 1.0) <= 1e-9))
            field.refuse(fmt::format("corrupt checkpoint: pellet {}'s orientation ({}, {}, {}, {}) "
                                     "is not a unit quaternion",
                                     i, q.w, q.x, q.y, q.z));
        c.centre.push_back(p);
        c.turn.push_back(q);
    }
    return c;
}

PelletCheckpoint read_pellet_checkpoint(const std::filesystem::path& path,
                                        const PelletBedParameters& parameters,
                                        const PelletColumn& column) {
    std::ifstream in = open_regular_file("--checkpoint", path);
    return read_pellet_checkpoint(in, path.native(), parameters, column);
}

} // namespace packbed
