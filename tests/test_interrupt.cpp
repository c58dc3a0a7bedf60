// Interrupted runs: SIGINT, SIGTERM and SIGHUP at several points of every long
// subcommand (generate, lattice, analyze, export), and SIGKILL during output.
//
// The points are found from outside, as a user would see them: every run stages its outputs in a
// hidden folder `.NAME.packbed-HOST-PID-XXXXXX` (export's files: `.packbed-HOST-PID-XXXXXX`,
// HOST the 12 hex digits of the host and PID namespace) beside the
// output, created before the work. "Early" is once that folder exists while no file with data
// has appeared in the run's folder (the computation), "output" once one has (a staged file),
// "gnuplot" while packbed has a gnuplot child (/proc/PID/task/PID/children), and the sweep sends
// the signal at delays spread over an uninterrupted run's duration and beyond. The points do not
// depend on the staging folder's name, so that a binary that writes its outputs otherwise (an
// older build) is put to the same tests.
//
// After SIGINT/SIGTERM/SIGHUP a run either exits 130 with exactly "packbed COMMAND: interrupted;
// nothing was written" on stderr and leaves its folder exactly as before, or, only where the
// signal can have come after the outputs were put in place, exits 0 with the complete output (the
// same files as an uninterrupted run). A run interrupted during its computation or its output
// (not yet in place) must exit 130. SIGINT goes to packbed's process group, as a terminal's
// Ctrl-C does (a gnuplot child in that group gets it too). After SIGKILL during output only hidden
// `.*packbed-HOST-PID-*` entries of the killed process may be left, and the next run with the same
// --out removes them and succeeds.
//
// PACKBED_TEST_EXE in the environment runs these tests on another binary (an older build).
#include <fcntl.h>
#include <signal.h>
#include <sys/types.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cctype>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <functional>
#include <map>
#include <optional>
#include <set>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include <gtest/gtest.h>

#include "run_packbed.hpp"

namespace fs = std::filesystem;
using packbed::test::exe;
using packbed::test::slurp;
namespace test = packbed::test;
using Clock = std::chrono::steady_clock;
using namespace std::chrono_literals;

namespace {

/// A run that does not end within this after its signal hangs: killed, and the test fails.
constexpr auto time_limit = 60s;

fs::path test_folder() {
    return test::test_folder("interrupt");
}

const auto* const remove_scratch =
    ::testing::AddGlobalTestEnvironment(new test::RemoveWhenPassed("interrupt"));

/// A fresh folder `NAME/work` (where the run happens) and `NAME/io` (its stdout and stderr) for
/// the running test.
fs::path scratch(const std::string& name) {
    const fs::path d = test_folder() / name;
    fs::remove_all(d);
    fs::create_directories(d / "work");
    fs::create_directories(d / "io");
    return d;
}

/// Start `packbed ARGS` in `root/work`, stdout and stderr into `root/io` (run_packbed.hpp).
pid_t spawn(const std::vector<std::string>& args, const fs::path& root) {
    return test::spawn(args, root / "work", root / "io");
}

/// Send `signal` as a user does: SIGINT is Ctrl-C, which the terminal sends to the whole
/// foreground job (packbed and any child in its process group); SIGTERM, SIGHUP and SIGKILL
/// go to packbed only (kill PID).
void interrupt(pid_t pid, int signal) {
    ::kill(signal == SIGINT ? -pid : pid, signal);
}

struct Ended {
    bool exited = false;    // by exit(), not by a signal
    int status = -1;        // the exit status, or the signal
    bool timed_out = false; // still running after time_limit: killed
    double seconds = 0.0;   // from `start`
    std::string out, err;
};

/// Wait for `pid` to end (reaped), at most time_limit.
Ended wait_end(pid_t pid, const fs::path& root, Clock::time_point start) {
    Ended e;
    int raw = 0;
    const auto deadline = Clock::now() + time_limit;
    while (::waitpid(pid, &raw, WNOHANG) == 0) {
        if (Clock::now() > deadline) {
            ::kill(pid, SIGKILL);
            ::waitpid(pid, &raw, 0);
            e.timed_out = true;
            break;
        }
        std::this_thread::sleep_for(1ms);
    }
    e.seconds = std::chrono::duration<double>(Clock::now() - start).count();
    e.exited = WIFEXITED(raw);
    e.status = WIFEXITED(raw) ? WEXITSTATUS(raw) : WIFSIGNALED(raw) ? WTERMSIG(raw) : -1;
    e.out = slurp(root / "io" / "out");
    e.err = slurp(root / "io" / "err");
    return e;
}

bool compared(const fs::path& p) {
    const std::string ext = p.extension().string();
    return ext == ".csv" || ext == ".vtu" || ext == ".stl";
}

/// What is under `root` (packbed::test::listing): the outputs that do not depend on the run
/// (.csv, .vtu, .stl) by their size and a hash of their contents, other files (summary.json
/// holds the run's seconds) by whether they are empty.
std::string listing(const fs::path& root) {
    return packbed::test::listing(root, [](const fs::path& p, std::uintmax_t size) {
        return compared(p) ? "file " + std::to_string(size) + " " +
                                 std::to_string(std::hash<std::string>{}(slurp(p)))
               : size > 0 ? std::string("file, not empty")
                          : std::string("file, empty");
    });
}

std::set<std::string> lines_of(const std::string& text) {
    std::set<std::string> out;
    std::istringstream in(text);
    for (std::string l; std::getline(in, l);)
        out.insert(l);
    return out;
}

/// `n` x `n` columns of spheres of diameter 1 on a square grid inside a cylinder of radius
/// `radius`, `layers` high: a valid bed for analyze and export (contacts everywhere).
std::string grid_bed(int radius, int layers) {
    std::string csv = "x,y,z,r\n";
    for (int k = 0; k < layers; ++k)
        for (int i = -radius; i <= radius; ++i)
            for (int j = -radius; j <= radius; ++j)
                if (std::hypot(i, j) + 0.5 <= radius)
                    csv += std::to_string(i) + "," + std::to_string(j) + "," + std::to_string(k) +
                           ".5,0.5\n";
    return csv;
}

struct Command {
    std::string name; // the subcommand, as in the message
    std::vector<std::string> args;
    std::string out; // the output (--out), relative to work
    bool plots;      // draws plots with gnuplot when it is installed
    std::function<void(const fs::path&)> prepare = [](const fs::path&) {}; // inputs into work
    std::string child = "gnuplot";   // the child program of Point::gnuplot
    std::string child_argument = ""; // one of its arguments, to tell one run of it from another
};

// Inputs sized so that each phase lasts long enough to be hit (on 2 busy cores: computation
// 0.3-1.5 s, output 0.1-0.3 s, gnuplot 20-60 ms) and a whole run stays near a second.
Command generate() {
    return {"generate",
            {"generate", "-q", "--solver", "fire", "-a", "5", "-n", "500", "--seed", "1",
             "--threads", "1", "--out", "out"},
            "out",
            true};
}
// The LAMMPS engine: packbed waits for lmp, a child program in its own process
// group, which the signal must stop with packbed.
Command generate_lammps() {
    Command c{"generate",
              {"generate", "-q", "--engine", "lammps", "-a", "5", "-n", "500", "--seed", "1",
               "--out", "out"},
              "out",
              true};
    c.child = "lmp";
    c.child_argument = "-in"; // the run, not the `lmp -h` that comes first
    return c;
}
Command lattice() { // about 1.8e5 balls: 20 MB of CSV and VTU, without the analysis (the
                    // cylinder's case below runs it)
    return {"lattice",
            {"lattice", "--type", "fcc", "--region", "box:50,50,50", "--no-analysis", "-q", "--out",
             "out"},
            "out",
            false};
}
Command lattice_cylinder() { // a lattice in a cylinder is analysed and plotted like a bed
    return {"lattice",
            {"lattice", "--type", "fcc", "--region", "cylinder:12,12", "-q", "--out", "out"},
            "out",
            true};
}
Command analyze() { // about 7 000 spheres
    return {"analyze",
            {"analyze", "bed.csv", "-R", "9", "-q", "--out", "out"},
            "out",
            true,
            [](const fs::path& work) { std::ofstream(work / "bed.csv") << grid_bed(9, 30); }};
}
Command export_stl() { // 970 spheres with caps at every contact, icosphere level 3: 77 MB
    return {"export",
            {"export", "bed.csv", "--format", "stl", "-R", "6", "--refine", "3", "--contacts",
             "caps:0.05", "-q", "--out", "surface.stl"},
            "surface.stl",
            false,
            [](const fs::path& work) { std::ofstream(work / "bed.csv") << grid_bed(6, 10); }};
}

/// An uninterrupted run of `c`: how long it takes and what its folder holds after it.
struct Reference {
    double seconds = 0.0;
    std::string after; // listing of its work folder
};

const Reference& reference(const Command& c) {
    static std::map<std::string, Reference> cache;
    const std::string key = c.out + ":" + [&] {
        std::string k;
        for (const auto& a : c.args)
            k += a + " ";
        return k;
    }();
    if (const auto it = cache.find(key); it != cache.end())
        return it->second;
    const fs::path root = scratch("reference-" + std::to_string(cache.size()));
    c.prepare(root / "work");
    const auto start = Clock::now();
    const Ended e = wait_end(spawn(c.args, root), root, start);
    EXPECT_TRUE(e.exited && e.status == 0) << "the uninterrupted run failed: " << e.err;
    EXPECT_EQ(e.err, "");
    Reference r{e.seconds, listing(root / "work")};
    fs::remove_all(root);
    return cache.emplace(key, r).first->second;
}

/// Whether `name` is a hidden name that process `pid` staged (`.NAME.packbed-HOST-PID-XXXXXX`
/// or `.packbed-HOST-PID-XXXXXX`, HOST 12 hex digits).
bool staged_by(const std::string& name, pid_t pid) {
    const std::size_t at = name.find("packbed-");
    const std::string tag = "-" + std::to_string(pid) + "-";
    return !name.empty() && name[0] == '.' && at != std::string::npos &&
           name.compare(at + 20, tag.size(), tag) == 0;
}

/// Whether process `pid` has a staging folder in `work`.
bool staging_exists(const fs::path& work, pid_t pid) {
    std::error_code ec;
    for (fs::directory_iterator it(work, ec), end; !ec && it != end; it.increment(ec))
        if (staged_by(it->path().filename().string(), pid))
            return true;
    return false;
}

/// Whether the run has written data: a file under `work` (staged, temporary or final) that
/// was not there before and is not empty.
bool new_data(const fs::path& work, const std::set<std::string>& inputs) {
    std::error_code ec;
    for (fs::recursive_directory_iterator it(work, ec), end; !ec && it != end; it.increment(ec))
        if (it->is_regular_file(ec) && it->file_size(ec) > 0 &&
            inputs.count(it->path().lexically_relative(work).string()) == 0)
            return true;
    return false;
}

/// Whether the output `out` is in place: a file, or a directory holding a file that is not
/// hidden (what a run stages or writes under a temporary name is hidden).
bool in_place(const fs::path& work, const std::string& out) {
    std::error_code ec;
    const fs::file_status s = fs::symlink_status(work / out, ec);
    if (fs::is_regular_file(s))
        return true;
    if (!fs::is_directory(s))
        return false;
    for (fs::directory_iterator it(work / out, ec), end; !ec && it != end; it.increment(ec))
        if (it->path().filename().string()[0] != '.' && it->is_regular_file(ec))
            return true;
    return false;
}

/// The pid of a gnuplot child of `pid`, or 0.
/// \return the child of `pid` running `program` with `argument` among its arguments (any when
/// `argument` is empty), or 0.
pid_t child_named(pid_t pid, const std::string& program, const std::string& argument) {
    std::ifstream children("/proc/" + std::to_string(pid) + "/task/" + std::to_string(pid) +
                           "/children");
    for (pid_t child = 0; children >> child;) {
        std::ifstream comm("/proc/" + std::to_string(child) + "/comm");
        std::string name;
        comm >> name;
        if (name != program)
            continue;
        if (argument.empty())
            return child;
        std::ifstream cmdline("/proc/" + std::to_string(child) + "/cmdline");
        for (std::string word; std::getline(cmdline, word, '\0');)
            if (word == argument)
                return child;
    }
    return 0;
}

/// Whether process `pid` is gone or a zombie (it runs no more).
bool ended(pid_t pid) {
    std::ifstream stat("/proc/" + std::to_string(pid) + "/stat");
    std::string line;
    if (!std::getline(stat, line))
        return true;
    const std::size_t close = line.rfind(')');
    return close != std::string::npos && close + 2 < line.size() && line[close + 2] == 'Z';
}

bool installed(const std::string& program) {
    const char* path = std::getenv("PATH");
    std::istringstream dirs(path != nullptr ? path : "/usr/bin:/bin");
    for (std::string dir; std::getline(dirs, dir, ':');)
        if (!dir.empty() && ::access((fs::path(dir) / program).c_str(), X_OK) == 0)
            return true;
    return false;
}

enum class Point { early, output, gnuplot };

const char* to_string(Point p) {
    return p == Point::early    ? "early (computing)"
           : p == Point::output ? "during output"
                                : "while its child program (gnuplot, lmp) runs";
}

/// One run of `c`, signalled with `signal` at `point` (or after `delay`).
struct Interrupted {
    bool reached = false;   // the point was reached before the run ended
    bool committed = false; // the output was in place when the signal was sent
    pid_t gnuplot = 0;      // the gnuplot child running when it was sent
    pid_t pid = 0;
    Ended end;
    std::string before; // the work folder before the run
    std::string after;  // and after it
};

Interrupted run_interrupted(const Command& c, const fs::path& root, int signal,
                            std::optional<Point> point, double delay = 0.0) {
    const fs::path work = root / "work";
    c.prepare(work);
    Interrupted r;
    r.before = listing(work);
    std::set<std::string> inputs;
    for (const auto& e : fs::recursive_directory_iterator(work))
        inputs.insert(e.path().lexically_relative(work).string());
    const auto start = Clock::now();
    r.pid = spawn(c.args, root);
    const auto at = start + std::chrono::duration<double>(delay);
    while (true) {
        siginfo_t info{};
        if (::waitid(P_PID, static_cast<id_t>(r.pid), &info, WEXITED | WNOHANG | WNOWAIT) != 0 ||
            info.si_pid != 0) // ended (a zombie, reaped below)
            break;
        if (Clock::now() > start + time_limit)
            break;
        bool now = false;
        if (!point) {
            now = Clock::now() >= at;
        } else if (*point == Point::early) {
            // Computing: nothing written yet, and the staging folder made (the subcommand
            // runs). For a binary that stages nothing: the output directory made, or 2 s gone.
            std::error_code ec;
            now = !new_data(work, inputs) &&
                  (staging_exists(work, r.pid) ||
                   fs::exists(fs::symlink_status(work / c.out, ec)) || Clock::now() > start + 2s);
        } else if (*point == Point::output) {
            now = new_data(work, inputs);
        } else {
            now = (r.gnuplot = child_named(r.pid, c.child, c.child_argument)) != 0;
        }
        if (now) {
            r.committed = in_place(work, c.out);
            interrupt(r.pid, signal);
            r.reached = true;
            break;
        }
        std::this_thread::sleep_for(200us);
    }
    r.end = wait_end(r.pid, root, start);
    if (r.gnuplot != 0) { // stopped by packbed (checked by the caller); never left running
        for (int i = 0; i < 5000 && !ended(r.gnuplot); ++i)
            std::this_thread::sleep_for(1ms);
    }
    r.after = listing(work);
    return r;
}

std::string describe(const Command& c, int signal, const std::string& when) {
    std::string s = "packbed";
    for (const auto& a : c.args)
        s += " " + a;
    return s + ": " + strsignal(signal) + " " + when;
}

/// The outcomes allowed after SIGINT, SIGTERM or SIGHUP (see the top of the file).
/// \param must_stop the signal came long before the end: only exit 130 is allowed
/// \return true when the run was interrupted (130), false when it completed
bool expect_interrupted_or_complete(const Command& c, const Interrupted& r, bool must_stop,
                                    const std::string& what) {
    SCOPED_TRACE(what);
    EXPECT_FALSE(r.end.timed_out) << "still running " << time_limit.count()
                                  << " s after the signal";
    EXPECT_TRUE(r.end.exited) << "ended by signal " << r.end.status << " ("
                              << strsignal(r.end.status) << "); stderr: " << r.end.err;
    if (!r.end.exited || r.end.timed_out)
        return false;
    EXPECT_EQ(r.end.out, "");
    if (r.end.status == 130 || must_stop || !(r.end.status == 0)) {
        EXPECT_EQ(r.end.status, 130) << r.end.err;
        EXPECT_EQ(r.end.err, "packbed " + c.name + ": interrupted; nothing was written\n");
        EXPECT_EQ(r.after, r.before) << "the interrupted run left its folder changed";
        return true;
    }
    // Exit 0: allowed only with the whole output, the same as an uninterrupted run's.
    EXPECT_EQ(r.end.err, "");
    EXPECT_EQ(r.after, reference(c).after) << "exit 0 after the signal, but the output differs "
                                              "from an uninterrupted run's";
    return false;
}

/// SIGINT and SIGTERM at `point`: each run retried (up to 3 times) until the point is reached.
void interrupt_at(const Command& c, Point point) {
    if (c.child == "lmp" && !installed("lmp"))
        GTEST_SKIP() << "lmp is not installed (Debian package lammps): no LAMMPS to interrupt";
    if (point == Point::gnuplot && !installed(c.child))
        GTEST_SKIP() << "gnuplot is not installed (Debian package gnuplot-nox): no plots to "
                        "interrupt";
    for (const int signal : {SIGINT, SIGTERM}) {
        const std::string what = describe(c, signal, to_string(point));
        Interrupted r;
        for (int attempt = 0; attempt < 3 && !r.reached; ++attempt)
            r = run_interrupted(
                c, scratch(std::string(sigabbrev_np(signal)) + "-" + std::to_string(attempt)),
                signal, point);
        ASSERT_TRUE(r.reached) << what << ": the run ended 3 times before the point was reached "
                               << "(exit " << r.end.status << ", stderr: " << r.end.err << ")";
        // During the computation and the output, the output is at least tens of milliseconds
        // from being in place: the run must stop. Gnuplot may be ending: either outcome.
        const bool stopped =
            expect_interrupted_or_complete(c, r, point != Point::gnuplot && !r.committed, what);
        std::printf("%s: %s after %.3f s: %s%s\n", c.name.c_str(), what.c_str(), r.end.seconds,
                    stopped ? "stopped" : "completed",
                    r.gnuplot != 0 ? (" (gnuplot pid " + std::to_string(r.gnuplot) + ")").c_str()
                                   : "");
        if (point == Point::gnuplot) {
            EXPECT_TRUE(ended(r.gnuplot))
                << what << ": gnuplot (pid " << r.gnuplot << ") still runs after packbed ended";
            if (!ended(r.gnuplot)) // a failed run: do not leave it behind
                ::kill(r.gnuplot, SIGKILL);
        }
    }
}

/// SIGKILL during output: only the killed run's hidden staging entries are left, and the next
/// run with the same --out removes them and succeeds.
void kill_during_output(const Command& c) {
    const std::string what = describe(c, SIGKILL, "during output");
    const fs::path root = scratch("killed");
    // Retried while the run ends before its output begins, or puts it in place before SIGKILL.
    Interrupted r;
    for (int attempt = 0; attempt < 3 && (!r.reached || r.committed || r.end.exited); ++attempt) {
        fs::remove_all(root / "work");
        fs::create_directories(root / "work");
        r = run_interrupted(c, root, SIGKILL, Point::output);
    }
    SCOPED_TRACE(what);
    ASSERT_TRUE(r.reached) << "the run ended 3 times before its output began (exit " << r.end.status
                           << ", stderr: " << r.end.err << ")";
    ASSERT_FALSE(r.committed) << "the run put its output in place 3 times before SIGKILL came";
    EXPECT_FALSE(r.end.exited) << "exit " << r.end.status << "; stderr: " << r.end.err;
    EXPECT_EQ(r.end.status, SIGKILL);
    const std::set<std::string> before = lines_of(r.before);
    std::size_t left = 0;
    for (const std::string& line : lines_of(r.after)) {
        if (before.count(line) != 0)
            continue;
        ++left;
        EXPECT_TRUE(staged_by(line.substr(0, std::min(line.find('/'), line.find(' '))), r.pid))
            << "left after SIGKILL, not a hidden entry of the killed process: " << line;
    }
    for (const std::string& line : before)
        EXPECT_EQ(lines_of(r.after).count(line), 1u) << "gone or changed after SIGKILL: " << line;
    EXPECT_GT(left, 0u) << "nothing staged was found after SIGKILL during output";

    // The next run with the same --out, uninterrupted.
    const auto start = Clock::now();
    const Ended next = wait_end(spawn(c.args, root), root, start);
    EXPECT_TRUE(next.exited && next.status == 0) << "the run after SIGKILL failed: " << next.err;
    EXPECT_EQ(next.err, "");
    EXPECT_EQ(listing(root / "work"), reference(c).after)
        << "the run after SIGKILL did not remove the leftovers or wrote another output";
}

/// SIGINT, SIGTERM and SIGHUP in turn at delays spread over an uninterrupted run's duration
/// and beyond: each run stops (130, nothing left) or, signalled when its output was already in
/// place or about to be, completes (0, the whole output); at least one must stop.
void sweep(const Command& c) {
    const double duration = reference(c).seconds;
    ASSERT_GT(duration, 0.0);
    const int signals[] = {SIGINT, SIGTERM, SIGHUP};
    int stopped = 0, completed = 0;
    const std::vector<double> fractions{0.1, 0.25, 0.4, 0.55, 0.7, 0.85, 1.0, 1.3};
    for (std::size_t i = 0; i < fractions.size(); ++i) {
        const int signal = signals[i % 3];
        const double delay = fractions[i] * duration;
        const std::string what =
            describe(c, signal,
                     "after " + std::to_string(delay) + " s (" + std::to_string(fractions[i]) +
                         " of an uninterrupted run)");
        const Interrupted r =
            run_interrupted(c, scratch("sweep-" + std::to_string(i)), signal, std::nullopt, delay);
        if (r.committed) { // the output was in place: the run ends as if not signalled
            SCOPED_TRACE(what);
            EXPECT_TRUE(r.end.exited && r.end.status == 0) << r.end.err;
            EXPECT_EQ(r.after, reference(c).after);
            ++completed;
            continue;
        }
        if (expect_interrupted_or_complete(c, r, false, what))
            ++stopped;
        else
            ++completed;
    }
    std::printf("%s: uninterrupted %.2f s; the sweep's signals stopped %d runs, %d completed\n",
                c.name.c_str(), duration, stopped, completed);
    // The early delays land in the computation of a run that takes `duration`: if none
    // stopped, the signals were ignored.
    EXPECT_GT(stopped, 0) << "no signal of the sweep stopped the run (" << completed
                          << " completed)";
}

struct Case {
    std::string name;
    std::function<Command()> command;
    std::string what; // early, output, gnuplot (or child: Command::child), kill, sweep
};

void PrintTo(const Case& c, std::ostream* os) {
    *os << c.name << " " << c.what;
}

class Interrupt : public ::testing::TestWithParam<Case> {};

TEST_P(Interrupt, LeavesNothingOrTheWholeOutput) {
    const Case& p = GetParam();
    const Command c = p.command();
    if (p.what == "early")
        interrupt_at(c, Point::early);
    else if (p.what == "output")
        interrupt_at(c, Point::output);
    else if (p.what == "gnuplot" || p.what == "child")
        interrupt_at(c, Point::gnuplot);
    else if (p.what == "kill")
        kill_during_output(c);
    else
        sweep(c);
}

std::vector<Case> cases() {
    std::vector<Case> out;
    for (const auto& [name, command] :
         std::vector<std::pair<std::string, std::function<Command()>>>{{"Generate", generate},
                                                                       {"Lattice", lattice},
                                                                       {"Analyze", analyze},
                                                                       {"Export", export_stl}})
        for (const std::string what : {"early", "output", "kill", "sweep"})
            out.push_back({name, command, what});
    out.push_back({"Generate", generate, "gnuplot"});
    out.push_back({"GenerateLammps", generate_lammps, "child"}); // while lmp runs
    out.push_back({"Analyze", analyze, "gnuplot"});
    out.push_back({"LatticeCylinder", lattice_cylinder, "gnuplot"});
    return out;
}

// Two real packbed processes started together, writing the same output: one wins
// whole, the other exits 2 with one line and leaves nothing; the output holds the winner's
// files only. An existing empty --out directory (claimed while the files move in), a new one
// (put in place by one rename that replaces nothing), one replaced with --force (it must still
// be the directory seen at the start), and export's file with its .json beside it (claimed,
// and each file must be the one seen at the start). Five rounds each: the runs end within
// milliseconds of each other, so their commits meet in some rounds and follow each other in
// the others.
TEST(Concurrent, TwoRunsIntoOneOutputOneWinsWhole) {
    const fs::path root = scratch("both");
    const fs::path work = root / "work";
    // Each run's output alone, to compare with.
    const auto bed = [](int seed, const std::string& out, bool force) {
        std::vector<std::string> args{
            "generate",      "-a", "3",  "-n", "40", "-s", std::to_string(seed),
            "--no-analysis", "-q", "-o", out};
        if (force)
            args.push_back("--force");
        return args;
    };
    const auto stl = [](int seed, const std::string& out) {
        return std::vector<std::string>{"export",   "bed" + std::to_string(seed) + ".csv",
                                        "-R",       "2",
                                        "-f",       "stl",
                                        "--refine", "1",
                                        "-o",       out};
    };
    std::string reference[2];
    for (int seed : {1, 2}) {
        const fs::path one = scratch("one-" + std::to_string(seed));
        const Ended e = wait_end(spawn(bed(seed, "out", false), one), one, Clock::now());
        ASSERT_EQ(e.status, 0) << e.err;
        reference[seed - 1] = listing(one / "work" / "out");
        fs::copy_file(one / "work" / "out" / "particles.csv",
                      work / ("bed" + std::to_string(seed) + ".csv"));
    }
    std::string stl_reference[2];
    for (int seed : {1, 2}) {
        const fs::path one = scratch("stl-" + std::to_string(seed));
        fs::copy_file(work / ("bed" + std::to_string(seed) + ".csv"),
                      one / "work" / ("bed" + std::to_string(seed) + ".csv"));
        const Ended e = wait_end(spawn(stl(seed, "bed.stl"), one), one, Clock::now());
        ASSERT_EQ(e.status, 0) << e.err;
        stl_reference[seed - 1] = slurp(one / "work" / "bed.stl");
    }
    std::map<std::string, int> met, followed; // where the loser found the other's output
    for (const std::string kind : {"empty", "new", "force", "file"}) {
        for (int round = 0; round < 5; ++round) {
            const std::string out = kind + std::to_string(round);
            if (kind == "empty" || kind == "force")
                fs::create_directories(work / out);
            if (kind == "force")
                std::ofstream(work / out / "old.txt") << "old\n";
            const fs::path a = scratch("a"), b = scratch("b");
            fs::remove_all(a / "work");
            fs::remove_all(b / "work");
            fs::create_directory_symlink(work, a / "work");
            fs::create_directory_symlink(work, b / "work");
            const auto args = [&](int seed) {
                return kind == "file" ? stl(seed, out + ".stl") : bed(seed, out, kind == "force");
            };
            const Clock::time_point start = Clock::now();
            const pid_t first = spawn(args(1), a), second = spawn(args(2), b);
            const Ended e[2] = {wait_end(first, a, start), wait_end(second, b, start)};
            SCOPED_TRACE(kind + " round " + std::to_string(round) + ": " + e[0].err + " | " +
                         e[1].err);
            ASSERT_TRUE(e[0].exited && e[1].exited);
            ASSERT_EQ(std::min(e[0].status, e[1].status), 0);
            if (kind == "file" && e[0].status == 0 && e[1].status == 0) {
                // One after the other (the second read the files after the first had put its
                // own in place): the second replaced both, as cp would; never a mix.
                const std::string got = slurp(work / (out + ".stl"));
                ASSERT_TRUE(got == stl_reference[0] || got == stl_reference[1]);
                const int last = got == stl_reference[0] ? 1 : 2;
                EXPECT_NE(slurp(work / (out + ".stl.json"))
                              .find("\"particles\": \"bed" + std::to_string(last) + ".csv\""),
                          std::string::npos);
                continue;
            }
            ASSERT_EQ(std::max(e[0].status, e[1].status), 2);
            const int winner = e[0].status == 0 ? 0 : 1;
            const std::string& lost = e[1 - winner].err;
            EXPECT_EQ(std::count(lost.begin(), lost.end(), '\n'), 1);
            EXPECT_TRUE(lost.find("another") != std::string::npos ||
                        lost.find("exists and is not empty") != std::string::npos);
            ++(lost.find("another") != std::string::npos ? met : followed)[kind];
            if (kind == "file") {
                EXPECT_EQ(slurp(work / (out + ".stl")), stl_reference[winner]);
                EXPECT_NE(slurp(work / (out + ".stl.json"))
                              .find("\"particles\": \"bed" + std::to_string(winner + 1) + ".csv\""),
                          std::string::npos);
            } else {
                EXPECT_EQ(listing(work / out), reference[winner]);
            }
        }
    }
    for (const auto& entry : fs::directory_iterator(work))
        EXPECT_NE(entry.path().filename().string()[0], '.') << "left behind: " << entry.path();
    for (const std::string kind : {"empty", "new", "force", "file"})
        std::printf("%s: in %d rounds the loser found the winner's output when it put its own in "
                    "place, in %d when it started\n",
                    kind.c_str(), met[kind], followed[kind]);
}

INSTANTIATE_TEST_SUITE_P(Runs, Interrupt, ::testing::ValuesIn(cases()),
                         [](const ::testing::TestParamInfo<Case>& param) {
                             std::string what = param.param.what;
                             what[0] = static_cast<char>(std::toupper(what[0]));
                             return param.param.name + what;
                         });

} // namespace
