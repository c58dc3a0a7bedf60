// Outputs that appear whole or not at all, and never in place of an input. Everything a run
// writes goes first into a hidden staging folder that only this process can enter (created
// exclusively under an unpredictable name, so no link planted by someone else is followed), and
// is put in place at the end by renames that refuse to replace what another run put there. An
// error, an exception or cancel_outputs() removes the staging folder; a process killed outright
// leaves it, and a later run that writes beside it on the same host removes it.
#pragma once

#include <cstdint>
#include <filesystem>
#include <initializer_list>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace packbed {

/// What an OutputDirectory owns.
enum class OutputKind {
    /// A whole directory: created, or an existing empty one filled, or (with `replace`) an
    /// existing one replaced whole in one rename; a non-empty one is refused otherwise.
    directory,
    /// Named files in a folder (created if missing): each replaces the file of its name (as cp
    /// does); other files in the folder stay.
    files,
};

/// A set of files written all or nothing (see the top of this header). Every check that can
/// refuse the output runs in the constructor, before the caller's work; commit() renames
/// everything into place. Destroyed without commit() (an error, an interruption), it removes
/// what it staged and leaves the target as it was. Not thread-safe; cancel_outputs() may be
/// called from another thread.
class OutputDirectory {
public:
    /// \param path the directory (OutputKind::directory) or the folder of the files
    /// \param input the option that named it, for messages ("--out")
    /// \param kind what the output owns
    /// \param replace OutputKind::directory: replace an existing non-empty directory (--force)
    /// \throws InvalidInput naming `input` when the path is not allowed (check_path), is a
    /// file, is a non-empty directory without `replace`, is the working directory or holds it
    /// (with `replace`), cannot be written, has a name too long for its file system, or is,
    /// holds or lies in an input or another output of the job (JobScope)
    explicit OutputDirectory(std::filesystem::path path, std::string input = "--out",
                             OutputKind kind = OutputKind::directory, bool replace = false);
    ~OutputDirectory();
    OutputDirectory(const OutputDirectory&) = delete;
    OutputDirectory& operator=(const OutputDirectory&) = delete;

    /// Write `contents` to the staged file `name` (a file name, or a relative path whose
    /// folders are created: "system/controlDict").
    /// \throws InvalidInput when `name` would replace an input of the job (JobScope), a
    /// directory, or is too long for the file system
    /// \throws std::runtime_error naming the file when writing fails
    /// \throws Cancelled after cancel_outputs()
    void stage(const std::string& name, const std::string& contents);

    /// Reserve the staged path of `name` for a file the caller or another program writes
    /// (a plot, a large surface); it is committed like staged files, and must exist by then.
    /// \return the path to write to (inside the staging folder). \throws as stage()
    std::filesystem::path reserve(const std::string& name);

    /// Forget a staged or reserved file and remove it (e.g. a plot that failed).
    void discard(const std::string& name);

    /// Put every staged file in place (see OutputKind), after checking that all of them exist.
    /// Two runs never mix their files: a new directory is put in place by one rename that
    /// refuses to replace anything; an existing empty one, or a folder of files, is claimed
    /// (a link `.packbed-claim` made in it) while the files move in; a directory replaced with
    /// --force, or a file, must still be the one seen at the start. A run that finds another
    /// run's output there fails and leaves it as it is. Folders it created are removed again
    /// when it fails.
    /// \throws InvalidInput when another run wrote the output meanwhile
    /// \throws std::runtime_error naming the file when one is missing or a rename fails
    /// \throws Cancelled after cancel_outputs()
    void commit();

    /// \return the output directory or folder, as given.
    const std::filesystem::path& path() const { return m_path; }
    /// \return the output directory or folder, absolute and normalised.
    const std::filesystem::path& target() const { return m_target; }
    /// \return the option that named it ("--out").
    const std::string& input() const { return m_input; }
    /// \return true when it owns a whole directory (OutputKind::directory).
    bool whole() const { return m_kind == OutputKind::directory; }
    /// \return true when it replaces an existing non-empty directory (--force).
    bool replaces() const { return m_replace; }
    /// \return the names staged or reserved so far.
    const std::vector<std::string>& names() const { return m_names; }
    /// \return `name` as the user would write it (the output's path / name).
    std::filesystem::path given_path(const std::string& name) const;

private:
    std::filesystem::path final_path(const std::string& name) const; // absolute
    void commit_files();
    void commit_directory();

    std::filesystem::path m_path;    // as given
    std::filesystem::path m_target;  // absolute, normalised
    std::filesystem::path m_staging; // the hidden folder everything is written to first
    std::string m_input;
    OutputKind m_kind;
    bool m_target_exists = false;     // kind directory: the target existed at construction
    bool m_replace = false;           // kind directory: replace a non-empty target
    bool m_in_target = false;         // the staging folder lies inside the target (no other room)
    std::vector<std::string> m_names; // staged and reserved names, in order
    /// What stood at the target (OutputKind::directory replaced) or at each reserved file
    /// (OutputKind::files) when it was claimed: device and inode, or {0, 0} for nothing; a
    /// commit refuses when it changed meanwhile (another run wrote it).
    std::vector<std::pair<std::uint64_t, std::uint64_t>> m_seen;
};

/// Replace `path` with `parts` written one after another, whole or not at all: a temporary
/// file created exclusively beside it, then renamed over it. For files written during a run
/// (checkpoints); removed by cancel_outputs() until renamed.
/// \throws InvalidInput naming `input` when the file cannot be written
void replace_file(const std::filesystem::path& path, std::string_view input,
                  std::initializer_list<std::string_view> parts);

/// Check, before a run, that replace_file(path, ...) can write: the path is allowed, is not a
/// directory or another non-regular file, and its folder takes a new file (probed with a
/// temporary file created and removed; an existing file of that name is not touched). The file
/// becomes an output of the job (JobScope): it must not be an input read under another option,
/// nor lie in an output directory.
/// \throws InvalidInput naming `input` otherwise
void check_writable_file(std::string_view input, const std::filesystem::path& path);

/// \return true when `a` and `b` name the same existing file (hard links and symbolic links
/// included); false when either does not exist.
bool same_file(const std::filesystem::path& a, const std::filesystem::path& b);

/// The files one job reads and writes (docs/reliability.md, "What is an input"). A job is one
/// run of the command line or one call of the Python module; a JobScope on its thread records,
/// while it lives,
/// - its inputs: every file opened by open_regular_file or read_small_file, and every folder
///   read as a whole (record_input: an OpenFOAM case, a LAMMPS job);
/// - its outputs: every OutputDirectory (a directory, or files in a folder) and every file
///   written during the run (check_writable_file: a checkpoint).
/// Whichever of a pair comes second is refused with InvalidInput, before anything is written,
/// when an output is an input, when an output directory is or holds an input, or when two
/// outputs overlap. A file read and written under the same option (a checkpoint resumed) is
/// one file. Scopes on one thread nest: an inner one adds to the outer. Without a scope nothing
/// is recorded.
class JobScope {
public:
    JobScope();
    ~JobScope();
    JobScope(const JobScope&) = delete;
    JobScope& operator=(const JobScope&) = delete;

private:
    bool m_outer = false; // this scope began the job (no scope was open on the thread)
};

/// Record that the current job (JobScope) reads `path`: a file, or a folder read as a whole.
/// \param input names it in messages (an option, "CASE"; "" for the particles file)
/// \throws InvalidInput when an output of the job is it, holds it or would replace it
void record_input(std::string_view input, const std::filesystem::path& path);

/// `message` with every staging folder of this process shown as the output the user named
/// (a writer's error names the file it wrote, which lies in a hidden staging folder).
std::string as_given(std::string message);

/// Stop every output of this process that is not yet in place, for the thread that handles
/// SIGINT/SIGTERM: waits for a commit or rename in progress to end, removes every staging
/// folder and temporary file, and makes later stage(), reserve() and commit() throw
/// Cancelled. Thread-safe.
/// \return true when an OutputDirectory had been committed before: the run's results are
/// complete and in place (the caller may let it end normally).
bool cancel_outputs();

} // namespace packbed
