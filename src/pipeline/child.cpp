// The programs the pipeline starts (child.hpp).
#include "child.hpp"

#include <fcntl.h>
#include <signal.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

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

int run_program(const std::vector<std::string>& words, const std::filesystem::path& folder,
                const std::filesystem::path& output, const std::function<bool()>& keep_going) {
    if (words.empty())
        return 127;
    posix_spawn_file_actions_t actions;
    posix_spawn_file_actions_init(&actions);
    posix_spawn_file_actions_addopen(&actions, STDIN_FILENO, "/dev/null", O_RDONLY, 0);
    posix_spawn_file_actions_addopen(&actions, STDOUT_FILENO, output.c_str(),
                                     O_WRONLY | O_CREAT | O_TRUNC, 0600);
    posix_spawn_file_actions_adddup2(&actions, STDOUT_FILENO, STDERR_FILENO);
    posix_spawn_file_actions_addchdir_np(&actions, folder.c_str());
    posix_spawnattr_t attributes;
    posix_spawnattr_init(&attributes);
    sigset_t none, defaults;
    sigemptyset(&none);
    sigemptyset(&defaults);
    sigaddset(&defaults, SIGINT);
    sigaddset(&defaults, SIGTERM);
    sigaddset(&defaults, SIGHUP);
    posix_spawnattr_setsigmask(&attributes, &none);
    posix_spawnattr_setsigdefault(&attributes, &defaults);
    posix_spawnattr_setpgroup(&attributes, 0);
    posix_spawnattr_setflags(&attributes, POSIX_SPAWN_SETSIGMASK | POSIX_SPAWN_SETSIGDEF |
                                              POSIX_SPAWN_SETPGROUP);
    std::vector<std::string> copies = words;
    std::vector<char*> argv;
    for (std::string& w : copies)
        argv.push_back(w.data());
    argv.push_back(nullptr);
    pid_t pid = 0;
    const int spawned = posix_spawnp(&pid, argv[0], &actions, &attributes, argv.data(), environ);
    posix_spawn_file_actions_destroy(&actions);
    posix_spawnattr_destroy(&attributes);
    if (spawned != 0)
        return 127;
    watch_child(pid);
    int status = 0;
    bool stopped = false;
    pid_t waited = 0;
    if (keep_going) {
        while ((waited = waitpid(pid, &status, WNOHANG)) == 0) {
            if (!stopped && !keep_going()) {
                kill(-pid, SIGTERM);
                stopped = true;
            }
            std::this_thread::sleep_for(std::chrono::milliseconds(100));
        }
    } else {
        waited = waitpid(pid, &status, 0);
    }
    watch_child(0);
    if (waited != pid || stopped || !WIFEXITED(status))
        return -1;
    return WEXITSTATUS(status);
}

} // namespace packbed
