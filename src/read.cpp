#include "packbed/read.hpp"

#include <algorithm>
#include <cctype>
#include <charconv>
#include <cmath>
#include <fstream>
#include <sstream>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "packbed/error.hpp"
#include "packbed/files.hpp"
#include "packbed/limits.hpp"

namespace packbed {

namespace {

std::string_view trim(std::string_view s) {
    while (!s.empty() && std::isspace(static_cast<unsigned char>(s.front())))
        s.remove_prefix(1);
    while (!s.empty() && std::isspace(static_cast<unsigned char>(s.back())))
        s.remove_suffix(1);
    return s;
}

std::string lower(std::string_view s) {
    std::string out(s);
    std::transform(out.begin(), out.end(), out.begin(),
                   [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
    return out;
}

std::vector<std::string_view> split_commas(std::string_view line) {
    std::vector<std::string_view> fields;
    for (std::size_t start = 0;;) {
        const std::size_t comma = line.find(',', start);
        fields.push_back(trim(line.substr(start, comma - start)));
        if (comma == std::string_view::npos)
            return fields;
        start = comma + 1;
    }
}

std::vector<std::string_view> split_spaces(std::string_view line) {
    std::vector<std::string_view> fields;
    std::size_t i = 0;
    while (i < line.size()) {
        while (i < line.size() && std::isspace(static_cast<unsigned char>(line[i])))
            ++i;
        const std::size_t start = i;
        while (i < line.size() && !std::isspace(static_cast<unsigned char>(line[i])))
            ++i;
        if (i > start)
            fields.push_back(line.substr(start, i - start));
    }
    return fields;
}

/// Reads lines and builds messages "NAME:LINE: reason".
class LineReader {
public:
    LineReader(std::istream& input, std::string_view name)
        : m_input(input)
        , m_name(printable(name)) {}

    /// Next line that is not blank and not a '#' comment; false at the end.
    bool next(std::string& line) {
        while (get(line)) {
            if (m_line == 1 && line.rfind("\xEF\xBB\xBF", 0) == 0) // UTF-8 byte-order mark
                line.erase(0, 3);
            if (!line.empty() && line.back() == '\r')
                line.pop_back();
            const auto t = trim(line);
            if (!t.empty() && t.front() != '#')
                return true;
        }
        return false;
    }

    /// Next line as it is (blank allowed); false at the end.
    bool raw(std::string& line) { return get(line); }

    [[noreturn]] void fail(std::string_view reason) const {
        throw InvalidInput(fmt::format("{}:{}: {}", m_name, m_line, reason));
    }
    [[noreturn]] void fail_file(std::string_view reason) const {
        throw InvalidInput(fmt::format("{}: {}", m_name, reason));
    }

    /// A field as a finite double, or a message naming the column and the value.
    double number(std::string_view field, std::string_view column) const {
        double value = 0.0;
        const char* end = field.data() + field.size();
        const auto [ptr, ec] = std::from_chars(field.data(), end, value);
        const std::string shown_column = printable(column.substr(0, 40));
        if (field.empty())
            fail(fmt::format("column '{}' is empty; a number is needed", shown_column));
        if (ec != std::errc() || ptr != end)
            fail(fmt::format("column '{}' value '{}' is not a number", shown_column,
                             printable(field.substr(0, 40))));
        if (!std::isfinite(value))
            fail(fmt::format("column '{}' value '{}' is not a finite number", shown_column,
                             printable(field.substr(0, 40))));
        return value;
    }

    /// A count of spheres declared by the file as a size, refused beyond limits::max_spheres.
    std::size_t count(double declared, std::string_view what, double low) const {
        if (!(declared >= low && declared <= static_cast<double>(limits::max_spheres)) ||
            declared != std::floor(declared))
            fail(fmt::format("{} {} is not allowed; allowed: a whole number from {} to {}", what,
                             declared, low, limits::max_spheres));
        return static_cast<std::size_t>(declared);
    }

    /// A sphere from its fields; the size must be > 0. `is_diameter` halves it.
    void add(ParticleFile& out, double x, double y, double z, double size, bool is_diameter,
             std::string_view size_column) const {
        if (out.packing.size() >= limits::max_spheres)
            fail(fmt::format("more than {} spheres; allowed: at most that many",
                             limits::max_spheres));
        // The diameter range of the command line's --diameter (a radius of 5e-324 would
        // otherwise halve to 0, and the analysis divides by it).
        const double scale = is_diameter ? 1.0 : 0.5;
        if (!(size >= scale * limits::min_diameter && size <= scale * limits::max_diameter))
            fail(fmt::format("column '{}' value {} is not allowed; a {} must be from {:g} to {:g}",
                             printable(size_column.substr(0, 40)), size,
                             is_diameter ? "diameter" : "radius", scale * limits::min_diameter,
                             scale * limits::max_diameter));
        for (const auto& [value, axis] : {std::pair{x, "x"}, {y, "y"}, {z, "z"}})
            if (!(std::abs(value) <= limits::max_length))
                fail(fmt::format("{} = {} is not allowed; allowed: a coordinate from {:g} to {:g}",
                                 axis, value, -limits::max_length, limits::max_length));
        out.packing.add({x, y, z}, is_diameter ? 0.5 * size : size);
        out.lines.push_back(m_line);
    }

private:
    /// The next line, within limits::max_line_length; false at the end.
    bool get(std::string& line) {
        const LineRead read = read_line(m_input, line, limits::max_line_length);
        if (read == LineRead::end)
            return false;
        if (read == LineRead::error)
            fail_file("cannot be read (an input/output error); allowed: a readable regular file");
        ++m_line;
        if (read == LineRead::too_long)
            fail(fmt::format("a line longer than {} bytes; allowed: lines up to that length (is "
                             "this a text file?)",
                             limits::max_line_length));
        return true;
    }

    std::istream& m_input;
    std::string m_name;
    std::size_t m_line = 0;
};

/// Index of the first header name in `names`, or -1.
int find_column(const std::vector<std::string>& header, std::initializer_list<const char*> names) {
    for (const char* name : names) {
        const auto it = std::find(header.begin(), header.end(), name);
        if (it != header.end())
            return static_cast<int>(it - header.begin());
    }
    return -1;
}

/// Column indices of x, y, z and the size, from a header.
struct Columns {
    int x = -1, y = -1, z = -1, size = -1;
    bool is_diameter = false;
    std::string size_name;
};

Columns columns_of(const std::vector<std::string>& header, const LineReader& in,
                   std::initializer_list<const char*> xs, std::initializer_list<const char*> ys,
                   std::initializer_list<const char*> zs) {
    Columns c;
    c.x = find_column(header, xs);
    c.y = find_column(header, ys);
    c.z = find_column(header, zs);
    c.size = find_column(header, {"r", "radius"});
    if (c.size < 0) {
        c.size = find_column(header, {"d", "diameter"});
        c.is_diameter = c.size >= 0;
    }
    const char* missing = c.x < 0 ? "x" : c.y < 0 ? "y" : c.z < 0 ? "z" : nullptr;
    if (missing)
        in.fail(fmt::format("missing column '{}'; needed: x, y, z and r, radius, d or diameter",
                            missing));
    if (c.size < 0)
        in.fail("missing column 'r'; needed: x, y, z and r, radius, d or diameter");
    c.size_name = header[static_cast<std::size_t>(c.size)];
    return c;
}

ParticleFile read_csv(LineReader& in) {
    ParticleFile out;
    out.format = ParticleFormat::csv;
    std::string line;
    if (!in.next(line))
        in.fail_file("empty file; expected a header line such as x,y,z,r");
    std::vector<std::string> header;
    for (const auto f : split_commas(line))
        header.push_back(lower(f));
    const Columns c = columns_of(header, in, {"x"}, {"y"}, {"z"});
    while (in.next(line)) {
        const auto fields = split_commas(line);
        if (fields.size() != header.size())
            in.fail(fmt::format("{} fields; the header has {}", fields.size(), header.size()));
        auto at = [&](int k) { return fields[static_cast<std::size_t>(k)]; };
        auto name = [&](int k) { return header[static_cast<std::size_t>(k)]; };
        in.add(out, in.number(at(c.x), name(c.x)), in.number(at(c.y), name(c.y)),
               in.number(at(c.z), name(c.z)), in.number(at(c.size), name(c.size)), c.is_diameter,
               c.size_name);
    }
    if (out.packing.size() == 0)
        in.fail_file("no spheres after the header");
    return out;
}

ParticleFile read_xyz(LineReader& in, const ReadOptions& options) {
    ParticleFile out;
    out.format = ParticleFormat::xyz;
    std::string line;
    if (!in.next(line))
        in.fail_file("empty file; expected the number of spheres on the first line");
    const std::size_t count = in.count(in.number(trim(line), "count"), "the count", 1);
    if (!in.raw(line)) // the comment line, which may be blank
        in.fail_file("ends after the count line; expected a comment line and the spheres");
    while (out.packing.size() < count && in.next(line)) {
        const auto f = split_spaces(line);
        if (f.size() == 4 && !options.radius)
            in.fail("no radius column (name x y z) and no radius given; allowed: name x y z "
                    "radius, or give the diameter");
        if (f.size() != 4 && f.size() != 5)
            in.fail(fmt::format("{} fields; allowed: name x y z [radius]", f.size()));
        const double radius = f.size() == 5 ? in.number(f[4], "radius") : *options.radius;
        in.add(out, in.number(f[1], "x"), in.number(f[2], "y"), in.number(f[3], "z"), radius, false,
               "radius");
    }
    if (out.packing.size() < count)
        in.fail_file(fmt::format("declares {} spheres but holds {}", count, out.packing.size()));
    if (in.next(line))
        in.fail(fmt::format("more lines than the {} spheres the first line declares", count));
    return out;
}

ParticleFile read_lammps_dump(LineReader& in) {
    ParticleFile out;
    out.format = ParticleFormat::lammps_dump;
    std::string line;
    std::size_t atoms = 0;
    bool have_count = false;
    if (!in.next(line))
        in.fail_file("empty file; expected a LAMMPS dump starting with ITEM: TIMESTEP");
    do {
        const auto t = trim(line);
        if (t.rfind("ITEM:", 0) != 0)
            in.fail(fmt::format("expected an ITEM: line, found '{}'", printable(t.substr(0, 40))));
        const std::string item(trim(t.substr(5))); // a copy: `line` is read over below
        if (item.rfind("NUMBER OF ATOMS", 0) == 0) {
            if (!in.next(line))
                in.fail_file("ends after ITEM: NUMBER OF ATOMS");
            // 0: a frame before particles were inserted
            atoms = in.count(in.number(trim(line), "NUMBER OF ATOMS"), "the number of atoms", 0);
            have_count = true;
        } else if (item.rfind("ATOMS", 0) == 0) {
            if (!have_count)
                in.fail("ITEM: ATOMS before ITEM: NUMBER OF ATOMS");
            std::vector<std::string> header;
            for (const auto f : split_spaces(std::string_view(item).substr(5)))
                header.push_back(lower(f));
            if (find_column(header, {"x", "xu"}) < 0 && find_column(header, {"xs", "xsu"}) >= 0)
                in.fail("scaled coordinates (xs ys zs) are not supported; allowed: dump x y z or "
                        "xu yu zu");
            const Columns c = columns_of(header, in, {"x", "xu"}, {"y", "yu"}, {"z", "zu"});
            out.packing = Packing{}; // a later snapshot replaces an earlier one
            out.lines.clear();
            for (std::size_t k = 0; k < atoms; ++k) {
                if (!in.next(line))
                    in.fail_file(fmt::format("ends after {} of {} atoms", k, atoms));
                const auto f = split_spaces(line);
                if (f.size() != header.size())
                    in.fail(
                        fmt::format("{} fields; ITEM: ATOMS names {}", f.size(), header.size()));
                auto at = [&](int i) { return f[static_cast<std::size_t>(i)]; };
                auto name = [&](int i) { return header[static_cast<std::size_t>(i)]; };
                in.add(out, in.number(at(c.x), name(c.x)), in.number(at(c.y), name(c.y)),
                       in.number(at(c.z), name(c.z)), in.number(at(c.size), name(c.size)),
                       c.is_diameter, c.size_name);
            }
        } else if (item.rfind("BOX BOUNDS", 0) == 0) {
            for (int k = 0; k < 3; ++k)
                if (!in.next(line))
                    in.fail_file("ends inside ITEM: BOX BOUNDS");
        } else if (!in.next(line)) { // TIMESTEP and other one-value items
            in.fail_file(fmt::format("ends after ITEM: {}", printable(item.substr(0, 40))));
        }
    } while (in.next(line));
    if (out.packing.size() == 0)
        in.fail_file("no spheres in the last snapshot (or no ITEM: ATOMS section)");
    return out;
}

std::string extension_of(const std::filesystem::path& path) {
    return lower(path.extension().string());
}

} // namespace

namespace {

/// The format from the extension or, failing that, the first line of `file` (which is then
/// read again from its start).
ParticleFormat detect(std::istream& file, const std::filesystem::path& path) {
    const std::string ext = extension_of(path);
    if (ext == ".csv")
        return ParticleFormat::csv;
    if (ext == ".xyz")
        return ParticleFormat::xyz;
    if (ext == ".dump" || ext == ".lammpstrj")
        return ParticleFormat::lammps_dump;
    LineReader in(file, path.native());
    std::string line;
    if (!in.next(line))
        in.fail_file("empty file");
    file.clear();
    file.seekg(0);
    const auto t = trim(line);
    if (t.rfind("ITEM:", 0) == 0)
        return ParticleFormat::lammps_dump;
    if (t.find(',') != std::string_view::npos)
        return ParticleFormat::csv;
    if (t.find_first_not_of("0123456789") == std::string_view::npos)
        return ParticleFormat::xyz;
    in.fail("cannot tell the format; allowed: .csv, .xyz, .dump or .lammpstrj files");
}

} // namespace

ParticleFormat detect_particle_format(const std::filesystem::path& path) {
    std::ifstream file = open_regular_file("", path);
    return detect(file, path);
}

ParticleFile read_particles(std::istream& input, std::string_view name, ParticleFormat format,
                            const ReadOptions& options) {
    LineReader in(input, name);
    switch (format) {
    case ParticleFormat::csv:
        return read_csv(in);
    case ParticleFormat::xyz:
        return read_xyz(in, options);
    case ParticleFormat::lammps_dump:
        return read_lammps_dump(in);
    }
    in.fail_file("unknown format");
}

ParticleFile read_particles(const std::filesystem::path& path, const ReadOptions& options) {
    std::ifstream file = open_regular_file("", path);
    const ParticleFormat format = options.format ? *options.format : detect(file, path);
    return read_particles(file, path.native(), format, options);
}

BedSummary read_bed_summary(std::istream& input, std::string_view name) {
    const std::string shown = printable(name);
    nlohmann::json json;
    try {
        json = nlohmann::json::parse(input);
    } catch (const nlohmann::json::exception& e) {
        throw InvalidInput(fmt::format("{}: not a summary.json ({}); allowed: the summary.json of "
                                       "packbed generate, lattice or analyze",
                                       shown,
                                       printable(std::string_view(e.what()).substr(0, 200))));
    }
    if (!json.is_object())
        throw InvalidInput(fmt::format("{}: not a summary.json (not a JSON object); allowed: the "
                                       "summary.json of packbed generate, lattice or analyze",
                                       shown));
    BedSummary out;
    // A number in (0, high], or in (0, 1) for a porosity.
    auto number = [&](const nlohmann::json& parent, const char* key, const char* path,
                      double high) -> std::optional<double> {
        if (!parent.is_object() || !parent.contains(key) || parent[key].is_null())
            return std::nullopt;
        const nlohmann::json& v = parent[key];
        const double value = v.is_number() ? v.get<double>() : std::nan("");
        const bool porosity = high == 1.0;
        if (!(value > 0.0 && (porosity ? value < 1.0 : value <= high)))
            throw InvalidInput(fmt::format("{}: {} = {} is not allowed; allowed: a number in (0, "
                                           "{:g}{}",
                                           shown, path, printable(v.dump().substr(0, 40)), high,
                                           porosity ? ")" : "]"));
        return value;
    };
    if (json.contains("container"))
        out.container_radius =
            number(json["container"], "radius", "container.radius", limits::max_length);
    out.diameter = number(json, "diameter", "diameter", limits::max_diameter);
    if (json.contains("lattice")) {
        out.porosity = number(json["lattice"], "porosity", "lattice.porosity", 1.0);
        const auto type = json.find("type");
        if (out.porosity)
            out.porosity_source = fmt::format("the porosity of the {} lattice",
                                              type != json.end() && type->is_string()
                                                  ? printable(type->get<std::string>())
                                                  : "?");
    }
    if (!out.porosity) {
        out.porosity = number(json, "void_fraction", "void_fraction", 1.0);
        if (out.porosity)
            out.porosity_source = "the overall void fraction";
    }
    return out;
}

BedSummary read_bed_summary(const std::filesystem::path& path) {
    std::istringstream text(read_small_file("", path, limits::max_small_file));
    return read_bed_summary(text, path.native());
}

const std::vector<std::pair<std::string, ParticleFormat>>& particle_formats() {
    static const std::vector<std::pair<std::string, ParticleFormat>> names{
        {"csv", ParticleFormat::csv},
        {"xyz", ParticleFormat::xyz},
        {"lammps-dump", ParticleFormat::lammps_dump}};
    return names;
}

} // namespace packbed
