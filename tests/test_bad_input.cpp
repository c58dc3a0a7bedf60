// Bad input on every subcommand and every option class: non-numbers, inf and nan,
// huge and tiny values, empty strings, paths with control characters, symlinks, FIFOs, devices,
// directories where a file is expected and files where a directory is expected, files that
// cannot be read, non-empty outputs, an output that is the input, and the audit's reproducers.
// Each case runs `packbed` (no shell: the arguments reach it byte for byte) in a scratch folder
// holding every kind of file the cases name, and asserts: exit status 2, stdout empty, exactly
// one line on stderr (the whole line where the message is pinned, else the parts that name the
// input and the value), and the scratch folder exactly as it was (a recursive listing with
// hidden entries, types, sizes, link targets and the contents of small files).
#include <fcntl.h>
#include <signal.h>
#include <sys/resource.h>
#include <sys/stat.h>
#include <sys/sysmacros.h>
#include <sys/types.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <functional>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include <gtest/gtest.h>

#include "run_packbed.hpp"

namespace fs = std::filesystem;
using packbed::test::exe;
using packbed::test::slurp;

namespace {

/// A case that does not end within this is a hang (every refusal takes milliseconds).
constexpr auto time_limit = std::chrono::seconds(15);

struct Outcome {
    bool exited = false;    // ended by exit(), not by a signal
    int status = -1;        // the exit status, or the signal that ended it
    bool timed_out = false; // killed after time_limit
    std::string out;
    std::string err;
};

/// Run PACKBED_EXE with `args` (no shell) in `cwd`, stdin from /dev/null, CI unset, stdout and
/// stderr into files in `io`; killed (its whole process group) after time_limit.
Outcome run_packbed(const std::vector<std::string>& args, const fs::path& cwd, const fs::path& io) {
    const pid_t pid = packbed::test::spawn(args, cwd, io);
    Outcome outcome;
    if (pid < 0) {
        outcome.err = "fork failed";
        return outcome;
    }
    const auto deadline = std::chrono::steady_clock::now() + time_limit;
    int raw = 0;
    while (::waitpid(pid, &raw, WNOHANG) == 0) {
        if (std::chrono::steady_clock::now() > deadline) {
            ::kill(-pid, SIGKILL);
            ::waitpid(pid, &raw, 0);
            outcome.timed_out = true;
            break;
        }
        std::this_thread::sleep_for(std::chrono::milliseconds(2));
    }
    outcome.exited = WIFEXITED(raw);
    outcome.status = WIFEXITED(raw) ? WEXITSTATUS(raw) : WIFSIGNALED(raw) ? WTERMSIG(raw) : -1;
    outcome.out = slurp(io / "out");
    outcome.err = slurp(io / "err");
    return outcome;
}

/// What is under `root`: regular files by their size and a hash of their contents (up to
/// 4 MiB), the rest by type or link target (packbed::test::listing).
std::string listing(const fs::path& root) {
    return packbed::test::listing(root, [](const fs::path& p, std::uintmax_t size) {
        std::string line = "file " + std::to_string(size);
        if (size <= (4u << 20))
            line += " " + std::to_string(std::hash<std::string>{}(slurp(p)));
        return line;
    });
}

void write(const fs::path& path, const std::string& text) {
    std::ofstream(path, std::ios::binary) << text;
}

/// `n` spheres of diameter 1 stacked on the axis from the floor (a valid bed for -R >= 0.5).
std::string column(int n) {
    std::string csv = "x,y,z,r\n";
    for (int i = 0; i < n; ++i)
        csv += "0,0," + std::to_string(i) + ".5,0.5\n";
    return csv;
}

/// `n` brackets opened and `n` closed.
std::string nested(std::size_t n) {
    return std::string(n, '[') + std::string(n, ']');
}

/// The inputs of the NothingLost cases: deep nesting in every reader of nested
/// text, beds and folders whose files an output could replace, and LAMMPS jobs.
void prepare_nothing_lost(const fs::path& d) {
    std::string dotted = "a";
    for (int k = 1; k < 50000; ++k)
        dotted += ".a";
    write(d / "dotted.toml", dotted + " = 1\n");
    write(d / "brackets.toml", "aspect-ratio = " + nested(100000) + "\n");
    write(d / "longkey.toml", std::string(100000, 'k') + " = 1\n");
    write(d / "header.toml", "[" + dotted.substr(0, 999) + "]\nx = 1\n");
    write(
        d / "inline.toml", "a = " + [] {
            std::string t;
            for (int k = 0; k < 100; ++k)
                t += "{b = ";
            return t + "1" + std::string(100, '}');
        }() + "\n");
    // A bed whose summary.json nests 1e5 deep under a key quoted in messages.
    fs::create_directory(d / "deep");
    write(d / "deep" / "bed.csv", column(40));
    write(d / "deep" / "summary.json", "{\"diameter\": " + nested(100000) + "}");
    // A bed with its summary (a tube of radius 1), a sieve file and a config in folders an
    // output could replace.
    fs::create_directory(d / "bed");
    write(d / "bed" / "particles.csv", column(40));
    write(d / "bed" / "summary.json", R"({"container": {"shape": "cylinder", "radius": 1}})");
    // Two pellets (cylinder:1,1, r = d_v / 2) with their orientations and summary, and a
    // summary whose shape is none.
    fs::create_directory(d / "pel");
    write(d / "pel" / "particles.csv",
          "x,y,z,r,qw,qx,qy,qz\n0,0,0.6,0.5724,1,0,0,0\n0,0,1.8,0.5724,1,0,0,0\n");
    write(d / "pel" / "summary.json", R"({"container": {"shape": "cylinder", "radius": 2}, )"
                                      R"("shape": {"kind": "cylinder", "spec": "cylinder:1,1"}})");
    // The same pellets without their summary.
    fs::create_directory(d / "pelraw");
    write(d / "pelraw" / "particles.csv",
          "x,y,z,r,qw,qx,qy,qz\n0,0,0.6,0.5724,1,0,0,0\n0,0,1.8,0.5724,1,0,0,0\n");
    fs::create_directory(d / "cone");
    write(d / "cone" / "particles.csv", "x,y,z,r\n0,0,0.6,0.5\n");
    write(d / "cone" / "summary.json", R"({"shape": {"spec": "cone:1,1"}})");
    fs::create_directory(d / "sz");
    write(d / "sz" / "sizes.csv", "diameter,cumulative_fraction\n1,0\n1.2,1\n");
    fs::create_directory(d / "cfg");
    write(d / "cfg" / "run.toml", "aspect-ratio = 3\nparticles = 30\n");
    write(d / "cfg" / "lattice.toml", "type = \"sc\"\n");
    write(d / "cfg" / "out.data.fluid.in", "density = 2500\n"); // a config, a sidecar's name
    write(d / "cfg" / "layers.toml",
          "aspect-ratio = 5\nparticles = 3000\nlayer-height = 10\nsolver = \"fire\"\n");
    // An OpenFOAM case (cfd-report reads it whole) inside a project folder.
    fs::create_directories(d / "proj" / "case" / "postProcessing");
    write(d / "proj" / "case" / "packbed.json", "{}");
    // LAMMPS jobs: one as --write-only writes it, with LAMMPS's files; its variants.
    const std::string request =
        R"("request": {"aspect_ratio": 3.0, "band_clearance": 1.0, "cg_step": 1.25e-07, "ck": 0.3, )"
        R"("container": "", "diameter": 1.0, "e0": 0.47, "fractions": "volume", )"
        R"("layer_height": 30.0, "max_iterations": 200000000, "mc_period": 100, )"
        R"("mc_tolerance": 0.05, "mc_window": 10, "overlap_high": 0.03, "overlap_low": 0.015, )"
        R"("particles": 30, "seed": 1, "sizes": "mono", "skin": 0.2, "solver": "fire", )"
        R"("tolerance": 0.0001, "update": "simultaneous"})";
    const auto job = [&](const std::string& name, const std::string& json) {
        fs::create_directory(d / name);
        write(d / name / "job.json", json);
        write(d / name / "log.lammps", "");
        write(d / name / "bed.dump", "");
    };
    job("lmpjob", "{\"command\": [\"lmp\"], \"pair_style\": \"gran/hooke\", " + request + "}");
    job("style", "{\"command\": [\"lmp\"], \"pair_style\": 5, " + request + "}");
    job("words", "{\"command\": [\"lmp\", " + nested(100000) + "], " + request + "}");
    job(
        "long", "{\"command\": [" +
                    [] {
                        std::string words = "\"w\"";
                        for (int k = 0; k < 1000; ++k)
                            words += ", \"w\"";
                        return words;
                    }() +
                    "], " + request + "}");
    job("loop", "{\"command\": [\"lmp\"], " + request + "}");
    fs::remove(d / "loop" / "log.lammps");
    fs::create_symlink("log.lammps", d / "loop" / "log.lammps");
    // A sphere 1e14 diameters up.
    write(d / "far.csv", "x,y,z,r\n0,0,1,0.5\n0,0,1e14,0.5\n");
}

/// Fill `d` with every kind of input the cases name (relative names; `@D/...` in the older
/// cases).
void prepare(const fs::path& d) {
    // Config files.
    write(d / "unknown.toml", "aspect-ratio = 4\nwarp_speed = 9\n");
    write(d / "broken.toml", "aspect-ratio = = 4\n");
    write(d / "typed.toml", "particles = [1, {a = 2}]\n");
    write(d / "range.toml", "aspect-ratio = 0.5\n");
    // Larger than limits::max_config_file (1 MiB), sparse: no disk space.
    write(d / "big.toml", "");
    ASSERT_EQ(::truncate((d / "big.toml").c_str(), (1 << 20) + 1), 0);
    // Beds.
    write(d / "plain", "x");
    write(d / "one.csv", "x,y,z,r\n0,0,0,0.5\n");
    write(d / "two.csv", "x,y,z,r\n0,0,1,0.5\n0.99,0,1,0.5\n");
    write(d / "bed.csv", column(40));
    write(d / "empty.csv", "");
    write(d / "header.csv", "x,y,z,r\n");
    write(d / "nan.csv", "x,y,z,r\n0,0,1,nan\n");
    write(d / "negative.csv", "x,y,z,r\n0,0,1,-1\n");
    write(d / "outside.csv", "x,y,z,r\n0,0,1,0.5\n1.1,0,0.5,0.5\n");
    // 40 spheres and one far above them.
    write(d / "far.csv", column(40) + "0,0,1e7,0.5\n");
    write(d / "far15.csv", column(40) + "0,0,1e15,0.5\n");
    // No newline in 2 MiB (sparse: zero bytes).
    write(d / "zeros", "");
    ASSERT_EQ(::truncate((d / "zeros").c_str(), 2 << 20), 0);
    // Special files.
    ASSERT_EQ(::mkfifo((d / "fifo").c_str(), 0644), 0);
    // A character device of our own (the null device's numbers), so that a regression that
    // writes over a device harms nothing outside the scratch folder; a FIFO where mknod is
    // not allowed.
    if (::mknod((d / "node").c_str(), S_IFCHR | 0644, ::makedev(1, 3)) != 0) {
        ASSERT_EQ(::mkfifo((d / "node").c_str(), 0644), 0);
    }
    fs::create_symlink("missing-target", d / "dangling");
    fs::create_directory(d / "dir");
    fs::create_directory(d / "full");
    write(d / "full" / "f", "x");
    write(d / "full" / "bed.csv", column(40));
    fs::create_directory_symlink("full", d / "dirlink");
    fs::create_symlink("two.csv", d / "twolink");
    fs::create_hard_link(d / "two.csv", d / "hard.csv");
    // summary.json beside a bed that is a directory, or a FIFO.
    fs::create_directory(d / "sumdir");
    write(d / "sumdir" / "bed.csv", column(40));
    fs::create_directory(d / "sumdir" / "summary.json");
    fs::create_directory(d / "sumfifo");
    write(d / "sumfifo" / "bed.csv", column(40));
    ASSERT_EQ(::mkfifo((d / "sumfifo" / "summary.json").c_str(), 0644), 0);
    // The readers' new inputs: two XYZ frames, a dump without a size column, a gzip file cut
    // short (the first 29 bytes of a 39-byte one).
    write(d / "frames.xyz", "1\n\nC 0 0 0.5 0.5\n2\n\nC 0 0 0.5 0.5\nC 0 0 1.5 0.5\n");
    write(d / "nosize.dump", "ITEM: TIMESTEP\n0\nITEM: NUMBER OF ATOMS\n1\nITEM: BOX BOUNDS ff ff "
                             "ff\n-1 1\n-1 1\n0 2\nITEM: ATOMS id x y z\n1 0 0 0.5\n");
    write(d / "cut.csv.gz", std::string("\x1f\x8b\x08\x00\x00\x00\x00\x00\x02\x03\xab\xd0\xa9"
                                        "\xd4\xa9\xd2\x29\xe2\x32\xd0\x01\x42\x3d\x53\x10\x06"
                                        "\xb3\x0d\xa1",
                                        29));
    // A bed in a directory with a newline in its name.
    fs::create_directory(d / "nl\ndir");
    write(d / "nl\ndir" / "bed.csv", column(40));
    prepare_nothing_lost(d);
}

fs::path test_folder() {
    return packbed::test::test_folder("bad-input");
}

const auto* const remove_scratch =
    ::testing::AddGlobalTestEnvironment(new packbed::test::RemoveWhenPassed("bad-input"));

/// A fresh scratch folder for the running test: `work` (the cases' folder) and `io`.
fs::path scratch() {
    const fs::path d = test_folder();
    fs::remove_all(d);
    fs::create_directories(d / "work");
    fs::create_directories(d / "io");
    return d;
}

std::string replace_all(std::string text, const std::string& from, const std::string& to) {
    for (std::size_t at = 0; (at = text.find(from, at)) != std::string::npos; at += to.size())
        text.replace(at, from.size(), to);
    return text;
}

std::vector<std::string> split(const std::string& words) {
    std::vector<std::string> out;
    std::istringstream in(words);
    for (std::string w; in >> w;)
        out.push_back(w);
    return out;
}

struct BadInput {
    std::vector<std::string> args;  // "@D" stands for the scratch folder
    std::string message;            // the whole line on stderr ("@D" replaced); "" not pinned
    std::vector<std::string> parts; // where it is not pinned: what the line must contain
};

/// Arguments split on spaces, and the exact line.
BadInput exact(const std::string& args, const std::string& message) {
    return {split(args), message, {}};
}
/// Arguments as given (empty strings, control characters), and the exact line.
BadInput exact(std::vector<std::string> args, const std::string& message) {
    return {std::move(args), message, {}};
}
/// A message not pinned word for word: the parts it must contain.
BadInput naming(const std::string& args, std::vector<std::string> parts) {
    return {split(args), "", std::move(parts)};
}
BadInput naming(std::vector<std::string> args, std::vector<std::string> parts) {
    return {std::move(args), "", std::move(parts)};
}

std::string escaped(const std::string& text) {
    std::string out;
    for (const unsigned char c : text)
        if (c < 0x20 || c == 0x7f) {
            char buffer[8];
            std::snprintf(buffer, sizeof buffer, "\\x%02x", c);
            out += buffer;
        } else {
            out += static_cast<char>(c);
        }
    return out;
}

void PrintTo(const BadInput& b, std::ostream* os) {
    *os << "packbed";
    for (const auto& a : b.args)
        *os << " '" << escaped(a) << "'";
}

class CliBadInput : public ::testing::TestWithParam<BadInput> {};

TEST_P(CliBadInput, Exit2OneLineNamingTheInputNothingLeft) {
    const fs::path root = scratch();
    const fs::path d = root / "work";
    prepare(d);
    if (::testing::Test::HasFatalFailure())
        return;
    if (!fs::is_character_file(d / "node") &&
        std::count(GetParam().args.begin(), GetParam().args.end(), "node") > 0)
        GTEST_SKIP() << "no device of our own here (mknod refused): 'node' is a FIFO";
    const std::string before = listing(d);
    std::vector<std::string> args = GetParam().args;
    for (auto& a : args)
        a = replace_all(a, "@D", d.string());
    const Outcome o = run_packbed(args, d, root / "io");

    EXPECT_FALSE(o.timed_out) << "still running after " << time_limit.count()
                              << " s: killed; stderr: " << o.err;
    EXPECT_TRUE(o.exited) << "ended by signal " << o.status << "; stderr: " << o.err;
    EXPECT_EQ(o.status, 2) << o.err;
    EXPECT_EQ(o.out, "");
    EXPECT_EQ(std::count(o.err.begin(), o.err.end(), '\n'), 1) << o.err;
    EXPECT_TRUE(!o.err.empty() && o.err.back() == '\n') << o.err;
    if (!GetParam().message.empty()) {
        EXPECT_EQ(o.err, replace_all(GetParam().message, "@D", d.string()) + "\n");
    }
    for (const std::string& part : GetParam().parts) {
        EXPECT_NE(o.err.find(replace_all(part, "@D", d.string())), std::string::npos)
            << "'" << part << "' not in: " << o.err;
    }
    EXPECT_EQ(listing(d), before)
        << "the run changed its folder (listing after it, then before it)";
}

const std::string subcommands =
    "allowed: generate, lattice, random-array, hydraulics, export, analyze, correlations, "
    "voxelize, cfd-report, "
    "import-lammps";
const std::string a_path = "allowed: a path of at most 4095 bytes without control characters "
                           "(newline, tab, ...)";
const std::string regular = "allowed: a readable regular file";
const std::string frame_allowed =
    "allowed: a whole number other than 0: 1 the first frame, 2 the second, ..., -1 the last, -2 "
    "the one before";
const std::string axis_allowed = "allowed: X,Y: two numbers from -1e+15 to 1e+15 (file units)";
const std::string not_empty =
    "exists and is not empty; allowed: a new or empty directory, or --force to replace it whole";

// The top level: subcommands and --config.
INSTANTIATE_TEST_SUITE_P(
    TopLevel, CliBadInput,
    ::testing::Values(
        exact("frobnicate", "packbed: 'frobnicate' is not a subcommand; " + subcommands),
        exact(std::vector<std::string>{""}, "packbed: '' is not a subcommand; " + subcommands),
        exact(std::vector<std::string>{"gen\nerate"},
              "packbed: 'gen\\nerate' is not a subcommand (did you mean generate?); " +
                  subcommands),
        naming("", {}),             // "A subcommand is required": see the report
        naming("--frobnicate", {}), // same message, not naming --frobnicate
        exact("--config missing.toml generate",
              "packbed: --config missing.toml: cannot open the file (No such file or "
              "directory); " +
                  regular),
        exact("--config dir generate", "packbed: --config dir: a directory; " + regular),
        exact("--config dirlink generate", "packbed: --config dirlink: a directory; " + regular),
        exact("--config dangling generate",
              "packbed: --config dangling: cannot open the file (No such file or directory); " +
                  regular),
        exact("--config fifo generate", "packbed: --config fifo: a FIFO (named pipe); " + regular),
        exact("--config /dev/zero generate", "packbed: --config /dev/zero: a device; " + regular),
        exact("--config /proc/self/mem generate",
              "packbed: --config /proc/self/mem: cannot be read (an input/output error); " +
                  regular),
        exact("--config big.toml generate",
              "packbed: --config big.toml: larger than 1048576 bytes; allowed: a file up to "
              "that size"),
        exact(std::vector<std::string>{"--config", "", "generate"},
              "packbed: --config '' is not allowed (an empty path); " + a_path),
        exact(std::vector<std::string>{"--config", "a\nb.toml", "generate"},
              "packbed: --config 'a\\nb.toml' is not allowed (a control character in the path); " +
                  a_path),
        exact(std::vector<std::string>{"--config", "a\x1b[31mb.toml", "generate"},
              "packbed: --config 'a\\x1b[31mb.toml' is not allowed (a control character in the "
              "path); " +
                  a_path),
        exact("voxelize @D/bed.csv --voxel-size 0.1 -o @D/im.png",
              "packbed voxelize: --out @D/im.png: the extension is not allowed; allowed: .npy, "
              ".tif (or "
              ".tiff) or .raw (with a .raw.json header)"),
        exact("--config range.toml generate",
              "packbed: --aspect-ratio: 0.5 is not allowed; allowed: a number in [1, 10000]"),
        exact("--config range.toml",
              "packbed: a subcommand is required; allowed: generate, lattice, random-array, "
              "hydraulics, "
              "export, analyze, correlations, voxelize, cfd-report, import-lammps"),
        exact("generate --config @D/unknown.toml",
              "packbed: --config @D/unknown.toml: line 2: unknown key 'warp_speed'; allowed: "
              "aspect-ratio, band-clearance, cg-step, checkpoint, ck, container, diameter, e0, "
              "engine, force, fractions, friction, layer-height, lmp, max-iterations, "
              "mc-period, mc-tolerance, mc-window, mpi-command, no-analysis, out, overlap-high, "
              "overlap-low, particles, quiet, ranks, seed, shape, sizes, skin, solver, "
              "target-void-fraction, threads, tolerance, update, wall-friction, write-only"),
        exact("generate --config @D/broken.toml",
              "packbed: --config @D/broken.toml: line 1, column 16: Error while parsing value: "
              "could not "
              "determine value type"),
        exact("generate --config @D/typed.toml",
              "packbed: --config @D/typed.toml: line 1: key 'particles' has a value of the wrong "
              "type; "
              "allowed: a number, a string or true/false")));

INSTANTIATE_TEST_SUITE_P(
    Generate, CliBadInput,
    ::testing::Values(
        // Sizes that do not add up, an unknown distribution, a ratio beyond the
        // solvers', a sphere wider than the tube.
        exact("generate --sizes discrete:1:0.5,2:0.4",
              "packbed generate: --sizes 'discrete:1:0.5,2:0.4' is not allowed: the fractions add "
              "up to 0.9; allowed: discrete:D1:F1,D2:F2,... with each diameter once, from 1e-12 "
              "to 1e+12, the largest at most 10 times the smallest, at most 100000 sizes, and "
              "fractions >= 0 adding up to 1 (within 1e-06)"),
        exact("generate --sizes gamma:1",
              "packbed generate: --sizes 'gamma:1' is not allowed: unknown distribution 'gamma'; "
              "allowed: mono, discrete:D1:F1,D2:F2,..., uniform:MIN,MAX, normal:MEAN,SD[,MIN,MAX], "
              "lognormal:MEDIAN,GSD[,MIN,MAX] or file:PATH"),
        naming("generate --sizes discrete:1:0.5,20:0.5", {"--sizes", "20", "10"}),
        // Options that would change nothing: --diameter beside the sizes, --update beside FIRE.
        exact("generate --sizes uniform:0.8,1.2 -d 2",
              "packbed generate: --diameter 2 is not allowed with --sizes 'uniform:0.8,1.2'; "
              "allowed: one of the two (the sizes give the diameters in length units, Dp is "
              "their Sauter mean d32)"),
        exact("generate --update in-place",
              "packbed generate: --update in-place is not allowed with --solver fire; allowed: "
              "--update with --solver paper (FIRE moves every sphere at once)"),
        naming("generate --sizes lognormal:1,0.9", {"--sizes", "GSD = 0.9"}),
        exact("generate --sizes discrete:1:0.5,2:0.5 --container cylinder:1.5",
              "packbed generate: --sizes: a diameter of 1.49776 Dp is not allowed in a tube of a = "
              "1.12332; allowed: diameters > 0 and below the tube's (a Dp, Dp = 1.33533 the "
              "reference diameter)"),
        // Containers that do not fit the spheres; an unknown one; two of them.
        exact("generate --container annulus:10,9.5",
              "packbed generate: --container annulus:10,9.5 is not allowed with Dp = 1; allowed: "
              "D up to 10000 Dp and DI <= D - 2 Dp: the gap between rod and tube, (D - DI) / 2, "
              "at least the largest sphere (1 Dp)"),
        exact("generate --container box:0.5,6 --diameter 1",
              "packbed generate: --container box:0.5,6 is not allowed with Dp = 1; allowed: "
              "widths from 1 Dp (the largest sphere) to 10000 Dp"),
        exact("generate --container periodic:3,8 --diameter 2",
              "packbed generate: --container periodic:3,8 is not allowed with Dp = 2; allowed: "
              "widths from 2 Dp (twice the largest sphere, for the minimum image) to 10000 Dp"),
        naming("generate --container sphere:3", {"--container", "sphere:3", "periodic:LX,LY"}),
        // Pellets (docs/generate.md, "Pellets"): a shape that is not one, an option of the
        // spheres' alone, a pellet wider than the tube.
        exact("generate --shape cylinder:1",
              "packbed generate: --shape: 'cylinder:1' is not allowed; allowed: sphere (the "
              "default); cylinder:D,L (a cylinder of diameter D and length L); ring:D,DI,L (a "
              "hollow cylinder, its bore of diameter DI, 0 < DI <= 0.9 D); trilobe:DL,DC,L "
              "(three cylinders of diameter DL, their axes on a circle of diameter DC, 0 < DC <= "
              "DL); multilobe:N,DL,DC,L (N = 2 to 8 such lobes); each length > 0 and at most "
              "1e+15, L / D (L / DL) from 0.1 to 10; or spherocylinder:D,L (a cylinder of "
              "diameter D and length L capped by two hemispheres, L >= 0, L / D at most 10); "
              "the volume-equivalent diameter d_v from 1e-12 to 1e+12"),
        naming("generate --shape trilobe:1,1.2,2", {"--shape", "trilobe:1,1.2,2", "DC <= DL"}),
        naming("generate --shape ring:1,1,1", {"--shape", "ring:1,1,1", "DI <= 0.9 D"}),
        naming("generate --shape ring:1,0.95,1", {"--shape", "ring:1,0.95,1", "DI <= 0.9 D"}),
        naming("generate --shape ring:1,0.5", {"--shape", "ring:1,0.5", "ring:D,DI,L"}),
        naming("generate --shape multilobe:9,1,0.8,2",
               {"--shape", "multilobe:9,1,0.8,2", "N = 2 to 8"}),
        naming("generate --shape cylinder:1,20", {"--shape", "cylinder:1,20", "L / D"}),
        naming("generate --shape spherocylinder:1,-1",
               {"--shape", "spherocylinder:1,-1", "L >= 0"}),
        naming("generate --shape spherocylinder:1,11",
               {"--shape", "spherocylinder:1,11", "L / D at most 10"}),
        naming("generate --shape spherocylinder:1",
               {"--shape", "spherocylinder:1", "spherocylinder:D,L"}),
        exact("generate --shape cylinder:1,1 --target-void-fraction 0.4",
              "packbed generate: --target-void-fraction is not allowed with --shape "
              "cylinder:1,1; allowed with a pellet: --aspect-ratio, --container, --particles, "
              "--seed, --shape, --out, --force, --threads, --quiet, --band-clearance, "
              "--no-analysis, --config, --friction, --wall-friction, --max-iterations, "
              "--sizes, --fractions, --layer-height, --checkpoint (docs/generate.md, "
              "\"Pellets\")"),
        exact("generate --shape cylinder:1,1 -n 20 -a 3 --layer-height 10 --checkpoint ck",
              "packbed generate: --checkpoint ck: only a pellet bed in layers can be resumed, "
              "this one is in one piece (its column 12.55 d_v, --layer-height 10); allowed: a "
              "column above twice --layer-height, which is 10 or more"),
        // Sizes on the pellet's D: parse_sizes' refusal; the largest pellet must fit (the
        // largest of 100 D drawn from uniform:1,3 is 2.977, its bounding diameter 2.977 sqrt(2)).
        naming("generate --shape cylinder:1,1 --sizes uniform:1,20",
               {"--sizes", "uniform:1,20", "MAX <= 10 MIN"}),
        exact("generate --shape cylinder:1,1 --sizes uniform:1,3 --container cylinder:3",
              "packbed generate: --shape: 'cylinder:1,1' does not fit in cylinder:3: a tube "
              "diameter from 4.21029 (the largest pellet's bounding diameter) to 20835.8"),
        naming("generate --shape cylinder:1,1 --friction -0.1", {"--friction", "-0.1"}),
        naming("generate --shape cylinder:1,1 --container cylinder:1",
               {"--shape", "cylinder:1,1", "does not fit"}),
        // A pellet's fit in the units the container was given in: --container's lengths (the
        // bounding diameter of cylinder:1,1 is sqrt(2); 1e4 d_v = 11447.1), or d_v for -a.
        exact("generate --shape cylinder:1,1 --container box:0.5,3",
              "packbed generate: --shape: 'cylinder:1,1' does not fit in box:0.5,3: widths from "
              "1.41421 (the pellet's bounding diameter) to 11447.1"),
        exact("generate --shape cylinder:1,1 --container periodic:0.5,3",
              "packbed generate: --shape: 'cylinder:1,1' does not fit in periodic:0.5,3: widths "
              "from 2.82843 (twice the pellet's bounding diameter, for the minimum image) to "
              "11447.1"),
        exact("generate --shape cylinder:1,1 -a 1.1",
              "packbed generate: --shape: 'cylinder:1,1' does not fit in a tube of a = 1.1: a tube "
              "diameter from 1.23543 d_v (the pellet's bounding diameter) to 10000 d_v"),
        naming("generate --container annulus:10", {"--container", "annulus:10", "annulus:D,DI"}),
        naming("generate --container annulus:4,6", {"--container", "annulus:4,6", "DI < D"}),
        exact("generate --container box:6,6 --aspect-ratio 5",
              "packbed generate: --aspect-ratio 5 and --container box:6,6 are both given; "
              "allowed: one of the two"),
        exact("generate --container periodic:8,8 --checkpoint c.json",
              "packbed generate: --checkpoint c.json is not allowed with --container "
              "periodic:8,8; allowed: --checkpoint with a cylinder (a checkpoint does not record "
              "the container yet)"),
        // The LAMMPS engine: its options without it, what it cannot run, an
        // engine or a launcher that is not one; import-lammps of a folder that is not a job.
        exact("generate --ranks 4",
              "packbed generate: --ranks, --mpi-command, --lmp and --write-only are not allowed "
              "with --engine packbed; allowed: with --engine lammps"),
        exact("generate --engine lammps --solver paper",
              "packbed generate: --solver paper is not allowed with --engine lammps; allowed: "
              "--solver fire (LAMMPS runs the fire solver's energy and schedule)"),
        exact("generate --engine lammps --checkpoint c.json",
              "packbed generate: --checkpoint c.json is not allowed with --engine lammps; "
              "allowed: --checkpoint with --engine packbed"),
        exact("generate --engine lammps --sizes uniform:0.5,1 -n 100 --write-only @D/job",
              "packbed generate: --engine lammps with 100 distinct sphere sizes is not allowed; "
              "allowed: at most 16 (one atom type and one group of wall fixes each): a --sizes "
              "of discrete diameters"),
        naming("generate --engine gromacs", {"--engine", "gromacs", "packbed, lammps"}),
        naming("generate --engine lammps --ranks 0", {"--ranks", "0"}),
        exact(std::vector<std::string>{"generate", "--engine", "lammps", "--mpi-command", " "},
              "packbed generate: --mpi-command '' is not allowed; allowed: a launcher's words "
              "such as 'srun -n 64'"),
        exact("import-lammps @D/nothing-here",
              "packbed import-lammps: FOLDER @D/nothing-here is not a directory; allowed: the "
              "folder of a job written by packbed generate --engine lammps --write-only"),
        // Non-numbers.
        exact("generate --aspect-ratio five",
              "packbed: --aspect-ratio: 'five' is not allowed; allowed: a number in [1, 10000]"),
        exact("generate --aspect-ratio 0x10",
              "packbed: --aspect-ratio: '0x10' is not allowed; allowed: a number in [1, 10000]"),
        exact("generate --particles 2.5",
              "packbed: --particles: '2.5' is not allowed; allowed: a whole number from 1 to "
              "100000000"),
        exact("generate --particles 1e3",
              "packbed: --particles: '1e3' is not allowed; allowed: a whole number from 1 to "
              "100000000"),
        exact("generate --seed abc",
              "packbed: --seed: 'abc' is not allowed; allowed: a whole number from 0 to "
              "18446744073709551615"),
        exact("generate --update sideways",
              "packbed: --update: 'sideways' is not allowed; allowed: in-place, simultaneous"),
        exact("generate --solver newton",
              "packbed: --solver: 'newton' is not allowed; allowed: paper, fire"),
        exact("generate --warp-speed 9",
              "packbed generate: '--warp-speed 9' is not expected; allowed: the options of "
              "'packbed generate --help'"),
        // CLI11's own messages for a repeated option, one without its value and a required
        // one left out, in the one-line form.
        exact("generate -a 3 -a 4",
              "packbed generate: --aspect-ratio is given 2 times; allowed: once"),
        exact("generate -n", "packbed generate: --particles has no value; allowed: a whole "
                             "number from 1 to 100000000"),
        exact("voxelize bed.csv --container cylinder:2",
              "packbed voxelize: --voxel-size is required and not given; allowed: --voxel-size "
              "with its value ('packbed voxelize --help')"),
        exact("cfd-report", "packbed cfd-report: CASE is required and not given; allowed: "
                            "packbed cfd-report CASE ... ('packbed cfd-report --help')"),
        // inf, nan.
        exact("generate --aspect-ratio nan",
              "packbed: --aspect-ratio: 'nan' is not allowed; allowed: a number in [1, 10000]"),
        exact("generate --aspect-ratio inf",
              "packbed: --aspect-ratio: 'inf' is not allowed; allowed: a number in [1, 10000]"),
        exact("generate --aspect-ratio -inf",
              "packbed: --aspect-ratio: '-inf' is not allowed; allowed: a number in [1, 10000]"),
        exact("generate --diameter nan",
              "packbed: --diameter: 'nan' is not allowed; allowed: a number in [1e-12, 1e+12]"),
        exact("generate --e0 inf", "packbed: --e0: 'inf' is not allowed; allowed: a number in "
                                   "(0, 1)"),
        exact("generate --ck nan", "packbed: --ck: 'nan' is not allowed; allowed: a number in "
                                   "[0.01, 1)"),
        exact("generate --cg-step nan",
              "packbed: --cg-step: 'nan' is not allowed; allowed: a number in (0, 5e-06]"),
        exact("generate --mc-tolerance nan",
              "packbed: --mc-tolerance: 'nan' is not allowed; allowed: a number in (0, 100]"),
        exact("generate --band-clearance inf",
              "packbed: --band-clearance: 'inf' is not allowed; allowed: a number >= 0"),
        // Huge.
        exact("generate --aspect-ratio 1e5",
              "packbed: --aspect-ratio: 1e5 is not allowed; allowed: a number in [1, 10000]"),
        exact("generate --particles 100000001",
              "packbed: --particles: 100000001 is not allowed; allowed: a whole number from 1 "
              "to 100000000"),
        exact("generate --seed 18446744073709551616",
              "packbed: --seed: '18446744073709551616' is not allowed; allowed: a whole number "
              "from 0 to 18446744073709551615"),
        exact("generate --diameter 1e300",
              "packbed: --diameter: 1e300 is not allowed; allowed: a number in [1e-12, 1e+12]"),
        exact("generate --diameter 1e400",
              "packbed: --diameter: '1e400' is not allowed; allowed: a number in [1e-12, 1e+12]"),
        exact("generate --max-iterations 18446744073709551616",
              "packbed: --max-iterations: '18446744073709551616' is not allowed; allowed: a "
              "whole number from 1 to 18446744073709551615"),
        exact("generate --threads 1025",
              "packbed: --threads: 1025 is not allowed; allowed: a whole number from 1 to "
              "1024"),
        exact("generate --mc-period 1000001",
              "packbed: --mc-period: 1000001 is not allowed; allowed: a whole number from 1 "
              "to 1000000"),
        exact("generate --mc-window 10001",
              "packbed: --mc-window: 10001 is not allowed; allowed: a whole number from 2 to "
              "10000"),
        exact("generate --friction -0.1",
              "packbed: --friction: -0.1 is not allowed; allowed: a number in [0, 100]"),
        exact("generate --wall-friction 1e3",
              "packbed: --wall-friction: 1e3 is not allowed; allowed: a number in [0, 100]"),
        exact("generate --friction 0.3 --solver paper",
              "packbed generate: --solver paper with --friction 0.3 is not allowed; allowed: "
              "friction with --solver fire (the paper's iteration has no rotations)"),
        exact("generate --engine lammps --write-only @D/job -n 50 --out bed",
              "packbed generate: --out bed is not allowed with --write-only; allowed: "
              "--write-only DIR alone (the job's folder; `packbed import-lammps DIR --out OUT` "
              "writes the bed)"),
        exact("generate --layer-height 10 --solver paper -n 300",
              "packbed generate: --layer-height 10 is not allowed with --solver paper; allowed: "
              "--layer-height with --solver fire (the paper's iteration relaxes the bed in one "
              "piece)"),
        exact("generate --wall-friction 0.2 --engine lammps --write-only @D/job",
              "packbed generate: --wall-friction 0.2 is not allowed with "
              "--engine lammps; allowed: 0 (LAMMPS minimises the frictionless energy; friction "
              "needs damped dynamics with contact history, docs/lammps.md) or friction with "
              "--engine packbed"),
        exact("generate --target-void-fraction 1",
              "packbed: --target-void-fraction: 1 is not allowed; allowed: a number in (0, 1)"),
        exact("generate --target-void-fraction 0.42 --friction 0.1",
              "packbed generate: --friction 0.1 and --target-void-fraction 0.42 are both "
              "given; allowed: one of the two"),
        exact("generate --target-void-fraction 0.42 --wall-friction 0",
              "packbed generate: --wall-friction 0 and --target-void-fraction 0.42 are both "
              "given; allowed: one of the two"),
        exact("generate --target-void-fraction 0.42 --solver paper",
              "packbed generate: --target-void-fraction 0.42 is not allowed with --solver paper "
              "or --engine lammps; allowed: with --solver fire and --engine packbed (the target "
              "is reached by friction)"),
        exact("generate -a 6 -n 200 --target-void-fraction 0.3",
              "packbed generate: --target-void-fraction 0.3 is not reachable in this container "
              "with these sizes; allowed: 0.418 (no friction) to 0.497 (friction 1), as "
              "measured on a bed of 200 of its spheres"),
        exact("generate --layer-height 1e7",
              "packbed: --layer-height: 1e7 is not allowed; allowed: a number in [0, 1e+06]"),
        exact("generate --ck 1.2", "packbed: --ck: 1.2 is not allowed; allowed: a number in "
                                   "[0.01, 1)"),
        exact("generate --e0 1", "packbed: --e0: 1 is not allowed; allowed: a number in (0, 1)"),
        exact("generate --cg-step 1e-3",
              "packbed: --cg-step: 1e-3 is not allowed; allowed: a number in (0, 5e-06]"),
        exact("generate --skin 2", "packbed: --skin: 2 is not allowed; allowed: a number in "
                                   "(0, 1]"),
        exact("generate --tolerance 0.5",
              "packbed: --tolerance: 0.5 is not allowed; allowed: a number in [1e-12, 0.01]"),
        // Tiny, zero, negative.
        exact("generate --aspect-ratio 0.8",
              "packbed: --aspect-ratio: 0.8 is not allowed; allowed: a number in [1, 10000]"),
        exact("generate --particles 0",
              "packbed: --particles: 0 is not allowed; allowed: a whole number from 1 to "
              "100000000"),
        exact("generate --particles -5",
              "packbed: --particles: '-5' is not allowed; allowed: a whole number from 1 to "
              "100000000"),
        exact("generate --seed -1",
              "packbed: --seed: '-1' is not allowed; allowed: a whole number from 0 to "
              "18446744073709551615"),
        exact("generate --diameter -1",
              "packbed: --diameter: -1 is not allowed; allowed: a number in [1e-12, 1e+12]"),
        exact("generate --diameter 0",
              "packbed: --diameter: 0 is not allowed; allowed: a number in [1e-12, 1e+12]"),
        exact("generate --diameter 1e-300",
              "packbed: --diameter: 1e-300 is not allowed; allowed: a number in [1e-12, 1e+12]"),
        exact("generate --diameter 1e-400",
              "packbed: --diameter: '1e-400' is not allowed; allowed: a number in [1e-12, "
              "1e+12]"),
        exact("generate --cg-step 0",
              "packbed: --cg-step: 0 is not allowed; allowed: a number in (0, 5e-06]"),
        exact("generate --tolerance 0",
              "packbed: --tolerance: 0 is not allowed; allowed: a number in [1e-12, 0.01]"),
        // Accepted before, and never reached: the run went on until --max-iterations.
        exact("generate --tolerance 1e-16",
              "packbed: --tolerance: 1e-16 is not allowed; allowed: a number in [1e-12, 0.01]"),
        exact("generate --ck 1e-300",
              "packbed: --ck: 1e-300 is not allowed; allowed: a number in [0.01, 1)"),
        exact("generate --overlap-low 0",
              "packbed: --overlap-low: 0 is not allowed; allowed: a number in (0, 0.5)"),
        exact("generate --skin 0", "packbed: --skin: 0 is not allowed; allowed: a number in "
                                   "(0, 1]"),
        exact("generate --mc-period 0",
              "packbed: --mc-period: 0 is not allowed; allowed: a whole number from 1 to "
              "1000000"),
        exact("generate --mc-window 1",
              "packbed: --mc-window: 1 is not allowed; allowed: a whole number from 2 to "
              "10000"),
        exact("generate --max-iterations 0",
              "packbed: --max-iterations: 0 is not allowed; allowed: a whole number from 1 to "
              "18446744073709551615"),
        exact("generate --threads 0",
              "packbed: --threads: 0 is not allowed; allowed: a whole number from 1 to 1024"),
        exact("generate --band-clearance -1",
              "packbed: --band-clearance: -1 is not allowed; allowed: a number >= 0"),
        exact("generate --layer-height 5",
              "packbed generate: layer-height = 5 is not allowed; allowed: 0 (one piece) or "
              "10 to 1000000 (Dp)"),
        exact("generate --layer-height -1",
              "packbed: --layer-height: -1 is not allowed; allowed: a number in [0, 1e+06]"),
        exact("generate --overlap-low 0.02 --overlap-high 0.01",
              "packbed generate: overlap-high = 0.01 is not allowed; allowed: overlap-low "
              "(0.02) < overlap-high < 0.5 (Dp)"),
        // An upper bound under the lower one of the fire solver's schedule (0.015).
        exact("generate --overlap-high 0.008",
              "packbed generate: overlap-high = 0.008 is not allowed; allowed: overlap-low "
              "(0.015) < overlap-high < 0.5 (Dp)"),
        // Refused after the options are read, with a new --out: not created.
        exact("generate --overlap-low 0.02 --overlap-high 0.01 --out new",
              "packbed generate: overlap-high = 0.01 is not allowed; allowed: overlap-low "
              "(0.02) < overlap-high < 0.5 (Dp)"),
        // Empty strings.
        exact(std::vector<std::string>{"generate", "--aspect-ratio", ""},
              "packbed: --aspect-ratio: '' is not allowed; allowed: a number in [1, 10000]"),
        exact(std::vector<std::string>{"generate", "--particles", ""},
              "packbed: --particles: '' is not allowed; allowed: a whole number from 1 to "
              "100000000"),
        naming(std::vector<std::string>{"generate", "--update", ""}, {"--update"}),
        naming(std::vector<std::string>{"generate", "--solver", ""}, {"--solver"}),
        exact(std::vector<std::string>{"generate", "--out", ""},
              "packbed: --out: '' is not allowed (an empty path); " + a_path),
        exact(std::vector<std::string>{"generate", "--checkpoint", ""},
              "packbed: --checkpoint: '' is not allowed (an empty path); " + a_path),
        // Control characters in paths (gnuplot injection).
        exact(std::vector<std::string>{"generate", "-q", "--solver", "fire", "-a", "4", "-n", "60",
                                       "--out", "x\nsystem(\"touch PWNED\") #"},
              "packbed: --out: 'x\\nsystem(\"touch PWNED\") #' is not allowed (a control "
              "character in the path); " +
                  a_path),
        exact(std::vector<std::string>{"generate", "--out", "a\tb"},
              "packbed: --out: 'a\\tb' is not allowed (a control character in the path); " +
                  a_path),
        exact(std::vector<std::string>{"generate", "--out", "a\x1b[31mb"},
              "packbed: --out: 'a\\x1b[31mb' is not allowed (a control character in the "
              "path); " +
                  a_path),
        exact(std::vector<std::string>{"generate", "--solver", "fire", "-n", "2000", "-a", "5",
                                       "--layer-height", "10", "--checkpoint", "c\nk"},
              "packbed: --checkpoint: 'c\\nk' is not allowed (a control character in the "
              "path); " +
                  a_path),
        // --out: files where a directory is expected, a non-empty directory, a dangling link.
        exact("generate --out plain",
              "packbed generate: --out plain: a file has that name; allowed: a directory"),
        exact("generate --out fifo",
              "packbed generate: --out fifo: a file has that name; allowed: a directory"),
        exact("generate --out node",
              "packbed generate: --out node: a file has that name; allowed: a directory"),
        exact("generate --out /proc/version/x",
              "packbed generate: --out /proc/version/x: /proc/version is a file; allowed: a "
              "directory"),
        exact("generate --out full", "packbed generate: --out full: " + not_empty),
        exact("generate --out dirlink", "packbed generate: --out dirlink: " + not_empty),
        exact("generate --out .", "packbed generate: --out .: " + not_empty),
        exact("generate --out . --force",
              "packbed generate: --out .: --force would replace the working directory or a "
              "folder holding it; allowed: another directory"),
        exact("generate -a 3 -n 40 --out dangling",
              "packbed generate: --out dangling: a symbolic link to nothing; allowed: a directory "
              "or a new name"),
        // --checkpoint: directories, FIFOs, devices, a file as a folder (item 12), not ours.
        exact("generate --solver fire -n 2000 -a 5 --layer-height 10 --checkpoint dir",
              "packbed generate: --checkpoint dir: a directory has that name; allowed: a file"),
        exact("generate --solver fire -n 2000 -a 5 --layer-height 10 --checkpoint dirlink",
              "packbed generate: --checkpoint dirlink: a directory has that name; allowed: a "
              "file"),
        exact("generate --solver fire -n 2000 -a 5 --layer-height 10 --checkpoint fifo",
              "packbed generate: --checkpoint fifo: not a regular file; allowed: a file"),
        exact("generate --solver fire -n 2000 -a 5 --layer-height 10 --checkpoint node",
              "packbed generate: --checkpoint node: not a regular file; allowed: a file"),
        exact("generate --solver fire -n 2000 -a 5 --layer-height 10 --checkpoint "
              "/proc/version/c",
              "packbed generate: --checkpoint /proc/version/c: /proc/version is not a folder; "
              "allowed: a file in a folder you can write to"),
        exact("generate --solver fire -n 2000 -a 5 --layer-height 10 --checkpoint plain",
              "packbed generate: --checkpoint plain: not a packbed checkpoint (its first line is "
              "not 'packbed-checkpoint 3'); allowed: a checkpoint written by `packbed generate "
              "--checkpoint` with the same options"),
        exact("generate --checkpoint ck",
              "packbed generate: --checkpoint ck: only a fire run in layers can be resumed, this "
              "run is in one piece; allowed: --solver fire with an initial height L0 = 25.16 Dp "
              "above twice --layer-height (now 30)"),
        exact("generate --solver paper --checkpoint ck",
              "packbed generate: --checkpoint ck: only a fire run in layers can be resumed, this "
              "run is paper mode; allowed: --solver fire with an initial height L0 = 25.16 Dp "
              "above twice --layer-height (now 30)")));

// Lattice: --region, --origin and --rotate are parsed by packbed, the rest by CLI11.
// The --region messages: only the option and the value are pinned.
INSTANTIATE_TEST_SUITE_P(
    Lattice, CliBadInput,
    ::testing::Values(
        naming("lattice --region box:1,2", {"--region", "box:1,2"}),
        naming("lattice --region box:1,2 --out new", {"--region", "box:1,2"}),
        naming("lattice --region cylinder:-3,2", {"--region", "cylinder:-3,2"}),
        naming("lattice --region box:1,2,x", {"--region", "box:1,2,x"}),
        naming("lattice --region sphere:1", {"--region", "sphere:1"}),
        naming(std::vector<std::string>{"lattice", "--region", ""}, {"--region"}),
        naming("lattice --region box:inf,1,1", {"--region", "box:inf,1,1"}),
        naming("lattice --region box:nan,1,1", {"--region", "box:nan,1,1"}),
        naming("lattice --region box:1e16,1,1", {"--region", "box:1e16,1,1"}),
        naming("lattice --region cylinder:1e16,1", {"--region", "cylinder:1e16,1"}),
        naming("lattice --region box:1e5,1e5,1e5", {"region"}),
        naming("lattice --region cylinder:1e5,1e5", {"region"}),
        naming("lattice --diameter 1e-12", {"1e-12"}),
        // A thin region far longer than the rest; an origin far away.
        naming("lattice --region box:1e11,0.001,0.001 --keep centres --type sc", {"--region"}),
        // A random array: hard spheres below their freezing point, a cell 2 sigma wide.
        exact("random-array -n 100 --solid-fraction 0.45 --gap 0.05 --out ra",
              "packbed random-array: --solid-fraction 0.45 with --gap 0.05 is not allowed: its "
              "hard spheres of diameter (1 + gap) d fill 0.5209; allowed: at most 0.49 (hard "
              "spheres freeze at 0.494), a solid fraction up to 0.4233 with this gap"),
        exact("random-array -n 4 --solid-fraction 0.4 --out ra",
              "packbed random-array: --count 4 is not allowed at --solid-fraction 0.4: the "
              "cell's edge 1.736 d is below twice the spheres' diameter (1 + gap) d; allowed: "
              "a count of at least 7"),
        exact("random-array -n 1 --out ra",
              "packbed: --count: 1 is not allowed; allowed: a whole number from 2 to 10000000"),
        exact("random-array -n 10 --solid-fraction 0.5 --out ra",
              "packbed: --solid-fraction: 0.5 is not allowed; allowed: a number in (0, 0.49]"),
        exact("random-array -n 10000000 --sweeps 10000 --out ra",
              "packbed random-array: --sweeps 10000 with --count 10000000 is not allowed: 1e+11 "
              "trial moves; allowed: at most 1e+10 (spheres times sweeps)"),
        exact("lattice --origin 1e18,0,0",
              "packbed lattice: --origin 1e+18,0,0 is not allowed (1e+18 ball diameters from the "
              "region: the positions would lose their precision); allowed: within 1e+06 ball "
              "diameters of the region"),
        exact("lattice --origin 1,x,2",
              "packbed lattice: --origin '1,x,2' is not allowed; allowed: x,y,z (three finite "
              "numbers)"),
        exact("lattice --origin a,b,c",
              "packbed lattice: --origin 'a,b,c' is not allowed; allowed: x,y,z (three finite "
              "numbers)"),
        exact("lattice --origin inf,0,0",
              "packbed lattice: --origin 'inf,0,0' is not allowed; allowed: x,y,z (three finite "
              "numbers)"),
        exact("lattice --origin nan,0,0",
              "packbed lattice: --origin 'nan,0,0' is not allowed; allowed: x,y,z (three finite "
              "numbers)"),
        exact("lattice --origin 1,2",
              "packbed lattice: --origin '1,2' is not allowed; allowed: x,y,z (three finite "
              "numbers)"),
        exact("lattice --rotate w:30",
              "packbed lattice: --rotate 'w:30' is not allowed; allowed: AXIS:DEGREES pairs "
              "separated by commas, AXIS x, y or z (e.g. z:30,x:10)"),
        exact("lattice --rotate z:inf",
              "packbed lattice: --rotate 'z:inf' is not allowed; allowed: AXIS:DEGREES pairs "
              "separated by commas, AXIS x, y or z (e.g. z:30,x:10)"),
        exact("lattice --rotate z:nan",
              "packbed lattice: --rotate 'z:nan' is not allowed; allowed: AXIS:DEGREES pairs "
              "separated by commas, AXIS x, y or z (e.g. z:30,x:10)"),
        exact("lattice --rotate x",
              "packbed lattice: --rotate 'x' is not allowed; allowed: AXIS:DEGREES pairs "
              "separated by commas, AXIS x, y or z (e.g. z:30,x:10)"),
        exact("lattice --type honeycomb",
              "packbed: --type: 'honeycomb' is not allowed; allowed: diamond, sc, bcc, fcc, hcp"),
        naming(std::vector<std::string>{"lattice", "--type", ""}, {"--type"}),
        exact("lattice --keep some",
              "packbed: --keep: 'some' is not allowed; allowed: whole, centres"),
        naming(std::vector<std::string>{"lattice", "--keep", ""}, {"--keep"}),
        exact("lattice --diameter x",
              "packbed: --diameter: 'x' is not allowed; allowed: a number in [1e-12, 1e+12]"),
        exact("lattice --diameter nan",
              "packbed: --diameter: 'nan' is not allowed; allowed: a number in [1e-12, 1e+12]"),
        exact("lattice --diameter 1e300",
              "packbed: --diameter: 1e300 is not allowed; allowed: a number in [1e-12, 1e+12]"),
        exact("lattice --diameter 1e-300",
              "packbed: --diameter: 1e-300 is not allowed; allowed: a number in [1e-12, 1e+12]"),
        exact("lattice --band-clearance nan",
              "packbed: --band-clearance: 'nan' is not allowed; allowed: a number in [0, 1e+06)"),
        exact("lattice --band-clearance 1e7",
              "packbed: --band-clearance: 1e7 is not allowed; allowed: a number in [0, 1e+06)"),
        exact("lattice --band-clearance -1",
              "packbed: --band-clearance: -1 is not allowed; allowed: a number in [0, 1e+06)"),
        naming(std::vector<std::string>{"lattice", "--out", ""}, {"--out", "''"}),
        naming(std::vector<std::string>{"lattice", "--out", "l\nx"}, {"--out", "'l\\nx'"}),
        naming(std::vector<std::string>{"lattice", "--out", "l\tx"}, {"--out", "'l\\tx'"}),
        exact("lattice --out plain",
              "packbed lattice: --out plain: a file has that name; allowed: a directory"),
        exact("lattice --out fifo",
              "packbed lattice: --out fifo: a file has that name; allowed: a directory"),
        exact("lattice --out node",
              "packbed lattice: --out node: a file has that name; allowed: a directory"),
        exact("lattice --out /proc/version/x",
              "packbed lattice: --out /proc/version/x: /proc/version is a file; allowed: a "
              "directory"),
        exact("lattice --out full", "packbed lattice: --out full: " + not_empty),
        exact("lattice --out dangling", "packbed lattice: --out dangling: a symbolic link to "
                                        "nothing; allowed: a directory or a new name")));

INSTANTIATE_TEST_SUITE_P(
    Analyze, CliBadInput,
    ::testing::Values(
        // The particles file: missing, a directory, links, a FIFO, devices, unreadable, binary.
        exact("analyze missing.csv -R 2",
              "packbed analyze: missing.csv: cannot open the file (No such file or directory); " +
                  regular),
        exact("analyze dir -R 2", "packbed analyze: dir: a directory; " + regular),
        exact("analyze dirlink -R 2", "packbed analyze: dirlink: a directory; " + regular),
        exact("analyze dangling -R 2",
              "packbed analyze: dangling: cannot open the file (No such file or directory); " +
                  regular),
        exact("analyze fifo -R 2", "packbed analyze: fifo: a FIFO (named pipe); " + regular),
        exact("analyze /dev/zero -R 2", "packbed analyze: /dev/zero: a device; " + regular),
        exact("analyze /dev/null -R 2", "packbed analyze: /dev/null: a device; " + regular),
        exact("analyze node -R 2", "packbed analyze: node: a device; " + regular),
        exact("analyze /proc/self/mem -R 2",
              "packbed analyze: /proc/self/mem: cannot be read (an input/output error); " +
                  regular),
        exact("analyze zeros -R 2",
              "packbed analyze: zeros:1: a line longer than 1048576 bytes; allowed: lines up to "
              "that length (is this a text file?)"),
        exact("analyze plain -R 2",
              "packbed analyze: plain:1: cannot tell the format; allowed: .csv, .tsv, .xyz, "
              ".dump, .lammpstrj or .data files (also .gz), or a table whose header names x, y "
              "and z"),
        exact("analyze empty.csv -R 2",
              "packbed analyze: empty.csv: empty file; expected a header line such as x,y,z,r"),
        exact("analyze header.csv -R 2",
              "packbed analyze: header.csv: no spheres after the header"),
        exact("analyze nan.csv -R 2",
              "packbed analyze: nan.csv:2: column 'r' value 'nan' is not a finite number"),
        exact("analyze negative.csv -R 2",
              "packbed analyze: negative.csv:2: column 'r' value -1 is not allowed; a radius "
              "must be from 5e-13 to 5e+11"),
        exact(std::vector<std::string>{"analyze", "", "-R", "2"},
              "packbed: particles: '' is not allowed (an empty path); " + a_path),
        exact(std::vector<std::string>{"analyze", "nl\ndir/bed.csv", "-R", "2"},
              "packbed: particles: 'nl\\ndir/bed.csv' is not allowed (a control character in "
              "the path); " +
                  a_path),
        exact(std::vector<std::string>{"analyze",
                                       "a\x1b"
                                       "b.csv",
                                       "-R", "2"},
              "packbed: particles: 'a\\x1bb.csv' is not allowed (a control character in the "
              "path); " +
                  a_path),
        // summary.json beside the file: a directory, a FIFO; none.
        exact("analyze sumdir/bed.csv",
              "packbed analyze: sumdir/summary.json: a directory; " + regular),
        exact("analyze sumfifo/bed.csv",
              "packbed analyze: sumfifo/summary.json: a FIFO (named pipe); " + regular),
        exact("analyze one.csv",
              "packbed analyze: --container (or --container-radius) is needed: no summary.json "
              "with a container next to one.csv"),
        // One sphere far above the rest (the bin limits named, not pinned word for word).
        naming("analyze far.csv -R 1.5", {"--slab-height"}),
        naming("analyze far.csv -R 1.5 --out new", {"--slab-height"}),
        naming("analyze far15.csv -R 1.5", {"--slab-height"}),
        // Numbers the validators accepted.
        exact("analyze bed.csv -R 1e300",
              "packbed: --container-radius: 1e300 is not allowed; allowed: a number in (0, "
              "1e+15]"),
        exact("analyze bed.csv -R 1e308",
              "packbed: --container-radius: 1e308 is not allowed; allowed: a number in (0, "
              "1e+15]"),
        naming("analyze bed.csv -R 1e9", {"--container-radius"}),
        naming("analyze bed.csv -R 1 --diameter 1e-9", {"--diameter"}),
        naming("analyze bed.csv -R 1 --diameter 1e-6", {"--diameter"}),
        // Numbers.
        exact("analyze bed.csv -R x",
              "packbed: --container-radius: 'x' is not allowed; allowed: a number in (0, 1e+15]"),
        exact("analyze bed.csv -R inf",
              "packbed: --container-radius: 'inf' is not allowed; allowed: a number in (0, "
              "1e+15]"),
        exact("analyze bed.csv -R nan",
              "packbed: --container-radius: 'nan' is not allowed; allowed: a number in (0, "
              "1e+15]"),
        exact(std::vector<std::string>{"analyze", "bed.csv", "-R", ""},
              "packbed: --container-radius: '' is not allowed; allowed: a number in (0, 1e+15]"),
        exact("analyze bed.csv -R 0",
              "packbed: --container-radius: 0 is not allowed; allowed: a number in (0, 1e+15]"),
        exact("analyze bed.csv -R -1",
              "packbed: --container-radius: -1 is not allowed; allowed: a number in (0, 1e+15]"),
        exact("analyze bed.csv -R 1 --shell-width 0",
              "packbed: --shell-width: 0 is not allowed; allowed: a number in [0.0001, 10]"),
        exact("analyze bed.csv -R 1 --shell-width 1e-5",
              "packbed: --shell-width: 1e-5 is not allowed; allowed: a number in [0.0001, 10]"),
        exact("analyze bed.csv -R 1 --slab-height nan",
              "packbed: --slab-height: 'nan' is not allowed; allowed: a number in [0.0001, 10]"),
        exact("analyze bed.csv -R 1 --centre-bin inf",
              "packbed: --centre-bin: 'inf' is not allowed; allowed: a number in [0.0001, 10]"),
        exact("analyze bed.csv -R 1 --contact-tolerance -1",
              "packbed: --contact-tolerance: -1 is not allowed; allowed: a number in [0, 0.5]"),
        exact("analyze bed.csv -R 1 --rdf-range 1e9",
              "packbed: --rdf-range: 1e9 is not allowed; allowed: a number in [0.1, 20]"),
        exact("analyze bed.csv -R 1 --rdf-bin 0",
              "packbed: --rdf-bin: 0 is not allowed; allowed: a number in [0.0001, 1]"),
        exact("analyze bed.csv -R 1 --outside-tolerance 2",
              "packbed: --outside-tolerance: 2 is not allowed; allowed: a number in [0, 1]"),
        exact("analyze bed.csv -R 1 --band-clearance 1e300",
              "packbed analyze: --band-clearance 1e+300 Dp is not allowed for this bed (top at 40, "
              "40 Dp); allowed: less than half its height"),
        exact("analyze bed.csv -R 1 --threads 0",
              "packbed: --threads: 0 is not allowed; allowed: a whole number from 1 to 1024"),
        exact("generate -n 010",
              "packbed: --particles: '010' is not allowed; allowed: a whole number from 1 to "
              "100000000, written without leading zeros"),
        exact("generate -s 010",
              "packbed: --seed: '010' is not allowed; allowed: a whole number from 0 to "
              "18446744073709551615, written without leading zeros"),
        exact("export bed.csv --format openfoam --ranks 02",
              "packbed: --ranks: '02' is not allowed; allowed: a whole number from 1 to 1024, "
              "written without leading zeros"),
        exact("analyze bed.csv -R 1 --format png",
              "packbed: --format: 'png' is not allowed; allowed: auto, csv, xyz, lammps-dump, "
              "lammps-data"),
        // Frames, the container's axis and floor, inputs of the newer readers.
        exact("analyze bed.csv -R 1 --frame 0",
              "packbed: --frame: '0' is not allowed; " + frame_allowed),
        exact("analyze bed.csv -R 1 --frame x",
              "packbed: --frame: 'x' is not allowed; " + frame_allowed),
        // A leading 0 would be read as octal by the parser (010 as 8): refused.
        exact("analyze bed.csv -R 1 --frame 010",
              "packbed: --frame: '010' is not allowed; " + frame_allowed),
        exact("analyze bed.csv -R 1 --frame=-01",
              "packbed: --frame: '-01' is not allowed; " + frame_allowed),
        exact("analyze bed.csv -R 1 --frame 1.5",
              "packbed: --frame: '1.5' is not allowed; " + frame_allowed),
        exact("analyze bed.csv -R 1 --frame 99999999999999999999",
              "packbed: --frame: '99999999999999999999' is not allowed; " + frame_allowed),
        exact("analyze bed.csv -R 1 --frame 2",
              "packbed analyze: bed.csv: frame 2 is not allowed: the file has 1 frame; allowed: 1 "
              "or -1"),
        exact("analyze frames.xyz -R 1 --frame 3",
              "packbed analyze: frames.xyz: frame 3 is not allowed: the file has 2 frames; "
              "allowed: 1 to 2, or -1 to -2 counting from the end"),
        exact("analyze frames.xyz -R 1 --frame -3",
              "packbed analyze: frames.xyz: frame -3 is not allowed: the file has 2 frames; "
              "allowed: 1 to 2, or -1 to -2 counting from the end"),
        exact("analyze bed.csv -R 1 --frames some",
              "packbed: --frames: 'some' is not allowed; allowed: all"),
        exact(
            "analyze bed.csv -R 1 --frames all --frame 1",
            "packbed analyze: --frame 1 and --frames all are both given; allowed: one of the two"),
        exact("analyze bed.csv -R 1 --axis 1",
              "packbed: --axis: '1' is not allowed; " + axis_allowed),
        exact("analyze bed.csv -R 1 --axis 1,2,3",
              "packbed: --axis: '1,2,3' is not allowed; " + axis_allowed),
        exact("analyze bed.csv -R 1 --axis 1,nan",
              "packbed: --axis: '1,nan' is not allowed; " + axis_allowed),
        exact("analyze bed.csv -R 1 --axis 1e300,0",
              "packbed: --axis: '1e300,0' is not allowed; " + axis_allowed),
        exact(std::vector<std::string>{"analyze", "bed.csv", "-R", "1", "--axis", ""},
              "packbed: --axis: '' is not allowed; " + axis_allowed),
        exact("analyze bed.csv -R 1 --floor nan",
              "packbed: --floor: 'nan' is not allowed; allowed: a number in [-1e+15, 1e+15]"),
        exact("analyze bed.csv -R 1 --floor 1e300",
              "packbed: --floor: 1e300 is not allowed; allowed: a number in [-1e+15, 1e+15]"),
        exact("analyze bed.csv -R 1 --axis 5,0",
              "packbed analyze: bed.csv:2: the sphere at (-5, 0, 0.5) (from --axis and --floor) "
              "sticks out of the container (radius 1, floor z = 0) by 4.5; allowed: up to 0.01 "
              "(--outside-tolerance times Dp, in the file's units)"),
        exact("analyze bed.csv -R 1 --floor 1",
              "packbed analyze: bed.csv:2: the sphere at (0, 0, -0.5) (from --axis and --floor) "
              "sticks out of the container (radius 1, floor z = 0) by 1; allowed: up to 0.01 "
              "(--outside-tolerance times Dp, in the file's units)"),
        exact("analyze frames.xyz -R 1 --frames all --floor 1",
              "packbed analyze: frame 1: frames.xyz:3: the sphere at (0, 0, -0.5) (from --axis "
              "and --floor) sticks out of the container (radius 1, floor z = 0) by 1; allowed: "
              "up to 0.01 (--outside-tolerance times Dp, in the file's units)"),
        exact("analyze nosize.dump -R 1",
              "packbed analyze: nosize.dump:9: missing column 'r'; needed: x, y, z and r, radius, "
              "d or diameter, or give the diameter (--diameter)"),
        exact("analyze cut.csv.gz -R 1",
              "packbed analyze: cut.csv.gz: the gzip data ends early (a truncated .gz file?); "
              "allowed: a complete gzip file"),
        naming(std::vector<std::string>{"analyze", "bed.csv", "-R", "1", "--format", ""},
               {"--format"}),
        // --out.
        exact("analyze bed.csv -R 1 --out full", "packbed analyze: --out full: " + not_empty),
        exact("analyze bed.csv -R 1 --out .", "packbed analyze: --out .: " + not_empty),
        exact("analyze bed.csv -R 1 --out plain",
              "packbed analyze: --out plain: a file has that name; allowed: a directory"),
        exact("analyze bed.csv -R 1 --out bed.csv",
              "packbed analyze: --out bed.csv: a file has that name; allowed: a directory"),
        exact("analyze bed.csv -R 1 --out fifo",
              "packbed analyze: --out fifo: a file has that name; allowed: a directory"),
        exact(std::vector<std::string>{"analyze", "bed.csv", "-R", "1", "--out", ""},
              "packbed: --out: '' is not allowed (an empty path); " + a_path),
        exact(std::vector<std::string>{"analyze", "bed.csv", "-R", "1", "--out", "o\nx"},
              "packbed: --out: 'o\\nx' is not allowed (a control character in the path); " +
                  a_path),
        exact("analyze full/bed.csv -R 1 --out full --force",
              "packbed analyze: the particles file full/bed.csv lies in --out full, which "
              "--force would replace; allowed: an output directory that does not hold the "
              "inputs"),
        exact("analyze bed.csv -R 1 --out dangling",
              "packbed analyze: --out dangling: a symbolic link to nothing; allowed: a directory "
              "or a new name"),
        exact("analyze @D/outside.csv --container-radius 1.5 --out new",
              "packbed analyze: @D/outside.csv:3: the sphere at (1.1, 0, 0.5) sticks out of the "
              "container (radius 1.5, floor z = 0) by 0.1; allowed: up to 0.01 "
              "(--outside-tolerance times Dp, in the file's units)")));

INSTANTIATE_TEST_SUITE_P(
    Export, CliBadInput,
    ::testing::Values(
        // The particles file.
        exact("export missing.csv",
              "packbed export: missing.csv: cannot open the file (No such file or directory); " +
                  regular),
        exact("export dir", "packbed export: dir: a directory; " + regular),
        exact("export dirlink", "packbed export: dirlink: a directory; " + regular),
        exact("export dangling",
              "packbed export: dangling: cannot open the file (No such file or directory); " +
                  regular),
        exact("export fifo", "packbed export: fifo: a FIFO (named pipe); " + regular),
        exact("export /dev/zero", "packbed export: /dev/zero: a device; " + regular),
        exact("export node", "packbed export: node: a device; " + regular),
        exact("export /proc/self/mem --out x.data",
              "packbed export: /proc/self/mem: cannot be read (an input/output error); " + regular),
        exact("export zeros --out x.data",
              "packbed export: zeros:1: a line longer than 1048576 bytes; allowed: lines up to "
              "that length (is this a text file?)"),
        exact(std::vector<std::string>{"export", ""},
              "packbed: particles: '' is not allowed (an empty path); " + a_path),
        exact(std::vector<std::string>{"export", "a\tb.csv"},
              "packbed: particles: 'a\\tb.csv' is not allowed (a control character in the "
              "path); " +
                  a_path),
        exact("export sumdir/bed.csv --format stl",
              "packbed export: sumdir/summary.json: a directory; " + regular),
        // --out is the input, by name, by link, by hard link.
        exact("export two.csv --out two.csv",
              "packbed export: the particles file two.csv: the output two.csv would overwrite "
              "it; allowed: an output that is not an input"),
        exact("export two.csv --out dir/../two.csv",
              "packbed export: the particles file two.csv: the output dir/../two.csv would "
              "overwrite "
              "it; allowed: an output that is not an input"),
        exact("export two.csv --out twolink",
              "packbed export: the particles file two.csv: the output twolink would overwrite "
              "it; allowed: an output that is not an input"),
        exact("export two.csv --out hard.csv",
              "packbed export: the particles file two.csv: the output hard.csv would "
              "overwrite it; allowed: an output that is not an input"),
        exact("export two.csv --format stl --out two.csv",
              "packbed export: the particles file two.csv: the output two.csv would overwrite "
              "it; allowed: an output that is not an input"),
        // --out a directory; other files where a file is expected.
        exact("export two.csv --out dir", "packbed export: --out dir: a directory has that "
                                          "name; allowed: a regular file name"),
        exact("export two.csv --out full", "packbed export: --out full: a directory has that "
                                           "name; allowed: a regular file name"),
        exact("export two.csv --out dir/",
              "packbed export: --out dir/ is not allowed; allowed: a file name"),
        exact("export two.csv --out fifo",
              "packbed export: --out fifo: a FIFO has that name; allowed: a regular file name"),
        exact("export two.csv --out node", "packbed export: --out node: a device or socket has "
                                           "that name; allowed: a regular file name"),
        exact(std::vector<std::string>{"export", "two.csv", "--out", ""},
              "packbed: --out: '' is not allowed (an empty path); " + a_path),
        exact(std::vector<std::string>{"export", "two.csv", "--out", "x\ny.data"},
              "packbed: --out: 'x\\ny.data' is not allowed (a control character in the path); " +
                  a_path),
        // OpenFOAM case directories.
        exact("export two.csv --format openfoam -R 2 --out full",
              "packbed export: --out full: " + not_empty),
        exact("export two.csv --format openfoam -R 2 --out plain",
              "packbed export: --out plain: a file has that name; allowed: a directory"),
        exact("export two.csv --format openfoam -R 2 --out two.csv",
              "packbed export: --out two.csv: a file has that name; allowed: a directory"),
        exact("export two.csv --format openfoam -R 2 --out dangling",
              "packbed export: --out dangling: a symbolic link to nothing; allowed: a directory or "
              "a new name"),
        exact("export @D/two.csv --format openfoam",
              "packbed export: --format openfoam needs the container: give --container (no "
              "summary.json with a container next to @D/two.csv)"),
        exact("export two.csv --format openfoam -R 2 --cells-per-diameter 0",
              "packbed: --cells-per-diameter: 0 is not allowed; allowed: a whole number from 1 "
              "to 100"),
        exact("export two.csv --format openfoam -R 2 --particle-level 9",
              "packbed: --particle-level: 9 is not allowed; allowed: a whole number from 0 to "
              "8"),
        exact("export two.csv --format openfoam -R 2 --wall-level x",
              "packbed: --wall-level: 'x' is not allowed; allowed: a whole number from 0 to 8"),
        exact("export two.csv --format openfoam -R 2 --layers 11",
              "packbed: --layers: 11 is not allowed; allowed: a whole number from 0 to 10"),
        exact("export two.csv --format openfoam -R 2 --mesh fine",
              "packbed: --mesh: 'fine' is not allowed; allowed: quick, accurate"),
        // A cell periodic along z: a periodic container, its period given, every sphere in it.
        exact("export two.csv --format openfoam -R 2 --flow periodic --container-height 2 --out pf",
              "packbed export: --flow periodic is not allowed with --container cylinder:4; "
              "allowed: a periodic cell (periodic:LX,LY), whose sides repeat across"),
        exact("export two.csv --format stl --flow periodic --out pf.stl",
              "packbed export: --flow periodic is not allowed with --format stl; allowed: "
              "--format openfoam"),
        exact("export two.csv --format openfoam --container periodic:4,4 --flow periodic --out pf",
              "packbed export: --flow periodic needs --container-height: the cell's period along "
              "z (a lattice's region height; a random array's summary.json gives its own); "
              "allowed: a height above every centre"),
        exact("export two.csv --format openfoam --container periodic:4,4 --flow periodic "
              "--container-height 0.8 --out pf",
              "packbed export: two.csv:2: the sphere centre at z = 1 is outside the cell "
              "periodic along z with period 0.8; allowed with --flow periodic: centres from "
              "z = 0 to below --container-height"),
        // Touching across a period exactly 2 d tall: each touches both copies of the other.
        exact("export two.csv --format openfoam --container periodic:4,4 --flow periodic "
              "--container-height 2 --contacts caps:0.02 --out pf",
              "packbed export: --container periodic:4,4 is not allowed for spheres of diameter "
              "up to 1 with --contacts caps:0.02; allowed: periods at least twice the largest "
              "diameter and the caps' gap, 2.04 (the minimum image)"),
        exact("export two.csv --format openfoam --container periodic:4,4 --flow periodic "
              "--container-height 2 --turbulence kEpsilon --out pf",
              "packbed export: --turbulence kEpsilon is not allowed with --flow periodic; "
              "allowed: laminar (a periodic cell has no inlet to set the turbulence at)"),
        exact("export two.csv --format openfoam --flow sideways",
              "packbed: --flow: 'sideways' is not allowed; allowed: inlet, periodic"),
        // Options.
        exact("export two.csv --format png",
              "packbed: --format: 'png' is not allowed; allowed: lammps-data, liggghts-data, stl, "
              "stl-ascii, obj, openfoam"),
        naming(std::vector<std::string>{"export", "two.csv", "--format", ""}, {"--format"}),
        exact("export @D/one.csv --density 0",
              "packbed: --density: 0 is not allowed; allowed: a number > 0"),
        exact("export two.csv --density nan",
              "packbed: --density: 'nan' is not allowed; allowed: a number > 0"),
        exact("export two.csv --density inf",
              "packbed: --density: 'inf' is not allowed; allowed: a number > 0"),
        exact("export two.csv --density 1e400",
              "packbed: --density: '1e400' is not allowed; allowed: a number > 0"),
        exact("export two.csv --density x",
              "packbed: --density: 'x' is not allowed; allowed: a number > 0"),
        exact("export @D/one.csv --box 0,1,0,1,1,0",
              "packbed export: --box '0,1,0,1,1,0' is not allowed; allowed: "
              "xlo,xhi,ylo,yhi,zlo,zhi with lo < hi"),
        exact("export two.csv --box 0,1,0,1,0,inf",
              "packbed export: --box '0,1,0,1,0,inf' is not allowed; allowed: "
              "xlo,xhi,ylo,yhi,zlo,zhi with lo < hi"),
        exact("export two.csv --box 0,1,0,1,0,nan",
              "packbed export: --box '0,1,0,1,0,nan' is not allowed; allowed: "
              "xlo,xhi,ylo,yhi,zlo,zhi with lo < hi"),
        exact("export @D/one.csv --box 1,2,1,2,1,2",
              "packbed export: sphere 1 at (0, 0, 0) lies outside the box [1, 2] x [1, 2] x "
              "[1, 2]; allowed: a box holding every centre"),
        // The data files in a known container: its height, a centre outside it, a name the
        // example DEM input cannot hold, a summary.json that is no file.
        exact("export two.csv -R 2 --container-height 1",
              "packbed export: --container-height 1 is not allowed; allowed: above the bed's top, "
              "1.5"),
        exact("export two.csv --format liggghts-data -R 0.5 --out x.data",
              "packbed export: two.csv:3: the sphere centre (0.99, 0, 1) is outside the container "
              "(radius 0.5, floor z = 0); allowed: centres inside it"),
        // A box: (0, 0, 1) lies on its faces x = 0 and y = 0.
        exact("export two.csv --format stl --container box:2,2 --out x.stl",
              "packbed export: two.csv:2: the sphere centre (0, 0, 1) is outside the container "
              "(box:2,2, floor z = 0); allowed: centres inside it"),
        exact("export two.csv --format lammps-data --container box:3,0.5 --out x.data",
              "packbed export: two.csv:2: the sphere centre (0, 0, 1) is outside the container "
              "(box:3,0.5, floor z = 0); allowed: centres inside it"),
        exact("export two.csv --format stl --container cone:10,2,5 --container-height 20 --out "
              "c.stl",
              "packbed export: --container-height 20 is not allowed with --container cone:10,2,5: "
              "the container has no cross-section there; allowed: a height where it has one"),
        exact("export two.csv --format openfoam --container box:0,2 --out c",
              "packbed: --container: 'box:0,2' is not allowed; allowed: cylinder:D, a tube of "
              "inner diameter D, a number in (0, 2e+15]; or box:LX,LY, walls at x = 0, LX and y = "
              "0, LY, each in (0, 1e+15]; or annulus:D,DI, between a tube of diameter D and a "
              "coaxial rod of diameter DI, 0 < DI < D <= 2e+15; or periodic:LX,LY, a cell "
              "periodic in x and y, each in (0, 1e+15]; or cone:DB,DT,H, a frustum of floor "
              "diameter DB at z = 0 and diameter DT at z = H, DB and DT in (0, 2e+15], H in (0, "
              "1e+15]"),
        exact(std::vector<std::string>{"export", "two.csv", "-R", "2", "--out", "a b.data"},
              "packbed export: --out a b.data: the file name 'a b.data' is not allowed with the "
              "example DEM input, which names it; allowed: letters, digits, '.', '_', '-' and '+' "
              "(or --no-container: no example)"),
        exact(std::vector<std::string>{"export", "two.csv", "-R", "2", "--format", "liggghts-data",
                                       "--out", "dir/$x.data"},
              "packbed export: --out dir/$x.data: the file name '$x.data' is not allowed with the "
              "example DEM input, which names it; allowed: letters, digits, '.', '_', '-' and '+' "
              "(or --no-container: no example)"),
        exact("export sumdir/bed.csv --format lammps-data",
              "packbed export: sumdir/summary.json: a directory; " + regular),
        exact("export two.csv --fluid-velocity inf",
              "packbed: --fluid-velocity: 'inf' is not allowed; allowed: a number >= 0"),
        exact("export two.csv --fluid-velocity -1",
              "packbed: --fluid-velocity: -1 is not allowed; allowed: a number >= 0"),
        exact("export two.csv --diameter 0",
              "packbed: --diameter: 0 is not allowed; allowed: a number > 0"),
        exact("export two.csv --frame 0", "packbed: --frame: '0' is not allowed; " + frame_allowed),
        exact("export two.csv --frame 2",
              "packbed export: two.csv: frame 2 is not allowed: the file has 1 frame; allowed: 1 "
              "or -1"),
        exact("export two.csv --axis 1,x",
              "packbed: --axis: '1,x' is not allowed; " + axis_allowed),
        exact("export two.csv --floor inf",
              "packbed: --floor: 'inf' is not allowed; allowed: a number in [-1e+15, 1e+15]"),
        exact("export cut.csv.gz --out x.data",
              "packbed export: cut.csv.gz: the gzip data ends early (a truncated .gz file?); "
              "allowed: a complete gzip file"),
        exact("export @D/two.csv --format stl --refine 9",
              "packbed: --refine: 9 is not allowed; allowed: a whole number from 0 to 7"),
        exact("export two.csv --format stl --refine -1",
              "packbed: --refine: '-1' is not allowed; allowed: a whole number from 0 to 7"),
        exact("export two.csv --format stl --refine x",
              "packbed: --refine: 'x' is not allowed; allowed: a whole number from 0 to 7"),
        exact(std::vector<std::string>{"export", "two.csv", "--format", "stl", "--refine", ""},
              "packbed: --refine: '' is not allowed; allowed: a whole number from 0 to 7"),
        exact("export two.csv --format stl --facets round",
              "packbed: --facets: 'round' is not allowed; allowed: inscribed, volume, auto"),
        // Facets grown by 0.289 % of the radius (level 3) would cross the gap of 0.002 that
        // shrink:0.012 leaves between the pair 0.99 apart (radii 0.494).
        exact("export two.csv --format stl --contacts shrink:0.012 --facets volume",
              "packbed export: --facets volume is not allowed here: it grows sphere 1's facets by "
              "0.00143, and its gap to sphere 2 is 0.002; allowed: a contact treatment that leaves "
              "wider gaps (caps:H, shrink:F), a finer --refine, or --facets inscribed or auto"),
        exact("export two.csv --format stl --edge 0",
              "packbed: --edge: 0 is not allowed; allowed: a number > 0"),
        exact("export two.csv --format stl --edge nan",
              "packbed: --edge: 'nan' is not allowed; allowed: a number > 0"),
        exact("export two.csv --format stl -R inf",
              "packbed: --container-radius: 'inf' is not allowed; allowed: a number > 0"),
        exact("export two.csv --format stl -R 1e-300 --out x.stl",
              "packbed export: two.csv:3: the sphere centre (0.99, 0, 1) is outside the container "
              "(radius 1e-300, floor z = 0); allowed: centres inside it"),
        exact("export @D/one.csv --format stl --container-radius 2",
              "packbed export: @D/one.csv:2: the sphere centre (0, 0, 0) is outside the "
              "container (radius 2, floor z = 0); allowed: centres inside it"),
        exact("export two.csv --format stl --container-height nan",
              "packbed: --container-height: 'nan' is not allowed; allowed: a number > 0"),
        exact("export @D/one.csv --format stl --contacts caps:0.7",
              "packbed export: --contacts 'caps:0.7' is not allowed; allowed: none, shrink:F, "
              "enlarge:F, caps:H or bridges:D with F, H, D fractions of Dp in (0, 0.5)"),
        exact("export @D/one.csv --format stl --contacts glue:0.2",
              "packbed export: --contacts 'glue:0.2' is not allowed; allowed: none, shrink:F, "
              "enlarge:F, caps:H or bridges:D with F, H, D fractions of Dp in (0, 0.5)"),
        exact("export two.csv --format stl --contacts glue:0.2 --out new/x.stl",
              "packbed export: --contacts 'glue:0.2' is not allowed; allowed: none, shrink:F, "
              "enlarge:F, caps:H or bridges:D with F, H, D fractions of Dp in (0, 0.5)"),
        exact("export two.csv --format stl --contacts caps:nan",
              "packbed export: --contacts 'caps:nan' is not allowed; allowed: none, shrink:F, "
              "enlarge:F, caps:H or bridges:D with F, H, D fractions of Dp in (0, 0.5)"),
        exact("export two.csv --format stl --contacts shrink:inf",
              "packbed export: --contacts 'shrink:inf' is not allowed; allowed: none, shrink:F, "
              "enlarge:F, caps:H or bridges:D with F, H, D fractions of Dp in (0, 0.5)"),
        // Numbers as every option reads them (from_chars: no sign, no space, no locale).
        exact("export two.csv --format stl --contacts caps:+0.01",
              "packbed export: --contacts 'caps:+0.01' is not allowed; allowed: none, shrink:F, "
              "enlarge:F, caps:H or bridges:D with F, H, D fractions of Dp in (0, 0.5)"),
        exact(std::vector<std::string>{"export", "two.csv", "--format", "stl", "--contacts",
                                       "caps: 0.01"},
              "packbed export: --contacts 'caps: 0.01' is not allowed; allowed: none, shrink:F, "
              "enlarge:F, caps:H or bridges:D with F, H, D fractions of Dp in (0, 0.5)"),
        exact(std::vector<std::string>{"export", "two.csv", "--format", "stl", "--contacts", ""},
              "packbed export: --contacts '' is not allowed; allowed: none, shrink:F, "
              "enlarge:F, caps:H or bridges:D with F, H, D fractions of Dp in (0, 0.5)"),
        exact("export @D/one.csv --format stl --contacts bridges:0.2",
              "packbed export: sphere 1 at (0, 0, 0) has its centre on or below the floor "
              "z = 0; allowed: centres above the floor for --contacts bridges"),
        exact("export @D/two.csv --format stl --contacts shrink:0.005",
              "packbed export: --contacts shrink:0.005 leaves spheres 1 and 2 overlapping "
              "(centres 0.99 apart, shrunk radii 0.4975 and 0.4975); allowed: F above the "
              "bed's largest overlap in Dp")));

// Hydraulics' options: the option and the value are pinned.
INSTANTIATE_TEST_SUITE_P(
    Hydraulics, CliBadInput,
    ::testing::Values(
        naming("hydraulics", {"--porosity", "--bed"}),
        naming("hydraulics --porosity 1.2", {"--porosity", "1.2"}),
        naming("hydraulics --porosity nan", {"--porosity", "nan"}),
        naming("hydraulics --porosity inf", {"--porosity", "inf"}),
        naming("hydraulics --porosity x", {"--porosity", "x"}),
        naming(std::vector<std::string>{"hydraulics", "--porosity", ""}, {"--porosity", "''"}),
        naming("hydraulics --porosity 1e-300", {"porosity", "1e-300"}),
        // Values that would print NaN and inf.
        naming("hydraulics --porosity 0.4 --diameter 1e-300", {"--diameter", "1e-300"}),
        naming("hydraulics --porosity 0.4 --diameter 1e-300 -u 0.1", {"--diameter", "1e-300"}),
        naming("hydraulics --porosity 0.4 --diameter 1e-300 --json", {"--diameter", "1e-300"}),
        // An overflow, which must name its option.
        naming("hydraulics --porosity 0.4 --viscosity 1e-300", {"--viscosity", "1e-300"}),
        naming("hydraulics --porosity 0.4 --viscosity 0", {"--viscosity", "0"}),
        naming("hydraulics --porosity 0.4 --diameter inf", {"--diameter", "inf"}),
        naming("hydraulics --porosity 0.4 --diameter 100", {"--diameter", "100"}),
        naming("hydraulics --porosity 0.4 --particle-density 900", {"particle-density", "900"}),
        naming("hydraulics --porosity 0.4 --particle-density 1e400",
               {"--particle-density", "1e400"}),
        naming("hydraulics --porosity 0.4 --fluid-density nan", {"--fluid-density", "nan"}),
        naming("hydraulics --porosity 0.4 --gravity 0", {"--gravity", "0"}),
        naming("hydraulics --porosity 0.4 -u 0", {"--velocity", "0"}),
        naming("hydraulics --porosity 0.4 -u 1e300", {"--velocity", "1e300"}),
        naming("hydraulics --porosity 0.4 -a 0.5", {"--aspect-ratio", "0.5"}),
        naming("hydraulics --porosity 0.4 -a inf", {"--aspect-ratio", "inf"}),
        naming("hydraulics --porosity 0.4 --bed one.csv", {"--porosity", "--bed"}),
        // --bed: every kind of file.
        naming("hydraulics --bed missing.json", {"--bed", "missing.json"}),
        naming("hydraulics --bed dir", {"--bed", "dir"}),
        naming("hydraulics --bed dangling", {"--bed", "dangling"}),
        naming("hydraulics --bed fifo", {"--bed", "fifo"}),
        naming("hydraulics --bed /dev/zero", {"--bed", "/dev/zero"}),
        naming("hydraulics --bed node", {"--bed", "node"}),
        naming("hydraulics --bed /proc/self/mem", {"--bed", "/proc/self/mem"}),
        naming("hydraulics --bed zeros", {"--bed", "zeros"}),
        naming("hydraulics --bed @D/plain", {"--bed", "@D/plain"}),
        naming("hydraulics --bed sumdir", {"--bed", "sumdir"}),
        naming("hydraulics --bed sumfifo", {"--bed", "sumfifo"}),
        naming(std::vector<std::string>{"hydraulics", "--bed", "a\nb"}, {"--bed", "a\\nb"})));

INSTANTIATE_TEST_SUITE_P(
    Correlations, CliBadInput,
    ::testing::Values(
        exact("correlations --aspect-ratio x",
              "packbed: --aspect-ratio: 'x' is not allowed; allowed: a number in [1, 10000]"),
        exact("correlations --aspect-ratio nan",
              "packbed: --aspect-ratio: 'nan' is not allowed; allowed: a number in [1, 10000]"),
        exact("correlations --aspect-ratio inf",
              "packbed: --aspect-ratio: 'inf' is not allowed; allowed: a number in [1, 10000]"),
        exact("correlations --aspect-ratio 0.5",
              "packbed: --aspect-ratio: 0.5 is not allowed; allowed: a number in [1, 10000]"),
        exact("correlations --aspect-ratio 1e5",
              "packbed: --aspect-ratio: 1e5 is not allowed; allowed: a number in [1, 10000]"),
        exact(std::vector<std::string>{"correlations", "--aspect-ratio", ""},
              "packbed: --aspect-ratio: '' is not allowed; allowed: a number in [1, 10000]"),
        exact("correlations --profile-step 0",
              "packbed: --profile-step: 0 is not allowed; allowed: a number in [0.0001, 1]"),
        exact("correlations --profile-step 1e-300",
              "packbed: --profile-step: 1e-300 is not allowed; allowed: a number in [0.0001, 1]"),
        exact("correlations --profile-to -1",
              "packbed: --profile-to: -1 is not allowed; allowed: a number in [0, 1000]"),
        exact("correlations --profile-to 1e300",
              "packbed: --profile-to: 1e300 is not allowed; allowed: a number in [0, 1000]"),
        exact("correlations --profile-to nan",
              "packbed: --profile-to: 'nan' is not allowed; allowed: a number in [0, 1000]"),
        // A profile of more than 1e5 steps (up to the axis, which ends it at a / 2).
        exact("correlations -a 1000 --profile-to 1000 --profile-step 0.0001",
              "packbed correlations: --profile-step 0.0001 to x = 500 d (the axis at a / 2) is "
              "not allowed: 5e+06 steps; allowed: at most 100000 steps"),
        exact("correlations --json=x", "packbed: Could not convert: --json = x"),
        exact("correlations extra",
              "packbed correlations: 'extra' is not expected; allowed: the options of 'packbed "
              "correlations --help'")));

// Injection through gnuplot, with characters that are allowed in a path: quotes, $(...),
// backquotes and semicolons reach no shell and no gnuplot command (the run succeeds, nothing
// else appears).
// The NothingLost cases: deep nesting in every reader; an output that is, holds or replaces an
// input, on every subcommand that reads one (the bed, its summary.json, --config, --sizes, a
// checkpoint, an OpenFOAM case, a LAMMPS job), its sidecars included; names too long for the
// file system; bad input that was answered as an internal error (exit 1).
const std::string too_deep_toml =
    " nested deeper than 64 levels (tables, dotted keys, arrays); allowed: at most that deep";
const std::string deep_summary =
    "deep/summary.json: not a summary.json (nested deeper than 64 levels); allowed: the "
    "summary.json of packbed generate, lattice or analyze";
const std::string not_an_input = "; allowed: an output that is not an input";
const std::string holds = "; allowed: an output directory that does not hold the inputs";
const std::string job_json = "; allowed: the job.json packbed generate --engine lammps "
                             "--write-only wrote";

INSTANTIATE_TEST_SUITE_P(
    ExportPellets, CliBadInput,
    ::testing::Values(
        exact("export pel/particles.csv -f stl --contacts caps:0.02 -o pel.stl",
              "packbed export: --contacts caps:0.02 is not allowed for a bed of pellets; "
              "allowed: none, or shrink:F (each pellet scaled by 1 - F about its centroid, F in "
              "(0, 0.5))"),
        exact("export pel/particles.csv -f liggghts-data -o pel.data",
              "packbed export: --format liggghts-data is not allowed for a bed of cylinder:1,1 "
              "pellets; allowed: stl, stl-ascii, obj, openfoam, lammps-data (LIGGGHTS makes its "
              "multisphere clumps from its own templates as it inserts them)"),
        exact("export pel/particles.csv --contacts shrink:0.1 -o pel.data",
              "packbed export: --contacts shrink:0.1 is not allowed with --format lammps-data; "
              "allowed: none (the clumps are the pellets' own)"),
        exact("export bed/particles.csv -f stl --shape cylinder:1,1 -o p.stl",
              "packbed export: bed/particles.csv: a bed of cylinder:1,1 pellets needs each "
              "pellet's orientation; allowed: a table with the columns qw, qx, qy, qz (what "
              "packbed generate --shape writes)"),
        naming("export pel/particles.csv -f stl --shape cylinder:1 -o p.stl",
               {"--shape", "cylinder:1", "cylinder:D,L"}),
        exact("analyze pel/particles.csv --frames all",
              "packbed analyze: --frames all is not allowed for a bed of cylinder:1,1 pellets; "
              "allowed: one frame"),
        naming("export cone/particles.csv -f stl -o c.stl",
               {"cone/summary.json", "shape 'cone:1,1'", "cylinder:D,L"}),
        naming("export pel/particles.csv -f stl --contacts shrink:0.01 --container cylinder:0.9 "
               "-o p.stl",
               {"--contacts shrink:0.01", "pel/particles.csv", "wall"}),
        // A pellet's size out of a sphere's range, a shape that is not the bed's, a table of
        // pellets exported as spheres, the spheres' options and a container the pellets do
        // not fit (upright, of radius 0.50004, in a tube of radius 0.45: 0.05004 out, tolerance
        // 0.01 d_v = 0.0114).
        naming("generate --shape cylinder:1e-13,1e-13",
               {"--shape", "cylinder:1e-13,1e-13", "d_v from 1e-12 to 1e+12"}),
        naming("generate --shape spherocylinder:1e13,1e13",
               {"--shape", "spherocylinder:1e13,1e13", "d_v from 1e-12 to 1e+12"}),
        exact("export pel/particles.csv -f stl --shape ring:1,0.5,1 -o p.stl",
              "packbed export: --shape 'ring:1,0.5,1' is not allowed for pel/particles.csv: the "
              "summary.json beside it records its pellets as 'cylinder:1,1'; allowed: that "
              "shape, or no --shape"),
        exact("export pel/particles.csv -f stl --shape sphere -o p.stl",
              "packbed export: --shape sphere is not allowed for pel/particles.csv: the "
              "summary.json beside it records its pellets as 'cylinder:1,1'; allowed: that "
              "shape, or no --shape"),
        exact("export pelraw/particles.csv -f stl -o p.stl",
              "packbed export: pelraw/particles.csv: its particles have orientations (qw, qx, "
              "qy, qz: a bed of pellets) but no pellet shape is given; allowed: --shape SPEC "
              "naming its pellets (a bed from generate --shape has it in the summary.json beside "
              "it)"),
        exact("export pelraw/particles.csv -f stl --shape sphere -o p.stl",
              "packbed export: pelraw/particles.csv: its particles have orientations (qw, qx, "
              "qy, qz: a bed of pellets) but no pellet shape is given; allowed: --shape SPEC "
              "naming its pellets (a bed from generate --shape has it in the summary.json beside "
              "it)"),
        // analyze and voxelize take a pellet's shape only from the summary.json beside it:
        // without one its pellets would be measured as balls of d_v.
        exact("analyze pelraw/particles.csv -R 3 --outside-tolerance 0.5",
              "packbed analyze: pelraw/particles.csv: its particles have orientations (qw, qx, "
              "qy, qz: a bed of pellets) but no summary.json beside it names their shape; "
              "allowed: a bed of spheres, or a pellet bed with the summary.json generate "
              "--shape wrote beside it"),
        exact("voxelize pelraw/particles.csv --container cylinder:3 --voxel-size 0.1 -o v.npy",
              "packbed voxelize: pelraw/particles.csv: its particles have orientations (qw, qx, "
              "qy, qz: a bed of pellets) but no summary.json beside it names their shape; "
              "allowed: a bed of spheres, or a pellet bed with the summary.json generate "
              "--shape wrote beside it"),
        exact("export pelraw/particles.csv -f stl --shape cylinder:2,2 -o p.stl",
              "packbed export: pelraw/particles.csv:2: r = 0.5724 is not allowed for "
              "cylinder:2,2 pellets; allowed: r = d_v / 2 = 1.1447142425533317 within 0.1 % (a "
              "pellet's size in the table: give the shape's lengths in the table's units)"),
        exact("analyze pel/particles.csv --friction 0.3",
              "packbed analyze: --friction is not allowed for a bed of cylinder:1,1 pellets; "
              "allowed with pellets: --container, --band, --band-clearance, --shell-width, "
              "--slab-height, --contact-tolerance, --outside-tolerance (lengths in d_v), "
              "--format, --frame, --axis, --floor, --out, --force, --threads, --quiet"),
        naming("analyze pel/particles.csv --rdf-bin 0.1", {"--rdf-bin is not allowed"}),
        naming("analyze pel/particles.csv -d 2", {"--diameter is not allowed"}),
        naming("analyze pel/particles.csv --container cylinder:0.9",
               {"pel/particles.csv:2: the pellet at (0, 0, 0.6) reaches out of the container",
                "by 0.05004; allowed: up to 0.01145 (--outside-tolerance times d_v"}),
        naming("voxelize pel/particles.csv --voxel-size 0.1 --container cylinder:0.9 -o v.npy",
               {"pel/particles.csv:2: the pellet at (0, 0, 0.6) reaches out"})));

INSTANTIATE_TEST_SUITE_P(
    NothingLost, CliBadInput,
    ::testing::Values(
        // 1. Recursion over user data.
        exact("generate --config dotted.toml",
              "packbed: --config dotted.toml: line 1:" + too_deep_toml),
        exact("--config header.toml generate",
              "packbed: --config header.toml: line 1:" + too_deep_toml),
        exact("--config brackets.toml generate",
              "packbed: --config brackets.toml: line 1:" + too_deep_toml),
        exact("--config inline.toml generate",
              "packbed: --config inline.toml: line 1:" + too_deep_toml),
        naming("--config longkey.toml generate", // a message quotes 80 bytes of a key
               {"packbed: --config longkey.toml: line 1: unknown key '" + std::string(80, 'k') +
                "'; allowed: "}),
        exact("analyze deep/bed.csv -o out", "packbed analyze: " + deep_summary),
        exact("export deep/bed.csv -f stl -o out.stl", "packbed export: " + deep_summary),
        exact("voxelize deep/bed.csv --voxel-size 0.5 -o out.npy",
              "packbed voxelize: " + deep_summary),
        exact("hydraulics --bed deep", "packbed hydraulics: --bed " + deep_summary),
        exact("import-lammps words -o out",
              "packbed import-lammps: FOLDER words: job.json is not JSON (nested deeper than 64 "
              "levels)" +
                  job_json),
        // 2. An output that is, holds or replaces an input, and its sidecars.
        exact("export bed/particles.csv -f stl -o bed/summary.json",
              "packbed export: the bed's summary bed/summary.json: the output bed/summary.json "
              "would overwrite it" +
                  not_an_input),
        exact("export bed/particles.csv -f stl -o bed/summary",
              "packbed export: the bed's summary bed/summary.json: the output bed/summary.json "
              "would overwrite it" +
                  not_an_input),
        exact("export bed/particles.csv -f stl-ascii -o bed/particles.csv",
              "packbed export: the particles file bed/particles.csv: the output "
              "bed/particles.csv would overwrite it" +
                  not_an_input),
        exact("--config cfg/out.data.fluid.in export bed/particles.csv --fluid-velocity 1 -o "
              "cfg/out.data",
              "packbed export: --config cfg/out.data.fluid.in: the output cfg/out.data.fluid.in "
              "would overwrite it" +
                  not_an_input),
        exact("export bed/particles.csv -f openfoam -o bed --force",
              "packbed export: the particles file bed/particles.csv lies in --out bed, which "
              "--force would replace" +
                  holds),
        exact("analyze bed/particles.csv -o bed --force",
              "packbed analyze: the particles file bed/particles.csv lies in --out bed, which "
              "--force would replace" +
                  holds),
        exact("voxelize bed/particles.csv --voxel-size 0.5 -o bed/summary.json",
              "packbed voxelize: --out bed/summary.json: the extension is not allowed; allowed: "
              ".npy, .tif (or .tiff) or .raw (with a .raw.json header)"),
        exact("voxelize bed/particles.csv --voxel-size 0.5 -o bed/summary",
              "packbed voxelize: --out bed/summary: the extension is not allowed; allowed: .npy, "
              ".tif (or .tiff) or .raw (with a .raw.json header)"),
        exact("generate --sizes file:sz/sizes.csv -n 30 -o sz --force",
              "packbed generate: --sizes sz/sizes.csv lies in --out sz, which --force would "
              "replace" +
                  holds),
        exact("generate --config cfg/run.toml -o cfg --force",
              "packbed generate: --config cfg/run.toml lies in --out cfg, which --force would "
              "replace" +
                  holds),
        exact("--config cfg/lattice.toml lattice -o cfg --force",
              "packbed lattice: --config cfg/lattice.toml lies in --out cfg, which --force would "
              "replace" +
                  holds),
        exact("generate --config cfg/layers.toml --checkpoint cfg/layers.toml -o out",
              "packbed generate: --checkpoint cfg/layers.toml: it is also --config "
              "cfg/layers.toml, which this run reads; allowed: a file that is not an input"),
        exact("generate --config cfg/layers.toml --checkpoint out -o out",
              "packbed generate: --checkpoint out lies in --out out, which this run writes; "
              "allowed: a file outside the run's other outputs"),
        exact("generate --config cfg/layers.toml --checkpoint full/run.ckpt -o full --force",
              "packbed generate: --checkpoint full/run.ckpt lies in --out full, which this run "
              "writes; allowed: a file outside the run's other outputs"),
        exact("cfd-report proj/case -o proj/case --force",
              "packbed cfd-report: CASE proj/case lies in --out proj/case, which --force would "
              "replace" +
                  holds),
        exact("cfd-report proj/case -o proj --force",
              "packbed cfd-report: CASE proj/case lies in --out proj, which --force would "
              "replace" +
                  holds),
        exact("import-lammps lmpjob -o lmpjob --force",
              "packbed import-lammps: FOLDER lmpjob lies in --out lmpjob, which --force would "
              "replace" +
                  holds),
        // 5. Checked before the work: names too long for the file system.
        exact("generate -n 30 -o " + std::string(300, 'o'),
              "packbed generate: --out " + std::string(200, 'o') + ": the name '" +
                  std::string(40, 'o') +
                  "...' has 300 bytes; allowed: names of at most 255 bytes on this file system"),
        exact("export two.csv -f stl -o " + std::string(300, 's') + ".stl",
              "packbed export: --out " + std::string(200, 's') + ": the name '" +
                  std::string(40, 's') +
                  "...' has 304 bytes; allowed: names of at most 255 bytes on this file system"),
        exact("generate --config cfg/layers.toml --checkpoint " + std::string(256, 'c') + " -o out",
              "packbed generate: --checkpoint " + std::string(200, 'c') + ": the name '" +
                  std::string(40, 'c') +
                  "...' has 256 bytes; allowed: names of at most 255 bytes on this file system"),
        // 8. Bad input that was an internal error.
        exact("import-lammps style -o out",
              "packbed import-lammps: FOLDER style: pair_style (gran/hooke or harmonic/cut) in "
              "job.json is missing or not allowed" +
                  job_json),
        exact("import-lammps long -o out",
              "packbed import-lammps: FOLDER long: command (a list of at most 64 words) in "
              "job.json is missing or not allowed" +
                  job_json),
        exact("import-lammps loop -o out",
              "packbed import-lammps: FOLDER loop: log.lammps is missing; allowed: a job folder "
              "after LAMMPS ran in it (README.md there says how)"),
        // 9. Quiet acceptance: refused with the library's words, as the Python module refuses.
        exact("export bed/particles.csv -f openfoam --fluid-velocity 0 -o case",
              "packbed export: --fluid-velocity 0 is not allowed with --format openfoam; "
              "allowed: the inlet's velocity > 0 m/s, or --reynolds"),
        exact("export bed/particles.csv -f openfoam --scale 1e-300 -o case",
              "packbed export: --scale 1e-300 is not allowed for spheres of 1 units: they would "
              "be 1e-300 m; allowed: a scale that makes them 1e-09 to 10 m"),
        exact("export bed/particles.csv -f openfoam --scale 1e-9 --reynolds 1e5 -o case",
              "packbed export: --reynolds 100000 is not allowed with spheres of 1e-09 m: the "
              "inlet's velocity would be 1.00381e+08 m/s; allowed: a Reynolds number that gives "
              "at most 10000 m/s (or --scale, --viscosity, --fluid-density)"),
        exact("export bed/particles.csv -f stl --edge 1e-300 -o s.stl",
              "packbed export: --edge 1e-300 is not allowed for spheres up to radius 0.5: it "
              "needs more than icosphere level 7; allowed: at least 0.00410742 (that level's "
              "edge)"),
        exact("generate -n 30 -a 3 --band-clearance 1e300",
              "packbed generate: --band-clearance 1e+300 Dp is not allowed for this bed (at most "
              "10.3857 Dp tall); allowed: less than half its height"),
        exact("export far.csv -R 2 -o far.data",
              "packbed export: far.csv:3: the sphere at (0, 0, 100000000000000) reaches 1e+14 "
              "mean diameters from the origin; allowed: at most 1e+06 (the surfaces and walls "
              "are written in single precision)")));

// A disk that fills up during the output (a file size limit, RLIMIT_FSIZE, as ulimit -f sets
// it, SIGXFSZ at its default: packbed ignores it, so every write beyond the limit fails with
// EFBIG as on a full disk): exit 1, one line naming the output as the user gave it (not the
// hidden staging folder) with the reason, nothing left.
TEST(CliDiskFull, OneLineNamingTheOutputAsGivenNothingLeft) {
    const fs::path root = scratch();
    const fs::path d = root / "work";
    write(d / "bed.csv", column(40));
    const std::string before = listing(d);
    const std::vector<std::vector<std::string>> runs{
        {"generate", "-n", "300", "-a", "5", "-q", "-o", "out"},
        {"voxelize", "bed.csv", "--container", "cylinder:2", "--voxel-size", "0.1", "-o", "im.raw"},
        {"export", "bed.csv", "-R", "1", "-f", "stl", "--refine", "1", "-o", "bed.stl"},
        {"export", "bed.csv", "-R", "1", "-f", "openfoam", "--refine", "1", "-o", "case"},
    };
    const std::vector<std::string> named{"out/particles.csv", "im.raw", "bed.stl",
                                         "case/constant/triSurface/particles.stl"};
    for (std::size_t k = 0; k < runs.size(); ++k) {
        const pid_t pid = packbed::test::spawn(runs[k], d, root / "io", {RLIMIT_FSIZE, 8 << 10});
        int status = 0;
        ::waitpid(pid, &status, 0);
        const std::string message = slurp(root / "io" / "err");
        EXPECT_TRUE(WIFEXITED(status) && WEXITSTATUS(status) == 1) << message;
        EXPECT_EQ(std::count(message.begin(), message.end(), '\n'), 1) << message;
        EXPECT_NE(message.find("cannot write " + named[k] +
                               " (File too large); nothing was "
                               "written"),
                  std::string::npos)
            << message;
        EXPECT_EQ(message.find("packbed-"), std::string::npos) << message;
        EXPECT_EQ(listing(d), before) << message;
    }
}

// Requests within the allowed ranges that do not fit in the memory this process may have
// (here its address space limited to 1.5 GB, RLIMIT_AS, as `ulimit -v` does): refused at once
// with exit 2 and the estimate, nothing written; before, each died after minutes with
// std::bad_alloc.
TEST(CliMemory, RequestsThatDoNotFitAreRefusedBeforeTheWork) {
    const fs::path root = scratch();
    const fs::path d = root / "work";
    write(d / "bed.csv", column(40));
    const std::string before = listing(d);
    const std::vector<std::pair<std::vector<std::string>, std::string>> runs{
        {{"generate", "-n", "100000000", "-q", "-o", "out"},
         "packbed generate: --particles 100000000 needs about 37.3 GiB of memory; "},
        {{"lattice", "--region", "box:500,500,500", "-q", "-o", "out"},
         "packbed lattice: --region box:500,500,500 (about 8.12e+07 balls) needs about 36.3 GiB "
         "of memory; "},
        {{"voxelize", "bed.csv", "--container", "cylinder:2", "--voxel-size", "0.003", "-o",
          "im.npy"},
         "packbed voxelize: --voxel-size 0.003 (an image of 5.932e+09 voxels of 1 byte) needs "
         "about 5.56 GiB of memory; "},
    };
    for (const auto& [args, message] : runs) {
        const auto start = std::chrono::steady_clock::now();
        const pid_t pid = packbed::test::spawn(args, d, root / "io", {RLIMIT_AS, 1500u << 20});
        int status = 0;
        ::waitpid(pid, &status, 0);
        const double seconds =
            std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
        const std::string said = slurp(root / "io" / "err");
        EXPECT_TRUE(WIFEXITED(status) && WEXITSTATUS(status) == 2) << said;
        EXPECT_EQ(std::count(said.begin(), said.end(), '\n'), 1) << said;
        EXPECT_EQ(said.rfind(message, 0), 0u) << said;
        EXPECT_NE(said.find(" is available here; allowed: "), std::string::npos) << said;
        EXPECT_LT(seconds, 5.0) << said;
        EXPECT_EQ(listing(d), before) << said;
    }
}

TEST(CliPaths, QuotesAndShellSyntaxInOutputPathsRunNothing) {
    const fs::path root = scratch();
    const fs::path d = root / "work";
    const std::string name = "o'; system(\"touch PWNED1\"); '$(touch PWNED2)`touch PWNED3`\"";
    const Outcome o = run_packbed(
        {"generate", "-q", "--solver", "fire", "-a", "4", "-n", "60", "--seed", "1", "--out", name},
        d, root / "io");
    ASSERT_EQ(o.status, 0) << o.err;
    EXPECT_TRUE(fs::exists(d / name / "particles.csv"));
    std::vector<std::string> entries;
    for (const auto& e : fs::directory_iterator(d))
        entries.push_back(e.path().filename().string());
    EXPECT_EQ(entries, std::vector<std::string>{name});
    if (fs::exists(d / name / "radial_void_fraction.svg")) { // gnuplot installed: it ran there
        EXPECT_GT(fs::file_size(d / name / "radial_void_fraction.svg"), 0u);
    }
}

} // namespace
