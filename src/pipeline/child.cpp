// The programs the pipeline starts (child.hpp).
#include "child.hpp"

#include <fcntl.h>
#include <signal.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <mutex>
#include <thread>

#include "packbed/pipeline.hpp"

namespace packbed {

namespace {

/// set_child_watcher's hook, and the lock that guards it.
std::mutex watcher_lock;
std::function<void(pid_t)> child_watcher;

void watch_child(pid_t pid) {
    std::function<void(pid_t)> watcher;
    {
        const std::lock_guard lock(watcher_lock);
        watcher = child_watcher;
    }
    if (watcher)
        watcher(pid);
}

} // namespace

void set_child_watcher(std::function<void(pid_t)> watcher) {
    const std::lock_guard lock(watcher_lock);
    child_watcher = std::move(watcher);
}

int run_programs(const std::vector<std::vector<std::string>>& commands,
                 const std::filesystem::path& folder, const std::filesystem::path& output,
                 const std::function<bool()>& keep_going) {
    if (commands.empty() ||
        std::any_of(commands.begin(), commands.end(), [](const auto& w) { return w.empty(); }))
        return 127;
    sigset_t none, defaults;
    sigemptyset(&none);
    sigemptyset(&defaults);
    sigaddset(&defaults, SIGINT);
    sigaddset(&defaults, SIGTERM);
    sigaddset(&defaults, SIGHUP);
    // The first program leads a new process group; the others join it, so that one kill of
    // the group (the interrupt handler's, keep_going's) stops them all.
    std::vector<pid_t> pids;
    pid_t group = 0;
    for (std::size_t k = 0; k < commands.size(); ++k) {
        posix_spawn_file_actions_t actions;
        posix_spawn_file_actions_init(&actions);
        posix_spawn_file_actions_addopen(&actions, STDIN_FILENO, "/dev/null", O_RDONLY, 0);
        posix_spawn_file_actions_addopen(&actions, STDOUT_FILENO, output.c_str(),
                                         O_WRONLY | O_CREAT | (k == 0 ? O_TRUNC : O_APPEND), 0600);
        posix_spawn_file_actions_adddup2(&actions, STDOUT_FILENO, STDERR_FILENO);
        posix_spawn_file_actions_addchdir_np(&actions, folder.c_str());
        posix_spawnattr_t attributes;
        posix_spawnattr_init(&attributes);
        posix_spawnattr_setsigmask(&attributes, &none);
        posix_spawnattr_setsigdefault(&attributes, &defaults);
        posix_spawnattr_setpgroup(&attributes, group);
        posix_spawnattr_setflags(&attributes, POSIX_SPAWN_SETSIGMASK | POSIX_SPAWN_SETSIGDEF |
                                                  POSIX_SPAWN_SETPGROUP);
        std::vector<std::string> copies = commands[k];
        std::vector<char*> argv;
        for (std::string& w : copies)
            argv.push_back(w.data());
        argv.push_back(nullptr);
        pid_t pid = 0;
        const int spawned =
            posix_spawnp(&pid, argv[0], &actions, &attributes, argv.data(), environ);
        posix_spawn_file_actions_destroy(&actions);
        posix_spawnattr_destroy(&attributes);
        if (spawned != 0) {
            // Those already started are stopped and waited for: no program outlives the call.
            if (group > 0)
                kill(-group, SIGTERM);
            for (const pid_t started : pids) {
                int ignored = 0;
                waitpid(started, &ignored, 0);
            }
            watch_child(0);
            return 127;
        }
        if (k == 0) {
            group = pid;
            watch_child(pid);
        }
        pids.push_back(pid);
    }
    std::vector<int> statuses(pids.size(), 0);
    std::vector<bool> done(pids.size(), false);
    bool stopped = false, lost = false;
    if (keep_going) {
        for (std::size_t running = pids.size(); running > 0;) {
            for (std::size_t k = 0; k < pids.size(); ++k) {
                if (done[k])
                    continue;
                const pid_t waited = waitpid(pids[k], &statuses[k], WNOHANG);
                if (waited == 0)
                    continue;
                lost = lost || waited != pids[k];
                done[k] = true;
                --running;
            }
            if (running == 0)
                break;
            if (!stopped && !keep_going()) {
                kill(-group, SIGTERM);
                stopped = true;
            }
            std::this_thread::sleep_for(std::chrono::milliseconds(100));
        }
    } else {
        for (std::size_t k = 0; k < pids.size(); ++k)
            lost = lost || waitpid(pids[k], &statuses[k], 0) != pids[k];
    }
    watch_child(0);
    if (stopped || lost)
        return -1;
    for (const int status : statuses) {
        if (!WIFEXITED(status))
            return -1;
        if (WEXITSTATUS(status) != 0)
            return WEXITSTATUS(status);
    }
    return 0;
}

int run_program(const std::vector<std::string>& words, const std::filesystem::path& folder,
                const std::filesystem::path& output, const std::function<bool()>& keep_going) {
    return run_programs({words}, folder, output, keep_going);
}

} // namespace packbed
