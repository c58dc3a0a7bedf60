// Outputs that appear whole or not at all. Everything a run writes goes first into a hidden
// staging folder that only this process can enter (created exclusively under an unpredictable
// name, so no link planted by someone else is followed), and is renamed into place at the end.
// An error, an exception or cancel_outputs() removes the staging folder; a process killed
// outright leaves it, and the next run that writes beside it removes it.
#pragma once

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
    /// (with `replace`), or cannot be written
    explicit OutputDirectory(std::filesystem::path path, std::string input = "--out",
                             OutputKind kind = OutputKind::directory, bool replace = false);
    ~OutputDirectory();
    OutputDirectory(const OutputDirectory&) = delete;
    OutputDirectory& operator=(const OutputDirectory&) = delete;

    /// Write `contents` to the staged file `name` (a file name, or a relative path whose
    /// folders are created: "system/controlDict").
    /// \throws InvalidInput when `name` would replace an input kept with keep() or a directory
    /// \throws std::runtime_error naming the file when writing fails
    /// \throws Cancelled after cancel_outputs()
    void stage(const std::string& name, const std::string& contents);

    /// Reserve the staged path of `name` for a file the caller or another program writes
    /// (a plot, a large surface); it is committed like staged files, and must exist by then.
    /// \return the path to write to (inside the staging folder). \throws as stage()
    std::filesystem::path reserve(const std::string& name);

    /// Forget a staged or reserved file and remove it (e.g. a plot that failed).
    void discard(const std::string& name);

    /// Refuse to write over an input of the run: throws InvalidInput naming `input` when
    /// `path` lies in a directory this output replaces or is one of its files, now or when
    /// reserved later.
    void keep(std::string_view input, const std::filesystem::path& path);

    /// Put every staged file in place (see OutputKind), after checking that all of them exist.
    /// \throws std::runtime_error naming the file when one is missing or a rename fails
    /// \throws Cancelled after cancel_outputs()
    void commit();

    /// \return the output directory or folder, as given.
    const std::filesystem::path& path() const { return m_path; }

private:
    std::filesystem::path final_path(const std::string& name) const; // absolute
    std::filesystem::path given_path(const std::string& name) const; // as the user gave it

    std::filesystem::path m_path;    // as given
    std::filesystem::path m_target;  // absolute, normalised
    std::filesystem::path m_staging; // the hidden folder everything is written to first
    std::string m_input;
    OutputKind m_kind;
    bool m_target_exists = false;     // kind directory: the target existed at construction
    bool m_replace = false;           // kind directory: replace a non-empty target
    bool m_in_target = false;         // the staging folder lies inside the target (no other room)
    std::vector<std::string> m_names; // staged and reserved names, in order
    std::vector<std::pair<std::string, std::filesystem::path>> m_kept; // inputs not to replace
};

/// Replace `path` with `parts` written one after another, whole or not at all: a temporary
/// file created exclusively beside it, then renamed over it. For files written during a run
/// (checkpoints); removed by cancel_outputs() until renamed.
/// \throws InvalidInput naming `input` when the file cannot be written
void replace_file(const std::filesystem::path& path, std::string_view input,
                  std::initializer_list<std::string_view> parts);

/// Check, before a run, that replace_file(path, ...) can write: the path is allowed, is not a
/// directory or another non-regular file, and its folder takes a new file (probed with a
/// temporary file created and removed; an existing file of that name is not touched).
/// \throws InvalidInput naming `input` otherwise
void check_writable_file(std::string_view input, const std::filesystem::path& path);

/// \return true when `a` and `b` name the same existing file (hard links and symbolic links
/// included); false when either does not exist.
bool same_file(const std::filesystem::path& a, const std::filesystem::path& b);

/// Stop every output of this process that is not yet in place, for the thread that handles
/// SIGINT/SIGTERM: waits for a commit or rename in progress to end, removes every staging
/// folder and temporary file, and makes later stage(), reserve() and commit() throw
/// Cancelled. Thread-safe.
/// \return true when an OutputDirectory had been committed before: the run's results are
/// complete and in place (the caller may let it end normally).
bool cancel_outputs();

} // namespace packbed
