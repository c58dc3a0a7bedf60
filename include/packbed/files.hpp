// Paths and input files from users, in one place: every path is checked before use, every
// file is opened without blocking and refused unless it is a regular file, and every line and
// small file is read within a bound. Paths and text from users are data: they are never
// handed to a shell or a script, and messages show them with control characters escaped.
#pragma once

#include <filesystem>
#include <fstream>
#include <istream>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "packbed/text.hpp"

namespace packbed {

/// \return `text` with every control character (bytes below 0x20 and 0x7f) written as an
/// escape (`\n`, `\t`, `\x1b`): what messages show of a path or a value from a user, so that
/// a message stays one line and shows what was given. Applied twice, it changes nothing more.
std::string printable(std::string_view text);

/// \return `text` as one word of a POSIX shell, for a command a message shows to be pasted: as
/// it is when it holds only letters, digits and `_./-+=:,@%`, else in single quotes (each quote
/// inside as '\''), control characters as printable writes them.
std::string shell_word(std::string_view text);
/// \return `words` as one line of a POSIX shell, each a shell_word, joined by spaces.
std::string shell_line(std::span<const std::string> words);

/// \return why `path` is not allowed as a path (empty, a control character such as a newline
/// or a tab, longer than 4095 bytes), or "" when it is allowed.
std::string path_problem(const std::filesystem::path& path);

/// Check a path given by a user (see path_problem).
/// \param input names the input in the message: an option ("--out") or an argument
/// \throws InvalidInput "INPUT 'PATH' is not allowed; allowed: ..." when it is not allowed
void check_path(std::string_view input, const std::filesystem::path& path);

/// Open a file for reading, refusing without blocking what is not a regular file (a missing
/// file, a directory, a FIFO, a device, a socket). The path is opened once: what is checked is
/// what is read.
/// \param input names the input in messages (an option such as "--bed"; "" for none: the
/// messages then start with the path)
/// \throws InvalidInput naming the input, the path and what is allowed
std::ifstream open_regular_file(std::string_view input, const std::filesystem::path& path);

/// \return the whole of a small regular file (opened as open_regular_file does).
/// \throws InvalidInput when it is not a regular file or holds more than `limit` bytes
std::string read_small_file(std::string_view input, const std::filesystem::path& path,
                            std::size_t limit);

/// What read_line found.
enum class LineRead {
    line,     ///< a line (without its newline) is in `line`
    end,      ///< the end of the input: no more lines
    too_long, ///< the line is longer than the limit; `line` holds its first `limit` bytes
    error,    ///< reading failed (an I/O error, as /proc/self/mem gives); the stream is bad
};

/// Read one line of at most `limit` bytes (without the '\n'), so that an input without
/// newlines (/dev/zero, a binary file) cannot grow one line until memory runs out.
LineRead read_line(std::istream& input, std::string& line, std::size_t limit);

} // namespace packbed
