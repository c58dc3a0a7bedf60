// Checkpoints of the runs in layers (the fire solver's and the pellet beds'): a real one reads
// back, and a pellet bed resumed from one has the bits of one never stopped; one taken with other
// options, damaged, or edited by hand (even with its hash recomputed) is refused naming what is
// wrong, and never crashes or hangs the reader.
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <sstream>
#include <string>
#include <vector>

#include <unistd.h>

#include <fmt/format.h>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "packbed/checkpoint.hpp"
#include "packbed/error.hpp"
#include "packbed/pellet_bed.hpp"
#include "packbed/soft_sphere.hpp"

using namespace packbed;
namespace fs = std::filesystem;
using nlohmann::json;

namespace {

/// A scratch file of this process: ctest runs each test in its own process, two at a time, and
/// a name shared between them let one test read the checkpoint another was writing.
fs::path scratch_file(const std::string& name) {
    return fs::temp_directory_path() /
           ("packbed-test-checkpoint-" + std::to_string(::getpid()) + "-" + name);
}

/// a = 5, 600 spheres, layers 10 Dp: three layers (as in test_layers.cpp).
SoftSphereParameters three_layers() {
    SoftSphereParameters p;
    p.container = Container::tube(5.0);
    p.particles = 600;
    p.seed = 1;
    p.solver = Solver::fire;
    p.layer_height = 10.0;
    return p;
}

/// The bytes of a real checkpoint after the first of three layers (computed once).
const std::string& real_checkpoint() {
    static const std::string bytes = [] {
        const SoftSphereParameters p = three_layers();
        LayerCheckpoint first;
        RunControl control;
        control.on_layer = [&](const LayerCheckpoint& s) {
            if (s.layers_done == 1)
                first = s;
        };
        relax_with_fire(p, control);
        const fs::path file = scratch_file("real.ckpt");
        write_checkpoint(file, p, first);
        std::string read;
        {
            std::ifstream in(file, std::ios::binary);
            read.assign(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
        }
        fs::remove(file);
        return read;
    }();
    return bytes;
}

/// A checkpoint's four parts: the format line, the header, the hash line, the data.
struct Parts {
    std::string format, header, hash, data;
};

Parts split(const std::string& bytes) {
    const std::size_t a = bytes.find('\n'), b = bytes.find('\n', a + 1),
                      c = bytes.find('\n', b + 1);
    return {bytes.substr(0, a), bytes.substr(a + 1, b - a - 1), bytes.substr(b + 1, c - b - 1),
            bytes.substr(c + 1)};
}

/// FNV-1a 64 of `bytes`, continued from `h` (the published algorithm, as the format states).
std::uint64_t fnv1a(const std::string& bytes, std::uint64_t h = 0xcbf29ce484222325ULL) {
    for (const char c : bytes) {
        h ^= static_cast<unsigned char>(c);
        h *= 0x100000001b3ULL;
    }
    return h;
}

/// A checkpoint with `header` and `data`, its hash recomputed as a forger would.
std::string forged(const std::string& header, const std::string& data) {
    return "packbed-checkpoint 3\n" + header + "\n" +
           fmt::format("fnv1a64 {:016x}\n", fnv1a(data, fnv1a(header + "\n"))) + data;
}

/// What reading `bytes` as a checkpoint of three_layers() says: "accepted" or the refusal.
std::string verdict(const std::string& bytes) {
    const fs::path file = scratch_file("case.ckpt");
    std::ofstream(file, std::ios::binary) << bytes;
    std::string said = "accepted";
    try {
        read_checkpoint(file, three_layers());
    } catch (const InvalidInput& e) {
        said = e.what();
    }
    fs::remove(file);
    return said;
}

/// The real checkpoint with one header field changed by `edit`, the hash recomputed.
template <class F> std::string with_header(F&& edit) {
    const Parts parts = split(real_checkpoint());
    json header = json::parse(parts.header);
    edit(header);
    return verdict(forged(header.dump(), parts.data));
}

bool says(const std::string& message, const std::string& part) {
    return message.find(part) != std::string::npos;
}

} // namespace

TEST(Checkpoint, ARealOneReadsBackAndItsHashCoversHeaderAndData) {
    const Parts parts = split(real_checkpoint());
    EXPECT_EQ(parts.format, "packbed-checkpoint 3");
    EXPECT_EQ(parts.data.size(), 600u * 4 * 8);
    EXPECT_EQ(parts.hash,
              fmt::format("fnv1a64 {:016x}", fnv1a(parts.data, fnv1a(parts.header + "\n"))));
    EXPECT_EQ(verdict(real_checkpoint()), "accepted");
    EXPECT_EQ(with_header([](json&) {}), "accepted"); // the same bytes, rewritten

    // One digit of the header changed without the hash: before format 3 this was not noticed.
    std::string edited = real_checkpoint();
    edited.replace(edited.find("\"layers_done\":1"), 15, "\"layers_done\":2");
    EXPECT_TRUE(says(verdict(edited), "the header and data do not match their hash"));
    std::string flipped = real_checkpoint();
    flipped[flipped.size() - 3] ^= 0x10; // one bit of the last radius
    EXPECT_TRUE(says(verdict(flipped), "the header and data do not match their hash"));
}

TEST(Checkpoint, EditedFieldsAreRefusedNamingTheField) {
    // The audit's cases: each crashed, hung or was taken as valid before.
    EXPECT_TRUE(says(with_header([](json& h) { h["stages"] = json::array(); }),
                     "corrupt checkpoint: stages is not a list of the 3 stages")); // SIGSEGV
    EXPECT_TRUE(says(with_header([](json& h) { h["stages"].erase(1); }),
                     "stages is not a list of the 3 stages")); // heap-buffer-overflow
    EXPECT_TRUE(says(with_header([](json& h) { h["top"] = 1e300; }),
                     "corrupt checkpoint: top = 1e+300 is not allowed; allowed: a number from 0 "
                     "to")); // a hang
    EXPECT_TRUE(says(with_header([](json& h) { h["spheres"] = (1ULL << 59) + 500; }),
                     "corrupt checkpoint: spheres = 576460752303423988 is not allowed; allowed: "
                     "a whole number from 600 to 600")); // a wrapped size check
    EXPECT_TRUE(says(with_header([](json& h) { h["layers_done"] = 4294967296ULL; }),
                     "layers_done = 4294967296 is not allowed; allowed: a whole number from 1 "
                     "to 3")); // another bed, exit 0
    EXPECT_TRUE(says(with_header([](json& h) { h["iterations"] = -1; }),
                     "iterations = -1 is not allowed")); // nonsense in summary.json
    EXPECT_TRUE(says(with_header([](json& h) { h["iterations"] = h["iterations"].get<int>() + 1; }),
                     "the stages' iterations add up to"));
    EXPECT_TRUE(says(with_header([](json& h) { h["iterations"] = 7; }),
                     "stages[0].iterations = ")); // more than the run's iterations
    EXPECT_TRUE(says(with_header([](json& h) { h["stages"][0]["name"] = "final"; }),
                     "stages[0].name = \"final\" is not allowed"));
    EXPECT_TRUE(says(with_header([](json& h) { h["stages"][2]["cg"] = "x"; }),
                     "stages[2].cg = \"x\" is not allowed"));
    EXPECT_TRUE(says(with_header([](json& h) { h.erase("neighbor_builds"); }),
                     "corrupt checkpoint: no field neighbor_builds"));
    EXPECT_TRUE(says(with_header([](json& h) { h["parameters"]["seed"] = 2; }),
                     "it was taken with seed = 2, this run has 1"));
    EXPECT_TRUE(says(with_header([](json& h) { h = json::array(); }), "no field parameters"));
}

TEST(Checkpoint, DeepNestingInTheHeaderIsRefusedWhereItIsRead) {
    // 1e5 nested brackets behind a valid hash: refused by the parser, not a stack overflow
    // when the value is compared with the run's or quoted in the message; 60 deep is read and
    // quoted within 40 bytes.
    const Parts parts = split(real_checkpoint());
    const std::string head = parts.header.substr(0, parts.header.size() - 1);
    const std::string deep =
        head + ",\"x\":" + std::string(100000, '[') + std::string(100000, ']') + "}";
    EXPECT_TRUE(says(verdict(forged(deep, parts.data)),
                     "corrupt checkpoint: the header is not JSON (nested deeper than 64 levels)"));
    std::string objects = "{\"parameters\":";
    for (int k = 0; k < 100000; ++k)
        objects += "{\"a\":";
    EXPECT_TRUE(says(verdict(forged(objects + "1" + std::string(100001, '}'), parts.data)),
                     "nested deeper than 64 levels"));
    EXPECT_TRUE(says(with_header([](json& h) {
                         json v = 1;
                         for (int k = 0; k < 60; ++k)
                             v = json::array({v});
                         h["parameters"]["seed"] = v;
                     }),
                     "it was taken with seed = " + std::string(40, '[') + "..., this run has 1"));
}

TEST(Checkpoint, DataOutsideTheContainerOrOfTheWrongSizeIsRefused) {
    const Parts parts = split(real_checkpoint());
    std::string data = parts.data;
    const double far = 1e300;
    std::memcpy(data.data() + 16, &far, sizeof far); // z of the first sphere
    EXPECT_TRUE(says(verdict(forged(parts.header, data)),
                     "corrupt checkpoint: sphere 0 is at (")); // the hash alone would pass it
    EXPECT_TRUE(says(verdict(forged(parts.header, parts.data.substr(8))),
                     "19192 bytes of data where 600 spheres need 19200"));
    EXPECT_TRUE(says(verdict(forged(parts.header, parts.data + "x")),
                     "more bytes of data where 600 spheres need 19200"));
}

TEST(Checkpoint, OtherFilesAreRefused) {
    EXPECT_TRUE(says(verdict("x,y,z,r\n0,0,0.5,0.5\n"), "not a packbed checkpoint"));
    EXPECT_TRUE(says(verdict(std::string(1 << 20, '\0')), "not a packbed checkpoint"));
    std::string older = real_checkpoint();
    older.replace(0, older.find('\n'), "packbed-checkpoint 2");
    EXPECT_TRUE(says(verdict(older), "checkpoint format '2', this packbed reads format 3"));
    EXPECT_TRUE(says(verdict("packbed-checkpoint 3\n" + std::string(2 << 20, '{')),
                     "no header line (cut short or too long)"));
    try {
        read_checkpoint(fs::temp_directory_path(), three_layers());
        FAIL() << "a directory was read as a checkpoint";
    } catch (const InvalidInput& e) {
        EXPECT_TRUE(says(e.what(), ": a directory; allowed: a readable regular file"));
    }
}

namespace {

/// 100 rods (L = D) in a tube of a = 3, layers of 10 d_v: five layers, 66 318 steps
/// (Cli.ATallPelletBedInLayers...).
PelletBedParameters five_pellet_layers() {
    PelletBedParameters p;
    p.shape = SpherocylinderShape::of_aspect(1.0);
    p.container = Container::tube(3.0);
    p.particles = 100;
    p.seed = 1;
    p.layer_height = 10.0;
    return p;
}

/// The bed never stopped and the state after each of its layers (computed once).
struct PelletRun {
    PelletBed bed;
    std::vector<PelletCheckpoint> states;
};

const PelletRun& pellet_run() {
    static const PelletRun run = [] {
        PelletRun r;
        PelletLayerHooks hooks;
        hooks.on_layer = [&](const PelletCheckpoint& s) { r.states.push_back(s); };
        r.bed = generate_pellet_bed(five_pellet_layers(), {}, hooks);
        return r;
    }();
    return run;
}

/// The bytes of the pellet checkpoint after the second layer, as written.
std::string pellet_checkpoint_bytes() {
    const fs::path file = scratch_file("pellets.ckpt");
    write_pellet_checkpoint(file, five_pellet_layers(), pellet_run().states.at(1));
    std::ifstream in(file, std::ios::binary);
    std::string read(std::istreambuf_iterator<char>(in), {});
    fs::remove(file);
    return read;
}

/// What reading `bytes` as a pellet checkpoint of five_pellet_layers() says.
std::string pellet_verdict(const std::string& bytes) {
    std::istringstream in(bytes);
    try {
        const PelletBedParameters p = five_pellet_layers();
        read_pellet_checkpoint(in, "bed.ckpt", p, pellet_column(p));
    } catch (const InvalidInput& e) {
        return e.what();
    }
    return "accepted";
}

/// The pellet checkpoint with its header edited by `edit`, the hash recomputed.
template <class F> std::string with_pellet_header(F&& edit) {
    const Parts parts = split(pellet_checkpoint_bytes());
    json header = json::parse(parts.header);
    edit(header);
    return pellet_verdict(
        parts.format + "\n" + header.dump() + "\n" +
        fmt::format("fnv1a64 {:016x}\n", fnv1a(parts.data, fnv1a(header.dump() + "\n"))) +
        parts.data);
}

} // namespace

TEST(PelletCheckpoint, ABedResumedAfterAnyLayerHasTheBitsOfOneNeverStopped) {
    const PelletRun& run = pellet_run();
    const PelletBedParameters p = five_pellet_layers();
    ASSERT_EQ(run.bed.layers, 5u);
    ASSERT_EQ(pellet_column(p).layers, 5u);
    ASSERT_EQ(run.states.size(), 5u); // no layer of this bed is empty
    for (std::uint32_t k = 0; k < 5; ++k)
        EXPECT_EQ(run.states[k].layers_done, k + 1);
    EXPECT_EQ(run.states.back().steps, run.bed.steps);
    for (const std::size_t after : {std::size_t{1}, std::size_t{3}}) {
        // Through the file: written, read back, resumed.
        const fs::path file = scratch_file("resume.ckpt");
        write_pellet_checkpoint(file, p, run.states[after]);
        const PelletCheckpoint read = read_pellet_checkpoint(file, p, pellet_column(p));
        fs::remove(file);
        EXPECT_EQ(read.centre, run.states[after].centre);
        EXPECT_EQ(read.turn, run.states[after].turn);
        PelletLayerHooks hooks;
        hooks.resume = &read;
        const PelletBed resumed = generate_pellet_bed(p, {}, hooks);
        EXPECT_EQ(resumed.packing.centers, run.bed.packing.centers) << "after layer " << after + 1;
        EXPECT_EQ(resumed.packing.orientations, run.bed.packing.orientations);
        EXPECT_EQ(resumed.steps, run.bed.steps);
        EXPECT_EQ(resumed.stages.size(), run.bed.stages.size());
        EXPECT_EQ(resumed.residual_force, run.bed.residual_force);
        EXPECT_EQ(resumed.max_depth_pair, run.bed.max_depth_pair);
    }
}

TEST(PelletCheckpoint, EditedFieldsAndOtherFilesAreRefusedNamingWhatIsWrong) {
    const Parts parts = split(pellet_checkpoint_bytes());
    EXPECT_EQ(parts.format, "packbed-pellet-checkpoint 1");
    EXPECT_EQ(parts.data.size(), 100u * 7 * 8); // x, y, z, qw, qx, qy, qz
    EXPECT_EQ(pellet_verdict(pellet_checkpoint_bytes()), "accepted");
    EXPECT_EQ(with_pellet_header([](json&) {}), "accepted");
    EXPECT_TRUE(says(with_pellet_header([](json& h) { h["layers_done"] = 6; }),
                     "layers_done = 6 is not allowed; allowed: a whole number from 1 to 5"));
    EXPECT_TRUE(says(with_pellet_header([](json& h) { h["parameters"]["seed"] = 2; }),
                     "it was taken with seed = 2, this run has 1"));
    EXPECT_TRUE(says(with_pellet_header([](json& h) { h["parameters"]["friction"] = 0.3; }),
                     "it was taken with friction = 0.3, this run has 0.0"));
    EXPECT_TRUE(says(with_pellet_header([](json& h) { h["stages"][0]["name"] = "pour"; }),
                     "stages[0].name = \"pour\" is not allowed"));
    EXPECT_TRUE(says(with_pellet_header([](json& h) { h["stages"][3]["layer"] = 2; }),
                     "stages[3].layer = 2 is not allowed; allowed: a whole number from 0 to 1"));
    EXPECT_TRUE(says(with_pellet_header([](json& h) { h["on_floor"] = 1; }),
                     "on_floor = 1 is not allowed; allowed: true or false"));
    EXPECT_TRUE(
        says(with_pellet_header([](json& h) { h["top"] = 1e300; }), "top = 1e+300 is not allowed"));
    // The data: a pellet far away, an orientation that is no rotation, a short file.
    const auto forge = [&](const std::string& data) {
        return pellet_verdict(
            parts.format + "\n" + parts.header + "\n" +
            fmt::format("fnv1a64 {:016x}\n", fnv1a(data, fnv1a(parts.header + "\n"))) + data);
    };
    std::string data = parts.data;
    const double far = 1e300, two = 2.0;
    std::memcpy(data.data() + 7 * 8 + 8, &far, sizeof far); // y of pellet 1
    EXPECT_TRUE(says(forge(data), "corrupt checkpoint: pellet 1 is at ("));
    data = parts.data;
    std::memcpy(data.data() + 3 * 8, &two, sizeof two); // qw of pellet 0
    EXPECT_TRUE(says(forge(data), "pellet 0's orientation (2, "));
    EXPECT_TRUE(
        says(forge(parts.data.substr(8)), "5592 bytes of data where 100 pellets need 5600"));
    // A sphere bed's checkpoint, and a pellet bed's in a sphere run, named as such.
    EXPECT_TRUE(says(pellet_verdict(real_checkpoint()),
                     "a checkpoint of a sphere bed, this run is of pellets"));
    EXPECT_TRUE(says(verdict(pellet_checkpoint_bytes()),
                     "a checkpoint of a pellet bed, this run is of spheres"));
}
