#include "interrupt.hpp"

#include <pthread.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <atomic>
#include <cstdio>
#include <mutex>
#include <thread>

#include <fmt/format.h>

#include "packbed/files.hpp"
#include "packbed/output.hpp"
#include "packbed/pipeline.hpp"

namespace packbed::cli {

namespace {

std::atomic<pid_t> g_child{0};
std::atomic<bool> g_progress_drawn{false};
std::mutex g_name_mutex;
std::string g_name;       // the subcommand, once chosen
std::string g_checkpoint; // generate --checkpoint, kept by an interrupted run
// Held by the handler thread from the signal to _exit: whoever else takes it waits for ever.
std::mutex g_exit_mutex;

sigset_t handled_signals() {
    sigset_t set;
    sigemptyset(&set);
    sigaddset(&set, SIGINT);
    sigaddset(&set, SIGTERM);
    sigaddset(&set, SIGHUP);
    return set;
}

/// The handler thread: a plain thread woken by sigwait, so what it does need not be
/// async-signal-safe.
void wait_for_signals(sigset_t set) {
    for (;;) {
        int signal = 0;
        if (sigwait(&set, &signal) != 0)
            continue;
        std::lock_guard exit_lock(g_exit_mutex);
        // The outputs first: from here on no commit can happen, whatever the main thread does
        // once the child below is gone (a child still writing into the removed staging folder
        // can create nothing there).
        if (cancel_outputs())
            continue; // the results were already in place: the run ends as it would have
        if (const pid_t child = g_child.load(); child > 0) {
            ::kill(-child, SIGKILL);
            siginfo_t info{};
            ::waitid(P_PID, static_cast<id_t>(child), &info, WEXITED | WNOWAIT);
        }
        const std::string message =
            (g_progress_drawn ? "\r\033[K" : "") + interrupted_message() + "\n";
        (void)!::write(STDERR_FILENO, message.data(), message.size());
        ::_exit(130);
    }
}

} // namespace

void block_interrupts() {
    const sigset_t set = handled_signals();
    pthread_sigmask(SIG_BLOCK, &set, nullptr);
}

void handle_interrupts() {
    // A file size limit (ulimit -f) would kill the run by SIGXFSZ mid-write, leaving its
    // staging folder: ignored, a write past it fails with EFBIG, reported as a full disk is.
    ::signal(SIGXFSZ, SIG_IGN);
    block_interrupts();
    const sigset_t set = handled_signals();
    // The pipeline's child programs (gnuplot), to stop first.
    set_child_watcher([](pid_t pid) { g_child = pid; });
    std::thread(wait_for_signals, set).detach();
}

void set_command_name(const std::string& name) {
    std::lock_guard lock(g_name_mutex);
    g_name = name;
}

void set_interrupt_checkpoint(const std::string& path) {
    std::lock_guard lock(g_name_mutex);
    g_checkpoint = path;
}

std::string interrupted_message() {
    std::lock_guard lock(g_name_mutex);
    const std::string command = g_name.empty() ? "packbed" : "packbed " + g_name;
    if (!g_checkpoint.empty() && ::access(g_checkpoint.c_str(), F_OK) == 0)
        return fmt::format("{}: interrupted; nothing was written but the checkpoint {} (the "
                           "same command resumes from it)",
                           command, printable(g_checkpoint));
    return command + ": interrupted; nothing was written";
}

void progress_line_drawn(bool drawn) {
    g_progress_drawn = drawn;
}

void await_interrupt() {
    std::lock_guard lock(g_exit_mutex); // held by the handler thread until it ends the process
}

} // namespace packbed::cli
