#include "packbed/read.hpp"

#include <zlib.h>

#include <algorithm>
#include <array>
#include <cctype>
#include <cmath>
#include <fstream>
#include <sstream>
#include <streambuf>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "base/json_input.hpp"
#include "packbed/error.hpp"
#include "packbed/files.hpp"
#include "packbed/limits.hpp"
#include "packbed/memory.hpp"
#include "packbed/output.hpp"
#include "packbed/text.hpp"

namespace packbed {

namespace {

namespace fs = std::filesystem;

std::string lower(std::string_view s) {
    std::string out(s);
    std::transform(out.begin(), out.end(), out.begin(),
                   [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
    return out;
}

/// The text before a '#' comment.
std::string_view before_comment(std::string_view line) {
    return line.substr(0, line.find('#'));
}

/// Whether `text` is wholly a number (from_chars' syntax).
bool is_number(std::string_view text) {
    return parse_number(text).has_value();
}

/// The fields of one line of a delimited table. `sep` ' ' splits at runs of white space;
/// any other separator splits at each occurrence (empty fields kept). A field in double quotes
/// may hold the separator, and "" stands for one quote; fields are trimmed.
class FieldSplitter {
public:
    explicit FieldSplitter(char sep)
        : m_sep(sep) {}

    const std::vector<std::string_view>& split(std::string_view line) {
        m_fields.clear();
        if (line.find('"') == std::string_view::npos) { // the fast path: views into the line
            if (m_sep == ' ') {
                m_fields = split_spaces(line);
                return m_fields;
            }
            for (std::size_t start = 0;;) {
                const std::size_t end = line.find(m_sep, start);
                m_fields.push_back(trim(line.substr(start, end - start)));
                if (end == std::string_view::npos)
                    return m_fields;
                start = end + 1;
            }
        }
        // Quoted fields: their text, unquoted, goes into m_text (reserved so that views stay).
        m_text.clear();
        m_text.reserve(line.size());
        std::vector<std::pair<std::size_t, std::size_t>> spans;
        std::size_t i = 0;
        auto is_blank = [&](char c) {
            return m_sep == ' ' ? std::isspace(static_cast<unsigned char>(c)) != 0
                                : (c == ' ' || c == '\t' || c == '\r') && c != m_sep;
        };
        for (;;) {
            while (i < line.size() && is_blank(line[i]))
                ++i;
            if (m_sep == ' ' && i == line.size())
                break;
            const std::size_t start = m_text.size();
            if (i < line.size() && line[i] == '"') {
                for (++i; i < line.size(); ++i) {
                    if (line[i] == '"') {
                        if (i + 1 < line.size() && line[i + 1] == '"') {
                            m_text.push_back('"');
                            ++i;
                        } else {
                            ++i;
                            break;
                        }
                    } else {
                        m_text.push_back(line[i]);
                    }
                }
            }
            // Unquoted text (or what follows a closing quote) up to the separator.
            while (i < line.size() && line[i] != m_sep &&
                   !(m_sep == ' ' && std::isspace(static_cast<unsigned char>(line[i]))))
                m_text.push_back(line[i++]);
            spans.emplace_back(start, m_text.size());
            if (i >= line.size())
                break;
            ++i; // the separator
        }
        for (const auto& [start, end] : spans)
            m_fields.push_back(trim(std::string_view(m_text).substr(start, end - start)));
        return m_fields;
    }

private:
    char m_sep;
    std::vector<std::string_view> m_fields;
    std::string m_text;
};

/// The separator of a table from its header line: ';', else ',', else a tab, else white space
/// (' '). Separators inside double quotes do not count.
char separator_of(std::string_view header) {
    bool quoted = false;
    bool semicolon = false, comma = false, tab = false;
    for (const char c : header) {
        if (c == '"')
            quoted = !quoted;
        else if (!quoted) {
            semicolon |= c == ';';
            comma |= c == ',';
            tab |= c == '\t';
        }
    }
    return semicolon ? ';' : comma ? ',' : tab ? '\t' : ' ';
}

/// The input as text: the bytes of a stream, or, when they start with gzip's magic bytes
/// (1f 8b), what they decompress to (every gzip member in turn), at most `max_bytes` of it.
/// A read error, corrupt or truncated gzip data and too much of it are recorded in error()
/// and thrown from underflow (read_line turns that into LineRead::error; LineReader then
/// reports error()).
class InputBuffer : public std::streambuf {
public:
    InputBuffer(std::istream& source, std::uint64_t max_bytes)
        : m_source(source.good() ? source.rdbuf() : nullptr)
        , m_max(max_bytes)
        , m_in(1 << 16) {}
    ~InputBuffer() override {
        if (m_gzip)
            inflateEnd(&m_z);
    }
    InputBuffer(const InputBuffer&) = delete;
    InputBuffer& operator=(const InputBuffer&) = delete;

    /// Why reading stopped early, or "".
    const std::string& error() const { return m_error; }

protected:
    int_type underflow() override {
        if (gptr() < egptr())
            return traits_type::to_int_type(*gptr());
        if (!m_error.empty())
            throw std::runtime_error(m_error);
        if (!m_started) {
            m_started = true;
            const std::size_t n = read_raw();
            if (n >= 2 && static_cast<unsigned char>(m_in[0]) == 0x1f &&
                static_cast<unsigned char>(m_in[1]) == 0x8b)
                start_gzip(n);
            else if (n > 0) {
                setg(m_in.data(), m_in.data(), m_in.data() + n);
                return traits_type::to_int_type(*gptr());
            } else
                return traits_type::eof();
        }
        if (!m_gzip) {
            const std::size_t n = read_raw();
            if (n == 0)
                return traits_type::eof();
            setg(m_in.data(), m_in.data(), m_in.data() + n);
            return traits_type::to_int_type(*gptr());
        }
        return inflate_more();
    }

private:
    /// Read the next bytes of the source into m_in; 0 at its end.
    std::size_t read_raw() {
        if (m_source == nullptr || m_source_end)
            return 0;
        std::streamsize n = 0;
        try {
            n = m_source->sgetn(m_in.data(), static_cast<std::streamsize>(m_in.size()));
        } catch (...) { // libstdc++'s filebuf throws on a read error
            fail("cannot be read (an input/output error); allowed: a readable regular file");
        }
        if (n <= 0) {
            m_source_end = true;
            return 0;
        }
        m_compressed += static_cast<std::uint64_t>(n);
        return static_cast<std::size_t>(n);
    }

    void start_gzip(std::size_t n) {
        m_z = z_stream{};
        if (inflateInit2(&m_z, 16 + MAX_WBITS) != Z_OK) // 16: a gzip header and trailer
            fail("cannot start zlib (out of memory?)");
        m_gzip = true;
        m_out.resize(1 << 18);
        m_z.next_in = reinterpret_cast<Bytef*>(m_in.data());
        m_z.avail_in = static_cast<uInt>(n);
    }

    int_type inflate_more() {
        for (;;) {
            if (m_z.avail_in == 0 && !m_source_end) {
                const std::size_t n = read_raw();
                m_z.next_in = reinterpret_cast<Bytef*>(m_in.data());
                m_z.avail_in = static_cast<uInt>(n);
            }
            if (m_member_end) {
                if (m_z.avail_in == 0 && m_source_end)
                    return traits_type::eof();
                inflateReset(&m_z); // another gzip member follows (`cat a.gz b.gz`)
                m_member_end = false;
            }
            m_z.next_out = reinterpret_cast<Bytef*>(m_out.data());
            m_z.avail_out = static_cast<uInt>(m_out.size());
            const int rc = inflate(&m_z, Z_NO_FLUSH);
            const std::size_t produced = m_out.size() - m_z.avail_out;
            if (rc == Z_STREAM_END)
                m_member_end = true;
            else if (rc == Z_BUF_ERROR && m_z.avail_in == 0 && m_source_end)
                fail("the gzip data ends early (a truncated .gz file?); allowed: a complete gzip "
                     "file");
            else if (rc != Z_OK && rc != Z_BUF_ERROR)
                fail(fmt::format("not valid gzip data (zlib: {}); allowed: a complete gzip file",
                                 m_z.msg != nullptr ? std::string(m_z.msg)
                                                    : "error " + std::to_string(rc)));
            if (produced > 0) {
                m_total += produced;
                if (m_total > m_max)
                    fail(fmt::format("more than {} bytes once decompressed; allowed: a gzip file "
                                     "of at most that many bytes of text",
                                     m_max));
                // What the reader keeps stays in proportion to the file: a bed's text
                // compresses 2 (random beds) to 17 times (lattices); 1e8 repeated rows 400.
                if (m_total > limits::max_gzip_ratio * m_compressed + (1u << 20))
                    fail(fmt::format("expands more than {:g} times when decompressed ({} bytes "
                                     "from {}); allowed: gzip data of a bed's text",
                                     limits::max_gzip_ratio, m_total, m_compressed));
                setg(m_out.data(), m_out.data(), m_out.data() + produced);
                return traits_type::to_int_type(*gptr());
            }
        }
    }

    [[noreturn]] void fail(std::string reason) {
        m_error = std::move(reason);
        setg(nullptr, nullptr, nullptr);
        throw std::runtime_error(m_error);
    }

    std::streambuf* m_source;
    std::uint64_t m_max;
    std::vector<char> m_in;
    std::vector<char> m_out;
    z_stream m_z{};
    bool m_started = false;
    bool m_gzip = false;
    bool m_source_end = false;
    bool m_member_end = false;
    std::uint64_t m_total = 0;      // bytes decompressed
    std::uint64_t m_compressed = 0; // bytes read from the source
    std::string m_error;
};

/// Reads lines and builds messages "NAME:LINE: reason".
class LineReader {
public:
    /// \param source what `input` reads from, whose error() explains a failed read
    /// \param offset subtracted from every centre (ReadOptions::axis and floor)
    LineReader(std::istream& input, std::string_view name, const InputBuffer* source = nullptr,
               Vec3 offset = {0.0, 0.0, 0.0})
        : m_input(input)
        , m_name(printable(name))
        , m_source(source)
        , m_offset(offset) {}

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

    /// The number of the line read last (1-based).
    std::size_t line_number() const { return m_line; }

    [[noreturn]] void fail(std::string_view reason) const { fail_at(m_line, reason); }
    [[noreturn]] void fail_at(std::size_t line, std::string_view reason) const {
        throw InvalidInput(fmt::format("{}:{}: {}", m_name, line, reason));
    }
    [[noreturn]] void fail_file(std::string_view reason) const {
        throw InvalidInput(fmt::format("{}: {}", m_name, reason));
    }

    /// A field as a finite double, or a message naming the column and the value.
    double number(std::string_view field, std::string_view column) const {
        const auto value = parse_number(field);
        if (value && std::isfinite(*value))
            return *value;
        const std::string shown_column = printable(column.substr(0, 40));
        if (field.empty())
            fail(fmt::format("column '{}' is empty; a number is needed", shown_column));
        fail(fmt::format("column '{}' value '{}' is not {}", shown_column,
                         printable(field.substr(0, 40)), value ? "a finite number" : "a number"));
    }

    /// A count of spheres declared by the file as a size, refused beyond limits::max_spheres.
    std::size_t count(double declared, std::string_view what, double low) const {
        if (!(declared >= low && declared <= static_cast<double>(limits::max_spheres)) ||
            declared != std::floor(declared))
            fail(fmt::format("{} {} is not allowed; allowed: a whole number from {} to {}", what,
                             declared, low, limits::max_spheres));
        return static_cast<std::size_t>(declared);
    }

    /// A sphere from its fields; the size must be > 0. `is_diameter` halves it. The offset
    /// (axis, floor) is subtracted from the centre.
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
        x -= m_offset.x;
        y -= m_offset.y;
        z -= m_offset.z;
        for (const auto& [value, axis] : {std::pair{x, "x"}, {y, "y"}, {z, "z"}})
            if (!(std::abs(value) <= limits::max_length))
                fail(fmt::format("{} = {} is not allowed; allowed: a coordinate from {:g} to {:g}",
                                 axis, value, -limits::max_length, limits::max_length));
        // Before a vector grows past a million spheres, and at each doubling after: the grown
        // vectors beside the old ones must fit in memory (a small gzip file can hold 1e8 rows).
        const std::size_t n = out.packing.size();
        if (n >= (std::size_t{1} << 20) && (n & (n - 1)) == 0) {
            const std::uint64_t need = 3 * read_sphere_bytes * n;
            const std::optional<std::uint64_t> left = available_memory();
            if (left && need > *left)
                fail(fmt::format("{} spheres read so far, and the next ones need about {} of "
                                 "memory; {} is available here; allowed: a bed that fits in "
                                 "memory",
                                 n, memory_text(need), memory_text(*left)));
        }
        out.packing.add({x, y, z}, is_diameter ? 0.5 * size : size);
        out.lines.push_back(m_line);
    }

private:
    /// The next line, within limits::max_line_length; false at the end.
    bool get(std::string& line) {
        const LineRead read = read_line(m_input, line, limits::max_line_length);
        if (read == LineRead::end)
            return false;
        if (read == LineRead::error) {
            if (m_source != nullptr && !m_source->error().empty())
                fail_file(m_source->error());
            fail_file("cannot be read (an input/output error); allowed: a readable regular file");
        }
        ++m_line;
        if (read == LineRead::too_long)
            fail(fmt::format("a line longer than {} bytes; allowed: lines up to that length (is "
                             "this a text file?)",
                             limits::max_line_length));
        return true;
    }

    std::istream& m_input;
    std::string m_name;
    const InputBuffer* m_source;
    Vec3 m_offset;
    std::size_t m_line = 0;
};

/// Where a reader hands each frame as it is read; false stops the reading.
using FrameSink = std::function<bool(ParticleFile&&)>;

/// Index of the first header name in `names`, or -1.
int find_column(const std::vector<std::string>& header, std::initializer_list<const char*> names) {
    for (const char* name : names) {
        const auto it = std::find(header.begin(), header.end(), name);
        if (it != header.end())
            return static_cast<int>(it - header.begin());
    }
    return -1;
}

/// Column indices of x, y, z and the size (-1: none, the radius given), from a header.
struct Columns {
    int x = -1, y = -1, z = -1, size = -1;
    bool is_diameter = false;
    std::string size_name = "radius";
};

constexpr const char* missing_size =
    "missing column 'r'; needed: x, y, z and r, radius, d or diameter, or give the diameter "
    "(--diameter)";

Columns columns_of(const std::vector<std::string>& header, const LineReader& in,
                   std::initializer_list<const char*> xs, std::initializer_list<const char*> ys,
                   std::initializer_list<const char*> zs, bool radius_given,
                   std::string_view names = "x, y, z") {
    Columns c;
    c.x = find_column(header, xs);
    c.y = find_column(header, ys);
    c.z = find_column(header, zs);
    c.size = find_column(header, {"r", "radius"});
    if (c.size < 0) {
        c.size = find_column(header, {"d", "diameter"});
        c.is_diameter = c.size >= 0;
    }
    const char* missing = c.x < 0   ? *xs.begin()
                          : c.y < 0 ? *ys.begin()
                          : c.z < 0 ? *zs.begin()
                                    : nullptr;
    if (missing)
        in.fail(fmt::format("missing column '{}'; needed: {} and r, radius, d or diameter", missing,
                            names));
    if (c.size < 0 && !radius_given)
        in.fail(missing_size);
    if (c.size >= 0)
        c.size_name = header[static_cast<std::size_t>(c.size)];
    return c;
}

/// A delimited table (see ParticleFormat::csv): one frame.
void read_table(LineReader& in, const ReadOptions& options, const FrameSink& sink) {
    ParticleFile out;
    out.format = ParticleFormat::csv;
    std::string line;
    if (!in.next(line))
        in.fail_file("empty file; expected a header line such as x,y,z,r");
    const char sep = separator_of(line);
    FieldSplitter splitter(sep);
    std::vector<std::string> header;
    for (const auto f : splitter.split(line))
        header.push_back(lower(f));
    const Columns c =
        columns_of(header, in, {"x", "points:0", "points_0"}, {"y", "points:1", "points_1"},
                   {"z", "points:2", "points_2"}, options.radius.has_value());
    // An orientation per particle: the four quaternion columns, or none of them.
    const std::array<int, 4> q{find_column(header, {"qw"}), find_column(header, {"qx"}),
                               find_column(header, {"qy"}), find_column(header, {"qz"})};
    const bool oriented = q[0] >= 0 && q[1] >= 0 && q[2] >= 0 && q[3] >= 0;
    if (!oriented && (q[0] >= 0 || q[1] >= 0 || q[2] >= 0 || q[3] >= 0))
        in.fail("some of the columns qw, qx, qy, qz but not all; allowed: all four (an "
                "orientation per particle) or none");
    std::string decimal; // a field with its decimal comma turned into a point
    auto number = [&](std::string_view field, const std::string& column) {
        if (sep == ';' && field.find(',') != std::string_view::npos) {
            decimal.assign(field);
            std::replace(decimal.begin(), decimal.end(), ',', '.');
            if (is_number(decimal))
                return in.number(decimal, column);
        }
        return in.number(field, column);
    };
    while (in.next(line)) {
        const auto& fields = splitter.split(line);
        if (fields.size() != header.size())
            in.fail(fmt::format("{} fields; the header has {}", fields.size(), header.size()));
        auto at = [&](int k) { return fields[static_cast<std::size_t>(k)]; };
        auto name = [&](int k) -> const std::string& {
            return header[static_cast<std::size_t>(k)];
        };
        const double size = c.size >= 0 ? number(at(c.size), name(c.size)) : *options.radius;
        in.add(out, number(at(c.x), name(c.x)), number(at(c.y), name(c.y)),
               number(at(c.z), name(c.z)), size, c.is_diameter, c.size_name);
        if (oriented) {
            Quaternion o{number(at(q[0]), "qw"), number(at(q[1]), "qx"), number(at(q[2]), "qy"),
                         number(at(q[3]), "qz")};
            const double length = std::sqrt(o.w * o.w + o.x * o.x + o.y * o.y + o.z * o.z);
            if (!(std::abs(length - 1.0) <= 1e-3))
                in.fail(fmt::format("the quaternion ({}, {}, {}, {}) has norm {}; allowed: a "
                                    "unit quaternion (norm 1 within 1e-3)",
                                    o.w, o.x, o.y, o.z, length));
            out.packing.orientations.push_back(
                {o.w / length, o.x / length, o.y / length, o.z / length});
        }
    }
    if (out.packing.size() == 0)
        in.fail_file("no spheres after the header");
    sink(std::move(out));
}

/// XYZ: frames of a count line, a comment line and the spheres.
void read_xyz(LineReader& in, const ReadOptions& options, const FrameSink& sink) {
    std::string line;
    if (!in.next(line))
        in.fail_file("empty file; expected the number of spheres on the first line");
    for (std::size_t frame = 1;; ++frame) {
        const std::size_t count_line = in.line_number();
        const std::size_t count = in.count(in.number(trim(line), "count"), "the count", 0);
        if (!in.raw(line)) // the comment line, which may be blank
            in.fail_file("ends after the count line; expected a comment line and the spheres");
        ParticleFile out;
        out.format = ParticleFormat::xyz;
        out.frame = frame;
        while (out.packing.size() < count && in.next(line)) {
            const auto f = split_spaces(line);
            if (f.size() == 4 && !options.radius)
                in.fail("no radius column (name x y z) and no radius given; allowed: name x y z "
                        "radius, or give the diameter (--diameter)");
            if (f.size() != 4 && f.size() != 5)
                in.fail(fmt::format("{} fields; allowed: name x y z [radius]", f.size()));
            const double radius = f.size() == 5 ? in.number(f[4], "radius") : *options.radius;
            in.add(out, in.number(f[1], "x"), in.number(f[2], "y"), in.number(f[3], "z"), radius,
                   false, "radius");
        }
        if (out.packing.size() < count)
            in.fail_file(
                fmt::format("{}declares {} spheres but holds {}",
                            frame == 1 ? "" : fmt::format("frame {} (line {}) ", frame, count_line),
                            count, out.packing.size()));
        if (!sink(std::move(out)) || !in.next(line))
            return;
        // The count line of the next frame, or one line too many.
        const auto f = split_spaces(line);
        if (f.size() != 1 || !is_number(f[0]))
            in.fail(frame == 1 ? fmt::format("more lines than the {} spheres the first line "
                                             "declares",
                                             count)
                               : fmt::format("more lines than the {} spheres the count on line {} "
                                             "declares",
                                             count, count_line));
    }
}

/// The box of a dump snapshot (ITEM: BOX BOUNDS and its three lines), parsed only when scaled
/// coordinates need it.
struct DumpBox {
    std::string flags; ///< what follows BOX BOUNDS ("ff ff ff", "xy xz yz pp pp pp", ...)
    std::array<std::string, 3> text;
    std::array<std::size_t, 3> lines{};
    std::size_t item_line = 0; ///< the line of ITEM: BOX BOUNDS
};

/// x = origin + xs a + ys b + zs c: the map from scaled to box coordinates.
struct BoxMap {
    Vec3 origin, a, b, c;
};

/// The LAMMPS formulas (Howto_triclinic): a dump writes the bounding box of a triclinic box
/// (xlo_bound = xlo + min(0, xy, xz, xy + xz), ...) with the tilts xy, xz, yz.
BoxMap box_map(const DumpBox& box, const LineReader& in) {
    const bool general = box.flags.find("abc") != std::string::npos;
    if (general)
        in.fail_at(box.item_line,
                   "a general triclinic box (ITEM: BOX BOUNDS abc origin) with scaled "
                   "coordinates is not supported; allowed: an orthogonal or restricted triclinic "
                   "box (xy xz yz), or dump x y z (xu yu zu)");
    const bool triclinic = box.flags.find("xy xz yz") != std::string::npos;
    std::array<std::array<double, 3>, 3> v{};
    for (int k = 0; k < 3; ++k) {
        const auto f = split_spaces(box.text[static_cast<std::size_t>(k)]);
        const std::size_t want = triclinic ? 3 : 2;
        if (f.size() != want)
            in.fail_at(box.lines[static_cast<std::size_t>(k)],
                       fmt::format("{} values in a line of ITEM: BOX BOUNDS{}; allowed: {}",
                                   f.size(), triclinic ? " xy xz yz" : "",
                                   triclinic ? "lo hi tilt" : "lo hi"));
        for (std::size_t i = 0; i < want; ++i) {
            const double value = parse_number(f[i]).value_or(std::nan(""));
            if (!(std::abs(value) <= limits::max_length))
                in.fail_at(box.lines[static_cast<std::size_t>(k)],
                           fmt::format("box bound '{}' is not allowed; allowed: a number from "
                                       "{:g} to {:g}",
                                       printable(f[i].substr(0, 40)), -limits::max_length,
                                       limits::max_length));
            v[static_cast<std::size_t>(k)][i] = value;
        }
    }
    const double xy = triclinic ? v[0][2] : 0.0;
    const double xz = triclinic ? v[1][2] : 0.0;
    const double yz = triclinic ? v[2][2] : 0.0;
    const double xlo = v[0][0] - std::min({0.0, xy, xz, xy + xz});
    const double xhi = v[0][1] - std::max({0.0, xy, xz, xy + xz});
    const double ylo = v[1][0] - std::min(0.0, yz);
    const double yhi = v[1][1] - std::max(0.0, yz);
    const double zlo = v[2][0], zhi = v[2][1];
    for (const auto& [lo, hi, k] : {std::tuple{xlo, xhi, 0}, {ylo, yhi, 1}, {zlo, zhi, 2}})
        if (!(lo < hi))
            in.fail_at(box.lines[static_cast<std::size_t>(k)],
                       fmt::format("the box is empty along {} (lo {} >= hi {}); allowed: lo < hi",
                                   "xyz"[k], lo, hi));
    return {{xlo, ylo, zlo}, {xhi - xlo, 0.0, 0.0}, {xy, yhi - ylo, 0.0}, {xz, yz, zhi - zlo}};
}

/// LAMMPS/LIGGGHTS text dump: one frame per ITEM: ATOMS section.
void read_lammps_dump(LineReader& in, const ReadOptions& options, const FrameSink& sink) {
    std::string line;
    std::size_t atoms = 0;
    bool have_count = false; // ITEM: NUMBER OF ATOMS seen in this snapshot
    std::optional<long long> timestep;
    std::optional<DumpBox> box;
    std::size_t frame = 0;
    if (!in.next(line))
        in.fail_file("empty file; expected a LAMMPS dump starting with ITEM: TIMESTEP");
    do {
        const auto t = trim(line);
        if (t.rfind("ITEM:", 0) != 0)
            in.fail(fmt::format("expected an ITEM: line, found '{}'", printable(t.substr(0, 40))));
        const std::string item(trim(t.substr(5))); // a copy: `line` is read over below
        if (item == "TIMESTEP") {
            if (!in.next(line))
                in.fail_file("ends after ITEM: TIMESTEP");
            timestep = parse_whole<long long>(trim(line)); // a dump's TIMESTEP
            if (!timestep || *timestep < 0)
                in.fail(fmt::format("ITEM: TIMESTEP '{}' is not allowed; allowed: a whole number "
                                    ">= 0",
                                    printable(trim(line).substr(0, 40))));
            have_count = false; // a new snapshot: its own count and box
            box.reset();
        } else if (item.rfind("NUMBER OF ATOMS", 0) == 0) {
            if (!in.next(line))
                in.fail_file("ends after ITEM: NUMBER OF ATOMS");
            // 0: a frame before particles were inserted
            atoms = in.count(in.number(trim(line), "NUMBER OF ATOMS"), "the number of atoms", 0);
            have_count = true;
        } else if (item.rfind("BOX BOUNDS", 0) == 0) {
            DumpBox& b = box.emplace();
            b.flags = item.substr(10);
            b.item_line = in.line_number();
            for (std::size_t k = 0; k < 3; ++k) {
                if (!in.next(line))
                    in.fail_file("ends inside ITEM: BOX BOUNDS");
                b.text[k] = line;
                b.lines[k] = in.line_number();
            }
        } else if (item.rfind("ATOMS", 0) == 0) {
            if (!have_count)
                in.fail("ITEM: ATOMS before ITEM: NUMBER OF ATOMS");
            const std::size_t count = atoms;
            std::vector<std::string> header;
            for (const auto f : split_spaces(std::string_view(item).substr(5)))
                header.push_back(lower(f));
            const bool scaled =
                find_column(header, {"x", "xu"}) < 0 && find_column(header, {"xs", "xsu"}) >= 0;
            const Columns c =
                scaled ? columns_of(header, in, {"xs", "xsu"}, {"ys", "ysu"}, {"zs", "zsu"},
                                    options.radius.has_value(), "xs, ys, zs (or xsu, ysu, zsu)")
                       : columns_of(header, in, {"x", "xu"}, {"y", "yu"}, {"z", "zu"},
                                    options.radius.has_value(),
                                    "x, y, z (or xu, yu, zu, or xs, ys, zs)");
            BoxMap map;
            if (scaled) {
                if (!box)
                    in.fail("scaled coordinates (xs ys zs) need the snapshot's ITEM: BOX BOUNDS; "
                            "allowed: a dump with its box before ITEM: ATOMS");
                map = box_map(*box, in);
            }
            ParticleFile out;
            out.format = ParticleFormat::lammps_dump;
            out.frame = ++frame;
            out.timestep = timestep;
            for (std::size_t k = 0; k < count; ++k) {
                if (!in.next(line))
                    in.fail_file(fmt::format("ends after {} of {} atoms", k, count));
                const auto f = split_spaces(line);
                if (f.size() != header.size())
                    in.fail(
                        fmt::format("{} fields; ITEM: ATOMS names {}", f.size(), header.size()));
                auto at = [&](int i) { return f[static_cast<std::size_t>(i)]; };
                auto name = [&](int i) { return header[static_cast<std::size_t>(i)]; };
                Vec3 p{in.number(at(c.x), name(c.x)), in.number(at(c.y), name(c.y)),
                       in.number(at(c.z), name(c.z))};
                if (scaled)
                    p = map.origin + map.a * p.x + map.b * p.y + map.c * p.z;
                const double size =
                    c.size >= 0 ? in.number(at(c.size), name(c.size)) : *options.radius;
                in.add(out, p.x, p.y, p.z, size, c.is_diameter, c.size_name);
            }
            if (!sink(std::move(out)))
                return;
        } else if (!in.next(line)) { // other one-value items (UNITS, TIME)
            in.fail_file(fmt::format("ends after ITEM: {}", printable(item.substr(0, 40))));
        }
    } while (in.next(line));
}

/// LAMMPS/LIGGGHTS data file: the header's atom count and the Atoms section.
void read_lammps_data(LineReader& in, const ReadOptions& options, const FrameSink& sink) {
    std::string line;
    if (!in.raw(line)) // the title line: any text
        in.fail_file("empty file; expected a LAMMPS data file (a title line, the header with "
                     "'N atoms', an Atoms section)");
    std::size_t atoms = 0;   // 0: no `N atoms` line yet
    bool in_section = false; // in a section other than Atoms (Masses, Velocities, ...)
    std::string style;
    for (;;) {
        if (!in.next(line))
            in.fail_file(atoms > 0 ? "no Atoms section; expected one after the header"
                                   : "no 'N atoms' line and no Atoms section; expected a LAMMPS "
                                     "data file");
        const auto f = split_spaces(before_comment(line));
        if (f.empty())
            continue;
        if (is_number(f[0])) {
            if (!in_section && f.size() == 2 && f[1] == "atoms")
                atoms = in.count(in.number(f[0], "atoms"), "the number of atoms", 1);
            continue; // other header lines (atom types, xlo xhi, ...), section contents
        }
        if (f[0] != "Atoms") { // another section: skipped
            in_section = true;
            continue;
        }
        if (atoms == 0)
            in.fail("Atoms section before the header's 'N atoms' line; allowed: a LAMMPS data "
                    "file");
        const auto hash = line.find('#');
        if (hash != std::string::npos) {
            const auto words = split_spaces(std::string_view(line).substr(hash + 1));
            if (!words.empty())
                style = lower(words[0]);
        }
        break;
    }
    const bool atomic = style == "atomic";
    if (!(style.empty() || style == "sphere" || style == "granular" || atomic))
        in.fail(fmt::format("atom style '{}' is not supported; allowed: sphere or granular (id "
                            "type diameter density x y z), or atomic (id type x y z) with the "
                            "diameter given",
                            printable(std::string_view(style).substr(0, 40))));
    if (atomic && !options.radius)
        in.fail("atom style atomic has no diameter column; allowed: give the diameter "
                "(--diameter), or atom style sphere or granular");
    ParticleFile out;
    out.format = ParticleFormat::lammps_data;
    const std::size_t columns = atomic ? 5 : 7; // + 3 image flags
    for (std::size_t k = 0; k < atoms; ++k) {
        if (!in.next(line))
            in.fail_file(fmt::format("ends after {} of {} atoms", k, atoms));
        const auto f = split_spaces(before_comment(line));
        if (f.size() != columns && f.size() != columns + 3)
            in.fail(fmt::format("{} fields in the Atoms section; allowed: {} or {} ({})", f.size(),
                                columns, columns + 3,
                                atomic ? "id type x y z [ix iy iz]"
                                       : "id type diameter density x y z [ix iy iz]"));
        const std::size_t x = atomic ? 2 : 4;
        if (!atomic)
            in.number(f[3], "density");
        in.add(out, in.number(f[x], "x"), in.number(f[x + 1], "y"), in.number(f[x + 2], "z"),
               atomic ? *options.radius : in.number(f[2], "diameter"), !atomic,
               atomic ? "radius" : "diameter");
    }
    sink(std::move(out));
}

/// The extension that tells the format: that of the name without a trailing .gz.
std::string extension_of(const fs::path& path) {
    const std::string ext = lower(path.extension().string());
    return ext == ".gz" ? lower(path.stem().extension().string()) : ext;
}

/// Read every frame of `input` as `format`, handing each to `sink` until it returns false.
void read_frames(std::istream& input, std::string_view name, ParticleFormat format,
                 const ReadOptions& options, const FrameSink& sink) {
    InputBuffer buffer(input, options.max_bytes);
    std::istream text(&buffer);
    LineReader in(text, name, &buffer, {options.axis[0], options.axis[1], options.floor});
    switch (format) {
    case ParticleFormat::csv:
        return read_table(in, options, sink);
    case ParticleFormat::xyz:
        return read_xyz(in, options, sink);
    case ParticleFormat::lammps_dump:
        return read_lammps_dump(in, options, sink);
    case ParticleFormat::lammps_data:
        return read_lammps_data(in, options, sink);
    }
    in.fail_file("unknown format");
}

/// Refuse options out of range.
void check_options(const ReadOptions& o) {
    if (o.radius &&
        !(*o.radius >= 0.5 * limits::min_diameter && *o.radius <= 0.5 * limits::max_diameter))
        throw InvalidInput(fmt::format("radius = {} is not allowed; allowed: a radius from {:g} to "
                                       "{:g} (half a diameter)",
                                       *o.radius, 0.5 * limits::min_diameter,
                                       0.5 * limits::max_diameter));
    for (const auto& [value, what] :
         {std::pair{o.axis[0], "axis x"}, {o.axis[1], "axis y"}, {o.floor, "floor"}})
        if (!(std::abs(value) <= limits::max_length))
            throw InvalidInput(fmt::format("{} = {} is not allowed; allowed: a number from {:g} "
                                           "to {:g}",
                                           what, value, -limits::max_length, limits::max_length));
}

/// "the file has 3 frames; allowed: 1 to 3, or -1 to -3 from the end"
std::string frames_allowed(std::size_t frames) {
    if (frames == 1)
        return "the file has 1 frame; allowed: 1 or -1";
    return fmt::format("the file has {} frames; allowed: 1 to {}, or -1 to -{} counting from the "
                       "end",
                       frames, frames, frames);
}

/// The frame `wanted` (> 0) of the input; `frames` is set to how many were read.
std::optional<ParticleFile> frame_at(std::istream& input, std::string_view name,
                                     ParticleFormat format, const ReadOptions& options,
                                     std::size_t wanted, std::size_t& frames) {
    std::optional<ParticleFile> found;
    frames = 0;
    read_frames(input, name, format, options, [&](ParticleFile&& f) {
        if (++frames != wanted)
            return true;
        found = std::move(f);
        return false;
    });
    return found;
}

} // namespace

namespace {

/// Whether the first lines of `text` hold the `N atoms` line of a LAMMPS data file header.
bool has_atoms_line(LineReader& in, std::string& line) {
    for (int k = 0; k < 10 && in.next(line); ++k) {
        const auto f = split_spaces(before_comment(line));
        if (f.size() == 2 && f[1] == "atoms" && is_number(f[0]))
            return true;
        if (!f.empty() && f[0] == "Atoms")
            return false;
    }
    return false;
}

/// Whether a table header names x, y and z.
bool names_xyz(std::string_view header) {
    FieldSplitter splitter(separator_of(header));
    std::vector<std::string> names;
    for (const auto f : splitter.split(header))
        names.push_back(lower(f));
    return find_column(names, {"x", "points:0", "points_0"}) >= 0 &&
           find_column(names, {"y", "points:1", "points_1"}) >= 0 &&
           find_column(names, {"z", "points:2", "points_2"}) >= 0;
}

/// The format from the extension or, failing that, the first lines of `file` (which is then
/// read again from its start).
ParticleFormat detect(std::istream& file, const fs::path& path, std::uint64_t max_bytes) {
    const std::string ext = extension_of(path);
    if (ext == ".csv" || ext == ".tsv")
        return ParticleFormat::csv;
    if (ext == ".xyz")
        return ParticleFormat::xyz;
    if (ext == ".dump" || ext == ".lammpstrj")
        return ParticleFormat::lammps_dump;
    if (ext == ".data")
        return ParticleFormat::lammps_data;
    std::optional<ParticleFormat> format;
    {
        InputBuffer buffer(file, max_bytes);
        std::istream text(&buffer);
        LineReader in(text, path.native(), &buffer);
        std::string line;
        if (!in.next(line))
            in.fail_file("empty file");
        const std::string first(trim(line));
        if (first.rfind("ITEM:", 0) == 0)
            format = ParticleFormat::lammps_dump;
        else if (first.find_first_not_of("0123456789") == std::string::npos)
            format = ParticleFormat::xyz;
        else {
            // A data file: a title line (read above, or skipped as blank or a comment; it may
            // say anything, "x y z" too), then the header with `N atoms`. Else a table.
            const bool header = names_xyz(first);
            const auto f = split_spaces(before_comment(first));
            if ((f.size() == 2 && f[1] == "atoms" && is_number(f[0])) || has_atoms_line(in, line))
                format = ParticleFormat::lammps_data;
            else if (header)
                format = ParticleFormat::csv;
        }
        if (!format)
            in.fail_at(1, "cannot tell the format; allowed: .csv, .tsv, .xyz, .dump, .lammpstrj "
                          "or .data files (also .gz), or a table whose header names x, y and z");
    }
    file.clear();
    file.seekg(0);
    return *format;
}

} // namespace

ParticleFormat detect_particle_format(const std::filesystem::path& path) {
    std::ifstream file = open_regular_file("", path);
    record_input("the particles file", path);
    return detect(file, path, limits::max_decompressed_bytes);
}

ParticleFile read_particles(std::istream& input, std::string_view name, ParticleFormat format,
                            const ReadOptions& options) {
    check_options(options);
    const std::string shown = printable(name);
    const long long wanted = options.frame;
    if (wanted == 0)
        throw InvalidInput(fmt::format("{}: frame 0 is not allowed; allowed: 1 (the first), 2, "
                                       "... or -1 (the last), -2, ...",
                                       shown));
    std::size_t frames = 0;
    std::optional<ParticleFile> found;
    if (wanted > 0) {
        found = frame_at(input, name, format, options, static_cast<std::size_t>(wanted), frames);
    } else if (wanted == -1) {
        read_frames(input, name, format, options, [&](ParticleFile&& f) {
            ++frames;
            found = std::move(f);
            return true;
        });
    } else { // counted from the end: count the frames, then read again up to that one
        const auto start = input.tellg();
        if (start == std::istream::pos_type(-1))
            throw InvalidInput(fmt::format("{}: frame {} counts from the end of an input that "
                                           "cannot be read twice; allowed: a regular file, or -1",
                                           shown, wanted));
        read_frames(input, name, format, options, [&](ParticleFile&&) {
            ++frames;
            return true;
        });
        if (static_cast<unsigned long long>(-wanted) <= frames) {
            input.clear();
            input.seekg(start);
            std::size_t again = 0;
            found = frame_at(input, name, format, options,
                             frames + 1 - static_cast<std::size_t>(-wanted), again);
        }
    }
    if (!found) {
        if (frames == 0) // a dump without ITEM: ATOMS (the other formats have a frame or fail)
            throw InvalidInput(fmt::format(
                "{}: no spheres in the last snapshot (or no ITEM: ATOMS section)", shown));
        throw InvalidInput(
            fmt::format("{}: frame {} is not allowed: {}", shown, wanted, frames_allowed(frames)));
    }
    if (found->packing.size() == 0) {
        if (wanted == -1)
            throw InvalidInput(fmt::format("{}: no spheres in the last {}", shown,
                                           found->format == ParticleFormat::xyz
                                               ? "frame"
                                               : "snapshot (or no ITEM: ATOMS section)"));
        throw InvalidInput(fmt::format(
            "{}: frame {}{} has no spheres; allowed: a frame with spheres", shown, found->frame,
            found->timestep ? fmt::format(" (timestep {})", *found->timestep) : std::string()));
    }
    return std::move(*found);
}

ParticleFile read_particles(const std::filesystem::path& path, const ReadOptions& options) {
    check_options(options);
    std::ifstream file = open_regular_file("", path);
    record_input("the particles file", path);
    const ParticleFormat format =
        options.format ? *options.format : detect(file, path, options.max_bytes);
    return read_particles(file, path.native(), format, options);
}

void for_each_particle_frame(std::istream& input, std::string_view name, ParticleFormat format,
                             const ReadOptions& options,
                             const std::function<void(ParticleFile&&)>& visit) {
    check_options(options);
    std::size_t frames = 0;
    read_frames(input, name, format, options, [&](ParticleFile&& f) {
        if (++frames > limits::max_frames)
            throw InvalidInput(fmt::format("{}: more than {} frames; allowed: at most that many "
                                           "(read one with the frame number)",
                                           printable(name), limits::max_frames));
        visit(std::move(f));
        return true;
    });
    if (frames == 0)
        throw InvalidInput(fmt::format("{}: no frame (no ITEM: ATOMS section)", printable(name)));
}

void for_each_particle_frame(const std::filesystem::path& path, const ReadOptions& options,
                             const std::function<void(ParticleFile&&)>& visit) {
    check_options(options);
    std::ifstream file = open_regular_file("", path);
    record_input("the particles file", path);
    const ParticleFormat format =
        options.format ? *options.format : detect(file, path, options.max_bytes);
    for_each_particle_frame(file, path.native(), format, options, visit);
}

namespace {

/// Collect frames, within limits::max_spheres in all.
std::function<void(ParticleFile&&)> collect(std::vector<ParticleFile>& frames,
                                            std::string_view name) {
    return [&frames, shown = printable(name), total = std::size_t{0}](ParticleFile&& f) mutable {
        total += f.packing.size();
        if (total > limits::max_spheres)
            throw InvalidInput(fmt::format("{}: more than {} spheres in all frames together; "
                                           "allowed: at most that many (read them one at a time)",
                                           shown, limits::max_spheres));
        frames.push_back(std::move(f));
    };
}

} // namespace

std::vector<ParticleFile> read_particle_frames(std::istream& input, std::string_view name,
                                               ParticleFormat format, const ReadOptions& options) {
    std::vector<ParticleFile> frames;
    for_each_particle_frame(input, name, format, options, collect(frames, name));
    return frames;
}

std::vector<ParticleFile> read_particle_frames(const std::filesystem::path& path,
                                               const ReadOptions& options) {
    std::vector<ParticleFile> frames;
    for_each_particle_frame(path, options, collect(frames, path.native()));
    return frames;
}

BedSummary read_bed_summary(std::istream& input, std::string_view name) {
    const std::string shown = printable(name);
    std::string text;
    char buffer[1 << 16];
    while (input.read(buffer, sizeof buffer) || input.gcount() > 0) {
        text.append(buffer, static_cast<std::size_t>(input.gcount()));
        if (text.size() > limits::max_small_file)
            throw InvalidInput(fmt::format("{}: larger than {} bytes; allowed: a summary.json up "
                                           "to that size",
                                           shown, limits::max_small_file));
    }
    const ParsedJson parsed = parse_json(text);
    if (!parsed.error.empty())
        throw InvalidInput(fmt::format("{}: not a summary.json ({}); allowed: the summary.json of "
                                       "packbed generate, lattice or analyze",
                                       shown, parsed.error));
    return read_bed_summary(parsed.value, name);
}

BedSummary read_bed_summary(const nlohmann::json& json, std::string_view name) {
    const std::string shown = printable(name);
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
                                           shown, path, json_excerpt(v, 40), high,
                                           porosity ? ")" : "]"));
        return value;
    };
    if (json.contains("container"))
        out.container_radius =
            number(json["container"], "radius", "container.radius", limits::max_length);
    out.diameter = number(json, "diameter", "diameter", limits::max_diameter);
    out.period_z = number(json, "period_z", "period_z", limits::max_length);
    out.sauter_mean = json.contains("sizes") && json["sizes"].is_object();
    if (out.sauter_mean && json["sizes"].contains("statistics")) {
        const nlohmann::json& statistics = json["sizes"]["statistics"];
        const auto smallest =
            number(statistics, "smallest", "sizes.statistics.smallest", limits::max_diameter);
        const auto largest =
            number(statistics, "largest", "sizes.statistics.largest", limits::max_diameter);
        if (smallest && largest) {
            if (!(*largest >= *smallest))
                throw InvalidInput(fmt::format(
                    "{}: sizes.statistics.largest = {} is not allowed; allowed: at least "
                    "sizes.statistics.smallest = {}",
                    shown, *largest, *smallest));
            out.size_range = std::pair{*smallest, *largest};
        }
    }
    // The container, read back by its shape (Container::summary_json's record; a lattice
    // without a container record: its region's, region_json).
    for (const char* key : {"container", "region"}) {
        const auto record = json.find(key);
        if (record == json.end() || !record->is_object() ||
            (!record->contains("shape") && !record->contains("radius")))
            continue;
        const ContainerRecord read = container_from_record(*record);
        if (!read.container)
            throw InvalidInput(fmt::format("{}: {} {} is not allowed; allowed: {}", shown, key,
                                           json_excerpt(*record, 80), read.allowed));
        out.container = read.container;
        break;
    }
    if (json.contains("lattice")) {
        out.porosity = number(json["lattice"], "porosity", "lattice.porosity", 1.0);
        const auto type = json.find("type");
        if (out.porosity)
            out.porosity_source = fmt::format("the porosity of the {} lattice",
                                              type != json.end() && type->is_string()
                                                  ? printable(type->get<std::string>())
                                                  : "?");
        const auto keep = json.find("keep");
        out.centres_kept = keep != json.end() && *keep == "centres";
    }
    // A sphere bed's friction and wall friction under its parameters, a pellet bed's beside
    // its shape.
    const auto parameters = json.find("parameters");
    const auto coefficient = [&](const char* key) -> std::optional<double> {
        const bool of_spheres =
            parameters != json.end() && parameters->is_object() && parameters->contains(key);
        const bool of_pellets = !of_spheres && json.contains("shape") && json.contains(key);
        if (!of_spheres && !of_pellets)
            return std::nullopt;
        const nlohmann::json& v = of_spheres ? (*parameters)[key] : json[key];
        const double value = v.is_number() ? v.get<double>() : std::nan("");
        if (!(value >= 0.0 && value <= 100.0))
            throw InvalidInput(
                fmt::format("{}: {}{} = {} is not allowed; allowed: a number in [0, 100]", shown,
                            of_spheres ? "parameters." : "", key, json_excerpt(v, 40)));
        return value;
    };
    out.friction = coefficient("friction");
    out.wall_friction = coefficient("wall_friction");
    if (const auto shape = json.find("shape"); shape != json.end() && shape->is_object()) {
        const auto spec = shape->find("spec");
        if (spec == shape->end() || !spec->is_string() || spec->get<std::string>().empty() ||
            spec->get<std::string>().size() > 200)
            throw InvalidInput(fmt::format("{}: shape {} is not allowed; allowed: a record with "
                                           "the spec packbed generate --shape was given",
                                           shown, json_excerpt(*shape, 80)));
        out.shape = spec->get<std::string>();
    }
    if (!out.porosity) {
        out.porosity = number(json, "void_fraction", "void_fraction", 1.0);
        if (out.porosity)
            out.porosity_source = "the overall void fraction";
    }
    // A bed written without a generation of its own (Python's Bed.write of a bed read or made
    // from arrays): the void fraction of the analysis beside it.
    if (const auto analysis = json.find("analysis");
        !out.porosity && analysis != json.end() && analysis->is_object()) {
        out.porosity = number(*analysis, "void_fraction", "analysis.void_fraction", 1.0);
        if (out.porosity)
            out.porosity_source = "the overall void fraction of its analysis";
    }
    return out;
}

BedSummary read_bed_summary(const std::filesystem::path& path) {
    std::istringstream text(read_small_file("", path, limits::max_small_file));
    record_input("the bed's summary", path);
    return read_bed_summary(text, path.native());
}

const Registry<std::optional<ParticleFormat>>& particle_formats() {
    static const Registry<std::optional<ParticleFormat>> names(
        "format", {{"auto", std::nullopt},
                   {"csv", ParticleFormat::csv},
                   {"xyz", ParticleFormat::xyz},
                   {"lammps-dump", ParticleFormat::lammps_dump},
                   {"lammps-data", ParticleFormat::lammps_data}});
    return names;
}

} // namespace packbed
