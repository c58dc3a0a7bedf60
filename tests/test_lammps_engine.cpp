// The LAMMPS engine's job and its result read back, without LAMMPS (check_lammps_engine.py
// runs the real program).
#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include <gtest/gtest.h>

#include "packbed/error.hpp"
#include "packbed/lammps_engine.hpp"
#include "packbed/limits.hpp"

using namespace packbed;

namespace {

/// The numbers of the data file's Atoms section: id type diameter density x y z.
struct Atom {
    int id, type;
    double diameter, density, x, y, z;
};

std::vector<Atom> atoms(const std::string& data) {
    std::istringstream in(data.substr(data.find("Atoms # sphere") + 15));
    std::vector<Atom> out;
    Atom a{};
    while (in >> a.id >> a.type >> a.diameter >> a.density >> a.x >> a.y >> a.z)
        out.push_back(a);
    return out;
}

/// The value of `variable NAME index VALUE` or `equal VALUE` in the input.
double variable(const std::string& input, const std::string& name) {
    const std::size_t at = input.find("\nvariable " + name + " ");
    if (at == std::string::npos)
        return NAN;
    std::istringstream line(input.substr(at + 10 + name.size()));
    std::string style;
    double value = NAN;
    line >> style >> value;
    return value;
}

struct Folder {
    std::filesystem::path path;
    Folder() {
        path = std::filesystem::temp_directory_path() /
               ("packbed-lammps-test-" +
                std::to_string(::testing::UnitTest::GetInstance()->random_seed()) + "-" +
                ::testing::UnitTest::GetInstance()->current_test_info()->name());
        std::filesystem::remove_all(path);
        std::filesystem::create_directories(path);
    }
    ~Folder() { std::filesystem::remove_all(path); }
    void write(const std::string& name, const std::string& text) const {
        std::ofstream(path / name) << text;
    }
};

/// A log of a run that ended, with its three stage lines.
std::string finished_log() {
    return "LAMMPS (7 Jan 2022)\n"
           "PACKBED stage initial step 300 g 0 pair 5e-05 wall 4e-05 mc 3 rounds 1\n"
           "Neighbor list builds = 12\n"
           "PACKBED stage intermediate step 5300 g 0.0002 pair 0.015 wall 0.012 mc 2.5 rounds 2\n"
           "Neighbor list builds = 30\n"
           "PACKBED stage final step 6000 g 5e-07 pair 9e-05 wall 8e-05 mc 2.6 rounds 1\n"
           "PACKBED done step 6000\n"
           "Total wall time: 0:01:05\n";
}

/// A dump of spheres (id type x y z radius).
std::string dump(const std::vector<std::array<double, 3>>& centres) {
    std::string out = "ITEM: TIMESTEP\n6000\nITEM: NUMBER OF ATOMS\n" +
                      std::to_string(centres.size()) +
                      "\nITEM: BOX BOUNDS ff ff mm\n-5 5\n-5 5\n-2 10\nITEM: ATOMS id type x "
                      "y z radius\n";
    for (std::size_t i = 0; i < centres.size(); ++i)
        out += std::to_string(i + 1) + " 1 " + std::to_string(centres[i][0]) + " " +
               std::to_string(centres[i][1]) + " " + std::to_string(centres[i][2]) + " 0.5\n";
    return out;
}

/// lammps_result's ConvergenceError message for the job folder, or "accepted".
std::string convergence_error(const SoftSphereParameters& p, const std::filesystem::path& folder) {
    try {
        lammps_result(p, folder);
    } catch (const ConvergenceError& e) {
        return e.what();
    }
    return "accepted";
}

} // namespace

TEST(LammpsJob, StartsFromTheFireSolversGenerationStage) {
    SoftSphereParameters p;
    p.particles = 200;
    p.seed = 7;
    const LammpsJob job = lammps_job(p, LammpsPairStyle::gran_hooke, "lmp");
    const std::vector<Atom> a = atoms(job.data);
    ASSERT_EQ(a.size(), 200u);
    // The same centres, bit for bit, as the generation stage of packbed's own solvers.
    const SoftSphereGenerator generator(p);
    const Packing& start = generator.packing_dp();
    for (std::size_t i = 0; i < a.size(); ++i) {
        EXPECT_EQ(a[i].id, static_cast<int>(i + 1));
        EXPECT_EQ(a[i].type, 1);
        EXPECT_EQ(a[i].diameter, 1.0);
        EXPECT_EQ(a[i].x, start.centers[i].x);
        EXPECT_EQ(a[i].y, start.centers[i].y);
        EXPECT_EQ(a[i].z, start.centers[i].z);
        // density 6 / pi: a sphere of Dp weighs 1
        EXPECT_NEAR(a[i].density * std::acos(-1.0) / 6.0, 1.0, 1e-15);
    }
    EXPECT_NE(job.data.find("1 atom types"), std::string::npos);
    // The fire solver's tolerance, LAMMPS's own band of eq. (7) (lammps_overlap_low, _high:
    // the band its settle rule was chosen with); gravity's first value from L0.
    EXPECT_EQ(variable(job.input, "tol"), 1e-4);
    EXPECT_EQ(variable(job.input, "low"), 0.01);
    EXPECT_EQ(variable(job.input, "high"), 0.02);
    EXPECT_EQ(variable(job.input, "settle"), lammps_settle);
    EXPECT_DOUBLE_EQ(variable(job.input, "g"), 0.3 * 0.015 / initial_bed_height(200, 5.0, 0.47));
    // The linear overlap law, unit stiffness, nothing else; the wall at Rt = 2.5 set back 1 Dp.
    EXPECT_NE(job.input.find("pair_style      gran/hooke 1.0 0.0 0.0 0.0 0.0 0\n"),
              std::string::npos);
    EXPECT_NE(job.input.find("region tube cylinder z 0 0 3.5 INF INF side in"), std::string::npos);
    EXPECT_NE(job.input.find("wall/region tube harmonic 0.5 1.0 1.5"), std::string::npos);
    EXPECT_NE(job.input.find("v_r+sqrt(x*x+y*y)-2.5"), std::string::npos);
    EXPECT_NE(job.input.find("min_style       fire"), std::string::npos);
    // No placeholder left for LAMMPS to trip on.
    EXPECT_EQ(job.input.find('@'), std::string::npos);
}

TEST(LammpsJob, SizesAreTypesAndTheirWalls) {
    SoftSphereParameters p;
    p.particles = 60;
    for (int i = 0; i < 60; ++i)
        p.sizes.push_back(i % 3 == 0 ? 1.5 : 0.75);
    const LammpsJob job = lammps_job(p, LammpsPairStyle::harmonic_cut, "lmp");
    EXPECT_EQ(job.types, 2u);
    const std::vector<Atom> a = atoms(job.data);
    ASSERT_EQ(a.size(), 60u);
    for (std::size_t i = 0; i < a.size(); ++i) {
        EXPECT_EQ(a[i].diameter, p.sizes[i]);
        EXPECT_EQ(a[i].type, p.sizes[i] == 0.75 ? 1 : 2);
    }
    // harmonic/cut: E = 0.5 (rc - r)^2 with rc the sum of the radii of each pair of types
    EXPECT_NE(job.input.find("pair_coeff      1 1 0.5 0.75\n"), std::string::npos);
    EXPECT_NE(job.input.find("pair_coeff      1 2 0.5 1.125\n"), std::string::npos);
    EXPECT_NE(job.input.find("pair_coeff      2 2 0.5 1.5\n"), std::string::npos);
    // each size its wall reach (radius + 1 Dp set back) and its weight d^3
    EXPECT_NE(job.input.find("fix side1 size1 wall/region tube harmonic 0.5 1.0 1.375"),
              std::string::npos);
    EXPECT_NE(job.input.find("fix side2 size2 wall/region tube harmonic 0.5 1.0 1.75"),
              std::string::npos);
    EXPECT_NE(job.input.find("addforce 0.0 0.0 $(-v_g*3.375:%.17g)"), std::string::npos);
    EXPECT_NE(job.input.find("addforce 0.0 0.0 $(-v_g*0.421875:%.17g)"), std::string::npos);

    for (int i = 0; i < 60; ++i)
        p.sizes[i] = 0.5 + 0.01 * (i % 17);
    EXPECT_THROW(lammps_job(p, LammpsPairStyle::gran_hooke, "lmp"), InvalidInput);
}

TEST(LammpsJob, EveryContainerMapsOntoLammps) {
    SoftSphereParameters p;
    p.particles = 50;
    p.container = Container(Box(4.0, 3.0));
    std::string input = lammps_job(p, LammpsPairStyle::gran_hooke, "lmp").input;
    EXPECT_NE(input.find("wall/harmonic xlo -1 0.5 1.0 1.5 xhi 5 0.5 1.0 1.5 ylo -1 0.5 1.0 1.5 "
                         "yhi 4 0.5 1.0 1.5"),
              std::string::npos);
    EXPECT_NE(input.find("boundary        f f m"), std::string::npos);

    p.container = Container(Periodic(4.0, 3.0));
    const LammpsJob periodic = lammps_job(p, LammpsPairStyle::gran_hooke, "lmp");
    EXPECT_NE(periodic.input.find("boundary        p p m"), std::string::npos);
    EXPECT_EQ(periodic.input.find("side1"), std::string::npos);
    EXPECT_NE(periodic.data.find("0 4 xlo xhi\n0 3 ylo yhi"), std::string::npos);
    // the floor is its one wall: compute reduce gives a scalar, not a vector
    EXPECT_NE(periodic.input.find("variable wall1 equal c_walls\n"), std::string::npos);
    EXPECT_NE(periodic.input.find("variable wall equal v_wall1"), std::string::npos);

    p.container = Container(Annulus(3.0, 0.8));
    input = lammps_job(p, LammpsPairStyle::gran_hooke, "lmp").input;
    // the rod set back by half its radius (less than all of it), its reach as much longer
    EXPECT_NE(input.find("region rod cylinder z 0 0 0.4 INF INF side out"), std::string::npos);
    EXPECT_NE(input.find("fix rod1 size1 wall/region rod harmonic 0.5 1.0 0.9"), std::string::npos);
    EXPECT_NE(input.find("v_r+0.8-sqrt(x*x+y*y)"), std::string::npos);
}

TEST(LammpsJob, LaunchWords) {
    LammpsLauncher l;
    EXPECT_EQ(lammps_launch(l), std::vector<std::string>{"lmp"});
    l.ranks = 4;
    const std::vector<std::string> mpi = lammps_launch(l);
    ASSERT_GE(mpi.size(), 4u);
    EXPECT_EQ((std::vector<std::string>(mpi.begin(), mpi.begin() + 3)),
              (std::vector<std::string>{"mpirun", "-np", "4"}));
    EXPECT_EQ(mpi.back(), "lmp");
    l.mpi_command = "srun  -n 64";
    l.lmp = "lmp_mpi";
    EXPECT_EQ(lammps_launch(l), (std::vector<std::string>{"srun", "-n", "64", "lmp_mpi"}));
    l.mpi_command = "srun\n-n 64";
    EXPECT_THROW(lammps_launch(l), InvalidInput);
    l.mpi_command = "   ";
    EXPECT_THROW(lammps_launch(l), InvalidInput);
}

TEST(LammpsResult, ErrorsAreLammpsOwnWords) {
    EXPECT_EQ(lammps_error("Step Temp\nERROR on proc 1: Lost atoms: original 2250 current 2248 "
                           "(src/thermo.cpp:439)\nLast command: minimize\n"),
              "ERROR on proc 1: Lost atoms: original 2250 current 2248");
    EXPECT_EQ(lammps_error("  print 'PACKBED FAILED not this one'\nPACKBED FAILED the bed did "
                           "not settle within 50 iterations\n"),
              "the bed did not settle within 50 iterations");
    EXPECT_EQ(lammps_error("all fine\n"), "");
}

TEST(LammpsResult, TheBedIsReadBackAndChecked) {
    SoftSphereParameters p;
    p.particles = 3;
    p.diameter = 2.0;
    const Folder f;
    f.write("log.lammps", finished_log());
    f.write("bed.dump", dump({{0, 0, 0.5}, {1.2, 0, 0.5}, {0.6, 0, 1.5}}));
    const SoftSphereResult r = lammps_result(p, f.path);
    ASSERT_EQ(r.packing.size(), 3u);
    EXPECT_DOUBLE_EQ(r.packing.centers[1].x, 2.4); // output units: Dp = 2
    EXPECT_EQ(r.packing.radii[0], 1.0);
    EXPECT_EQ(r.iterations, 6000u);
    ASSERT_EQ(r.stages.size(), 3u);
    EXPECT_EQ(r.stages[0].iterations, 300u);
    EXPECT_EQ(r.stages[1].iterations, 5000u);
    EXPECT_EQ(r.stages[1].steps, 2u);
    EXPECT_DOUBLE_EQ(r.stages[1].cg, 0.0002 * p.ck);
    EXPECT_EQ(r.stages[2].iterations, 700u);
    EXPECT_EQ(r.neighbor_builds, 42u);
    EXPECT_EQ(r.seconds, 65.0); // LAMMPS's own wall time, what import-lammps reports
    EXPECT_EQ(r.max_overlap_pair, 0.0);

    // a pair overlapping by 0.001 Dp: LAMMPS's bed fails packbed's own check
    f.write("bed.dump", dump({{0, 0, 0.5}, {0.999, 0, 0.5}, {0.6, 0, 1.5}}));
    try {
        lammps_result(p, f.path);
        FAIL() << "an overlap of 1e-3 Dp passed";
    } catch (const ConvergenceError& e) {
        EXPECT_NE(std::string(e.what()).find("fails packbed's check"), std::string::npos);
    }
    // a sphere through the floor
    f.write("bed.dump", dump({{0, 0, 0.49}, {1.2, 0, 0.5}, {0.6, 0, 1.5}}));
    EXPECT_THROW(lammps_result(p, f.path), ConvergenceError);

    // a run that failed: LAMMPS's message, from the screen output where it is
    f.write("log.lammps", "LAMMPS (7 Jan 2022)\nStep Temp\n");
    f.write("screen.txt", "ERROR on proc 1: Lost atoms: original 3 current 2 "
                          "(src/thermo.cpp:439)\n");
    try {
        lammps_result(p, f.path);
        FAIL() << "a failed run passed";
    } catch (const ConvergenceError& e) {
        EXPECT_EQ(std::string(e.what()),
                  "LAMMPS: ERROR on proc 1: Lost atoms: original 3 current 2");
    }
}

TEST(LammpsResult, ALogNotWrittenByTheJobIsRefusedWithItsLine) {
    // import-lammps reads a folder from elsewhere: a log cut, edited or from another job gives
    // a ConvergenceError naming what is wrong, never a count converted beyond its range.
    SoftSphereParameters p;
    p.particles = 3;
    const Folder f;
    f.write("bed.dump", dump({{0, 0, 0.5}, {1.2, 0, 0.5}, {0.6, 0, 1.5}}));
    const auto refused = [&](const std::string& from, const std::string& to) {
        std::string log = finished_log();
        log.replace(log.find(from), from.size(), to);
        f.write("log.lammps", log);
        return convergence_error(p, f.path);
    };
    EXPECT_EQ(refused("step 300", "step -300"),
              "LAMMPS's log has a stage line whose step is -300; allowed: a whole number from 0 "
              "to 9.0072e+15");
    EXPECT_EQ(refused("step 5300", "step 1e30"),
              "LAMMPS's log has a stage line whose step is 1e30; allowed: a whole number from 0 "
              "to 9.0072e+15");
    EXPECT_EQ(refused("rounds 2", "rounds 1e20"),
              "LAMMPS's log has a stage line whose rounds is 1e20; allowed: a whole number from "
              "0 to 4.29497e+09");
    EXPECT_EQ(refused("step 6000 g", "step 6000.5 g"),
              "LAMMPS's log has a stage line whose step is 6000.5; allowed: a whole number from "
              "0 to 9.0072e+15");
    EXPECT_EQ(refused("pair 0.015", "pair nan"),
              "LAMMPS's log has a stage line that is not numbers: 'PACKBED stage intermediate "
              "step 5300 g 0.0002 pair nan wall 0.012 mc 2.5 rounds 2'");
    EXPECT_EQ(refused("stage final", "stage initial"),
              "LAMMPS's log has the stages initial, intermediate, initial; the job prints "
              "initial, intermediate, final");
    EXPECT_EQ(refused("stage initial", "stage \x1b[2J"),
              "LAMMPS's log has the stages \\x1b[2J, intermediate, final; the job prints "
              "initial, intermediate, final");

    // a log too large to be a job's (sparse: no disk written) is refused before it is read
    f.write("log.lammps", finished_log());
    std::filesystem::resize_file(f.path / "log.lammps", limits::max_small_file + 1);
    try {
        lammps_result(p, f.path);
        FAIL() << "a log of 64 MiB was read";
    } catch (const InvalidInput& e) {
        EXPECT_NE(std::string(e.what()).find("log.lammps is 67108865 bytes; allowed: at most "
                                             "67108864"),
                  std::string::npos)
            << e.what();
    }
    // no ERROR line (mpirun refused to start): the last line printed, not a folder's path
    f.write("log.lammps", "");
    f.write("screen.txt", "------\nmpirun has detected an attempt to run as root.\n\n  \n");
    EXPECT_EQ(convergence_error(p, f.path),
              "LAMMPS ended without writing the bed (no 'PACKBED done' in its log.lammps); the "
              "last it printed: 'mpirun has detected an attempt to run as root.'");
    std::filesystem::remove(f.path / "screen.txt");
    // a screen output that is a device (a link to /dev/zero) is not read: the log's words
    f.write("log.lammps", "LAMMPS (7 Jan 2022)\nPACKBED FAILED the bed did not settle within 9 "
                          "iterations\n");
    std::filesystem::create_symlink("/dev/zero", f.path / "screen.txt");
    EXPECT_EQ(convergence_error(p, f.path), "LAMMPS: the bed did not settle within 9 iterations");
}
