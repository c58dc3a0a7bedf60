#include "packbed/files.hpp"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <cstring>
#include <iterator>

#include <fmt/format.h>

#include "packbed/error.hpp"
#include "packbed/output.hpp"

namespace packbed {

namespace {

/// The longest path accepted (PATH_MAX on Linux, with its terminating zero).
constexpr std::size_t max_path = 4095;

std::string kind_of(mode_t mode) {
    if (S_ISDIR(mode))
        return "a directory";
    if (S_ISFIFO(mode))
        return "a FIFO (named pipe)";
    if (S_ISCHR(mode) || S_ISBLK(mode))
        return "a device";
    if (S_ISSOCK(mode))
        return "a socket";
    return "not a regular file";
}

} // namespace

std::string printable(std::string_view text) {
    std::string out;
    out.reserve(text.size());
    for (const char c : text) {
        const auto u = static_cast<unsigned char>(c);
        if (c == '\n')
            out += "\\n";
        else if (c == '\t')
            out += "\\t";
        else if (c == '\r')
            out += "\\r";
        else if (u < 0x20 || u == 0x7f)
            out += fmt::format("\\x{:02x}", u);
        else
            out += c;
    }
    return out;
}

std::string shell_word(std::string_view text) {
    const bool plain = !text.empty() && std::all_of(text.begin(), text.end(), [](char c) {
        return std::isalnum(static_cast<unsigned char>(c)) ||
               std::string_view("_./-+=:,@%").find(c) != std::string_view::npos;
    });
    if (plain)
        return std::string(text);
    std::string out = "'";
    for (const char c : printable(text))
        out += c == '\'' ? std::string("'\\''") : std::string(1, c);
    return out + "'";
}

std::string shell_line(std::span<const std::string> words) {
    std::string line;
    for (const std::string& w : words)
        line += (line.empty() ? "" : " ") + shell_word(w);
    return line;
}

namespace {

/// "INPUT PATH" for messages, or "PATH" when there is no input name.
std::string named(std::string_view input, const std::filesystem::path& path) {
    return input.empty() ? printable(path.native())
                         : fmt::format("{} {}", input, printable(path.native()));
}

} // namespace

std::string path_problem(const std::filesystem::path& path) {
    const std::string& text = path.native();
    if (text.empty())
        return "an empty path";
    if (text.size() > max_path)
        return fmt::format("a path of {} bytes", text.size());
    for (const char c : text) {
        const auto u = static_cast<unsigned char>(c);
        if (u < 0x20 || u == 0x7f)
            return "a control character in the path";
    }
    return {};
}

void check_path(std::string_view input, const std::filesystem::path& path) {
    if (const std::string problem = path_problem(path); !problem.empty())
        throw InvalidInput(fmt::format("{} '{}' is not allowed ({}); allowed: a path of at most "
                                       "{} bytes without control characters (newline, tab, ...)",
                                       input, printable(path.native().substr(0, 200)), problem,
                                       max_path));
}

std::ifstream open_regular_file(std::string_view input, const std::filesystem::path& path) {
    check_path(input.empty() ? "file" : input, path);
    const std::string shown = named(input, path);
    // O_NONBLOCK: opening a FIFO without a writer returns at once instead of waiting.
    const int fd = ::open(path.c_str(), O_RDONLY | O_NONBLOCK | O_CLOEXEC | O_NOCTTY);
    if (fd < 0) {
        const int error = errno;
        throw UnopenableFile(fmt::format("{}: cannot open the file ({}); allowed: a readable "
                                         "regular file",
                                         shown, std::strerror(error)),
                             error, path.string());
    }
    struct stat info {};
    const bool stat_ok = ::fstat(fd, &info) == 0;
    if (!stat_ok || !S_ISREG(info.st_mode)) {
        ::close(fd);
        throw InvalidInput(fmt::format("{}: {}; allowed: a readable regular file", shown,
                                       stat_ok ? kind_of(info.st_mode) : "cannot stat"));
    }
    // Read through the descriptor just checked, so the file cannot be swapped in between.
    std::ifstream file(fmt::format("/proc/self/fd/{}", fd), std::ios::binary);
    if (!file)
        file.open(path, std::ios::binary); // no /proc: the path, checked a moment ago
    ::close(fd);
    if (!file)
        throw InvalidInput(
            fmt::format("{}: cannot open the file; allowed: a readable regular file", shown));
    record_input(input, path); // an input of the job: no output may replace it
    return file;
}

std::string read_small_file(std::string_view input, const std::filesystem::path& path,
                            std::size_t limit) {
    std::ifstream file = open_regular_file(input, path);
    const std::string shown = named(input, path);
    std::string text;
    char buffer[1 << 16];
    while (file.read(buffer, sizeof buffer) || file.gcount() > 0) {
        text.append(buffer, static_cast<std::size_t>(file.gcount()));
        if (text.size() > limit)
            throw InvalidInput(fmt::format(
                "{}: larger than {} bytes; allowed: a file up to that size", shown, limit));
    }
    if (file.bad())
        throw InvalidInput(
            fmt::format("{}: cannot be read (an input/output error); allowed: a readable regular "
                        "file",
                        shown));
    return text;
}

LineRead read_line(std::istream& input, std::string& line, std::size_t limit) {
    line.clear();
    std::streambuf* buffer = input.rdbuf();
    if (!input.good() || buffer == nullptr) {
        input.setstate(std::ios::failbit);
        return LineRead::end;
    }
    using traits = std::char_traits<char>;
    for (;;) {
        traits::int_type c = traits::eof();
        try {
            c = buffer->sbumpc();
        } catch (const std::exception&) { // libstdc++'s filebuf throws on a read error
            input.setstate(std::ios::badbit);
            return LineRead::error;
        }
        if (traits::eq_int_type(c, traits::eof())) {
            input.setstate(line.empty() ? std::ios::eofbit | std::ios::failbit : std::ios::eofbit);
            return line.empty() ? LineRead::end : LineRead::line;
        }
        if (traits::to_char_type(c) == '\n')
            return LineRead::line;
        if (line.size() == limit)
            return LineRead::too_long;
        line.push_back(traits::to_char_type(c));
    }
}

} // namespace packbed
