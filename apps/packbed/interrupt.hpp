// Ctrl-C, SIGTERM and SIGHUP, handled in one place for every subcommand: an interrupted
// command leaves nothing behind and exits 130, whenever the signal comes before its outputs
// are in place.
#pragma once

#include <sys/types.h>

#include <string>

namespace packbed::cli {

/// Block SIGINT, SIGTERM and SIGHUP in the calling thread, and so in every thread it starts
/// later (OpenMP's): one that arrives now waits, pending, for handle_interrupts. Call first
/// thing in main.
void block_interrupts();

/// block_interrupts, and start the thread that waits for the signals. When one arrives (or
/// was pending), that thread stops the child program being waited on (set_child_watcher),
/// removes every output not yet in place (cancel_outputs), erases the progress line, prints
/// "packbed COMMAND: interrupted; nothing was written" and ends the process with status 130.
/// If the outputs were already in place, it does nothing and the run ends normally. Call once,
/// after set_command_name and before the command runs, so that a signal sent while the
/// command line is parsed (a slow start under a sanitizer) still names the command.
void handle_interrupts();

/// Name the subcommand for the message.
void set_command_name(const std::string& name);

/// Name the run's checkpoint (generate --checkpoint), kept by an interrupted run: where it is
/// on the disk, the message says so instead of "nothing was written".
void set_interrupt_checkpoint(const std::string& path);

/// "packbed COMMAND: interrupted; nothing was written", or "... nothing was written but the
/// checkpoint FILE (...)" where a checkpoint named by set_interrupt_checkpoint is on the disk.
std::string interrupted_message();

/// Tell the interrupt handler whether a progress line is on the terminal.
void progress_line_drawn(bool drawn);

/// For the main thread before it reports an error: while an interrupt is being handled (the
/// error may be its doing, e.g. Cancelled from an output it removed), wait for the handler
/// thread to end the process with status 130; otherwise return at once.
void await_interrupt();

} // namespace packbed::cli
