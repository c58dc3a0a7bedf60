// Outputs whole or not at all: staging, commit, refusals before any work, replacement with
// --force, temporaries that follow no link, leftovers of killed runs, cancellation.
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

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
    OutputDirectory out(d, "--out", OutputKind::directory, true);
    EXPECT_NE(refusal([&] {
                  out.keep("the particles file", d / "particles.csv");
              }).find("which --force would replace"),
              std::string::npos);
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
    OutputDirectory out(root, "--out", OutputKind::files);
    out.keep("the particles file", root / "x.csv");
    EXPECT_NE(refusal([&] { out.reserve("x.csv"); }).find("the output"), std::string::npos);
    EXPECT_NE(refusal([&] { out.reserve("link.csv"); }).find("would overwrite it"),
              std::string::npos);
    write(root / "y.data", "an older export, read again\n");
    out.reserve("y.data");
    EXPECT_NE(refusal([&] { out.keep("--box-file", root / "y.data"); }).find("would overwrite it"),
              std::string::npos);
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

TEST(OutputDirectory, LeftoversOfKilledRunsAreRemovedOthersKept) {
    const fs::path root = scratch();
    const pid_t child = ::fork(); // a process that has ended: its pid runs no more
    if (child == 0)
        ::_exit(0);
    ::waitpid(child, nullptr, 0);
    const std::string dead = std::to_string(child), alive = std::to_string(::getppid());
    fs::create_directories(root / (".out.packbed-" + dead + "-Ab12Cd") / "sub");
    write(root / (".x.data.packbed-" + dead + "-zzzzzz"), "left");
    fs::create_directories(root / (".out.packbed-" + alive + "-Ab12Cd")); // still running
    write(root / ".out.packbed-notes", "mine");                           // not our name pattern
    { OutputDirectory out(root / "out"); }
    EXPECT_EQ(tree(root),
              (std::set<std::string>{".out.packbed-" + alive + "-Ab12Cd", ".out.packbed-notes"}));
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
