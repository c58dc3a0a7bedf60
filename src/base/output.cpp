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
#include <deque>
#include <fstream>
#include <mutex>
#include <optional>
#include <random>
#include <system_error>
#include <thread>

#include <fmt/format.h>

#include "fnv1a.hpp"
#include "packbed/error.hpp"
#include "packbed/files.hpp"

namespace packbed {

namespace fs = std::filesystem;

namespace {

/// The temporaries of this process, for cancel_outputs(), and the staging folders' given
/// names, for as_given().
struct Registry {
    std::mutex mutex;
    bool cancelled = false;
    std::size_t committed = 0;
    std::vector<fs::path> temporaries;                  // staging folders and temporary files
    std::deque<std::pair<std::string, std::string>> as; // staging path -> path as given
};

Registry& registry() {
    static Registry r;
    return r;
}

void unregister(const fs::path& path) {
    auto& t = registry().temporaries;
    t.erase(std::remove(t.begin(), t.end(), path), t.end());
}

/// Remember how the user named what is staged at `staging` (the last 64 outputs): the folder
/// as `given`, a file in it as given/NAME (NAME alone when `given` is ".").
void remember_given(const fs::path& staging, const fs::path& given) {
    auto& as = registry().as;
    as.emplace_back(staging.string() + "/", given == "." ? "" : given.string() + "/");
    as.emplace_back(staging.string(), given.string());
    while (as.size() > 128)
        as.pop_front();
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

std::string shown(const fs::path& path) {
    return printable(path.native());
}

// ---------------------------------------------------------------------------------------------
// Who made a temporary: the host (and PID namespace) and the process.

/// This process's host, as 12 hex digits: a hash of the kernel's boot id and of the PID
/// namespace, so that two processes share it exactly when a process id means the same process
/// to both. Another machine on a shared disk, another container, or the same machine after a
/// reboot has another. Where either cannot be read, a random value that no other process has.
std::string compute_host_identity() {
    std::string boot;
    std::ifstream("/proc/sys/kernel/random/boot_id") >> boot;
    char ns[128] = {};
    const ssize_t n = ::readlink("/proc/self/ns/pid", ns, sizeof ns - 1);
    std::uint64_t h = 0;
    if (boot.size() >= 32 && n > 0)
        h = detail::fnv1a(boot + "/" + std::string(ns, static_cast<std::size_t>(n)));
    else
        h = std::random_device()() * 0x100000000ull + std::random_device()();
    return fmt::format("{:012x}", h & 0xffffffffffffull);
}

/// compute_host_identity(), computed again in a child that fork() made (it may be in another
/// PID namespace than its parent).
std::string host_identity() {
    static pid_t computed_by = 0;
    static std::string id;
    static std::mutex mutex;
    std::lock_guard lock(mutex);
    if (computed_by != ::getpid()) {
        id = compute_host_identity();
        computed_by = ::getpid();
    }
    return id;
}

/// The marker in the names of our temporaries (see temporary_name).
constexpr std::string_view marker = "packbed-";

/// "packbed-HOST-PID": who made a temporary or holds a claim.
std::string owner_tag() {
    return fmt::format("{}{}-{}", marker, host_identity(), ::getpid());
}

/// A template for mkdtemp/mkstemp: `.STEM.packbed-HOST-PID-XXXXXX`, or `.packbed-HOST-PID-XXXXXX`.
std::string temporary_name(std::string_view stem) {
    return fmt::format("{}{}.{}-XXXXXX", stem.empty() ? "" : ".", stem.substr(0, 64), owner_tag());
}

/// The host and process in `text` when it ends with `packbed-HOST-PID` followed by `tail`
/// characters (a claim's link: 0; a temporary: 7, "-XXXXXX"); nothing for another text.
std::optional<std::pair<std::string, pid_t>> owner_of(std::string_view text, std::size_t tail) {
    const std::size_t at = text.rfind(marker);
    if (at == std::string_view::npos)
        return std::nullopt;
    std::string_view rest = text.substr(at + marker.size());
    if (rest.size() < 12 + 2 + tail)
        return std::nullopt;
    const std::string_view host = rest.substr(0, 12);
    if (!std::all_of(host.begin(), host.end(),
                     [](char c) { return (c >= '0' && c <= '9') || (c >= 'a' && c <= 'f'); }) ||
        rest[12] != '-')
        return std::nullopt;
    rest = rest.substr(13);
    std::size_t i = 0;
    long long pid = 0;
    while (i < rest.size() && i < 10 && rest[i] >= '0' && rest[i] <= '9')
        pid = pid * 10 + (rest[i++] - '0');
    if (i == 0 || pid <= 0 || pid > 0x7fffffff || rest.size() != i + tail ||
        (tail > 0 && rest[i] != '-'))
        return std::nullopt;
    return std::pair{std::string(host), static_cast<pid_t>(pid)};
}

/// True when the owner `tag` names a process of this host that has ended: only then can
/// what it left be removed. A process of another host or PID namespace (a shared disk, another
/// container) is never taken for dead.
bool ended(const std::optional<std::pair<std::string, pid_t>>& owner) {
    return owner && owner->first == host_identity() && owner->second != ::getpid() &&
           ::kill(owner->second, 0) != 0 && errno == ESRCH;
}

/// Remove the temporaries that ended packbed processes of this host left in `folder` (names
/// `.*packbed-HOST-PID-XXXXXX`, optionally `.old`, whose HOST is ours and whose PID runs no
/// more), and a claim such a process left.
void remove_stale_temporaries(const fs::path& folder) {
    std::error_code ec;
    fs::directory_iterator it(folder, ec), end;
    std::vector<fs::path> stale;
    for (; !ec && it != end; it.increment(ec)) {
        std::string name = it->path().filename().string();
        if (name.ends_with(".old")) // moved aside by a commit without RENAME_EXCHANGE
            name.resize(name.size() - 4);
        if (name.empty() || name[0] != '.')
            continue;
        if (ended(owner_of(name, 7)))
            stale.push_back(it->path());
    }
    for (const auto& path : stale)
        remove_tree(path);
}

// ---------------------------------------------------------------------------------------------
// Paths

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

/// Check that the names of `path` below the existing folder `base` fit that file system
/// (NAME_MAX, as pathconf says) and the whole path fits PATH_MAX, before any work: a name too
/// long would otherwise fail only when the output is put in place.
void check_name_lengths(const fs::path& path, const fs::path& base, std::string_view input,
                        const fs::path& given) {
    const long name_max = ::pathconf(base.c_str(), _PC_NAME_MAX);
    const std::size_t longest = name_max > 0 ? static_cast<std::size_t>(name_max) : 255;
    for (const fs::path& part : path.lexically_relative(base))
        if (part.native().size() > longest)
            throw InvalidInput(fmt::format(
                "{} {}: the name '{}...' has {} bytes; allowed: names of at most {} bytes on this "
                "file system",
                input, printable(given.native().substr(0, 200)),
                printable(part.native().substr(0, 40)), part.native().size(), longest));
    if (path.native().size() > 4000)
        throw InvalidInput(fmt::format("{} {}...: {} bytes as an absolute path; allowed: at most "
                                       "4000",
                                       input, printable(given.native().substr(0, 200)),
                                       path.native().size()));
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

/// `path` normalised with every link of its existing part resolved.
fs::path resolved(const fs::path& path) {
    std::error_code ec;
    fs::path p = fs::weakly_canonical(normalised(path), ec);
    if (ec)
        return normalised(path);
    if (!p.has_filename() && p.has_relative_path())
        p = p.parent_path();
    return p;
}

/// True when the resolved `path` is `folder` or lies in it (both resolved).
bool within(const fs::path& path, const fs::path& folder) {
    const auto [f_end, p_at] =
        std::mismatch(folder.begin(), folder.end(), path.begin(), path.end());
    return f_end == folder.end();
}

bool inside(const fs::path& path, const fs::path& folder) {
    return within(resolved(path), resolved(folder));
}

/// Device and inode of what `path` names (not following a last link), or {0, 0} for nothing.
std::pair<std::uint64_t, std::uint64_t> identity(const fs::path& path) {
    struct stat info {};
    if (::lstat(path.c_str(), &info) != 0)
        return {0, 0};
    return {static_cast<std::uint64_t>(info.st_dev), static_cast<std::uint64_t>(info.st_ino)};
}

/// The folders of `path` that do not exist, outermost first, created; \return them.
std::vector<fs::path> create_missing(const fs::path& path) {
    std::vector<fs::path> missing;
    std::error_code ec;
    for (fs::path p = path; p.has_relative_path() && !fs::exists(fs::symlink_status(p, ec));
         p = p.parent_path())
        missing.push_back(p);
    std::reverse(missing.begin(), missing.end());
    std::vector<fs::path> created;
    for (const fs::path& p : missing) {
        if (::mkdir(p.c_str(), 0777) != 0)
            break;
        created.push_back(p);
    }
    return created;
}

/// Remove the folders `created` (innermost first) that are still empty.
void remove_created(const std::vector<fs::path>& created) {
    for (auto it = created.rbegin(); it != created.rend(); ++it)
        ::rmdir(it->c_str());
}

/// rename(2) that refuses to replace anything at `to` (RENAME_NOREPLACE); where the file
/// system lacks the flag, plain rename, which still refuses to replace a non-empty directory.
int rename_new(const fs::path& from, const fs::path& to) {
    if (::renameat2(AT_FDCWD, from.c_str(), AT_FDCWD, to.c_str(), RENAME_NOREPLACE) == 0)
        return 0;
    if (errno != EINVAL && errno != ENOSYS)
        return -1;
    return ::rename(from.c_str(), to.c_str());
}

// ---------------------------------------------------------------------------------------------
// Claims: a folder that files move into, taken by one run at a time.

/// A claim on `folder`: the symbolic link `folder/.packbed-claim` pointing to "packbed-HOST-PID"
/// (made atomically, also on NFS, and removed when done). A claim that an ended process of this
/// host left is removed and taken.
class Claim {
public:
    Claim(const fs::path& folder, std::string_view input, const fs::path& given)
        : m_link(folder / ".packbed-claim") {
        const std::string tag = owner_tag();
        for (int attempt = 0; attempt < 2; ++attempt) {
            if (::symlink(tag.c_str(), m_link.c_str()) == 0)
                return;
            if (errno != EEXIST)
                throw std::runtime_error(fmt::format("{} {}: cannot claim it ({}); nothing was "
                                                     "written",
                                                     input, shown(given), std::strerror(errno)));
            char owner[128] = {};
            const ssize_t n = ::readlink(m_link.c_str(), owner, sizeof owner - 1);
            const std::string_view text(owner, n > 0 ? static_cast<std::size_t>(n) : 0);
            if (!ended(owner_of(text, 0)))
                throw InvalidInput(fmt::format(
                    "{} {}: another packbed run ({}) is writing there now; nothing was written; "
                    "allowed: an output no other run writes to at the same time",
                    input, shown(given), printable(text.substr(0, 40))));
            ::unlink(m_link.c_str()); // an ended process's claim
        }
        throw InvalidInput(fmt::format("{} {}: another packbed run is writing there now; nothing "
                                       "was written; allowed: an output no other run writes to at "
                                       "the same time",
                                       input, shown(given)));
    }
    ~Claim() { ::unlink(m_link.c_str()); }
    Claim(const Claim&) = delete;
    Claim& operator=(const Claim&) = delete;
    const fs::path& link() const { return m_link; }

private:
    fs::path m_link;
};

// ---------------------------------------------------------------------------------------------
// The job's inputs and outputs (JobScope).

struct JobInput {
    std::string input; // as named in messages
    fs::path given;
    fs::path where; // resolved
    std::pair<std::uint64_t, std::uint64_t> id;
};

struct JobFile { // a file written during the run (a checkpoint)
    std::string input;
    fs::path given;
    fs::path where; // resolved
};

struct Job {
    std::vector<JobInput> inputs;
    std::vector<const OutputDirectory*> outputs;
    std::vector<JobFile> files;
};

thread_local Job* current_job = nullptr;

std::string named(const std::string& input, const fs::path& path) {
    return input.empty() ? "the input file " + shown(path) : input + " " + shown(path);
}

/// True when the resolved `a` and the path `b` name the same file.
bool same(const fs::path& a, const std::pair<std::uint64_t, std::uint64_t>& a_id,
          const fs::path& b) {
    if (a == resolved(b))
        return true;
    return a_id.second != 0 && identity(b) == a_id;
}

/// Refuse when `output` is, holds or would overwrite `in`.
void check(const OutputDirectory& output, const JobInput& in) {
    if (output.whole()) {
        if (within(in.where, resolved(output.target())))
            throw InvalidInput(fmt::format(
                "{} lies in {} {}, which {}; allowed: an output directory that does not hold the "
                "inputs",
                named(in.input, in.given), output.input(), shown(output.path()),
                output.replaces() ? "--force would replace" : "this run writes whole"));
        return;
    }
    for (const std::string& name : output.names())
        if (same(in.where, in.id, output.target() / name))
            throw InvalidInput(fmt::format("{}: the output {} would overwrite it; allowed: an "
                                           "output that is not an input",
                                           named(in.input, in.given),
                                           shown(output.given_path(name))));
}

/// Refuse when the file `file` written during the run is an input read under another name.
void check(const JobFile& file, const JobInput& in) {
    if (file.input != in.input && same(in.where, in.id, file.where))
        throw InvalidInput(fmt::format("{}: it is also {}, which this run reads; allowed: a file "
                                       "that is not an input",
                                       named(file.input, file.given), named(in.input, in.given)));
}

/// Refuse when `file` lies in `output`'s directory or is one of its files.
void check(const OutputDirectory& output, const JobFile& file) {
    if (output.whole() ? within(file.where, resolved(output.target()))
                       : std::any_of(output.names().begin(), output.names().end(),
                                     [&](const std::string& name) {
                                         return resolved(output.target() / name) == file.where;
                                     }))
        throw InvalidInput(fmt::format("{} lies in {} {}, which this run writes; allowed: a file "
                                       "outside the run's other outputs",
                                       named(file.input, file.given), output.input(),
                                       shown(output.path())));
}

/// Refuse when two outputs overlap: a directory in (or being) the other, or a file of one in
/// the other's directory, or the same file in both.
void check(const OutputDirectory& a, const OutputDirectory& b) {
    const fs::path ta = resolved(a.target()), tb = resolved(b.target());
    bool overlap = false;
    if (a.whole() && b.whole())
        overlap = within(ta, tb) || within(tb, ta);
    else if (a.whole() || b.whole()) {
        const OutputDirectory& files = a.whole() ? b : a;
        const fs::path& folder = a.whole() ? ta : tb;
        for (const std::string& name : files.names())
            overlap = overlap || within(resolved(files.target() / name), folder);
    } else
        for (const std::string& name : a.names())
            for (const std::string& other : b.names())
                overlap = overlap || resolved(a.target() / name) == resolved(b.target() / other);
    if (overlap)
        throw InvalidInput(fmt::format("{} {} and {} {} overlap; allowed: outputs apart from each "
                                       "other",
                                       a.input(), shown(a.path()), b.input(), shown(b.path())));
}

/// Check a new or grown output against everything the job has recorded.
void check_output(const OutputDirectory& output) {
    if (current_job == nullptr)
        return;
    for (const JobInput& in : current_job->inputs)
        check(output, in);
    for (const JobFile& file : current_job->files)
        check(output, file);
    for (const OutputDirectory* other : current_job->outputs)
        if (other != &output)
            check(output, *other);
}

} // namespace

JobScope::JobScope() {
    if (current_job == nullptr) {
        current_job = new Job();
        m_outer = true;
    }
}

JobScope::~JobScope() {
    if (m_outer) {
        delete current_job;
        current_job = nullptr;
    }
}

void record_input(std::string_view input, const fs::path& path) {
    if (current_job == nullptr)
        return;
    JobInput in{std::string(input), path, resolved(path), {0, 0}};
    for (JobInput& known : current_job->inputs)
        if (known.where == in.where) { // read again: named by the more telling name
            if (known.input.empty())
                known.input = in.input;
            return;
        }
    struct stat info {};
    if (::stat(path.c_str(), &info) == 0)
        in.id = {static_cast<std::uint64_t>(info.st_dev), static_cast<std::uint64_t>(info.st_ino)};
    for (const OutputDirectory* output : current_job->outputs)
        check(*output, in);
    for (const JobFile& file : current_job->files)
        check(file, in);
    current_job->inputs.push_back(std::move(in));
}

std::string as_given(std::string message) {
    std::lock_guard lock(registry().mutex);
    for (auto it = registry().as.begin(); it != registry().as.end(); ++it)
        for (std::size_t at = message.find(it->first); at != std::string::npos;
             at = message.find(it->first, at + it->second.size()))
            message.replace(at, it->first.size(), it->second);
    return message;
}

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
    if (m_replace)
        m_seen.push_back(identity(m_target)); // the directory --force replaces

    // The staging folder: beside the directory (it becomes the directory), or in the folder of
    // the files; in the nearest folder that exists, since nothing is created before commit().
    const fs::path base =
        nearest_existing(whole ? m_target.parent_path() : m_target, m_input, m_path);
    check_name_lengths(m_target, base, m_input, m_path);
    if (current_job) { // refused before anything is created
        check_output(*this);
        current_job->outputs.push_back(this);
    }
    struct Unlist { // if the constructor throws from here on
        OutputDirectory* self;
        bool done = false;
        ~Unlist() {
            if (!done && current_job)
                std::erase(current_job->outputs, self);
        }
    } unlist{this};
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
    remember_given(m_staging, m_path);
    unlist.done = true;
}

OutputDirectory::~OutputDirectory() {
    if (current_job)
        std::erase(current_job->outputs, this);
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

fs::path OutputDirectory::reserve(const std::string& name) {
    const fs::path relative = fs::path(name).lexically_normal();
    if (name.empty() || relative.is_absolute() || *relative.begin() == "..")
        throw std::logic_error("OutputDirectory: '" + name + "' is not a name inside it");
    const fs::path target = final_path(name);
    const bool known = std::find(m_names.begin(), m_names.end(), name) != m_names.end();
    if (!known) {
        check_name_lengths(target, m_target, m_input, given_path(name));
        m_names.push_back(name);
        try {
            check_output(*this);
        } catch (...) {
            m_names.pop_back();
            throw;
        }
        m_names.pop_back();
    }
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
    if (!known) {
        m_names.push_back(name);
        if (m_kind == OutputKind::files)
            m_seen.push_back(identity(target)); // what commit() may replace
    }
    return staged;
}

void OutputDirectory::stage(const std::string& name, const std::string& contents) {
    const fs::path staged = reserve(name);
    const int fd = ::open(staged.c_str(), O_WRONLY | O_TRUNC | O_NOFOLLOW | O_CLOEXEC);
    int error = fd < 0 ? errno : 0;
    for (std::size_t done = 0; fd >= 0 && error == 0 && done < contents.size();) {
        const ssize_t n = ::write(fd, contents.data() + done, contents.size() - done);
        if (n < 0 && errno == EINTR)
            continue;
        if (n <= 0)
            error = n < 0 ? errno : EIO;
        else
            done += static_cast<std::size_t>(n);
    }
    if (fd >= 0 && ::close(fd) != 0 && error == 0)
        error = errno;
    std::lock_guard lock(registry().mutex);
    if (registry().cancelled)
        throw Cancelled();
    if (error != 0)
        throw std::runtime_error(fmt::format("cannot write {} ({}); nothing was written",
                                             shown(given_path(name)), std::strerror(error)));
}

void OutputDirectory::discard(const std::string& name) {
    const auto at = std::find(m_names.begin(), m_names.end(), name);
    if (at == m_names.end())
        return;
    if (m_kind == OutputKind::files)
        m_seen.erase(m_seen.begin() + (at - m_names.begin()));
    m_names.erase(at);
    std::error_code ec;
    fs::remove(m_staging / name, ec);
}

namespace {

std::runtime_error put_in_place_failed(const std::string& input, const fs::path& given,
                                       const fs::path& what, int error) {
    return std::runtime_error(fmt::format("{} {}: cannot put {} in place ({}); nothing was "
                                          "written",
                                          input, shown(given), shown(what), std::strerror(error)));
}

InvalidInput written_meanwhile(const std::string& input, const fs::path& given) {
    return InvalidInput(fmt::format("{} {}: another run wrote it while this one ran; nothing was "
                                    "written; allowed: an output no other run writes to at the "
                                    "same time",
                                    input, shown(given)));
}

} // namespace

void OutputDirectory::commit_files() {
    // Each file replaces its namesake (as cp does), under a claim of the folder so that two
    // runs never interleave their files, and only if no other run replaced it meanwhile.
    const std::vector<fs::path> created = create_missing(m_target);
    try {
        const Claim claim(m_target, m_input, m_path);
        for (std::size_t k = 0; k < m_names.size(); ++k)
            if (identity(final_path(m_names[k])) != m_seen[k])
                throw written_meanwhile(m_input, given_path(m_names[k]));
        for (const std::string& name : m_names) {
            const fs::path target = final_path(name);
            const std::vector<fs::path> folders = create_missing(target.parent_path());
            if (::rename((m_staging / name).c_str(), target.c_str()) != 0) {
                const int error = errno;
                remove_created(folders);
                throw put_in_place_failed(m_input, m_path, given_path(name), error);
            }
        }
    } catch (...) {
        remove_created(created);
        throw;
    }
    remove_tree(m_staging);
}

void OutputDirectory::commit_directory() {
    ::chmod(m_staging.c_str(), default_mode(0777));
    const std::vector<fs::path> created = create_missing(m_target.parent_path());
    try {
        if (!m_target_exists) {
            // One rename puts the whole directory in place, or fails when another run's is
            // there now: the two never mix.
            if (rename_new(m_staging, m_target) != 0) {
                if (errno == EEXIST || errno == ENOTEMPTY)
                    throw written_meanwhile(m_input, m_path);
                throw put_in_place_failed(m_input, m_path, m_path, errno);
            }
        } else if (m_replace) {
            // One rename swaps the old directory for the new; the old one is then removed. It
            // must be the directory seen at the start: swapped back when another run's
            // directory came in between.
            if (identity(m_target) != m_seen.front())
                throw written_meanwhile(m_input, m_path);
            if (::renameat2(AT_FDCWD, m_staging.c_str(), AT_FDCWD, m_target.c_str(),
                            RENAME_EXCHANGE) == 0) {
                if (identity(m_staging) != m_seen.front()) {
                    ::renameat2(AT_FDCWD, m_staging.c_str(), AT_FDCWD, m_target.c_str(),
                                RENAME_EXCHANGE);
                    throw written_meanwhile(m_input, m_path);
                }
            } else {
                if (errno != EINVAL && errno != ENOSYS)
                    throw put_in_place_failed(m_input, m_path, m_path, errno);
                // A file system without the exchange: move the old aside, then the new in.
                fs::path old = m_staging;
                old += ".old";
                if (::rename(m_target.c_str(), old.c_str()) != 0)
                    throw put_in_place_failed(m_input, m_path, m_path, errno);
                if (rename_new(m_staging, m_target) != 0) {
                    const int error = errno;
                    ::rename(old.c_str(), m_target.c_str());
                    throw put_in_place_failed(m_input, m_path, m_path, error);
                }
                remove_tree(old);
            }
            remove_tree(m_staging); // the old directory, now
        } else {
            // An existing empty directory (perhaps the working one, or a mount point): claimed,
            // checked to be still empty, and the files moved into it.
            const Claim claim(m_target, m_input, m_path);
            std::error_code ec;
            for (const fs::directory_entry& entry : fs::directory_iterator(m_target, ec))
                if (entry.path() != claim.link() && entry.path() != m_staging)
                    throw written_meanwhile(m_input, m_path);
            std::vector<fs::path> staged;
            for (const fs::directory_entry& entry : fs::directory_iterator(m_staging, ec))
                staged.push_back(entry.path());
            for (std::size_t k = 0; k < staged.size(); ++k)
                if (rename_new(staged[k], m_target / staged[k].filename()) != 0) {
                    const int error = errno;
                    for (std::size_t j = 0; j < k; ++j) // back out: nothing was written
                        ::rename((m_target / staged[j].filename()).c_str(), staged[j].c_str());
                    throw put_in_place_failed(m_input, m_path,
                                              given_path(staged[k].filename().string()), error);
                }
            remove_tree(m_staging);
        }
    } catch (...) {
        remove_created(created);
        throw;
    }
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
    if (m_kind == OutputKind::files)
        commit_files();
    else
        commit_directory();
    unregister(m_staging);
    m_staging.clear();
    m_names.clear();
    m_seen.clear();
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
    check_name_lengths(normalised(path), normalised(folder), input, path);
    if (current_job) {
        JobFile file{std::string(input), path, resolved(path)};
        for (const JobInput& in : current_job->inputs)
            check(file, in);
        for (const OutputDirectory* output : current_job->outputs)
            check(*output, file);
        current_job->files.push_back(std::move(file));
    }
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
