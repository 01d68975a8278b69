#include "cl/program_cache.h"

#include "cl/pocl_cache_guard.h"

#include <fcntl.h>
#include <sys/file.h>
#include <sys/stat.h>
#include <unistd.h>

#include <array>
#include <atomic>
#include <cerrno>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <mutex>
#include <system_error>

namespace penumbra::cl_backend {

namespace fs = std::filesystem;

// ---- where ------------------------------------------------------------------

static std::string environment(const char* name)
{
    const char* value = std::getenv(name);
    return value ? std::string(value) : std::string();
}

std::string cache_directory()
{
    if (std::string dir = environment("PENUMBRA_CACHE_DIR"); !dir.empty()) return dir;
    // The XDG spec says a relative XDG_CACHE_HOME is invalid and must be ignored.
    if (std::string xdg = environment("XDG_CACHE_HOME"); !xdg.empty() && xdg.front() == '/')
        return xdg + "/penumbra";
    if (std::string home = environment("HOME"); !home.empty()) return home + "/.cache/penumbra";
    return "/tmp/penumbra-cache-" + std::to_string(::geteuid());
}

std::string pocl_cache_directory()
{
    prepare_driver_cache_environment();
    return environment("POCL_CACHE_DIR");
}

// Creates the missing parts of `dir` readable by the owner only: the cache holds
// code we execute, so nobody else should be able to write into it.
static void create_private_directories(const fs::path& dir, std::error_code& error)
{
    fs::path partial;
    for (const fs::path& part : dir) {
        partial /= part;
        if (fs::is_directory(partial, error)) continue;
        if (!fs::create_directory(partial, error)) {
            if (error) return;
            continue;  // another process created it meanwhile
        }
        fs::permissions(partial, fs::perms::owner_all, error);
        if (error) return;
    }
    error.clear();
}

namespace {

// What prepare_driver_cache_environment found; written once, under its once_flag.
std::string g_driver_cache_problem, g_driver_cache_warning;
bool g_guarded = false;  // the PoCL folder is ours, usable, and checked

fs::path pocl_manifest() { return fs::path(cache_directory()) / "pocl.manifest"; }

// The lock of DriverCacheLock: -1 when the folder has no usable lock file.
int lock_driver_cache() noexcept
{
    try {
        const std::string path = cache_directory() + "/pocl.lock";
        int fd = -1;
        do fd = ::open(path.c_str(), O_RDWR | O_CREAT | O_CLOEXEC | O_NOFOLLOW, 0600);
        while (fd < 0 && errno == EINTR);
        if (fd < 0) return -1;
        int locked = -1;
        do locked = ::flock(fd, LOCK_EX);
        while (locked != 0 && errno == EINTR);
        if (locked != 0) {
            ::close(fd);
            return -1;
        }
        return fd;
    } catch (...) {
        return -1;  // out of memory composing the path
    }
}

void unlock_driver_cache(int fd) noexcept
{
    if (fd >= 0) ::close(fd);  // closing the last descriptor releases the flock
}

extern "C" void record_pocl_cache_at_exit()
{
    const int fd = lock_driver_cache();
    record_pocl_cache(pocl_cache_directory(), pocl_manifest());
    unlock_driver_cache(fd);
}

// PoCL drops its device, silently, when it cannot create or write its cache
// folder; say so in words that name the folder and the variable to change.
std::string unusable_folder_problem(const fs::path& dir, const std::error_code& error)
{
    std::string why = error ? error.message() : std::string("not writable");
    std::error_code ignored;
    for (fs::path part = dir; !part.empty() && part != part.parent_path(); part = part.parent_path())
        if (fs::exists(part, ignored) && !fs::is_directory(part, ignored)) why = part.string() + " is not a directory";
    return "the OpenCL cache folder " + dir.string() + " cannot be used (" + why +
           "); set PENUMBRA_CACHE_DIR to a folder you can write";
}

}  // namespace

void prepare_driver_cache_environment() noexcept
{
    static std::once_flag once;
    std::call_once(once, [] {
        if (std::getenv("POCL_CACHE_DIR")) return;
        try {
            const std::string dir = cache_directory() + "/pocl";
            std::error_code error;
            create_private_directories(dir, error);
            if (error || ::access(dir.c_str(), W_OK | X_OK) != 0) {
                g_driver_cache_problem = unusable_folder_problem(dir, error);
            } else {
                const int fd = lock_driver_cache();  // no other run writes while we check
                g_driver_cache_warning = check_pocl_cache(dir, pocl_manifest()).warning;
                unlock_driver_cache(fd);
                g_guarded = true;
                std::atexit(record_pocl_cache_at_exit);
                std::at_quick_exit(record_pocl_cache_at_exit);  // the CLI ends with quick_exit (host/cli/main.cpp)
            }
            ::setenv("POCL_CACHE_DIR", dir.c_str(), /*overwrite=*/0);
        } catch (...) {
            // Out of memory while composing a path: PoCL then uses its default.
        }
    });
}

std::string driver_cache_problem()
{
    prepare_driver_cache_environment();
    return g_driver_cache_problem;
}

std::string driver_cache_warning()
{
    prepare_driver_cache_environment();
    return g_driver_cache_warning;
}

DriverCacheLock::DriverCacheLock() noexcept
{
    prepare_driver_cache_environment();
    fd_ = lock_driver_cache();
}

DriverCacheLock::~DriverCacheLock() { unlock_driver_cache(fd_); }

void record_driver_cache()
{
    prepare_driver_cache_environment();
    if (g_guarded) record_pocl_cache(pocl_cache_directory(), pocl_manifest());
}

// ---- key ----------------------------------------------------------------------

namespace {

// 64-bit FNV-1a (Fowler, Noll, Vo); constants from the reference description.
class Fnv1a64 {
public:
    void add(const void* data, std::size_t size)
    {
        const auto* bytes = static_cast<const unsigned char*>(data);
        for (std::size_t i = 0; i < size; ++i) {
            state_ ^= bytes[i];
            state_ *= 1099511628211ull;
        }
    }
    // Length first, so that ("ab", "c") and ("a", "bc") hash differently.
    void add_field(std::string_view text)
    {
        const std::uint64_t size = text.size();
        add(&size, sizeof size);
        add(text.data(), text.size());
    }
    std::uint64_t value() const { return state_; }

private:
    std::uint64_t state_ = 14695981039346656037ull;
};

std::uint64_t checksum(std::span<const unsigned char> bytes)
{
    Fnv1a64 hash;
    hash.add(bytes.data(), bytes.size());
    return hash.value();
}

}  // namespace

std::uint64_t program_key(const ProgramIdentity& id)
{
    Fnv1a64 hash;
    hash.add_field("penumbra program cache v2");  // bump when the file format or what a binary holds changes
    for (std::string_view field : {id.source, id.options, id.device_name, id.device_version,
                                   id.driver_version, id.platform_name, id.platform_version, id.work_groups})
        hash.add_field(field);
    return hash.value();
}

// ---- files --------------------------------------------------------------------

namespace {

// The file is [header][payload]. Host byte order: the cache never leaves the machine.
struct FileHeader {
    std::array<char, 8> magic;
    std::uint64_t key;
    std::uint64_t payload_size;
    std::uint64_t payload_checksum;
};
constexpr std::array<char, 8> file_magic = {'P', 'N', 'C', 'L', 'B', 'I', 'N', '1'};

std::string hex(std::uint64_t value)
{
    static constexpr char digits[] = "0123456789abcdef";
    std::string text(16, '0');
    for (int i = 15; i >= 0; --i, value >>= 4) text[i] = digits[value & 0xf];
    return text;
}

// Record why the cache was not used, for callers that ask.
std::nullopt_t miss(std::string* why_not, std::string text)
{
    if (why_not) *why_not = std::move(text);
    return std::nullopt;
}

bool failed(std::string* why_not, std::string text)
{
    if (why_not) *why_not = std::move(text);
    return false;
}

// A file someone else owns was not written by us (nor, for a seed, by the
// installer); do not hand it to the driver.
bool owned_by_this_user(const fs::path& file, bool or_root)
{
    struct stat status {};
    return ::stat(file.c_str(), &status) == 0 && (status.st_uid == ::geteuid() || (or_root && status.st_uid == 0));
}

// One read of the file's size, not a byte at a time: a warm run reads a
// binary of 50 to 150 KB per program.
std::optional<std::vector<unsigned char>> read_whole_file(const fs::path& file)
{
    std::ifstream in(file, std::ios::binary | std::ios::ate);
    if (!in) return std::nullopt;
    const std::streamoff size = in.tellg();
    if (size < 0 || !in.seekg(0)) return std::nullopt;
    std::vector<unsigned char> bytes(static_cast<std::size_t>(size));
    if (!in.read(reinterpret_cast<char*>(bytes.data()), size)) return std::nullopt;
    return bytes;
}

// Why `bytes` is not a valid cache file for `key`, or empty when it is.
std::string validate(std::span<const unsigned char> bytes, std::uint64_t key)
{
    FileHeader header;
    if (bytes.size() < sizeof header) return "shorter than its header";
    std::memcpy(&header, bytes.data(), sizeof header);
    const auto payload = bytes.subspan(sizeof header);
    if (header.magic != file_magic) return "not a penumbra program cache file";
    if (header.key != key) return "written for another key";
    if (header.payload_size == 0 || header.payload_size != payload.size()) return "truncated or padded";
    if (header.payload_checksum != checksum(payload)) return "checksum mismatch (corrupt)";
    return {};
}

std::atomic<unsigned> temporary_counter{0};

}  // namespace

ProgramCache::ProgramCache(fs::path directory) : directory_(std::move(directory)) {}

ProgramCache ProgramCache::in_default_directory()
{
    return ProgramCache(fs::path(cache_directory()) / "binaries");
}

ProgramCache ProgramCache::seed(fs::path directory)
{
    ProgramCache seed(std::move(directory));
    seed.root_may_own_ = true;
    return seed;
}

fs::path ProgramCache::file_for(std::uint64_t key) const
{
    return directory_ / (hex(key) + ".bin");
}

std::optional<std::vector<unsigned char>> ProgramCache::load(std::uint64_t key,
                                                             std::string* why_not) const
{
    if (!enabled()) return miss(why_not, "cache disabled");
    try {
        const fs::path file = file_for(key);
        auto bytes = read_whole_file(file);
        if (!bytes) return miss(why_not, "no cached binary " + file.string());
        if (!owned_by_this_user(file, root_may_own_))
            return miss(why_not, file.string() + " is owned by another user");
        if (std::string problem = validate(*bytes, key); !problem.empty())
            return miss(why_not, file.string() + ": " + problem);
        bytes->erase(bytes->begin(), bytes->begin() + sizeof(FileHeader));
        return bytes;
    } catch (const std::exception& error) {
        return miss(why_not, error.what());
    }
}

bool ProgramCache::store(std::uint64_t key, std::span<const unsigned char> binary,
                         std::string* why_not) const
{
    if (!enabled()) return failed(why_not, "cache disabled");
    if (binary.empty()) return failed(why_not, "the driver returned an empty binary");
    try {
        std::error_code error;
        create_private_directories(directory_, error);
        if (error) return failed(why_not, directory_.string() + ": " + error.message());

        const fs::path final_file = file_for(key);
        fs::path temporary = final_file;
        temporary += ".tmp." + std::to_string(::getpid()) + "." + std::to_string(temporary_counter++);

        const FileHeader header{file_magic, key, binary.size(), checksum(binary)};
        {
            std::ofstream out(temporary, std::ios::binary | std::ios::trunc);
            out.write(reinterpret_cast<const char*>(&header), sizeof header);
            out.write(reinterpret_cast<const char*>(binary.data()), static_cast<std::streamsize>(binary.size()));
            out.close();
            if (!out) {
                fs::remove(temporary, error);
                return failed(why_not, "could not write " + temporary.string());
            }
        }
        // No fsync: after a crash the file may be empty or short, which load()
        // detects and treats as a miss, so durability buys nothing here.
        fs::rename(temporary, final_file, error);
        if (error) {
            std::string problem = "could not rename to " + final_file.string() + ": " + error.message();
            fs::remove(temporary, error);
            return failed(why_not, std::move(problem));
        }
        return true;
    } catch (const std::exception& error) {
        return failed(why_not, error.what());
    }
}

}  // namespace penumbra::cl_backend
