// Reading beds from CSV, XYZ and LAMMPS dumps: the same spheres from every format, and each
// bad file refused with its line and reason.
#include <sys/stat.h>

#include <filesystem>
#include <fstream>
#include <sstream>

#include <gtest/gtest.h>

#include "packbed/error.hpp"
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
                "bed:1: missing column 'r'; needed: x, y, z and r, radius, d or diameter"},
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
        // A diameter whose half is 0 (issue 14's fuzzing: 5e-324 halved is 0).
        BadFile{ParticleFormat::csv, "x,y,z,diameter\n1,2,3,5e-324\n",
                "bed:2: column 'diameter' value 5e-324 is not allowed; a diameter must be from "
                "1e-12 to 1e+12"},
        BadFile{ParticleFormat::xyz, "3\n\nC 0 0 0 0.5\n", "bed: declares 3 spheres but holds 1"},
        BadFile{ParticleFormat::xyz, "1\n\nC 0 0 0 0.5\nC 1 1 1 0.5\n",
                "bed:4: more lines than the 1 spheres the first line declares"},
        BadFile{ParticleFormat::xyz, "1\n\nC 0 0 0\n",
                "bed:3: no radius column (name x y z) and no radius given; allowed: name x y z "
                "radius, or give the diameter"},
        BadFile{ParticleFormat::xyz, "two\n", "bed:1: column 'count' value 'two' is not a number"},
        BadFile{ParticleFormat::lammps_dump,
                "ITEM: TIMESTEP\n0\nITEM: NUMBER OF ATOMS\n2\nITEM: ATOMS id xs ys zs radius\n",
                "bed:5: scaled coordinates (xs ys zs) are not supported; allowed: dump x y z or "
                "xu yu zu"},
        BadFile{ParticleFormat::lammps_dump,
                "ITEM: TIMESTEP\n0\nITEM: NUMBER OF ATOMS\n2\nITEM: ATOMS id x y z radius\n"
                "1 0 0 0 0.5\n",
                "bed: ends after 1 of 2 atoms"},
        BadFile{ParticleFormat::lammps_dump,
                "ITEM: TIMESTEP\n0\nITEM: NUMBER OF ATOMS\n1\nITEM: ATOMS id x y z\n1 0 0 0\n",
                "bed:5: missing column 'r'; needed: x, y, z and r, radius, d or diameter"},
        BadFile{ParticleFormat::lammps_dump, "",
                "bed: empty file; expected a LAMMPS dump starting with ITEM: TIMESTEP"},
        // The audit's cases: undefined behaviour before (a float-to-integer overflow, then
        // "0 spheres"; a message read from a line already overwritten).
        BadFile{ParticleFormat::xyz, "1e308\n\n",
                "bed:1: the count 1e+308 is not allowed; allowed: a whole number from 1 to "
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
    // Deep nesting is read and refused, not a stack overflow.
    EXPECT_EQ(error(std::string(100000, '[') + std::string(100000, ']')),
              "summary.json: not a summary.json (not a JSON object); allowed: the summary.json of "
              "packbed generate, lattice or analyze");
}
