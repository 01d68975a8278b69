// All-or-nothing publication of output files (penumbra/output_files.h).
#include "penumbra/output_files.h"

#include <dirent.h>
#include <fcntl.h>
#include <sys/file.h>
#include <sys/stat.h>
#include <unistd.h>

#include <atomic>
#include <cerrno>
#include <csignal>
#include <cstdlib>
#include <cstring>
#include <string_view>
#include <filesystem>
#include <mutex>
#include <set>
#include <system_error>

#include "penumbra/error.h"
#include "penumbra/input_file.h"  // file_type_name
#include "quoted.h"

namespace penumbra {
namespace {

namespace fs = std::filesystem;

using detail::in_quotes;
std::string errno_text(int code) { return std::generic_category().message(code); }

[[noreturn]] void throw_io(std::string_view operation, const std::string& message)
{
    throw Error(ErrorCategory::Io, operation, message);
}


fs::path directory_of(const fs::path& target) { return target.has_parent_path() ? target.parent_path() : "."; }

// ---------------------------------------------------------------- signal cleanup

// Named temporaries (the fallback, and the moment between link and rename)
// are listed here so that SIGINT, SIGTERM and SIGHUP remove them. The handler
// may only call async-signal-safe functions: it walks a fixed array of
// pointers to strings that stay alive while they are listed, and unlink()s.
constexpr int kSlots = 256;
std::atomic<const char*> g_named[kSlots];

extern "C" void remove_named_and_reraise(int signal_number)
{
    for (auto& slot : g_named)
        if (const char* name = slot.load()) ::unlink(name);
    ::signal(signal_number, SIG_DFL);
    ::raise(signal_number);
}

void install_cleanup_handlers()
{
    static std::once_flag once;
    std::call_once(once, [] {
        for (int s : {SIGINT, SIGTERM, SIGHUP}) {
            struct sigaction previous {};
            ::sigaction(s, nullptr, &previous);
            if (previous.sa_handler != SIG_DFL) continue;  // the program has its own policy
            struct sigaction action {};
            action.sa_handler = remove_named_and_reraise;
            sigemptyset(&action.sa_mask);
            ::sigaction(s, &action, nullptr);
        }
    });
}

}  // namespace

// In detail, not the anonymous namespace: OutputFiles::Staged, a class of the
// public API, holds one.
namespace detail {

// Lists a name for the handler; unlisted when destroyed.
class NamedTemporary {
public:
    NamedTemporary() = default;
    ~NamedTemporary() { release(); }
    // Lists `name` (before the file exists, so that no moment is unguarded).
    void assign(std::string name)
    {
        release();
        name_ = std::move(name);
        install_cleanup_handlers();
        for (auto& slot : g_named) {
            const char* empty = nullptr;
            if (slot.compare_exchange_strong(empty, name_.c_str())) {
                slot_ = &slot;
                return;
            }
        }
    }
    NamedTemporary(const NamedTemporary&) = delete;
    NamedTemporary& operator=(const NamedTemporary&) = delete;

    const std::string& name() const { return name_; }
    bool empty() const { return name_.empty(); }
    void remove()
    {
        if (!name_.empty()) ::unlink(name_.c_str());
        release();
    }
    // The file now has its final name: stop removing it.
    void release()
    {
        if (slot_) slot_->store(nullptr);
        slot_ = nullptr;
        name_.clear();
    }

private:
    std::string name_;
    std::atomic<const char*>* slot_ = nullptr;
};

}  // namespace detail

namespace {

// ".NAME.penumbra-tmp-PID-N": hidden, named after the target so that a stray
// one says what it was, and distinctive, so that the stale-temporary sweep
// below never takes another program's file for one of ours.
constexpr std::string_view kTemporaryTag = ".penumbra-tmp-";

std::string hidden_name_beside(const fs::path& target)
{
    static std::atomic<unsigned> counter{0};
    std::string name = ".";
    name += target.filename().string();
    name += kTemporaryTag;
    name += std::to_string(::getpid());
    name += '-';
    name += std::to_string(counter++);
    return (directory_of(target) / name).string();
}

[[noreturn]] void cannot_create_in(std::string_view operation, const fs::path& target, int error)
{
    const fs::path directory = directory_of(target);
    std::error_code ignored;
    if (error == ENOENT && !fs::is_directory(directory, ignored))
        throw_io(operation, "cannot write " + in_quotes(target.string()) + ": directory " + in_quotes(directory.string()) +
                                " does not exist; create it first");
    throw_io(operation, "cannot create a file in " + in_quotes(directory.string()) + " to write " +
                            in_quotes(target.string()) + " (" + errno_text(error) +
                            "); check that it is a directory you may write to");
}

void flush_to_disk(int fd, const std::string& what)
{
    if (::fsync(fd) != 0) throw std::system_error(errno, std::generic_category(), "flushing " + what + " to disk");
}

// Test hook: PENUMBRA_TEST_SIGKILL_AT=POINT makes the process SIGKILL itself at
// POINT ("linked": every temporary named, none renamed; "renamed-1": the first
// target replaced), so that tests hit the publication window every time
// instead of by a lucky signal.
void sigkill_at_for_tests(std::string_view point)
{
    const char* at = std::getenv("PENUMBRA_TEST_SIGKILL_AT");
    if (at && point == at) ::raise(SIGKILL);
}

// ---------------------------------------------------------------- stale temporaries

// Every temporary carries an exclusive flock(2) from its creation until it is
// renamed or removed. The kernel drops the lock when its owner dies, even by
// SIGKILL, so an unlocked ".*.penumbra-tmp-*" file is an orphan: a process that
// was killed between naming its temporaries and renaming them (see publish()).
// A lock, unlike a PID in the name, is not fooled by PID reuse, by another PID
// namespace sharing the folder, or by a reboot.

bool has_temporary_name(std::string_view name)
{
    const std::size_t tag = name.rfind(kTemporaryTag);
    if (name.size() < 2 || name.front() != '.' || tag == std::string_view::npos || tag == 0) return false;
    // then PID-N: digits, one '-', digits
    const std::string_view rest = name.substr(tag + kTemporaryTag.size());
    const std::size_t dash = rest.find('-');
    auto digits = [](std::string_view text) {
        return !text.empty() && text.find_first_not_of("0123456789") == std::string_view::npos;
    };
    return dash != std::string_view::npos && digits(rest.substr(0, dash)) && digits(rest.substr(dash + 1));
}

bool same_file(const struct stat& a, const struct stat& b) { return a.st_dev == b.st_dev && a.st_ino == b.st_ino; }

// Removes `name` in `directory_fd` if it is a regular file nobody holds locked.
// The name is checked to still lead to the locked file just before it is
// unlinked: its owner may have renamed it into place meanwhile.
void remove_if_orphaned(int directory_fd, const char* name)
{
    const int fd = ::openat(directory_fd, name, O_RDONLY | O_NONBLOCK | O_NOFOLLOW | O_CLOEXEC);
    if (fd < 0) return;
    struct stat locked {}, named {};
    if (::fstat(fd, &locked) == 0 && S_ISREG(locked.st_mode) && ::flock(fd, LOCK_EX | LOCK_NB) == 0 &&
        ::fstatat(directory_fd, name, &named, AT_SYMLINK_NOFOLLOW) == 0 && same_file(locked, named))
        ::unlinkat(directory_fd, name, 0);
    ::close(fd);
}

// Sweeps `directory` once per process, before the first temporary goes there.
// Best effort: a folder that cannot be listed is left alone (staging into it
// reports the real problem).
void remove_orphaned_temporaries_in(const fs::path& directory)
{
    static std::mutex mutex;
    static std::set<std::string> swept;
    std::error_code ignored;
    const fs::path key = fs::weakly_canonical(fs::absolute(directory, ignored), ignored);
    {
        std::lock_guard<std::mutex> lock(mutex);
        if (!swept.insert(key.empty() ? directory.string() : key.string()).second) return;
    }
    DIR* listing = ::opendir(directory.c_str());
    if (!listing) return;
    while (const dirent* entry = ::readdir(listing))
        if (has_temporary_name(entry->d_name)) remove_if_orphaned(::dirfd(listing), entry->d_name);
    ::closedir(listing);
}

// Takes the lock that marks a temporary as owned (see above); waits if a sweep
// holds it for the moment of its check. A file system without locks fails here
// and in the sweep's flock alike, so nothing there is ever swept.
void lock_as_owned(int fd)
{
    while (::flock(fd, LOCK_EX) != 0 && errno == EINTR) {
    }
}

}  // namespace

// ---------------------------------------------------------------- one staged file

struct OutputFiles::Staged {
    std::string target;
    int fd = -1;              // the temporary, open and flock()ed until published or removed
    bool unnamed = false;     // O_TMPFILE (written through /proc/self/fd), else the named fallback
    detail::NamedTemporary named;  // the fallback's file, or the linked name before rename
    ~Staged()
    {
        named.remove();  // while still locked, so that no sweep races the unlink
        if (fd >= 0) ::close(fd);
    }
    std::string writer_path() const { return unnamed ? "/proc/self/fd/" + std::to_string(fd) : named.name(); }
};

namespace {

// An unnamed file in the target's directory, reachable for writing through
// /proc/self/fd/N; -1 (errno set) when the file system or /proc do not allow it.
int open_unnamed_beside(const fs::path& target)
{
#ifdef O_TMPFILE
    // For file systems that accept O_TMPFILE but fail linkat() on it (some FUSE
    // mounts), and for the tests of the fallback.
    if (const char* off = std::getenv("PENUMBRA_NO_O_TMPFILE"); off && *off && std::string_view(off) != "0") {
        errno = EOPNOTSUPP;
        return -1;
    }
    const int fd = ::open(directory_of(target).c_str(), O_TMPFILE | O_WRONLY | O_CLOEXEC, 0666);
    if (fd < 0) return -1;
    if (::access(("/proc/self/fd/" + std::to_string(fd)).c_str(), F_OK) != 0) {
        ::close(fd);
        errno = EOPNOTSUPP;
        return -1;
    }
    // O_TMPFILE files start with mode 0666 & ~umask, like any new file. Locked
    // before it has a name, so that its name is never seen unlocked.
    lock_as_owned(fd);
    return fd;
#else
    (void)target;
    errno = EOPNOTSUPP;
    return -1;
#endif
}

bool unnamed_unsupported(int error) { return error == EOPNOTSUPP || error == EISDIR || error == EINVAL; }

// The fallback's named temporary, returned open and locked. Between creating
// it and locking it a sweep may find it unlocked and remove it: so once locked,
// the name must still lead to it, or another name is tried.
int create_named_beside(const fs::path& target, std::string_view operation, detail::NamedTemporary& named)
{
    for (int attempt = 0; attempt < 100; ++attempt) {
        named.assign(hidden_name_beside(target));
        const int fd = ::open(named.name().c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0666);
        if (fd >= 0) {
            lock_as_owned(fd);
            struct stat opened {}, now {};
            if (::fstat(fd, &opened) == 0 && ::lstat(named.name().c_str(), &now) == 0 && same_file(opened, now))
                return fd;
            ::close(fd);
            named.release();
            continue;
        }
        const int error = errno;
        named.release();
        if (error != EEXIST) cannot_create_in(operation, target, error);
    }
    throw_io(operation, "cannot find a free temporary name beside " + in_quotes(target.string()) +
                            "; remove stale '.*.tmp-*' files from its directory");
}

// Gives the unnamed file a hidden name beside its target (linkat through
// /proc/self/fd: AT_EMPTY_PATH would need CAP_DAC_READ_SEARCH).
void link_unnamed(OutputFiles::Staged& file, std::string_view operation)
{
    for (int attempt = 0; attempt < 100; ++attempt) {
        std::string name = hidden_name_beside(file.target);
        file.named.assign(name);
        if (::linkat(AT_FDCWD, file.writer_path().c_str(), AT_FDCWD, name.c_str(), AT_SYMLINK_FOLLOW) == 0) return;
        const int error = errno;
        file.named.release();
        if (error != EEXIST) cannot_create_in(operation, file.target, error);
    }
    throw_io(operation, "cannot find a free temporary name beside " + in_quotes(file.target));
}

}  // namespace

OutputFiles::OutputFiles(std::string operation) : operation_(std::move(operation)) {}
OutputFiles::~OutputFiles() = default;

void OutputFiles::stage(const std::string& path, const std::function<void(const std::string& temporary)>& write)
{
    remove_orphaned_temporaries_in(directory_of(path));
    auto file = std::make_unique<Staged>();
    file->target = path;
    file->fd = open_unnamed_beside(path);
    file->unnamed = file->fd >= 0;
    if (!file->unnamed) {
        if (!unnamed_unsupported(errno)) cannot_create_in(operation_, path, errno);
        file->fd = create_named_beside(path, operation_, file->named);
    }
    try {
        write(file->writer_path());
    } catch (const Error&) {
        throw;
    } catch (const std::exception& e) {
        throw_io(operation_, "cannot write " + in_quotes(path) + ": " + e.what() +
                                 "; check free disk space and write permission");
    }
    staged_.push_back(std::move(file));
}

void OutputFiles::publish()
{
    try {
        publish_all();
    } catch (...) {
        staged_.clear();  // each unpublished temporary is removed now, not when *this dies
        throw;
    }
}

void OutputFiles::publish_all()
{
    // Every slow step (fsync) comes before the first name is given, so that the
    // window a SIGKILL can hit -- temporaries named, targets not all replaced --
    // is only the links and renames themselves.
    try {
        for (auto& file : staged_) flush_to_disk(file->fd, file->target);
        for (auto& file : staged_)
            if (file->unnamed) link_unnamed(*file, operation_);
    } catch (const Error&) {
        throw;
    } catch (const std::exception& e) {
        throw_io(operation_, std::string(e.what()) + "; no output was replaced; check free disk space");
    }
    sigkill_at_for_tests("linked");
    // rename(2) replaces each target in one step: readers see the old file or
    // the new one, never a mix. (A symbolic link as target is replaced, not followed.)
    std::vector<std::string> done;
    for (auto& file : staged_) {
        if (::rename(file->named.name().c_str(), file->target.c_str()) != 0) {
            const int error = errno;
            std::string message = "cannot replace " + in_quotes(file->target) + " (" + errno_text(error) + ")";
            if (done.empty()) message += "; no output was replaced";
            else {
                message += "; already replaced:";
                for (const std::string& d : done) {
                    message += ' ';
                    message += in_quotes(d);
                }
                message += "; not replaced: every other output";
            }
            throw_io(operation_, message + "; if a directory of that name is in the way, move it or choose another path");
        }
        file->named.release();
        done.push_back(file->target);
        if (done.size() == 1) sigkill_at_for_tests("renamed-1");
    }
    staged_.clear();
}

// ---------------------------------------------------------------- target checks

void require_safe_outputs(const std::vector<std::string>& outputs, const std::vector<std::string>& inputs,
                          std::string_view operation)
{
    std::set<std::pair<dev_t, ino_t>> input_ids;
    for (const std::string& input : inputs) {
        struct stat status {};
        if (!input.empty() && ::stat(input.c_str(), &status) == 0) input_ids.insert({status.st_dev, status.st_ino});
    }
    std::set<std::string> seen;
    for (const std::string& output : outputs) {
        if (output.empty()) throw_io(operation, "an output file name is empty");
        struct stat status {};
        const fs::path directory = directory_of(output);
        if (::stat(directory.c_str(), &status) != 0 || !S_ISDIR(status.st_mode))
            throw_io(operation, "cannot write " + in_quotes(output) + ": directory " + in_quotes(directory.string()) +
                                    " does not exist; create it first");
        if (::lstat(output.c_str(), &status) == 0 && !S_ISREG(status.st_mode) && !S_ISLNK(status.st_mode))
            throw_io(operation,
                    in_quotes(output) + " is " + file_type_name(status.st_mode) +
                        "; an output must be a regular file (or a new name), choose another path");
        if (::stat(output.c_str(), &status) == 0)
            if (input_ids.count({status.st_dev, status.st_ino}))
                throw_io(operation, in_quotes(output) +
                                        " is one of the inputs; writing it would destroy that input, choose another path");
        std::error_code ignored;
        const fs::path absolute = fs::weakly_canonical(fs::absolute(output, ignored), ignored);
        if (!seen.insert(absolute.empty() ? output : absolute.string()).second)
            throw_io(operation, in_quotes(output) + " is given as two outputs; give each output its own path");
    }
}

}  // namespace penumbra
