// Outputs whole or not at all: staging, commit, refusals before any work, replacement with
// --force, temporaries that follow no link, leftovers of killed runs, cancellation.
#include <sched.h>
#include <sys/mount.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <set>
#include <sstream>

#include <gtest/gtest.h>

#include "packbed/error.hpp"
#include "packbed/output.hpp"

using namespace packbed;
namespace fs = std::filesystem;

namespace {

/// A fresh folder private to the running test.
fs::path scratch() {
    const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
    const fs::path d = fs::temp_directory_path() / "packbed-test-output" /
                       (std::string(info->test_suite_name()) + "." + info->name());
    fs::remove_all(d);
    fs::create_directories(d);
    return d;
}

std::string slurp(const fs::path& path) {
    std::ifstream in(path, std::ios::binary);
    std::ostringstream s;
    s << in.rdbuf();
    return s.str();
}

void write(const fs::path& path, const std::string& text) {
    std::ofstream(path, std::ios::binary) << text;
}

/// Every entry under `folder`, hidden ones included, as relative paths.
std::set<std::string> tree(const fs::path& folder) {
    std::set<std::string> out;
    for (const auto& e : fs::recursive_directory_iterator(folder))
        out.insert(e.path().lexically_relative(folder).string());
    return out;
}

/// The message of the InvalidInput that `f` throws, or "" when it throws none.
template <class F> std::string refusal(F&& f) {
    try {
        f();
    } catch (const InvalidInput& e) {
        return e.what();
    }
    return "";
}

} // namespace

TEST(OutputDirectory, NothingAppearsBeforeCommit) {
    const fs::path root = scratch(), d = root / "new" / "out";
    {
        OutputDirectory out(d);
        out.stage("a.txt", "alpha\n");
        out.stage("sub/b.txt", "beta\n");
        EXPECT_FALSE(fs::exists(root / "new")); // not even the parent, before the commit
        out.commit();
    }
    EXPECT_EQ(slurp(d / "a.txt"), "alpha\n");
    EXPECT_EQ(slurp(d / "sub" / "b.txt"), "beta\n");
    EXPECT_EQ(tree(root), (std::set<std::string>{"new", "new/out", "new/out/a.txt", "new/out/sub",
                                                 "new/out/sub/b.txt"}));
    // The directory gets the usual permissions, not the staging folder's 0700.
    struct stat info {};
    ASSERT_EQ(::stat(d.c_str(), &info), 0);
    const mode_t mask = ::umask(0);
    ::umask(mask);
    EXPECT_EQ(info.st_mode & 0777, 0777 & ~mask);
}

TEST(OutputDirectory, AbandonedOutputLeavesNothing) {
    const fs::path root = scratch();
    {
        OutputDirectory out(root / "out");
        out.stage("a.txt", "alpha\n");
        EXPECT_EQ(tree(root).size(), 2u); // the hidden staging folder and its file
    }                                     // destroyed without commit, as after an exception
    EXPECT_TRUE(tree(root).empty());
}

TEST(OutputDirectory, RefusalsComeBeforeAnythingIsCreated) {
    const fs::path root = scratch();
    write(root / "plain", "x");
    EXPECT_NE(refusal([&] { OutputDirectory(root / "plain"); }).find("a file has that name"),
              std::string::npos);
    EXPECT_NE(refusal([&] { OutputDirectory(root / "plain" / "sub"); })
                  .find("--out " + (root / "plain" / "sub").string() + ": " +
                        (root / "plain").string() + " is a file; allowed: a directory"),
              std::string::npos);
    EXPECT_NE(refusal([&] {
                  OutputDirectory(root / "bad\nname");
              }).find("'" + root.string() + "/bad\\nname' is not allowed (a control character"),
              std::string::npos);
    EXPECT_EQ(tree(root), std::set<std::string>{"plain"});
}

TEST(OutputDirectory, NonEmptyDirectoryIsRefusedWithoutForce) {
    const fs::path root = scratch(), d = root / "out";
    fs::create_directories(d);
    write(d / "old.csv", "old\n");
    EXPECT_EQ(refusal([&] { OutputDirectory(d, "--out"); }),
              "--out " + d.string() +
                  ": exists and is not empty; allowed: a new or empty directory, or --force to "
                  "replace it whole");
    EXPECT_EQ(tree(root), (std::set<std::string>{"out", "out/old.csv"}));
}

TEST(OutputDirectory, ForceReplacesTheDirectoryWhole) {
    const fs::path root = scratch(), d = root / "out";
    fs::create_directories(d / "stale");
    write(d / "axial_void_fraction.csv", "old\n");
    write(d / "stale" / "x", "old\n");
    {
        OutputDirectory out(d, "--out", OutputKind::directory, true);
        out.stage("particles.csv", "new\n");
        EXPECT_EQ(slurp(d / "axial_void_fraction.csv"), "old\n"); // untouched until the commit
        out.commit();
    }
    EXPECT_EQ(tree(root), (std::set<std::string>{"out", "out/particles.csv"}));
}

TEST(OutputDirectory, ForceRefusesTheWorkingDirectoryAndInputsInside) {
    const fs::path root = scratch(), d = root / "out";
    fs::create_directories(d / "inner");
    write(d / "particles.csv", "x,y,z,r\n");
    const fs::path was = fs::current_path();
    fs::current_path(d / "inner");
    const std::string message =
        refusal([&] { OutputDirectory(d, "--out", OutputKind::directory, true); });
    fs::current_path(was);
    EXPECT_NE(message.find("--force would replace the working directory or a folder holding it"),
              std::string::npos)
        << message;
    const JobScope job;
    OutputDirectory out(d, "--out", OutputKind::directory, true);
    EXPECT_EQ(refusal([&] { record_input("the particles file", d / "particles.csv"); }),
              "the particles file " + (d / "particles.csv").string() + " lies in --out " +
                  d.string() +
                  ", which --force would replace; allowed: an output directory that does not "
                  "hold the inputs");
}

TEST(OutputDirectory, AnEmptyDirectoryIsFilled) {
    const fs::path root = scratch(), d = root / "out";
    fs::create_directories(d);
    OutputDirectory out(d);
    out.stage("a.txt", "alpha\n");
    out.commit();
    EXPECT_EQ(tree(root), (std::set<std::string>{"out", "out/a.txt"}));
}

TEST(OutputDirectory, FilesReplaceTheirNamesakesOnly) {
    const fs::path root = scratch();
    write(root / "bed.data", "old\n");
    write(root / "other.txt", "mine\n");
    fs::create_directories(root / "case.stl");
    OutputDirectory out(root, "--out", OutputKind::files);
    EXPECT_NE(refusal([&] { out.reserve("case.stl"); }).find("a directory has that name"),
              std::string::npos);
    ASSERT_EQ(::mkfifo((root / "pipe.data").c_str(), 0600), 0);
    EXPECT_NE(refusal([&] { out.reserve("pipe.data"); }).find("a FIFO has that name"),
              std::string::npos);
    OutputDirectory dev("/dev", "--out", OutputKind::files);
    EXPECT_EQ(refusal([&] { dev.reserve("null"); }),
              "--out /dev/null: a device or socket has that name; allowed: a regular file name");
    out.stage("bed.data", "new\n");
    out.commit();
    EXPECT_EQ(slurp(root / "bed.data"), "new\n");
    EXPECT_EQ(tree(root),
              (std::set<std::string>{"bed.data", "case.stl", "other.txt", "pipe.data"}));
}

TEST(OutputDirectory, AnInputIsNeverOverwritten) {
    // packbed export x.csv --out x.csv, and the same through a link.
    const fs::path root = scratch();
    write(root / "x.csv", "x,y,z,r\n0,0,1,0.5\n");
    fs::create_symlink(root / "x.csv", root / "link.csv");
    const JobScope job;
    OutputDirectory out(root, "--out", OutputKind::files);
    record_input("the particles file", root / "x.csv");
    EXPECT_NE(refusal([&] { out.reserve("x.csv"); }).find("the output"), std::string::npos);
    EXPECT_NE(refusal([&] { out.reserve("link.csv"); }).find("would overwrite it"),
              std::string::npos);
    write(root / "y.data", "an older export, read again\n");
    out.reserve("y.data");
    EXPECT_NE(
        refusal([&] { record_input("--box-file", root / "y.data"); }).find("would overwrite it"),
        std::string::npos);
    EXPECT_EQ(tree(root).count("y.data"), 1u);
}

// What a job reads and writes (JobScope): an output is never an input, never holds one and
// never overlaps another output, whichever is recorded first; a folder read whole may hold an
// output that holds nothing read.
TEST(JobScope, NoOutputIsHoldsOrReplacesAnInputWhicheverComesFirst) {
    const fs::path root = scratch();
    fs::create_directories(root / "bed");
    write(root / "bed" / "particles.csv", "x,y,z,r\n");
    write(root / "bed" / "summary.json", "{}");
    fs::create_directories(root / "case" / "postProcessing");
    write(root / "case" / "packbed.json", "{}");
    write(root / "case" / "postProcessing" / "p0.dat", "1");
    write(root / "sizes.csv", "1,0\n");
    const std::string sizes = (root / "sizes.csv").string();
    {
        // The input first, then the output (a sidecar, a directory holding it, the folder of
        // the input as a file output's folder: allowed).
        const JobScope job;
        record_input("", root / "bed" / "particles.csv");
        record_input("the bed's summary", root / "bed" / "summary.json");
        OutputDirectory files(root / "bed", "--out", OutputKind::files);
        files.reserve("particles.stl");
        EXPECT_EQ(refusal([&] { files.reserve("summary.json"); }),
                  "the bed's summary " + (root / "bed" / "summary.json").string() +
                      ": the output " + (root / "bed" / "summary.json").string() +
                      " would overwrite it; allowed: an output that is not an input");
        EXPECT_NE(
            refusal([&] { OutputDirectory(root / "bed", "--out", OutputKind::directory, true); })
                .find("the input file " + (root / "bed" / "particles.csv").string() +
                      " lies in --out"),
            std::string::npos);
        EXPECT_NE(refusal([&] {
                      OutputDirectory(root, "--out", OutputKind::directory, true);
                  }).find("lies in --out"),
                  std::string::npos);
    }
    {
        // The output first, then the input (a --sizes file in the directory --force replaces);
        // a file written during the run (a checkpoint) read under another option, or inside
        // the output directory; the same file read and written as the checkpoint: one file.
        const JobScope job;
        fs::create_directories(root / "out");
        write(root / "out" / "sizes.csv", "1,0\n");
        write(root / "out" / "old", "x");
        OutputDirectory out(root / "out", "--out", OutputKind::directory, true);
        EXPECT_NE(refusal([&] {
                      record_input("--sizes", root / "out" / "sizes.csv");
                  }).find("which --force would replace"),
                  std::string::npos);
        EXPECT_NE(
            refusal([&] {
                check_writable_file("--checkpoint", root / "out" / "run.ckpt");
            }).find("--checkpoint " + (root / "out" / "run.ckpt").string() + " lies in --out"),
            std::string::npos);
        EXPECT_NE(refusal([&] {
                      check_writable_file("--checkpoint", root / "out");
                  }).find("a directory has that name"),
                  std::string::npos);
        record_input("--sizes", root / "sizes.csv");
        EXPECT_EQ(refusal([&] { check_writable_file("--checkpoint", root / "sizes.csv"); }),
                  "--checkpoint " + sizes + ": it is also --sizes " + sizes +
                      ", which this run reads; allowed: a file that is not an input");
        check_writable_file("--checkpoint", root / "run.ckpt");
        write(root / "run.ckpt", "resumed");
        record_input("--checkpoint", root / "run.ckpt"); // read to resume: allowed
        EXPECT_NE(refusal([&] { OutputDirectory(root / "out" / "inner"); }).find("overlap"),
                  std::string::npos);
    }
    {
        // A folder read whole (an OpenFOAM case): an output may lie in it (cfd-report's
        // default CASE/cfd-report) but not be it, hold it or hold a file read from it.
        const JobScope job;
        record_input("CASE", root / "case");
        record_input("CASE", root / "case" / "packbed.json");
        record_input("CASE", root / "case" / "postProcessing" / "p0.dat");
        OutputDirectory report(root / "case" / "cfd-report");
        EXPECT_NE(refusal([&] {
                      OutputDirectory(root / "case", "--out", OutputKind::directory, true);
                  }).find("CASE " + (root / "case").string() + " lies in --out"),
                  std::string::npos);
        EXPECT_NE(refusal([&] {
                      OutputDirectory(root / "case" / "postProcessing", "--out",
                                      OutputKind::directory, true);
                  }).find("CASE " + (root / "case" / "postProcessing" / "p0.dat").string()),
                  std::string::npos);
    }
    {
        // Outside a scope nothing is recorded; a nested scope adds to the outer one.
        record_input("--sizes", root / "sizes.csv");
        OutputDirectory files(root, "--out", OutputKind::files);
        files.reserve("sizes.csv");
        const JobScope outer;
        {
            const JobScope inner;
            record_input("--sizes", root / "sizes.csv");
        }
        OutputDirectory again(root, "--out", OutputKind::files);
        EXPECT_NE(refusal([&] { again.reserve("sizes.csv"); }).find("would overwrite it"),
                  std::string::npos);
    }
    EXPECT_EQ(slurp(root / "sizes.csv"), "1,0\n");
    EXPECT_EQ(slurp(root / "bed" / "summary.json"), "{}");
}

TEST(OutputDirectory, ALinkInPlaceOfAnOutputIsReplacedNotFollowed) {
    const fs::path root = scratch();
    write(root / "victim", "precious\n");
    fs::create_symlink(root / "victim", root / "bed.data");
    OutputDirectory out(root, "--out", OutputKind::files);
    out.stage("bed.data", "new\n");
    out.commit();
    EXPECT_EQ(slurp(root / "victim"), "precious\n");
    EXPECT_FALSE(fs::is_symlink(root / "bed.data"));
    EXPECT_EQ(slurp(root / "bed.data"), "new\n");
}

namespace {

/// A process id that ran and has ended.
pid_t ended_pid() {
    const pid_t child = ::fork();
    if (child == 0)
        ::_exit(0);
    ::waitpid(child, nullptr, 0);
    return child;
}

/// This process's host identity, as it names its staging folders (`.NAME.packbed-HOST-PID-X`).
std::string own_host(const fs::path& folder) {
    const OutputDirectory probe(folder / "probe");
    for (const auto& e : fs::directory_iterator(folder)) {
        const std::string name = e.path().filename().string();
        if (name.starts_with(".probe.packbed-"))
            return name.substr(15, 12);
    }
    return "";
}

} // namespace

TEST(OutputDirectory, LeftoversOfEndedRunsOfThisHostAreRemovedOthersKept) {
    const fs::path root = scratch();
    const std::string host = own_host(root);
    ASSERT_EQ(host.size(), 12u);
    const std::string other = host == "0123456789ab" ? "ba9876543210" : "0123456789ab";
    const std::string dead = std::to_string(ended_pid()), alive = std::to_string(::getppid());
    // Removed: this host's, their process ended.
    fs::create_directories(root / (".out.packbed-" + host + "-" + dead + "-Ab12Cd") / "sub");
    write(root / (".x.data.packbed-" + host + "-" + dead + "-zzzzzz"), "left");
    fs::create_directories(root / (".out.packbed-" + host + "-" + dead + "-Ab12Cd.old"));
    // Kept: still running; another host's or PID namespace's (a shared disk, a container),
    // whose process id means nothing here; the names of older versions (no host); not ours.
    const std::set<std::string> kept{".out.packbed-" + host + "-" + alive + "-Ab12Cd",
                                     ".out.packbed-" + other + "-" + dead + "-Ab12Cd",
                                     ".y.packbed-" + other + "-" + dead + "-Qw12Er",
                                     ".out.packbed-" + dead + "-Ab12Cd", ".out.packbed-notes"};
    for (const std::string& name : kept)
        fs::create_directories(root / name);
    { OutputDirectory out(root / "out"); }
    EXPECT_EQ(tree(root), kept);
}

// A run in another PID namespace (a container on the same disk) whose process id is, out
// here, that of an ended process: its staging folder is not taken for a leftover, and it puts
// its output in place. The namespace's next id is set (ns_last_pid) so that the run inside
// gets exactly that id.
TEST(OutputDirectory, ALiveRunInAnotherPidNamespaceKeepsItsStagingFolder) {
    const fs::path root = scratch();
    const pid_t dead = ended_pid();
    int ready[2], go[2];
    ASSERT_EQ(::pipe(ready), 0);
    ASSERT_EQ(::pipe(go), 0);
    const pid_t outer = ::fork();
    if (outer == 0) {
        if (::unshare(CLONE_NEWPID) != 0)
            ::_exit(3);              // not allowed here
        const pid_t init = ::fork(); // pid 1 of the new namespace
        if (init == 0) {
            std::ofstream("/proc/sys/kernel/ns_last_pid") << dead - 1;
            const pid_t run = ::fork();
            if (run == 0) {
                if (::getpid() != dead)
                    ::_exit(5);
                int code = 6;
                try {
                    OutputDirectory out(root / "inner");
                    out.stage("a.txt", "inside\n");
                    char byte = 0;
                    if (::write(ready[1], "r", 1) == 1 && ::read(go[0], &byte, 1) == 1) {
                        out.commit();
                        code = 0;
                    }
                } catch (...) {
                    code = 9;
                }
                ::_exit(code);
            }
            int status = 0;
            ::waitpid(run, &status, 0);
            ::_exit(WIFEXITED(status) ? WEXITSTATUS(status) : 7);
        }
        int status = 0;
        ::waitpid(init, &status, 0);
        ::_exit(WIFEXITED(status) ? WEXITSTATUS(status) : 8);
    }
    char byte = 0;
    ::close(ready[1]);
    const bool started = ::read(ready[0], &byte, 1) == 1;
    if (started) {
        OutputDirectory out(root / "outer"); // removes what ended runs left beside it
        out.stage("b.txt", "outside\n");
        out.commit();
        EXPECT_EQ(::write(go[1], "g", 1), 1);
    }
    ::close(go[1]);
    int status = 0;
    ::waitpid(outer, &status, 0);
    ASSERT_TRUE(WIFEXITED(status));
    ASSERT_NE(WEXITSTATUS(status), 3) << "unshare(CLONE_NEWPID) is not allowed here";
    ASSERT_NE(WEXITSTATUS(status), 5) << "the run inside did not get the process id " << dead;
    EXPECT_EQ(WEXITSTATUS(status), 0);
    EXPECT_EQ(slurp(root / "inner" / "a.txt"), "inside\n");
    EXPECT_EQ(slurp(root / "outer" / "b.txt"), "outside\n");
}

// Two processes that put their output in the same place at the same time: one wins whole,
// the other fails saying so, and the place holds the winner's files only. A new directory,
// an existing empty one, files in a folder, and a directory replaced with --force.
TEST(OutputDirectory, TwoRunsOneOutputOneWinsWhole) {
    const fs::path root = scratch();
    for (int round = 0; round < 40; ++round) {
        const int kind = round % 4;
        const fs::path d = root / std::to_string(round);
        if (kind == 1)
            fs::create_directories(d);
        if (kind == 2) {
            fs::create_directories(d);
            write(d / "a.txt", "old\n");
            write(d / "a.txt.json", "old\n");
        }
        if (kind == 3) {
            fs::create_directories(d);
            write(d / "old.txt", "old\n");
        }
        int go[2], ready[2];
        ASSERT_EQ(::pipe(go), 0);
        ASSERT_EQ(::pipe(ready), 0);
        pid_t children[2];
        for (int c = 0; c < 2; ++c) {
            children[c] = ::fork();
            if (children[c] == 0) {
                ::close(go[1]);
                ::close(ready[0]);
                int code = 9;
                try {
                    OutputDirectory out(d, "--out",
                                        kind == 2 ? OutputKind::files : OutputKind::directory,
                                        kind == 3);
                    const std::string mine = std::to_string(c) + "\n";
                    for (const char* name : {"a.txt", "a.txt.json", "b.txt", "c.txt"})
                        if (kind != 2 || name[0] == 'a')
                            out.stage(name, mine);
                    char byte = 0;
                    if (::write(ready[1], "r", 1) == 1 && ::read(go[0], &byte, 1) == 0)
                        out.commit(); // both staged: they commit together
                    code = 0;
                } catch (const InvalidInput& e) {
                    code = std::string(e.what()).find("another") != std::string::npos ? 2 : 3;
                } catch (...) {
                    code = 4;
                }
                ::_exit(code);
            }
        }
        ::close(go[0]);
        ::close(ready[1]);
        char byte = 0;
        for (int c = 0; c < 2; ++c)
            ASSERT_EQ(::read(ready[0], &byte, 1), 1);
        ::close(ready[0]);
        ::close(go[1]); // end of file: both go
        int codes[2];
        for (int c = 0; c < 2; ++c) {
            int status = 0;
            ::waitpid(children[c], &status, 0);
            codes[c] = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
        }
        ASSERT_TRUE((codes[0] == 0 && codes[1] == 2) || (codes[0] == 2 && codes[1] == 0))
            << "round " << round << ": exit codes " << codes[0] << ", " << codes[1];
        const std::string winner = slurp(d / "a.txt");
        ASSERT_TRUE(winner == "0\n" || winner == "1\n") << "round " << round;
        std::set<std::string> names;
        for (const auto& e : fs::directory_iterator(d)) {
            names.insert(e.path().filename().string());
            EXPECT_EQ(slurp(e.path()), winner) << "round " << round << ": " << e.path();
        }
        EXPECT_EQ(names, kind == 2
                             ? (std::set<std::string>{"a.txt", "a.txt.json"})
                             : (std::set<std::string>{"a.txt", "a.txt.json", "b.txt", "c.txt"}))
            << "round " << round;
        for (const auto& e : fs::directory_iterator(root))
            EXPECT_FALSE(e.path().filename().string().starts_with("."))
                << "left behind: " << e.path();
    }
}

// A name too long for the file system is refused before any work, and a commit that fails
// removes the folders it created for the output.
TEST(OutputDirectory, NamesTooLongAreRefusedAtOnceAndAFailedCommitLeavesNoFolder) {
    const fs::path root = scratch();
    const std::string long_name(300, 'n');
    EXPECT_NE(refusal([&] {
                  OutputDirectory(root / "a" / long_name / "out");
              }).find("has 300 bytes; allowed: names of at most 255 bytes"),
              std::string::npos);
    {
        OutputDirectory files(root / "a" / "b", "--out", OutputKind::files);
        EXPECT_NE(refusal([&] { files.reserve(long_name + ".stl"); }).find("has 304 bytes"),
                  std::string::npos);
    }
    EXPECT_NE(refusal([&] {
                  check_writable_file("--checkpoint", root / long_name);
              }).find("has 300 bytes"),
              std::string::npos);
    EXPECT_TRUE(tree(root).empty());
    // A commit whose directory another process took meanwhile: the parents it made go again.
    {
        OutputDirectory out(root / "p" / "q" / "out");
        out.stage("a.txt", "a\n");
        fs::create_directories(root / "p" / "q" / "out");
        write(root / "p" / "q" / "out" / "theirs", "x");
        EXPECT_NE(refusal([&] { out.commit(); }).find("another run wrote it"), std::string::npos);
    }
    EXPECT_EQ(tree(root), (std::set<std::string>{"p", "p/q", "p/q/out", "p/q/out/theirs"}));
    fs::remove_all(root / "p");
    {
        OutputDirectory out(root / "p" / "q" / "out");
        const fs::path staging = *std::find_if(
            fs::directory_iterator(root), fs::directory_iterator(),
            [](const auto& e) { return e.path().filename().string().starts_with(".out."); });
        fs::remove_all(staging); // the rename fails after p and p/q were made for it
        EXPECT_THROW(out.commit(), std::runtime_error);
    }
    EXPECT_TRUE(tree(root).empty());
}

// A writer's error names the file the user asked for, not the hidden staging folder.
TEST(OutputDirectory, MessagesNameTheOutputAsGiven) {
    const fs::path root = scratch();
    OutputDirectory out(root / "out");
    const fs::path staged = out.reserve("image.raw");
    EXPECT_EQ(as_given("cannot write " + staged.string() + ": No space left on device"),
              "cannot write " + (root / "out" / "image.raw").string() +
                  ": No space left on device");
    OutputDirectory files(root, "--out", OutputKind::files);
    const fs::path stl = files.reserve("bed.stl");
    EXPECT_EQ(as_given("cannot write " + stl.string()),
              "cannot write " + (root / "bed.stl").string());
}

TEST(ReplaceFile, WholeOrNotAtAllFollowingNoLink) {
    const fs::path root = scratch(), file = root / "run.ckpt";
    write(root / "victim", "precious\n");
    fs::create_symlink(root / "victim", root / "run.ckpt.partial"); // the old temporary name
    replace_file(file, "--checkpoint", {"head\n", "data"});
    replace_file(file, "--checkpoint", {"second"});
    EXPECT_EQ(slurp(file), "second");
    EXPECT_EQ(slurp(root / "victim"), "precious\n");
    EXPECT_EQ(tree(root), (std::set<std::string>{"run.ckpt", "run.ckpt.partial", "victim"}));
}

TEST(CheckWritableFile, ProbesWithoutTouchingFiles) {
    const fs::path root = scratch(), file = root / "run.ckpt";
    write(root / "run.ckpt.partial", "the user's\n"); // the old probe deleted this
    check_writable_file("--checkpoint", file);
    EXPECT_EQ(tree(root), std::set<std::string>{"run.ckpt.partial"});
    EXPECT_NE(refusal([&] {
                  check_writable_file("--checkpoint", "/proc/version/c");
              }).find("--checkpoint /proc/version/c: /proc/version is not a folder"),
              std::string::npos);
    EXPECT_NE(refusal([&] {
                  check_writable_file("--checkpoint", root);
              }).find("a directory has that name"),
              std::string::npos);
}

namespace {

/// Stage, cancel, try to write more: 0 when everything was removed and later writes refused.
int cancel_while_staging(const fs::path& root) {
    OutputDirectory out(root / "out");
    out.stage("a.txt", "alpha\n");
    const bool committed = cancel_outputs();
    bool stage_cancelled = false, commit_cancelled = false;
    try {
        out.stage("b.txt", "beta\n");
    } catch (const Cancelled&) {
        stage_cancelled = true;
    }
    try {
        out.commit();
    } catch (const Cancelled&) {
        commit_cancelled = true;
    }
    return (committed ? 1 : 0) + (stage_cancelled ? 0 : 2) + (commit_cancelled ? 0 : 4) +
           (tree(root).empty() ? 0 : 8);
}

/// Commit, then cancel: 0 when cancel_outputs says the results stand.
int cancel_after_commit(const fs::path& root) {
    OutputDirectory out(root / "out");
    out.stage("a.txt", "alpha\n");
    out.commit();
    return cancel_outputs() ? 0 : 1;
}

} // namespace

// cancel_outputs() stops every later output of its process: each case runs in a child that
// starts afresh ("threadsafe" re-runs the test binary), with nothing committed before.
TEST(CancelOutputs, RemovesEverythingStagedAndStopsLaterWrites) {
    ::testing::GTEST_FLAG(death_test_style) = "threadsafe";
    const fs::path root = scratch();
    EXPECT_EXIT(std::_Exit(cancel_while_staging(root)), ::testing::ExitedWithCode(0), "");
    EXPECT_TRUE(tree(root).empty());
}

TEST(CancelOutputs, AfterACommitTheResultsStand) {
    ::testing::GTEST_FLAG(death_test_style) = "threadsafe";
    const fs::path root = scratch();
    EXPECT_EXIT(std::_Exit(cancel_after_commit(root)), ::testing::ExitedWithCode(0), "");
    EXPECT_EQ(tree(root), (std::set<std::string>{"out", "out/a.txt"}));
}
