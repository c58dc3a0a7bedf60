// Reading beds from tables (CSV, ParaView, ;/tab/space separated), XYZ, LAMMPS dumps and data
// files, plain or gzip-compressed, one frame or all: the same spheres from every format, and
// each bad file refused with its line and reason.
#include <sys/resource.h>
#include <sys/stat.h>
#include <zlib.h>

#include <array>
#include <filesystem>
#include <fstream>
#include <sstream>

#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include "packbed/container.hpp"
#include "packbed/error.hpp"
#include "packbed/io.hpp"
#include "packbed/read.hpp"

using namespace packbed;
namespace fs = std::filesystem;

namespace {

fs::path write(const std::string& name, const std::string& text) {
    const fs::path dir = fs::temp_directory_path() / "packbed-test-read";
    fs::create_directories(dir);
    std::ofstream(dir / name) << text;
    return dir / name;
}

/// Three spheres, the reference every format must reproduce.
Packing reference() {
    Packing p;
    p.add({0.1, -0.25, 0.5}, 0.5);
    p.add({1.125, 0.0, 0.5}, 0.5);
    p.add({0.5, 0.75, 1.3}, 0.25);
    return p;
}

void expect_reference(const ParticleFile& f) {
    const Packing ref = reference();
    ASSERT_EQ(f.packing.size(), ref.size());
    for (std::size_t i = 0; i < ref.size(); ++i) {
        EXPECT_EQ(f.packing.centers[i], ref.centers[i]) << i;
        EXPECT_EQ(f.packing.radii[i], ref.radii[i]) << i;
    }
}

/// The message of the InvalidInput that reading `text` as `format` throws.
std::string error_of(const std::string& text, ParticleFormat format, ReadOptions options = {}) {
    std::istringstream in(text);
    try {
        read_particles(in, "bed", format, options);
    } catch (const InvalidInput& e) {
        return e.what();
    }
    return "no error";
}

} // namespace

TEST(ReadParticles, EveryFormatGivesTheSameSpheres) {
    expect_reference(read_particles(write("a.csv", "x,y,z,r\n0.1,-0.25,0.5,0.5\n"
                                                   "1.125,0,0.5,0.5\n0.5,0.75,1.3,0.25\n")));
    expect_reference(read_particles(write("b.csv", "id, X, Y, Z, d, type\n# comment\n"
                                                   "1, 0.1, -0.25, 0.5, 1, 1\n"
                                                   "2, 1.125, 0, 0.5, 1, 1\n\n"
                                                   "3, 0.5, 0.75, 1.3, 0.5, 2\n")));
    expect_reference(read_particles(write("c.xyz", "3\n\nC 0.1 -0.25 0.5 0.5\n"
                                                   "C 1.125 0 0.5 0.5\nC 0.5 0.75 1.3 0.25\n")));
    // Two snapshots: the last one is read.
    const std::string dump = "ITEM: TIMESTEP\n0\nITEM: NUMBER OF ATOMS\n3\n"
                             "ITEM: BOX BOUNDS ff ff ff\n-2 2\n-2 2\n0 3\n"
                             "ITEM: ATOMS id type x y z diameter\n"
                             "1 1 9 9 9 1\n2 1 8 8 8 1\n3 1 7 7 7 1\n"
                             "ITEM: TIMESTEP\n1000\nITEM: NUMBER OF ATOMS\n3\n"
                             "ITEM: BOX BOUNDS ff ff ff\n-2 2\n-2 2\n0 3\n"
                             "ITEM: ATOMS id type x y z diameter\n"
                             "1 1 0.1 -0.25 0.5 1\n2 1 1.125 0 0.5 1\n3 1 0.5 0.75 1.3 0.5\n";
    const auto f = read_particles(write("d.dump", dump));
    expect_reference(f);
    EXPECT_EQ(f.format, ParticleFormat::lammps_dump);
    EXPECT_EQ(f.lines, (std::vector<std::size_t>{22, 23, 24}));
    // XYZ without radius column, radius given.
    std::istringstream xyz("3\ncomment\nC 0.1 -0.25 0.5\nC 1.125 0 0.5\nC 0.5 0.75 1.3\n");
    const auto g =
        read_particles(xyz, "e.xyz", ParticleFormat::xyz, {.radius = 0.5, .format = std::nullopt});
    EXPECT_EQ(g.packing.radii[2], 0.5);
    EXPECT_EQ(g.packing.centers[2], reference().centers[2]);
}

TEST(ReadParticles, OrientationsFromTheFourQuaternionColumns) {
    // What generate --shape writes: x,y,z,r,qw,qx,qy,qz; a norm within 1e-3 of 1 is made 1.
    const auto f = read_particles(write("q.csv", "x,y,z,r,qw,qx,qy,qz\n0,0,1,0.5,1,0,0,0\n"
                                                 "1,0,1,0.5,0,0.6,0.8,0\n"
                                                 "2,0,1,0.5,0.5005,0.5,0.5,0.5\n"));
    ASSERT_EQ(f.packing.orientations.size(), 3u);
    EXPECT_EQ(f.packing.orientations[1].x, 0.6);
    EXPECT_EQ(f.packing.orientations[1].y, 0.8);
    const Quaternion& q = f.packing.orientations[2];
    EXPECT_NEAR(q.w * q.w + q.x * q.x + q.y * q.y + q.z * q.z, 1.0, 1e-15);
    // Without them: none.
    EXPECT_TRUE(
        read_particles(write("n.csv", "x,y,z,r\n0,0,1,0.5\n")).packing.orientations.empty());
    // Some of the four, or a quaternion that is not a rotation: refused, naming the line.
    EXPECT_NE(error_of("x,y,z,r,qw,qx\n0,0,1,0.5,1,0\n", ParticleFormat::csv)
                  .find(":1: some of the columns qw, qx, qy, qz but not all"),
              std::string::npos);
    EXPECT_NE(error_of("x,y,z,r,qw,qx,qy,qz\n0,0,1,0.5,1,0.1,0,0\n", ParticleFormat::csv)
                  .find(":2: the quaternion (1, 0.1, 0, 0) has norm 1.00498"),
              std::string::npos);
}

TEST(ReadParticles, EmptyFirstFrameAndByteOrderMark) {
    // LIGGGHTS writes a frame with 0 atoms before the particles are inserted.
    std::istringstream dump(
        "ITEM: TIMESTEP\n0\nITEM: NUMBER OF ATOMS\n0\n"
        "ITEM: BOX BOUNDS ff ff ff\n-2 2\n-2 2\n0 3\nITEM: ATOMS id x y z radius\n"
        "ITEM: TIMESTEP\n100\nITEM: NUMBER OF ATOMS\n1\n"
        "ITEM: BOX BOUNDS ff ff ff\n-2 2\n-2 2\n0 3\nITEM: ATOMS id x y z radius\n"
        "1 0.5 0 0.5 0.5\n");
    const auto f = read_particles(dump, "d", ParticleFormat::lammps_dump);
    ASSERT_EQ(f.packing.size(), 1u);
    EXPECT_EQ(f.packing.centers[0], (Vec3{0.5, 0, 0.5}));
    EXPECT_EQ(error_of("ITEM: TIMESTEP\n0\nITEM: NUMBER OF ATOMS\n0\nITEM: ATOMS id x y z radius\n",
                       ParticleFormat::lammps_dump),
              "bed: no spheres in the last snapshot (or no ITEM: ATOMS section)");
    // An XYZ trajectory may start empty too, as a dump's; its last frame must have spheres.
    std::istringstream xyz("0\nempty\n1\nsecond\nC 0.5 0 0.5 0.5\n");
    const auto g = read_particles(xyz, "x", ParticleFormat::xyz);
    ASSERT_EQ(g.packing.size(), 1u);
    EXPECT_EQ(g.frame, 2u);
    EXPECT_EQ(error_of("0\nempty\n", ParticleFormat::xyz), "bed: no spheres in the last frame");
    // A CSV saved by a spreadsheet may start with a UTF-8 byte-order mark.
    std::istringstream bom("\xEF\xBB\xBFx,y,z,r\n1,2,3,0.5\n");
    EXPECT_EQ(read_particles(bom, "b", ParticleFormat::csv).packing.size(), 1u);
}

TEST(ReadParticles, FormatFromExtensionOrFirstLine) {
    EXPECT_EQ(detect_particle_format(write("f.lammpstrj", "")), ParticleFormat::lammps_dump);
    EXPECT_EQ(detect_particle_format(write("f.txt", "ITEM: TIMESTEP\n0\n")),
              ParticleFormat::lammps_dump);
    EXPECT_EQ(detect_particle_format(write("g.txt", "x,y,z,r\n")), ParticleFormat::csv);
    EXPECT_EQ(detect_particle_format(write("h.txt", "12\n")), ParticleFormat::xyz);
    EXPECT_THROW(detect_particle_format(write("i.txt", "hello world\n")), InvalidInput);
}

struct BadFile {
    ParticleFormat format;
    const char* text;
    const char* message;
};

void PrintTo(const BadFile& b, std::ostream* os) {
    *os << b.message;
}

class ReadParticlesBadFile : public ::testing::TestWithParam<BadFile> {};

TEST_P(ReadParticlesBadFile, RefusedWithLineAndReason) {
    EXPECT_EQ(error_of(GetParam().text, GetParam().format), GetParam().message);
}

INSTANTIATE_TEST_SUITE_P(
    Cases, ReadParticlesBadFile,
    ::testing::Values(
        BadFile{ParticleFormat::csv, "", "bed: empty file; expected a header line such as x,y,z,r"},
        BadFile{ParticleFormat::csv, "x,y,z,r\n", "bed: no spheres after the header"},
        BadFile{ParticleFormat::csv, "x,y,r\n1,2,3\n",
                "bed:1: missing column 'z'; needed: x, y, z and r, radius, d or diameter"},
        BadFile{ParticleFormat::csv, "x,y,z\n1,2,3\n",
                "bed:1: missing column 'r'; needed: x, y, z and r, radius, d or diameter, or give "
                "the diameter (--diameter)"},
        BadFile{ParticleFormat::csv, "x,y,z,r\n1,2,3,0.5\n1,2,3\n",
                "bed:3: 3 fields; the header has 4"},
        BadFile{ParticleFormat::csv, "x,y,z,r\n1,abc,3,0.5\n",
                "bed:2: column 'y' value 'abc' is not a number"},
        BadFile{ParticleFormat::csv, "x,y,z,r\n1,,3,0.5\n",
                "bed:2: column 'y' is empty; a number is needed"},
        BadFile{ParticleFormat::csv, "x,y,z,r\n1,2,nan,0.5\n",
                "bed:2: column 'z' value 'nan' is not a finite number"},
        BadFile{
            ParticleFormat::csv, "x,y,z,r\n1,2,3,-0.5\n",
            "bed:2: column 'r' value -0.5 is not allowed; a radius must be from 5e-13 to 5e+11"},
        BadFile{ParticleFormat::csv, "x,y,z,diameter\n1,2,3,0\n",
                "bed:2: column 'diameter' value 0 is not allowed; a diameter must be from 1e-12 to "
                "1e+12"},
        // A diameter whose half is 0 (found by fuzzing: 5e-324 halved is 0).
        BadFile{ParticleFormat::csv, "x,y,z,diameter\n1,2,3,5e-324\n",
                "bed:2: column 'diameter' value 5e-324 is not allowed; a diameter must be from "
                "1e-12 to 1e+12"},
        BadFile{ParticleFormat::xyz, "3\n\nC 0 0 0 0.5\n", "bed: declares 3 spheres but holds 1"},
        BadFile{ParticleFormat::xyz, "1\n\nC 0 0 0 0.5\nC 1 1 1 0.5\n",
                "bed:4: more lines than the 1 spheres the first line declares"},
        BadFile{ParticleFormat::xyz, "1\n\nC 0 0 0\n",
                "bed:3: no radius column (name x y z) and no radius given; allowed: name x y z "
                "radius, or give the diameter (--diameter)"},
        BadFile{ParticleFormat::xyz, "two\n", "bed:1: column 'count' value 'two' is not a number"},
        BadFile{ParticleFormat::lammps_dump,
                "ITEM: TIMESTEP\n0\nITEM: NUMBER OF ATOMS\n2\nITEM: ATOMS id xs ys zs radius\n",
                "bed:5: scaled coordinates (xs ys zs) need the snapshot's ITEM: BOX BOUNDS; "
                "allowed: a dump with its box before ITEM: ATOMS"},
        BadFile{ParticleFormat::lammps_dump,
                "ITEM: TIMESTEP\n0\nITEM: NUMBER OF ATOMS\n2\nITEM: ATOMS id x y z radius\n"
                "1 0 0 0 0.5\n",
                "bed: ends after 1 of 2 atoms"},
        BadFile{ParticleFormat::lammps_dump,
                "ITEM: TIMESTEP\n0\nITEM: NUMBER OF ATOMS\n1\nITEM: ATOMS id x y z\n1 0 0 0\n",
                "bed:5: missing column 'r'; needed: x, y, z and r, radius, d or diameter, or give "
                "the diameter (--diameter)"},
        BadFile{ParticleFormat::lammps_dump, "",
                "bed: empty file; expected a LAMMPS dump starting with ITEM: TIMESTEP"},
        // The audit's cases: undefined behaviour before (a float-to-integer overflow, then
        // "0 spheres"; a message read from a line already overwritten).
        BadFile{ParticleFormat::xyz, "1e308\n\n",
                "bed:1: the count 1e+308 is not allowed; allowed: a whole number from 0 to "
                "100000000"},
        BadFile{ParticleFormat::lammps_dump, "ITEM: TIMESTEP\n0\nITEM: NUMBER OF ATOMS\n1e20\n",
                "bed:4: the number of atoms 1e+20 is not allowed; allowed: a whole number from 0 "
                "to 100000000"},
        BadFile{ParticleFormat::lammps_dump,
                "ITEM: TIMESTEP WITH A LONG NAME, LONGER THAN THE SMALL-STRING BUFFER\n"
                "# a comment line longer still, so that reading it reallocates the line buffer\n",
                "bed: ends after ITEM: TIMESTEP WITH A LONG NAME, LONGER THAN T"},
        // Control characters and long fields are shown escaped and cut: one line.
        BadFile{ParticleFormat::csv, "x,y,z,r\n1,\x1b[2J\x1b[H,3,0.5\n",
                "bed:2: column 'y' value '\\x1b[2J\\x1b[H' is not a number"},
        BadFile{ParticleFormat::lammps_dump, "ITEM:\x1b]0;pwned\x07\n",
                "bed: ends after ITEM: \\x1b]0;pwned\\x07"},
        // Coordinates where a double no longer resolves a sphere are refused.
        BadFile{ParticleFormat::csv, "x,y,z,r\n1,2,1e300,0.5\n",
                "bed:2: z = 1e+300 is not allowed; allowed: a coordinate from -1e+15 to 1e+15"}));

TEST(ReadParticles, LinesAndFilesAreBounded) {
    // A line longer than limits::max_line_length (1 MiB): refused at that length, not read whole.
    EXPECT_EQ(error_of("x,y,z,r\n" + std::string(3 << 20, '1') + "\n", ParticleFormat::csv),
              "bed:2: a line longer than 1048576 bytes; allowed: lines up to that length (is this "
              "a text file?)");
    EXPECT_EQ(error_of(std::string(2 << 20, '\0'), ParticleFormat::xyz),
              "bed:1: a line longer than 1048576 bytes; allowed: lines up to that length (is this "
              "a text file?)");
    // Not regular files: refused at once, where a FIFO waited for a writer for ever and
    // /dev/zero filled memory.
    const fs::path dir = write("placeholder", "").parent_path();
    const fs::path fifo = dir / "bed.fifo";
    fs::remove(fifo);
    ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
    for (const fs::path& path : {fifo, fs::path("/dev/zero"), dir, fs::path("/proc/self/mem")}) {
        try {
            read_particles(path);
            ADD_FAILURE() << path << " was read";
        } catch (const InvalidInput& e) {
            EXPECT_NE(std::string(e.what()).find("; allowed: a readable regular file"),
                      std::string::npos)
                << e.what();
        }
    }
}

TEST(ReadBedSummary, ContainerAndPorosityOrARefusalNamingTheKey) {
    auto read = [](const std::string& text) {
        std::istringstream in(text);
        return read_bed_summary(in, "summary.json");
    };
    auto error = [&](const std::string& text) {
        try {
            read(text);
        } catch (const InvalidInput& e) {
            return std::string(e.what());
        }
        return std::string("accepted");
    };
    const BedSummary bed = read(R"({"container": {"shape": "cylinder", "radius": 2.5},
                                    "void_fraction": 0.41})");
    EXPECT_EQ(bed.container_radius, 2.5);
    EXPECT_EQ(bed.porosity, 0.41);
    EXPECT_EQ(bed.porosity_source, "the overall void fraction");
    EXPECT_FALSE(bed.diameter);
    ASSERT_TRUE(bed.container);
    EXPECT_EQ(bed.container->spec(), "cylinder:5");
    // A lattice in a box: its region, no container record.
    const BedSummary boxed = read(R"({"region": {"shape": "box", "size": [4, 5, 6.5]}})");
    ASSERT_TRUE(boxed.container);
    EXPECT_EQ(boxed.container->spec(), "box:4,5");
    EXPECT_FALSE(boxed.container_radius);
    EXPECT_EQ(error(R"({"region": {"shape": "box", "size": [4, -5, 6]}})"),
              "summary.json: region {\"shape\":\"box\",\"size\":[4,-5,6]} is not allowed; "
              "allowed: box: size, two numbers in (0, 1e+15] (three in a lattice's region)");
    // Every shape reads back what it records, to the bit; an unknown one is refused.
    for (const char* spec :
         {"cylinder:2.5", "box:3,4.5", "annulus:10,2", "periodic:6,6", "cone:6.1,14.3,40.7"}) {
        const Container c = *parse_container(spec);
        const nlohmann::json record = {{"container", c.summary_json()}};
        const BedSummary back = read(record.dump());
        ASSERT_TRUE(back.container) << spec;
        EXPECT_EQ(back.container->spec_numbers(), c.spec_numbers()) << spec;
    }
    EXPECT_EQ(error(R"({"container": {"shape": "sphere", "radius": 2}})"),
              "summary.json: container {\"radius\":2,\"shape\":\"sphere\"} is not allowed; "
              "allowed: a shape of cylinder, box, annulus, periodic, cone");
    const BedSummary lattice =
        read(R"({"type": "diamond", "diameter": 0.002, "lattice": {"porosity": 0.66}})");
    EXPECT_EQ(lattice.diameter, 0.002);
    EXPECT_FALSE(lattice.container_radius);
    EXPECT_EQ(lattice.porosity, 0.66);
    EXPECT_EQ(lattice.porosity_source, "the porosity of the diamond lattice");
    EXPECT_FALSE(read(R"({"void_fraction": null})").porosity); // a bed too short to measure
    EXPECT_EQ(error(R"({"container": {"radius": -1}})"),
              "summary.json: container.radius = -1 is not allowed; allowed: a number in (0, "
              "1e+15]");
    EXPECT_EQ(error(R"({"container": {"radius": "2"}})"),
              "summary.json: container.radius = \"2\" is not allowed; allowed: a number in (0, "
              "1e+15]");
    EXPECT_EQ(error(R"({"diameter": 0})"),
              "summary.json: diameter = 0 is not allowed; allowed: a number in (0, 1e+12]");
    EXPECT_EQ(error(R"({"void_fraction": 1.5})"),
              "summary.json: void_fraction = 1.5 is not allowed; allowed: a number in (0, 1)");
    EXPECT_EQ(error("[[[[").substr(0, 30), "summary.json: not a summary.js");
    EXPECT_EQ(error("[1, 2]"), "summary.json: not a summary.json (not a JSON object); allowed: "
                               "the summary.json of packbed generate, lattice or analyze");
    // Deep nesting is refused where it is read, not a stack overflow when a value is shown in a
    // message, compared or destroyed: at the top, under a key quoted in messages, in an object.
    const std::string deep = "summary.json: not a summary.json (nested deeper than 64 levels); "
                             "allowed: the summary.json of packbed generate, lattice or analyze";
    EXPECT_EQ(error(std::string(100000, '[') + std::string(100000, ']')), deep);
    EXPECT_EQ(error("{\"diameter\": " + std::string(100000, '[') + std::string(100000, ']') + "}"),
              deep);
    std::string objects;
    for (int k = 0; k < 100000; ++k)
        objects += "{\"a\":";
    EXPECT_EQ(error("{\"container\": " + objects + "1" + std::string(100000, '}') + "}"), deep);
    // 64 levels are read; a value shown in a message is cut short whatever its size.
    EXPECT_EQ(error("{\"diameter\": " + std::string(63, '[') + std::string(63, ']') + "}"),
              "summary.json: diameter = " + std::string(40, '[') +
                  "... is not allowed; allowed: a number in (0, 1e+12]");
    EXPECT_EQ(error("{\"diameter\": \"" + std::string(1000000, 'x') + "\"}"),
              "summary.json: diameter = \"" + std::string(39, 'x') +
                  "... is not allowed; allowed: a number in (0, 1e+12]");
}

// ---------------------------------------------------------------------------------------------
// Files that do not fit the next tool: what DEM users have.

namespace {

/// `text` compressed as one gzip member (zlib's deflate with a gzip header).
std::string gzip(const std::string& text) {
    z_stream z{};
    EXPECT_EQ(
        deflateInit2(&z, Z_BEST_COMPRESSION, Z_DEFLATED, 16 + MAX_WBITS, 8, Z_DEFAULT_STRATEGY),
        Z_OK);
    std::string out(deflateBound(&z, static_cast<uLong>(text.size())) + 64, '\0');
    z.next_in = reinterpret_cast<Bytef*>(const_cast<char*>(text.data()));
    z.avail_in = static_cast<uInt>(text.size());
    z.next_out = reinterpret_cast<Bytef*>(out.data());
    z.avail_out = static_cast<uInt>(out.size());
    EXPECT_EQ(deflate(&z, Z_FINISH), Z_STREAM_END);
    out.resize(z.total_out);
    deflateEnd(&z);
    return out;
}

ReadOptions radius_of(double radius) {
    ReadOptions o;
    o.radius = radius;
    return o;
}

ReadOptions frame_of(long long frame) {
    ReadOptions o;
    o.frame = frame;
    return o;
}

ParticleFile read_text(const std::string& text, ParticleFormat format, ReadOptions options = {}) {
    std::istringstream in(text);
    return read_particles(in, "bed", format, options);
}

std::string frames_error(const std::string& text, ParticleFormat format) {
    std::istringstream in(text);
    try {
        read_particle_frames(in, "bed", format);
    } catch (const InvalidInput& e) {
        return e.what();
    }
    return "no error";
}

/// A dump snapshot with the given ATOMS columns, box lines and atom lines.
std::string snapshot(long long step, const std::string& box_flags, const std::string& box,
                     const std::string& columns, const std::vector<std::string>& atoms) {
    std::string s = "ITEM: TIMESTEP\n" + std::to_string(step) + "\nITEM: NUMBER OF ATOMS\n" +
                    std::to_string(atoms.size()) + "\nITEM: BOX BOUNDS " + box_flags + "\n" + box +
                    "ITEM: ATOMS " + columns + "\n";
    for (const auto& a : atoms)
        s += a + "\n";
    return s;
}

} // namespace

TEST(ReadDump, ScaledCoordinatesAreUnscaledWithTheSnapshotsBox) {
    // x = xlo + xs (xhi - xlo): box [-2, 2] x [-1, 3] x [0, 10].
    const auto f =
        read_text(snapshot(5, "ff ff ff", "-2 2\n-1 3\n0 10\n", "id type xs ys zs radius",
                           {"1 1 0.25 0.5 0.125 0.5", "2 1 1 0 0.5 0.25"}),
                  ParticleFormat::lammps_dump);
    ASSERT_EQ(f.packing.size(), 2u);
    EXPECT_EQ(f.packing.centers[0], (Vec3{-1.0, 1.0, 1.25}));
    EXPECT_EQ(f.packing.centers[1], (Vec3{2.0, -1.0, 5.0}));
    EXPECT_EQ(f.packing.radii[1], 0.25);
    EXPECT_EQ(f.lines, (std::vector<std::size_t>{10, 11}));
    EXPECT_EQ(f.timestep, 5);
    // Unwrapped scaled coordinates (xsu ysu zsu) may lie outside [0, 1].
    const auto u = read_text(snapshot(0, "pp pp ff", "-2 2\n-1 3\n0 10\n",
                                      "id xsu ysu zsu diameter", {"1 1.25 -0.25 0.5 1"}),
                             ParticleFormat::lammps_dump);
    EXPECT_EQ(u.packing.centers[0], (Vec3{3.0, -2.0, 5.0}));
    EXPECT_EQ(u.packing.radii[0], 0.5);
    // Unscaled columns win where both are written.
    const auto both = read_text(snapshot(0, "ff ff ff", "-2 2\n-1 3\n0 10\n",
                                         "id x y z xs ys zs radius", {"1 7 8 9 0 0 0 0.5"}),
                                ParticleFormat::lammps_dump);
    EXPECT_EQ(both.packing.centers[0], (Vec3{7.0, 8.0, 9.0}));
}

TEST(ReadDump, TriclinicBoxesByTheLammpsFormulas) {
    // The box xlo 0, xhi 4, ylo 0, yhi 2, zlo 0, zhi 8 with tilts xy 1, xz -0.5, yz 0.25, written
    // as its bounding box: xlo_bound = xlo + min(0, xy, xz, xy + xz) = -0.5, xhi_bound = xhi +
    // max(0, xy, xz, xy + xz) = 5, ylo_bound = 0, yhi_bound = 2.25.
    const auto f = read_text(snapshot(0, "xy xz yz ff ff ff", "-0.5 5 1\n0 2.25 -0.5\n0 8 0.25\n",
                                      "id xs ys zs radius", {"1 0.5 0.5 0.25 0.5", "2 0 0 0 0.5"}),
                             ParticleFormat::lammps_dump);
    ASSERT_EQ(f.packing.size(), 2u);
    // x = xlo + xs lx + ys xy + zs xz = 2 + 0.5 - 0.125; y = ylo + ys ly + zs yz; z = zs lz
    EXPECT_EQ(f.packing.centers[0], (Vec3{2.375, 1.0625, 2.0}));
    EXPECT_EQ(f.packing.centers[1], (Vec3{0.0, 0.0, 0.0}));
    // Refusals: a general triclinic box, a box line that is not two (three) numbers, an empty
    // box, scaled coordinates without a box.
    EXPECT_EQ(
        error_of(snapshot(0, "abc origin pp pp pp", "1 0 0 0\n0 1 0 0\n0 0 1 0\n",
                          "id xs ys zs radius", {"1 0.5 0.5 0.5 0.5"}),
                 ParticleFormat::lammps_dump),
        "bed:5: a general triclinic box (ITEM: BOX BOUNDS abc origin) with scaled coordinates "
        "is not supported; allowed: an orthogonal or restricted triclinic box (xy xz yz), or "
        "dump x y z (xu yu zu)");
    EXPECT_EQ(error_of(snapshot(0, "xy xz yz ff ff ff", "-0.5 5\n0 2.25 -0.5\n0 8 0.25\n",
                                "id xs ys zs radius", {"1 0.5 0.5 0.5 0.5"}),
                       ParticleFormat::lammps_dump),
              "bed:6: 2 values in a line of ITEM: BOX BOUNDS xy xz yz; allowed: lo hi tilt");
    EXPECT_EQ(error_of(snapshot(0, "ff ff ff", "-2 2\n-1 abc\n0 10\n", "id xs ys zs radius",
                                {"1 0.5 0.5 0.5 0.5"}),
                       ParticleFormat::lammps_dump),
              "bed:7: box bound 'abc' is not allowed; allowed: a number from -1e+15 to 1e+15");
    EXPECT_EQ(error_of(snapshot(0, "ff ff ff", "-2 2\n3 3\n0 10\n", "id xs ys zs radius",
                                {"1 0.5 0.5 0.5 0.5"}),
                       ParticleFormat::lammps_dump),
              "bed:7: the box is empty along y (lo 3 >= hi 3); allowed: lo < hi");
    // Unscaled coordinates do not need the box: a general triclinic one is skipped.
    EXPECT_EQ(read_text(snapshot(0, "abc origin pp pp pp", "1 0 0 0\n0 1 0 0\n0 0 1 0\n",
                                 "id x y z radius", {"1 0.5 0.5 0.5 0.5"}),
                        ParticleFormat::lammps_dump)
                  .packing.centers[0],
              (Vec3{0.5, 0.5, 0.5}));
    // A scaled column missing.
    EXPECT_EQ(error_of(snapshot(0, "ff ff ff", "-2 2\n-1 3\n0 10\n", "id xs ys radius",
                                {"1 0.5 0.5 0.5"}),
                       ParticleFormat::lammps_dump),
              "bed:9: missing column 'zs'; needed: xs, ys, zs (or xsu, ysu, zsu) and r, radius, d "
              "or diameter");
}

TEST(ReadDump, NoSizeColumnTakesTheDiameterGiven) {
    const std::string dump =
        snapshot(0, "ff ff ff", "-2 2\n-2 2\n0 3\n", "id type x y z", {"1 1 0.5 0 0.5"});
    EXPECT_EQ(error_of(dump, ParticleFormat::lammps_dump),
              "bed:9: missing column 'r'; needed: x, y, z and r, radius, d or diameter, or give "
              "the diameter (--diameter)");
    const auto f = read_text(dump, ParticleFormat::lammps_dump, radius_of(0.125));
    EXPECT_EQ(f.packing.radii, (std::vector<double>{0.125}));
    EXPECT_EQ(f.packing.centers[0], (Vec3{0.5, 0.0, 0.5}));
    // A size column wins over the diameter given.
    const auto g = read_text(
        snapshot(0, "ff ff ff", "-2 2\n-2 2\n0 3\n", "id x y z diameter", {"1 0.5 0 0.5 0.75"}),
        ParticleFormat::lammps_dump, radius_of(0.125));
    EXPECT_EQ(g.packing.radii, (std::vector<double>{0.375}));
    // So do tables without r or d.
    const auto t = read_text("x,y,z,type\n1,2,3,1\n", ParticleFormat::csv, radius_of(2.5));
    EXPECT_EQ(t.packing.radii, (std::vector<double>{2.5}));
    EXPECT_EQ(t.packing.centers[0], (Vec3{1.0, 2.0, 3.0}));
    // The radius given must be one a diameter allows.
    EXPECT_EQ(error_of("x,y,z\n1,2,3\n", ParticleFormat::csv, radius_of(1e-20)),
              "radius = 1e-20 is not allowed; allowed: a radius from 5e-13 to 5e+11 (half a "
              "diameter)");
}

TEST(ReadGzip, CompressedFilesReadAsTheirText) {
    const std::string csv = "x,y,z,r\n0.1,-0.25,0.5,0.5\n1.125,0,0.5,0.5\n0.5,0.75,1.3,0.25\n";
    // By path: .gz after any extension; the format from the extension before it.
    const fs::path path = write("bed.csv.gz", gzip(csv));
    EXPECT_EQ(detect_particle_format(path), ParticleFormat::csv);
    const auto f = read_particles(path);
    expect_reference(f);
    EXPECT_EQ(f.lines, (std::vector<std::size_t>{2, 3, 4}));
    // A name without an extension under .gz: the format from the decompressed first line.
    const std::string dump =
        snapshot(7, "ff ff ff", "-2 2\n-2 2\n0 3\n", "id x y z radius", {"1 0.5 0 0.5 0.5"});
    const fs::path bare = write("bed.gz", gzip(dump));
    EXPECT_EQ(detect_particle_format(bare), ParticleFormat::lammps_dump);
    EXPECT_EQ(read_particles(bare).timestep, 7);
    // From a stream, recognised by gzip's first bytes; several members (cat a.gz b.gz) in turn.
    const auto two = read_text(gzip("x,y,z,r\n0.1,-0.25,0.5,0.5\n") +
                                   gzip("1.125,0,0.5,0.5\n0.5,0.75,1.3,0.25\n"),
                               ParticleFormat::csv);
    expect_reference(two);
    // A file larger than 256 KiB decompressed (several output buffers).
    std::string big = "x,y,z,r\n";
    for (int i = 0; i < 20000; ++i)
        big += "0.000000000,0.000000000," + std::to_string(i) + ".5,0.5\n";
    const auto b = read_text(gzip(big), ParticleFormat::csv);
    ASSERT_EQ(b.packing.size(), 20000u);
    EXPECT_EQ(b.packing.centers[19999], (Vec3{0.0, 0.0, 19999.5}));
    EXPECT_EQ(b.lines.back(), 20001u);
}

TEST(ReadGzip, CorruptTruncatedAndBombsAreRefused) {
    const std::string csv = "x,y,z,r\n0.1,-0.25,0.5,0.5\n1.125,0,0.5,0.5\n0.5,0.75,1.3,0.25\n";
    const std::string gz = gzip(csv);
    // Cut short: refused, not read as the spheres before the cut.
    EXPECT_EQ(error_of(gz.substr(0, gz.size() - 10), ParticleFormat::csv),
              "bed: the gzip data ends early (a truncated .gz file?); allowed: a complete gzip "
              "file");
    // A changed byte: the CRC or the deflate data no longer match.
    std::string corrupt = gz;
    corrupt[corrupt.size() - 6] ^= 0x55; // in the CRC-32 of the trailer
    EXPECT_EQ(error_of(corrupt, ParticleFormat::csv),
              "bed: not valid gzip data (zlib: incorrect data check); allowed: a complete gzip "
              "file");
    // Bytes after the last member that are not another one.
    EXPECT_EQ(error_of(gz + "trailing", ParticleFormat::csv),
              "bed: not valid gzip data (zlib: incorrect header check); allowed: a complete gzip "
              "file");
    // A zip bomb: refused once more than max_bytes have come out (here 1 MB of blank lines,
    // compressed to about 1 kB, against a limit of 100 000 bytes).
    const std::string bomb = gzip("x,y,z,r\n" + std::string(1 << 20, '\n'));
    EXPECT_LT(bomb.size(), 2000u);
    ReadOptions small;
    small.max_bytes = 100000;
    EXPECT_EQ(error_of(bomb, ParticleFormat::csv, small),
              "bed: more than 100000 bytes once decompressed; allowed: a gzip file of at most that "
              "many bytes of text");
    EXPECT_EQ(limits::max_decompressed_bytes, 17179869184u);
    // What a reader keeps stays in proportion to the file: 1e6 identical rows (10 MB) compress
    // to about 10 kB, refused once they expand 100 times their compressed bytes; a lattice's
    // text (its coordinates repeat, about 16 times) is read.
    std::string rows = "x y z r\n";
    for (int k = 0; k < 1000000; ++k)
        rows += "0 0 0 0.5\n";
    const std::string identical = gzip(rows);
    EXPECT_LT(identical.size(), 40000u);
    EXPECT_NE(error_of(identical, ParticleFormat::csv)
                  .find("bed: expands more than 100 times when decompressed ("),
              std::string::npos);
    std::string lattice = "x,y,z,r\n";
    for (int i = 0; i < 40; ++i)
        for (int j = 0; j < 40; ++j)
            for (int k = 0; k < 40; ++k)
                lattice += std::to_string(i) + ".5," + std::to_string(j) + ".5," +
                           std::to_string(k) + ".5,0.5\n";
    EXPECT_EQ(read_text(gzip(lattice), ParticleFormat::csv).packing.size(), 64000u);
    // Plain text has no such limit (its lines and spheres have theirs).
    EXPECT_EQ(read_text(csv + std::string(200000, '\n'), ParticleFormat::csv, small).packing.size(),
              3u);
}

TEST(ReadFrames, XyzFramesTheLastByDefaultOrTheOneAsked) {
    const std::string xyz = "2\nframe 1\nC 0 0 1 0.5\nC 0 0 2 0.5\n"
                            "1\nframe 2\nC 0 0 3 0.5\n"
                            "3\n\nC 0 0 4 0.5\nC 0 0 5 0.5\nC 0 0 6 0.5\n";
    auto z_of = [](const ParticleFile& f) {
        std::vector<double> z;
        for (const Vec3& c : f.packing.centers)
            z.push_back(c.z);
        return z;
    };
    const auto last = read_text(xyz, ParticleFormat::xyz);
    EXPECT_EQ(z_of(last), (std::vector<double>{4, 5, 6}));
    EXPECT_EQ(last.frame, 3u);
    EXPECT_EQ(last.lines, (std::vector<std::size_t>{10, 11, 12}));
    EXPECT_FALSE(last.timestep);
    EXPECT_EQ(z_of(read_text(xyz, ParticleFormat::xyz, frame_of(1))), (std::vector<double>{1, 2}));
    const auto second = read_text(xyz, ParticleFormat::xyz, frame_of(2));
    EXPECT_EQ(z_of(second), (std::vector<double>{3}));
    EXPECT_EQ(second.frame, 2u);
    EXPECT_EQ(second.lines, (std::vector<std::size_t>{7}));
    // Counted from the end: -1 the last, -3 the first.
    EXPECT_EQ(z_of(read_text(xyz, ParticleFormat::xyz, frame_of(-2))), (std::vector<double>{3}));
    const auto first = read_text(xyz, ParticleFormat::xyz, frame_of(-3));
    EXPECT_EQ(z_of(first), (std::vector<double>{1, 2}));
    EXPECT_EQ(first.frame, 1u);
    // Past the end, either way, and 0.
    EXPECT_EQ(error_of(xyz, ParticleFormat::xyz, frame_of(4)),
              "bed: frame 4 is not allowed: the file has 3 frames; allowed: 1 to 3, or -1 to -3 "
              "counting from the end");
    EXPECT_EQ(error_of(xyz, ParticleFormat::xyz, frame_of(-4)),
              "bed: frame -4 is not allowed: the file has 3 frames; allowed: 1 to 3, or -1 to -3 "
              "counting from the end");
    EXPECT_EQ(error_of(xyz, ParticleFormat::xyz, frame_of(0)),
              "bed: frame 0 is not allowed; allowed: 1 (the first), 2, ... or -1 (the last), -2, "
              "...");
    // One-frame formats: 1 and -1.
    EXPECT_EQ(error_of("x,y,z,r\n1,2,3,0.5\n", ParticleFormat::csv, frame_of(2)),
              "bed: frame 2 is not allowed: the file has 1 frame; allowed: 1 or -1");
    // A frame that holds fewer spheres than its count, or a line that is neither a sphere nor
    // a next count.
    EXPECT_EQ(error_of("1\n\nC 0 0 1 0.5\n2\n\nC 0 0 2 0.5\n", ParticleFormat::xyz),
              "bed: frame 2 (line 4) declares 2 spheres but holds 1");
    EXPECT_EQ(error_of("1\n\nC 0 0 1 0.5\n1\n\nC 0 0 2 0.5\nC 0 0 3 0.5\n", ParticleFormat::xyz),
              "bed:7: more lines than the 1 spheres the count on line 4 declares");
    EXPECT_EQ(error_of("1\n\nC 0 0 1 0.5\n1.5\n\nC 0 0 2 0.5\n", ParticleFormat::xyz),
              "bed:4: the count 1.5 is not allowed; allowed: a whole number from 0 to 100000000");
    // The frame asked for is read; the rest of the file is not (a broken later frame).
    EXPECT_EQ(read_text("1\n\nC 0 0 1 0.5\n2\n\nC 0 0 2 x\n", ParticleFormat::xyz, frame_of(1))
                  .packing.size(),
              1u);
}

TEST(ReadFrames, DumpSnapshotsAndTheWholeSeries) {
    const std::string box = "-2 2\n-2 2\n0 3\n";
    const std::string dump =
        snapshot(0, "ff ff ff", box, "id x y z radius", {}) +
        snapshot(100, "ff ff ff", box, "id x y z radius", {"1 0 0 0.5 0.5"}) +
        snapshot(200, "ff ff ff", box, "id x y z radius", {"1 0 0 0.5 0.5", "2 0 0 1.5 0.5"});
    // All frames, the empty one too, with their timesteps and lines.
    std::istringstream in(dump);
    const auto frames = read_particle_frames(in, "bed", ParticleFormat::lammps_dump);
    ASSERT_EQ(frames.size(), 3u);
    EXPECT_EQ(frames[0].packing.size(), 0u);
    EXPECT_EQ(frames[1].packing.size(), 1u);
    EXPECT_EQ(frames[2].packing.size(), 2u);
    for (std::size_t k = 0; k < 3; ++k) {
        EXPECT_EQ(frames[k].frame, k + 1);
        EXPECT_EQ(frames[k].timestep, static_cast<long long>(100 * k));
    }
    EXPECT_EQ(frames[1].lines, (std::vector<std::size_t>{19}));
    EXPECT_EQ(frames[2].lines, (std::vector<std::size_t>{29, 30}));
    EXPECT_EQ(frames[2].packing.centers[1], (Vec3{0.0, 0.0, 1.5}));
    // One frame: the last, or the one asked for; an empty one is refused.
    EXPECT_EQ(read_text(dump, ParticleFormat::lammps_dump).timestep, 200);
    EXPECT_EQ(read_text(dump, ParticleFormat::lammps_dump, frame_of(2)).timestep, 100);
    EXPECT_EQ(read_text(dump, ParticleFormat::lammps_dump, frame_of(-2)).timestep, 100);
    EXPECT_EQ(error_of(dump, ParticleFormat::lammps_dump, frame_of(1)),
              "bed: frame 1 (timestep 0) has no spheres; allowed: a frame with spheres");
    EXPECT_EQ(error_of(dump, ParticleFormat::lammps_dump, frame_of(9)),
              "bed: frame 9 is not allowed: the file has 3 frames; allowed: 1 to 3, or -1 to -3 "
              "counting from the end");
    // The series of a file: the same by path, through for_each_particle_frame one at a time.
    const fs::path path = write("series.dump", dump);
    std::vector<std::size_t> sizes;
    for_each_particle_frame(path, {}, [&](ParticleFile&& f) { sizes.push_back(f.packing.size()); });
    EXPECT_EQ(sizes, (std::vector<std::size_t>{0, 1, 2}));
    EXPECT_EQ(read_particle_frames(path).size(), 3u);
    // A timestep must be a whole number >= 0; a snapshot needs its own atom count.
    EXPECT_EQ(error_of("ITEM: TIMESTEP\n1.5\n", ParticleFormat::lammps_dump),
              "bed:2: ITEM: TIMESTEP '1.5' is not allowed; allowed: a whole number >= 0");
    EXPECT_EQ(error_of(snapshot(0, "ff ff ff", box, "id x y z radius", {"1 0 0 0.5 0.5"}) +
                           "ITEM: TIMESTEP\n1\nITEM: ATOMS id x y z radius\n1 0 0 0.5 0.5\n",
                       ParticleFormat::lammps_dump),
              "bed:13: ITEM: ATOMS before ITEM: NUMBER OF ATOMS");
    EXPECT_EQ(frames_error("ITEM: TIMESTEP\n0\n", ParticleFormat::lammps_dump),
              "bed: no frame (no ITEM: ATOMS section)");
}

TEST(ReadFrames, TheSeriesIsBounded) {
    // limits::max_frames frames are read, one more is refused (one sphere each: 1.4 MB).
    std::string xyz;
    for (std::size_t k = 0; k <= limits::max_frames; ++k)
        xyz += "1\n\nC 0 0 1 0.5\n";
    std::istringstream in(xyz);
    std::size_t seen = 0;
    try {
        for_each_particle_frame(in, "bed", ParticleFormat::xyz, {},
                                [&](ParticleFile&&) { ++seen; });
        ADD_FAILURE() << "read " << seen << " frames";
    } catch (const InvalidInput& e) {
        EXPECT_STREQ(e.what(), "bed: more than 100000 frames; allowed: at most that many (read "
                               "one with the frame number)");
    }
    EXPECT_EQ(seen, limits::max_frames);
    // One frame of such a file is read without the bound: the last.
    EXPECT_EQ(read_text(xyz, ParticleFormat::xyz).frame, limits::max_frames + 1);
}

TEST(ReadLammpsData, OurExportReadsBackTheSameSpheres) {
    const Packing ref = reference();
    const std::string data =
        lammps_data(ref, 2500.0, {{-1, -1, 0}, {2, 1, 2}}, "3 spheres (packbed export)");
    const fs::path path = write("bed.data", data);
    EXPECT_EQ(detect_particle_format(path), ParticleFormat::lammps_data);
    const auto f = read_particles(path);
    expect_reference(f);
    EXPECT_EQ(f.format, ParticleFormat::lammps_data);
    EXPECT_EQ(f.lines,
              (std::vector<std::size_t>{12, 13, 14})); // after "Atoms # sphere" and a blank
    // By its `N atoms` line under another name, and gzip-compressed.
    EXPECT_EQ(detect_particle_format(write("bed.txt", data)), ParticleFormat::lammps_data);
    expect_reference(read_particles(write("bed.data.gz", gzip(data))));
}

TEST(ReadLammpsData, LiggghtsStylesSectionsAndImageFlags) {
    // LIGGGHTS: no style comment (sphere assumed), other sections around Atoms, image flags,
    // comments.
    const std::string liggghts = "LIGGGHTS data file via write_data\n\n"
                                 "2 atoms\n1 atom types\n"
                                 "-1 1 xlo xhi\n-1 1 ylo yhi\n0 2 zlo zhi\n\n"
                                 "Masses\n\n1 1.0\n\n"
                                 "Atoms\n\n"
                                 "7 1 0.002 2500 0.25 -0.5 0.75 0 0 0\n"
                                 "3 1 0.004 2500 0 0 1.5 0 0 1 # a comment\n\n"
                                 "Velocities\n\n7 0 0 0 0 0 0\n3 0 0 0 0 0 0\n";
    const auto f = read_text(liggghts, ParticleFormat::lammps_data);
    ASSERT_EQ(f.packing.size(), 2u);
    EXPECT_EQ(f.packing.centers[0], (Vec3{0.25, -0.5, 0.75}));
    EXPECT_EQ(f.packing.radii[0], 0.001);
    EXPECT_EQ(f.packing.centers[1], (Vec3{0.0, 0.0, 1.5})); // image flags ignored
    EXPECT_EQ(f.packing.radii[1], 0.002);
    EXPECT_EQ(f.lines, (std::vector<std::size_t>{15, 16}));
    // atom_style atomic: no diameter, so the one given.
    const std::string atomic = "title\n\n1 atoms\n\nAtoms # atomic\n\n1 1 0.5 0.25 2\n";
    EXPECT_EQ(error_of(atomic, ParticleFormat::lammps_data),
              "bed:5: atom style atomic has no diameter column; allowed: give the diameter "
              "(--diameter), or atom style sphere or granular");
    const auto a = read_text(atomic, ParticleFormat::lammps_data, radius_of(0.25));
    EXPECT_EQ(a.packing.centers[0], (Vec3{0.5, 0.25, 2.0}));
    EXPECT_EQ(a.packing.radii[0], 0.25);
    // Refusals.
    EXPECT_EQ(error_of("title\n\n1 atoms\n\nAtoms # full\n\n1 1 1 0 0.5 0.25 2\n",
                       ParticleFormat::lammps_data),
              "bed:5: atom style 'full' is not supported; allowed: sphere or granular (id type "
              "diameter density x y z), or atomic (id type x y z) with the diameter given");
    EXPECT_EQ(error_of("title\n\n2 atoms\n\nAtoms # sphere\n\n1 1 1 2500 0 0 0.5\n",
                       ParticleFormat::lammps_data),
              "bed: ends after 1 of 2 atoms");
    EXPECT_EQ(error_of("title\n\n1 atoms\n\nAtoms # sphere\n\n1 1 1 2500 0 0\n",
                       ParticleFormat::lammps_data),
              "bed:7: 6 fields in the Atoms section; allowed: 7 or 10 (id type diameter density x "
              "y z [ix iy iz])");
    EXPECT_EQ(error_of("title\n\n1 atoms\n\nAtoms # sphere\n\n1 1 0 2500 0 0 0.5\n",
                       ParticleFormat::lammps_data),
              "bed:7: column 'diameter' value 0 is not allowed; a diameter must be from 1e-12 to "
              "1e+12");
    EXPECT_EQ(error_of("title\n\nAtoms\n\n1 1 1 2500 0 0 0.5\n", ParticleFormat::lammps_data),
              "bed:3: Atoms section before the header's 'N atoms' line; allowed: a LAMMPS data "
              "file");
    EXPECT_EQ(error_of("title\n\n1 atoms\n", ParticleFormat::lammps_data),
              "bed: no Atoms section; expected one after the header");
    EXPECT_EQ(error_of("title\n\n0 atoms\n", ParticleFormat::lammps_data),
              "bed:3: the number of atoms 0 is not allowed; allowed: a whole number from 1 to "
              "100000000");
    EXPECT_EQ(error_of("", ParticleFormat::lammps_data),
              "bed: empty file; expected a LAMMPS data file (a title line, the header with 'N "
              "atoms', an Atoms section)");
    EXPECT_EQ(error_of("title\n\n1 atoms\n\nAtoms # sphere\n\n1 1 1 2500 0 0 0.5\n",
                       ParticleFormat::lammps_data, frame_of(2)),
              "bed: frame 2 is not allowed: the file has 1 frame; allowed: 1 or -1");
}

TEST(ReadTables, ParaViewCsvExport) {
    // ParaView's File > Save Data (CSV) of a LIGGGHTS VTK: quoted names, the point coordinates
    // as Points:0..2, other arrays (diameter, Points_Magnitude) beside them.
    const std::string paraview =
        "\"id\",\"type\",\"diameter\",\"radius\",\"Points:0\",\"Points:1\",\"Points:2\","
        "\"Points_Magnitude\"\n"
        "1,1,1,0.5,0.1,-0.25,0.5,0.56\n2,1,1,0.5,1.125,0,0.5,1.23\n3,1,0.5,0.25,0.5,0.75,1.3,1.6\n";
    expect_reference(read_text(paraview, ParticleFormat::csv));
    EXPECT_EQ(detect_particle_format(write("paraview.txt", paraview)), ParticleFormat::csv);
    // Newer ParaView writes Points_0; only a diameter column: halved.
    expect_reference(read_text("\"Points_0\",\"Points_1\",\"Points_2\",\"diameter\"\n"
                               "0.1,-0.25,0.5,1\n1.125,0,0.5,1\n0.5,0.75,1.3,0.5\n",
                               ParticleFormat::csv));
    // A quoted field may hold the separator and "" for a quote.
    const auto q = read_text("\"name, with comma\",x,y,z,r\n\"a \"\"b\"\", c\",1,2,3,0.5\n",
                             ParticleFormat::csv);
    EXPECT_EQ(q.packing.centers[0], (Vec3{1.0, 2.0, 3.0}));
    // Quoted names in a space-separated table, a quoted name holding a space (a header with a
    // tab would make a tab-separated one).
    const auto w = read_text("  \"sphere id\"  \"x\" \"y\" \"z\" \"r\"\n 7  1 2\t3 0.5 \n",
                             ParticleFormat::csv);
    EXPECT_EQ(w.packing.centers[0], (Vec3{1.0, 2.0, 3.0}));
    EXPECT_EQ(w.packing.radii[0], 0.5);
}

TEST(ReadTables, SemicolonTabAndSpaceSeparated) {
    // A spreadsheet of a comma-decimal locale: ';' between fields, ',' in numbers.
    expect_reference(read_text("x;y;z;d\n0,1;-0,25;0,5;1\n1,125;0;0,5;1\n0,5;0,75;1,3;0,5\n",
                               ParticleFormat::csv));
    // ...or points.
    expect_reference(read_text("X; Y; Z; R\n0.1; -0.25; 0.5; 0.5\n1.125; 0; 0.5; 0.5\n"
                               "0.5; 0.75; 1.3; 0.25\n",
                               ParticleFormat::csv));
    // Tab-separated (an empty field between two tabs is empty, not skipped).
    expect_reference(read_text("id\tx\ty\tz\tr\n1\t0.1\t-0.25\t0.5\t0.5\n2\t1.125\t0\t0.5\t0.5\n"
                               "3\t0.5\t0.75\t1.3\t0.25\n",
                               ParticleFormat::csv));
    EXPECT_EQ(error_of("x\ty\tz\tr\n1\t\t3\t0.5\n", ParticleFormat::csv),
              "bed:2: column 'y' is empty; a number is needed");
    // White space: any run of spaces and tabs, aligned columns.
    const std::string table = "  x      y      z     r\n"
                              "  0.1   -0.25   0.5   0.5\n"
                              "  1.125  0      0.5   0.5\n"
                              "  0.5    0.75 \t1.3   0.25\n";
    expect_reference(read_text(table, ParticleFormat::csv));
    EXPECT_EQ(detect_particle_format(write("table.txt", table)), ParticleFormat::csv);
    expect_reference(
        read_particles(write("table.tsv", "x\ty\tz\tr\n0.1\t-0.25\t0.5\t0.5\n"
                                          "1.125\t0\t0.5\t0.5\n0.5\t0.75\t1.3\t0.25\n")));
    EXPECT_EQ(error_of("x y z r\n1 2 3\n", ParticleFormat::csv),
              "bed:2: 3 fields; the header has 4");
    // A decimal comma where the separator is a comma is no number.
    EXPECT_EQ(error_of("x;y;z;r\n1,2,3;1;1;0.5\n", ParticleFormat::csv),
              "bed:2: column 'x' value '1,2,3' is not a number");
}

TEST(ReadOptionsOffset, AxisAndFloorAreSubtractedFromEveryCentre) {
    ReadOptions o;
    o.axis = {10.5, -20.25};
    o.floor = 4.0;
    const auto f =
        read_text("x,y,z,r\n10.5,-20.25,4.5,0.5\n11.5,-20,6,0.25\n", ParticleFormat::csv, o);
    EXPECT_EQ(f.packing.centers[0], (Vec3{0.0, 0.0, 0.5}));
    EXPECT_EQ(f.packing.centers[1], (Vec3{1.0, 0.25, 2.0}));
    EXPECT_EQ(f.packing.radii[1], 0.25);
    // Every format, the scaled dump too (x = -1, y = 1, z = 1.25 in the file).
    const auto d = read_text(snapshot(0, "ff ff ff", "-2 2\n-1 3\n0 10\n", "id xs ys zs radius",
                                      {"1 0.25 0.5 0.125 0.5"}),
                             ParticleFormat::lammps_dump, o);
    EXPECT_EQ(d.packing.centers[0], (Vec3{-11.5, 21.25, -2.75}));
    // Out of range: refused before reading.
    ReadOptions far;
    far.axis = {1e300, 0.0};
    EXPECT_EQ(error_of("x,y,z,r\n1,2,3,0.5\n", ParticleFormat::csv, far),
              "axis x = 1e+300 is not allowed; allowed: a number from -1e+15 to 1e+15");
    ReadOptions nan_floor;
    nan_floor.floor = std::nan("");
    EXPECT_EQ(error_of("x,y,z,r\n1,2,3,0.5\n", ParticleFormat::csv, nan_floor),
              "floor = nan is not allowed; allowed: a number from -1e+15 to 1e+15");
}

namespace {

/// 0 when reading `rows` with the address space limited to 80 MB more than this process maps
/// is refused at the millionth sphere (the message on stderr).
int read_with_memory_limit(const std::string& rows) {
    std::ifstream status("/proc/self/status");
    std::string line;
    std::uint64_t mapped = 0;
    while (std::getline(status, line))
        if (line.starts_with("VmSize:"))
            mapped = std::stoull(line.substr(7)) * 1024;
    const rlimit limit{mapped + (80u << 20), mapped + (80u << 20)};
    ::setrlimit(RLIMIT_AS, &limit);
    const std::string said = error_of(rows, ParticleFormat::csv);
    std::fprintf(stderr, "%s\n", said.c_str());
    return said.find("1048576 spheres read so far, and the next ones need about") !=
                   std::string::npos
               ? 0
               : 1;
}

} // namespace

// A bed larger than the memory left is refused as it is read, before the vectors that would
// not fit are made: in a child whose address space is limited (RLIMIT_AS) to 80 MB more than
// it maps, 1 100 000 spheres (40 bytes each, kept twice while a vector grows) stop at the
// millionth.
TEST(ReadParticles, ABedBeyondTheMemoryLeftIsRefusedAsItIsRead) {
    std::string rows = "x,y,z,r\n";
    for (int k = 0; k < 1100000; ++k)
        rows += std::to_string(k) + ",0,0.5,0.5\n";
    ::testing::GTEST_FLAG(death_test_style) = "threadsafe";
    EXPECT_EXIT(std::_Exit(read_with_memory_limit(rows)), ::testing::ExitedWithCode(0),
                "is available here; allowed: a bed that fits in memory");
}

TEST(ReadParticles, FormatRegistryAndDetection) {
    std::vector<std::string> names;
    for (const auto& [name, format] : particle_formats())
        names.push_back(name);
    EXPECT_EQ(names,
              (std::vector<std::string>{"auto", "csv", "xyz", "lammps-dump", "lammps-data"}));
    EXPECT_EQ(detect_particle_format(write("a.data", "")), ParticleFormat::lammps_data);
    EXPECT_EQ(detect_particle_format(write("a.dump.gz", "")), ParticleFormat::lammps_dump);
    EXPECT_EQ(detect_particle_format(write("a.XYZ.GZ", "")), ParticleFormat::xyz);
    // A data file whose title says x y z is still a data file.
    EXPECT_EQ(detect_particle_format(write("t.txt", "x y z of a bed\n\n2 atoms\n")),
              ParticleFormat::lammps_data);
    try {
        detect_particle_format(write("u.txt", "hello world\n"));
        ADD_FAILURE() << "detected";
    } catch (const InvalidInput& e) {
        EXPECT_NE(std::string(e.what()).find(
                      "u.txt:1: cannot tell the format; allowed: .csv, .tsv, .xyz, .dump, "
                      ".lammpstrj or .data files (also .gz), or a table whose header names x, y "
                      "and z"),
                  std::string::npos)
            << e.what();
    }
}
