#include "packbed/output.hpp"

#include <fcntl.h>
#include <signal.h>
#include <stdio.h> // renameat2
#include <stdlib.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <cstring>
#include <fstream>
#include <mutex>
#include <system_error>
#include <thread>

#include <fmt/format.h>

#include "packbed/error.hpp"
#include "packbed/files.hpp"

namespace packbed {

namespace fs = std::filesystem;

namespace {

/// The temporaries of this process, for cancel_outputs().
struct Registry {
    std::mutex mutex;
    bool cancelled = false;
    std::size_t committed = 0;
    std::vector<fs::path> temporaries; // staging folders and temporary files
};

Registry& registry() {
    static Registry r;
    return r;
}

void unregister(const fs::path& path) {
    auto& t = registry().temporaries;
    t.erase(std::remove(t.begin(), t.end(), path), t.end());
}

/// Remove a file or a folder tree, again while something is still creating files in it.
void remove_tree(const fs::path& path) {
    for (int attempt = 0; attempt < 200; ++attempt) {
        std::error_code ec;
        fs::remove_all(path, ec);
        if (!fs::exists(fs::symlink_status(path, ec)))
            return;
        std::this_thread::sleep_for(std::chrono::milliseconds(1));
    }
}

/// The marker in the names of our temporaries (see temporary_name).
constexpr std::string_view marker = ".packbed-";

/// A template for mkdtemp/mkstemp: `.STEM.packbed-PID-XXXXXX`, or `.packbed-PID-XXXXXX`.
std::string temporary_name(std::string_view stem) {
    return fmt::format("{}{}{}{}-XXXXXX", stem.empty() ? "" : ".", stem.substr(0, 64), marker,
                       ::getpid());
}

/// Remove the temporaries that killed packbed processes left in `folder` (names
/// `.*packbed-PID-XXXXXX` whose PID no longer runs).
void remove_stale_temporaries(const fs::path& folder) {
    std::error_code ec;
    fs::directory_iterator it(folder, ec), end;
    std::vector<fs::path> stale;
    for (; !ec && it != end; it.increment(ec)) {
        std::string name = it->path().filename().string();
        if (name.ends_with(".old")) // moved aside by a commit without RENAME_EXCHANGE
            name.resize(name.size() - 4);
        const std::size_t at = name.rfind("packbed-");
        if (name.empty() || name[0] != '.' || at == std::string::npos)
            continue;
        std::size_t i = at + 8, pid = 0;
        const std::size_t digits = i;
        while (i < name.size() && name[i] >= '0' && name[i] <= '9' && i - digits < 10)
            pid = pid * 10 + static_cast<std::size_t>(name[i++] - '0');
        if (i == digits || i + 7 != name.size() || name[i] != '-')
            continue;
        const auto id = static_cast<pid_t>(pid);
        if (id != ::getpid() && ::kill(id, 0) != 0 && errno == ESRCH)
            stale.push_back(it->path());
    }
    for (const auto& path : stale)
        remove_tree(path);
}

/// The nearest folder of `path` (itself included) that exists.
/// \throws InvalidInput naming `input` when that is a file, not a folder
fs::path nearest_existing(fs::path path, const std::string& input, const fs::path& given) {
    std::error_code ec;
    while (!fs::exists(fs::status(path, ec)) && path.has_relative_path())
        path = path.parent_path();
    if (!fs::is_directory(path, ec))
        throw InvalidInput(fmt::format("{} {}: {} is a file; allowed: a directory", input,
                                       printable(given.native()), printable(path.native())));
    return path;
}

mode_t default_mode(mode_t full) {
    const mode_t mask = ::umask(0);
    ::umask(mask);
    return full & ~mask;
}

/// `path` absolute, normalised, without a trailing separator.
fs::path normalised(const fs::path& path) {
    fs::path p = fs::absolute(path).lexically_normal();
    if (!p.has_filename() && p.has_relative_path())
        p = p.parent_path();
    return p;
}

bool inside(const fs::path& path, const fs::path& folder) {
    std::error_code ec;
    const fs::path p = fs::weakly_canonical(path, ec), f = fs::weakly_canonical(folder, ec);
    const auto [f_end, p_at] = std::mismatch(f.begin(), f.end(), p.begin(), p.end());
    return f_end == f.end();
}

std::string shown(const fs::path& path) {
    return printable(path.native());
}

} // namespace

OutputDirectory::OutputDirectory(fs::path path, std::string input, OutputKind kind, bool replace)
    : m_path(std::move(path))
    , m_input(std::move(input))
    , m_kind(kind)
    , m_replace(replace) {
    check_path(m_input, m_path);
    m_target = normalised(m_path);
    const bool whole = kind == OutputKind::directory;
    std::error_code ec;
    const fs::file_status status = fs::status(m_target, ec);
    m_target_exists = fs::exists(status);
    if (!m_target_exists && fs::is_symlink(fs::symlink_status(m_target, ec)))
        throw InvalidInput(fmt::format("{} {}: a symbolic link to nothing; allowed: a directory "
                                       "or a new name",
                                       m_input, shown(m_path)));
    if (m_target_exists && !fs::is_directory(status))
        throw InvalidInput(fmt::format("{} {}: a file has that name; allowed: a directory", m_input,
                                       shown(m_path)));
    bool non_empty = false;
    if (whole && m_target_exists) {
        fs::directory_iterator it(m_target, ec);
        if (ec)
            throw InvalidInput(fmt::format("{} {}: cannot be read ({}); allowed: a directory "
                                           "you can write to",
                                           m_input, shown(m_path), ec.message()));
        non_empty = it != fs::directory_iterator();
        if (non_empty && !replace)
            throw InvalidInput(fmt::format("{} {}: exists and is not empty; allowed: a new or "
                                           "empty directory, or --force to replace it whole",
                                           m_input, shown(m_path)));
        if (non_empty && (!m_target.has_relative_path() || inside(fs::current_path(), m_target)))
            throw InvalidInput(fmt::format("{} {}: --force would replace the working directory "
                                           "or a folder holding it; allowed: another directory",
                                           m_input, shown(m_path)));
    }
    if (whole && m_target_exists && !non_empty && ::access(m_target.c_str(), W_OK | X_OK) != 0)
        throw InvalidInput(fmt::format("{} {}: the directory is not writable; allowed: a "
                                       "directory you can write to",
                                       m_input, shown(m_path)));
    m_replace = non_empty;

    // The staging folder: beside the directory (it becomes the directory), or in the folder of
    // the files; in the nearest folder that exists, since nothing is created before commit().
    const fs::path base =
        nearest_existing(whole ? m_target.parent_path() : m_target, m_input, m_path);
    remove_stale_temporaries(base);
    std::string name = (base / temporary_name(whole ? m_target.filename().string() : "")).string();
    std::unique_lock lock(registry().mutex);
    if (registry().cancelled)
        throw Cancelled();
    if (::mkdtemp(name.data()) == nullptr) {
        const int error = errno;
        // An existing empty directory in a folder we cannot write: stage inside it.
        if (whole && m_target_exists && !non_empty) {
            name = (m_target / temporary_name("")).string();
            m_in_target = ::mkdtemp(name.data()) != nullptr;
        }
        if (!m_in_target)
            throw InvalidInput(fmt::format("{} {}: cannot write in {} ({}); allowed: a "
                                           "directory in a folder you can write to",
                                           m_input, shown(m_path), shown(base),
                                           std::strerror(error)));
    }
    m_staging = name;
    registry().temporaries.push_back(m_staging);
}

OutputDirectory::~OutputDirectory() {
    if (m_staging.empty())
        return;
    std::lock_guard lock(registry().mutex);
    remove_tree(m_staging);
    unregister(m_staging);
}

fs::path OutputDirectory::final_path(const std::string& name) const {
    return m_target / name;
}

fs::path OutputDirectory::given_path(const std::string& name) const {
    return m_path == "." ? fs::path(name) : m_path / name;
}

void OutputDirectory::keep(std::string_view input, const fs::path& path) {
    if (m_kind == OutputKind::directory && m_replace && inside(path, m_target))
        throw InvalidInput(fmt::format("{} {} lies in {} {}, which --force would replace; "
                                       "allowed: an output directory that does not hold the "
                                       "inputs",
                                       input, shown(path), m_input, shown(m_path)));
    for (const std::string& name : m_names)
        if (same_file(path, final_path(name)))
            throw InvalidInput(fmt::format("{} {}: the output {} would overwrite it; allowed: "
                                           "an output that is not an input",
                                           input, shown(path), shown(given_path(name))));
    m_kept.emplace_back(std::string(input), path);
}

fs::path OutputDirectory::reserve(const std::string& name) {
    const fs::path relative = fs::path(name).lexically_normal();
    if (name.empty() || relative.is_absolute() || *relative.begin() == "..")
        throw std::logic_error("OutputDirectory: '" + name + "' is not a name inside it");
    const fs::path target = final_path(name);
    for (const auto& [input, path] : m_kept)
        if (same_file(path, target))
            throw InvalidInput(fmt::format("{} {}: the output {} would overwrite it; allowed: "
                                           "an output that is not an input",
                                           input, shown(path), shown(given_path(name))));
    std::error_code ec;
    const fs::file_status status = fs::symlink_status(target, ec);
    // A file replaces a file or a link (the link itself, not what it points to); never a
    // directory, a FIFO or a device (as root, renaming over /dev/null would replace it).
    if (m_kind == OutputKind::files && fs::exists(status) && !fs::is_regular_file(status) &&
        !fs::is_symlink(status))
        throw InvalidInput(fmt::format("{} {}: {} has that name; allowed: a regular file name",
                                       m_input, shown(given_path(name)),
                                       fs::is_directory(status) ? "a directory"
                                       : fs::is_fifo(status)    ? "a FIFO"
                                                                : "a device or socket"));
    const fs::path staged = m_staging / relative;
    std::lock_guard lock(registry().mutex);
    if (registry().cancelled)
        throw Cancelled();
    fs::create_directories(staged.parent_path(), ec);
    // Our own folder (mode 0700): the file is new, so nothing else can be in its place.
    const int fd =
        ::open(staged.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_NOFOLLOW | O_CLOEXEC, 0666);
    if (fd < 0 && errno != EEXIST)
        throw std::runtime_error(
            fmt::format("cannot write {}: {}", shown(given_path(name)), std::strerror(errno)));
    if (fd >= 0)
        ::close(fd);
    if (std::find(m_names.begin(), m_names.end(), name) == m_names.end())
        m_names.push_back(name);
    return staged;
}

void OutputDirectory::stage(const std::string& name, const std::string& contents) {
    const fs::path staged = reserve(name);
    std::ofstream file(staged, std::ios::binary | std::ios::trunc);
    file.write(contents.data(), static_cast<std::streamsize>(contents.size()));
    file.close();
    std::lock_guard lock(registry().mutex);
    if (registry().cancelled)
        throw Cancelled();
    if (!file)
        throw std::runtime_error(fmt::format("cannot write {}", shown(given_path(name))));
}

void OutputDirectory::discard(const std::string& name) {
    const auto at = std::find(m_names.begin(), m_names.end(), name);
    if (at == m_names.end())
        return;
    m_names.erase(at);
    std::error_code ec;
    fs::remove(m_staging / name, ec);
}

void OutputDirectory::commit() {
    std::lock_guard lock(registry().mutex);
    if (registry().cancelled)
        throw Cancelled();
    std::error_code ec;
    // All or nothing: a missing file stops the commit before anything is renamed.
    for (const std::string& name : m_names)
        if (!fs::is_regular_file(fs::symlink_status(m_staging / name, ec)))
            throw std::runtime_error(fmt::format("cannot write {}: its staged file is missing",
                                                 shown(given_path(name))));
    auto fail = [&](const fs::path& what, int error) {
        return std::runtime_error(fmt::format("{} {}: cannot put {} in place ({}); nothing was "
                                              "written",
                                              m_input, shown(m_path), shown(what),
                                              std::strerror(error)));
    };
    if (m_kind == OutputKind::files || m_in_target) {
        fs::create_directories(m_target, ec);
        for (const std::string& name : m_names) {
            const fs::path target = final_path(name);
            fs::create_directories(target.parent_path(), ec);
            if (::rename((m_staging / name).c_str(), target.c_str()) != 0)
                throw fail(target, errno);
        }
        remove_tree(m_staging);
    } else {
        ::chmod(m_staging.c_str(), default_mode(0777));
        fs::create_directories(m_target.parent_path(), ec);
        if (!m_target_exists) {
            if (::rename(m_staging.c_str(), m_target.c_str()) != 0)
                throw fail(m_target, errno);
        } else if (m_replace) {
            // One rename swaps the old directory for the new; the old one is then removed.
            if (::renameat2(AT_FDCWD, m_staging.c_str(), AT_FDCWD, m_target.c_str(),
                            RENAME_EXCHANGE) != 0) {
                if (errno != EINVAL && errno != ENOSYS)
                    throw fail(m_target, errno);
                // A file system without the exchange: move the old aside, then the new in.
                fs::path old = m_staging;
                old += ".old";
                if (::rename(m_target.c_str(), old.c_str()) != 0)
                    throw fail(m_target, errno);
                if (::rename(m_staging.c_str(), m_target.c_str()) != 0) {
                    const int error = errno;
                    ::rename(old.c_str(), m_target.c_str());
                    throw fail(m_target, error);
                }
                remove_tree(old);
            }
            remove_tree(m_staging); // the old directory, now
        } else {
            // An existing empty directory (perhaps the working one): move the files into it.
            for (const fs::directory_entry& entry : fs::directory_iterator(m_staging, ec)) {
                const fs::path target = m_target / entry.path().filename();
                if (::rename(entry.path().c_str(), target.c_str()) != 0)
                    throw fail(target, errno);
            }
            remove_tree(m_staging);
        }
    }
    unregister(m_staging);
    m_staging.clear();
    m_names.clear();
    ++registry().committed;
}

void replace_file(const fs::path& path, std::string_view input,
                  std::initializer_list<std::string_view> parts) {
    check_path(input, path);
    const fs::path folder = path.has_parent_path() ? path.parent_path() : fs::path(".");
    std::size_t bytes = 0;
    for (const auto part : parts)
        bytes += part.size();
    auto refuse = [&](int error) {
        return InvalidInput(fmt::format("{} {}: cannot be written ({}); allowed: a file in a "
                                        "writable folder with room for {} bytes",
                                        input, shown(path), std::strerror(error), bytes));
    };
    remove_stale_temporaries(folder);
    std::string name = (folder / temporary_name(path.filename().string())).string();
    int fd = -1;
    {
        std::lock_guard lock(registry().mutex);
        if (registry().cancelled)
            throw Cancelled();
        fd = ::mkostemp(name.data(), O_CLOEXEC);
        if (fd < 0)
            throw refuse(errno);
        registry().temporaries.emplace_back(name);
    }
    auto abandon = [&](int error) {
        std::lock_guard lock(registry().mutex);
        ::unlink(name.c_str());
        unregister(name);
        return refuse(error);
    };
    ::fchmod(fd, default_mode(0666));
    for (const auto part : parts)
        for (std::size_t done = 0; done < part.size();) {
            const ssize_t n = ::write(fd, part.data() + done, part.size() - done);
            if (n < 0 && errno == EINTR)
                continue;
            if (n <= 0) {
                const int error = n < 0 ? errno : EIO;
                ::close(fd);
                throw abandon(error);
            }
            done += static_cast<std::size_t>(n);
        }
    if (::fsync(fd) != 0 || ::close(fd) != 0)
        throw abandon(errno);
    std::lock_guard lock(registry().mutex);
    if (registry().cancelled)
        throw Cancelled();
    if (::rename(name.c_str(), path.c_str()) != 0) {
        const int error = errno;
        ::unlink(name.c_str());
        unregister(name);
        throw refuse(error);
    }
    unregister(name);
}

void check_writable_file(std::string_view input, const fs::path& path) {
    check_path(input, path);
    std::error_code ec;
    const fs::file_status status = fs::status(path, ec);
    if (fs::exists(status) && !fs::is_regular_file(status))
        throw InvalidInput(fmt::format("{} {}: {}; allowed: a file", input, shown(path),
                                       fs::is_directory(status) ? "a directory has that name"
                                                                : "not a regular file"));
    const fs::path folder = path.has_parent_path() ? path.parent_path() : fs::path(".");
    if (!fs::is_directory(folder, ec))
        throw InvalidInput(fmt::format("{} {}: {} is not a folder; allowed: a file in a folder "
                                       "you can write to",
                                       input, shown(path), shown(folder)));
    std::string probe = (folder / temporary_name(path.filename().string())).string();
    const int fd = ::mkostemp(probe.data(), O_CLOEXEC);
    if (fd < 0)
        throw InvalidInput(fmt::format("{} {}: cannot be written ({}); allowed: a file in a "
                                       "folder you can write to",
                                       input, shown(path), std::strerror(errno)));
    ::close(fd);
    ::unlink(probe.c_str());
}

bool same_file(const fs::path& a, const fs::path& b) {
    std::error_code ec;
    return fs::equivalent(a, b, ec) && !ec;
}

bool cancel_outputs() {
    Registry& r = registry();
    std::lock_guard lock(r.mutex);
    r.cancelled = true;
    for (const fs::path& path : r.temporaries)
        remove_tree(path);
    r.temporaries.clear();
    return r.committed > 0;
}

} // namespace packbed
