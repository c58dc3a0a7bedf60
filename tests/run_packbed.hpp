// The packbed binary run from tests as a user runs it: no shell (the arguments reach it byte
// for byte), stdin from /dev/null, CI unset, the signals it handles at their defaults whatever
// the test runner set, in a process group of its own (as a shell's job).
#pragma once

#include <fcntl.h>
#include <signal.h>
#include <sys/resource.h>
#include <sys/types.h>
#include <unistd.h>

#include <algorithm>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <system_error>
#include <utility>
#include <vector>

#include <gtest/gtest.h>

extern char** environ;

namespace packbed::test {

/// The binary under test: PACKBED_TEST_EXE from the environment (e.g. an older build, to see
/// the cases fail), else the one built with the tests.
inline std::string exe() {
    const char* e = std::getenv("PACKBED_TEST_EXE");
    return e != nullptr && *e != '\0' ? e : PACKBED_EXE;
}

/// \return the bytes of a file ("" when it cannot be read).
inline std::string slurp(const std::filesystem::path& path) {
    std::ifstream in(path, std::ios::binary);
    std::ostringstream s;
    s << in.rdbuf();
    return s.str();
}

/// A resource limit for a spawned run (setrlimit): RLIMIT_AS for a machine with little memory,
/// RLIMIT_FSIZE for a full disk (SIGXFSZ left at its default, as a shell's ulimit -f leaves it:
/// packbed ignores it, so a write past the limit fails with EFBIG as on a full disk).
struct Limit {
    int resource = -1; ///< -1: none
    rlim_t bytes = 0;
};

/// Start `packbed ARGS` in `cwd`, its stdout and stderr into the files `io/out` and `io/err`.
/// \return its pid (also its process group), or -1 when fork fails.
inline pid_t spawn(const std::vector<std::string>& args, const std::filesystem::path& cwd,
                   const std::filesystem::path& io, Limit limit = {}) {
    std::vector<std::string> words{exe()};
    words.insert(words.end(), args.begin(), args.end());
    std::vector<char*> argv;
    for (std::string& w : words)
        argv.push_back(w.data());
    argv.push_back(nullptr);
    std::vector<char*> envp;
    for (char** e = environ; *e != nullptr; ++e)
        if (std::strncmp(*e, "CI=", 3) != 0)
            envp.push_back(*e);
    envp.push_back(nullptr);
    const std::string out = (io / "out").string(), err = (io / "err").string();
    const std::string dir = cwd.string();
    const pid_t pid = ::fork();
    if (pid == 0) { // only async-signal-safe calls until exec
        ::setpgid(0, 0);
        sigset_t none;
        sigemptyset(&none);
        ::sigprocmask(SIG_SETMASK, &none, nullptr);
        for (const int s : {SIGINT, SIGTERM, SIGHUP, SIGPIPE, SIGXFSZ})
            ::signal(s, SIG_DFL);
        if (limit.resource >= 0) {
            const rlimit value{limit.bytes, limit.bytes};
            if (::setrlimit(limit.resource, &value) != 0)
                ::_exit(127);
        }
        const int in = ::open("/dev/null", O_RDONLY);
        const int o = ::open(out.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
        const int e = ::open(err.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
        if (in < 0 || o < 0 || e < 0 || ::chdir(dir.c_str()) != 0)
            ::_exit(127);
        ::dup2(in, STDIN_FILENO);
        ::dup2(o, STDOUT_FILENO);
        ::dup2(e, STDERR_FILENO);
        ::execve(argv[0], argv.data(), envp.data());
        ::_exit(127);
    }
    if (pid > 0)
        ::setpgid(pid, pid); // also here, so that it is done before any signal is sent
    return pid;
}

/// Every entry under `root`, hidden ones included, links not followed, sorted, one line each:
/// its path and type; a regular file described by `describe_file(path, size)`, a link by its
/// target. What tests compare before and after a run to see what it left behind.
template <class DescribeFile>
std::string listing(const std::filesystem::path& root, DescribeFile describe_file) {
    namespace fs = std::filesystem;
    std::vector<std::string> lines;
    std::error_code ec;
    for (fs::recursive_directory_iterator it(root, fs::directory_options::none, ec), end;
         !ec && it != end; it.increment(ec)) {
        const fs::path& p = it->path();
        std::string line = p.lexically_relative(root).string() + " ";
        switch (fs::symlink_status(p, ec).type()) {
        case fs::file_type::regular:
            line += describe_file(p, fs::file_size(p, ec));
            break;
        case fs::file_type::directory:
            line += "dir";
            break;
        case fs::file_type::symlink:
            line += "link -> " + fs::read_symlink(p, ec).string();
            break;
        case fs::file_type::fifo:
            line += "fifo";
            break;
        case fs::file_type::character:
            line += "char";
            break;
        case fs::file_type::block:
            line += "block";
            break;
        case fs::file_type::socket:
            line += "socket";
            break;
        default:
            line += "other";
        }
        lines.push_back(line);
    }
    if (ec)
        lines.push_back("(listing failed: " + ec.message() + ")");
    std::sort(lines.begin(), lines.end());
    std::string all;
    for (const auto& l : lines)
        all += l + "\n";
    return all;
}

/// The running test's scratch folder, private to this process (the same test may run in
/// several processes at once: two people running the suite): `packbed-test-PROGRAM-PID/TEST`
/// in the temporary directory. The program's folder goes when every test it ran passed
/// (RemoveWhenPassed); what failed stays for a look.
inline std::filesystem::path test_folder(const std::string& program) {
    const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
    std::string test = std::string(info->test_suite_name()) + "." + info->name();
    std::replace(test.begin(), test.end(), '/', '_');
    return std::filesystem::temp_directory_path() /
           ("packbed-test-" + program + "-" + std::to_string(::getpid())) / test;
}

/// Removes this process's `packbed-test-PROGRAM-PID` folder at the end of the test program
/// when every test passed. Register once per program: `::testing::AddGlobalTestEnvironment(new
/// RemoveWhenPassed("PROGRAM"))`.
class RemoveWhenPassed : public ::testing::Environment {
public:
    explicit RemoveWhenPassed(std::string program)
        : m_program(std::move(program)) {}
    void TearDown() override {
        if (!::testing::UnitTest::GetInstance()->Passed())
            return;
        std::error_code ec;
        std::filesystem::remove_all(
            std::filesystem::temp_directory_path() /
                ("packbed-test-" + m_program + "-" + std::to_string(::getpid())),
            ec);
    }

private:
    std::string m_program;
};

} // namespace packbed::test
