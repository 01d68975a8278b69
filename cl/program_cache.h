// Where compiled OpenCL programs are kept between runs, and our own binary cache.
//
// Two caches live under one directory (cache_directory()):
//  - pocl/      PoCL's own kernel cache. PoCL reads POCL_CACHE_DIR once, when the
//               ICD loader first initialises it, so prepare_driver_cache_environment()
//               must run before the first OpenCL call of the process; every entry
//               point of opencl_runtime.h calls it. A user's POCL_CACHE_DIR wins.
//  - binaries/  clGetProgramInfo(CL_PROGRAM_BINARIES) of each program we built, as
//               <16 hex digits>.bin, so that drivers without a cache of their own
//               (most GPU drivers) also skip the front end on the second run.
//
// The key hashes everything that changes the binary: source, options, device,
// device and driver versions, platform and platform version (STYLE.md, "Not to
// copy": a cache keyed on the device name alone serves stale code after a driver
// update). The hash is 64-bit FNV-1a: fast and stable across runs and compilers.
// It is not collision resistant and need not be: the directory belongs to the
// user, and whoever can write there can already replace what we run, so the hash
// only has to avoid accidental collisions (about n^2 / 2^65 for n programs).
//
// Drivers do not validate binaries: PoCL 3.1 segfaults on a truncated or altered
// one (measured here). Each file therefore carries a header with the key, the
// payload size and a checksum, and load() hands the driver only a payload that
// matches them; anything else is a cache miss, never an error.
#pragma once

#include <cstdint>
#include <filesystem>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

namespace penumbra::cl_backend {

// The root of penumbra's caches: $PENUMBRA_CACHE_DIR, else $XDG_CACHE_HOME/penumbra,
// else $HOME/.cache/penumbra, else /tmp/penumbra-cache-<uid> (per user, because a
// directory shared with other users would let them plant binaries we then run).
std::string cache_directory();

// The directory PoCL uses: $POCL_CACHE_DIR once prepare_driver_cache_environment()
// has run (ours, or the one the user set).
std::string pocl_cache_directory();

// Sets POCL_CACHE_DIR to cache_directory()/pocl unless the user set it. Runs once
// per process (later calls do nothing) and never throws; call it before any
// OpenCL call. It changes the environment, so it must not race with threads that
// read the environment: the first OpenCL use is early enough in practice.
void prepare_driver_cache_environment() noexcept;

// Why the driver cache folder cannot be used (it cannot be created, is not a
// directory, or is read-only), naming it and PENUMBRA_CACHE_DIR; empty when it
// can, or when the user chose POCL_CACHE_DIR.
std::string driver_cache_problem();

// The one warning of the PoCL cache check (pocl_cache_guard.h): empty unless
// the folder was found damaged and cleared at the start of this process.
std::string driver_cache_warning();

// Records PoCL's cache files in the manifest now (after a program build; also
// done at exit), so that a crash later in the run still leaves a record.
void record_driver_cache();

// Holds, for its scope, an advisory lock (flock) on cache_directory()/pocl.lock
// that every penumbra process and thread sharing the cache folder takes while
// it checks, builds into, packs binaries from or records PoCL's cache. PoCL
// 3.1 keys its cache on the preprocessed source and packs a program binary
// from that folder's files, so two processes building the same program at
// once (two runs started together, ctest -j2 on a cold cache) could pack one
// another's half-written files: an abort in pocl_binary_get_kernels_metadata
// (`len > 0`) seen once in CI's fresh-machine run. Without a usable folder it
// holds nothing and the build goes on unserialised. Not reentrant: never nest two.
class DriverCacheLock {
public:
    DriverCacheLock() noexcept;
    ~DriverCacheLock();
    DriverCacheLock(const DriverCacheLock&) = delete;
    DriverCacheLock& operator=(const DriverCacheLock&) = delete;

private:
    int fd_ = -1;
};

// Everything that decides what a program binary contains.
struct ProgramIdentity {
    std::string_view source;
    std::string_view options;
    std::string_view device_name;
    std::string_view device_version;
    std::string_view driver_version;
    std::string_view platform_name;
    std::string_view platform_version;
    // The launches' local sizes (cl/opencl_work_groups.h): a binary holds the
    // work-group functions of the sizes it was launched with.
    std::string_view work_groups;
};

std::uint64_t program_key(const ProgramIdentity& identity);

// A directory of program binaries. A default-constructed cache is disabled: it
// loads nothing and stores nothing.
class ProgramCache {
public:
    ProgramCache() = default;
    explicit ProgramCache(std::filesystem::path directory);

    // cache_directory()/binaries
    static ProgramCache in_default_directory();
    // The binaries made at build time (cl/program_seed.h): read when the user's
    // cache misses, never written at run time. Its files may be owned by root
    // (a package's install) as well as by this user.
    static ProgramCache seed(std::filesystem::path directory);
    // seed(seed_directory()), or a disabled cache when there is none.
    static ProgramCache installed_seed();

    bool enabled() const { return !directory_.empty(); }
    const std::filesystem::path& directory() const { return directory_; }
    std::filesystem::path file_for(std::uint64_t key) const;

    // The binary stored under `key`, or nothing when there is none or the file is
    // unreadable, truncated, or fails its checksum; `why_not` (if given) says which.
    std::optional<std::vector<unsigned char>> load(std::uint64_t key,
                                                   std::string* why_not = nullptr) const;

    // Writes atomically (a temporary file, then rename), so a reader never sees a
    // half-written file and concurrent writers of one key do not clash. Returns
    // false, saying why in `why_not`, when it could not write; never throws.
    bool store(std::uint64_t key, std::span<const unsigned char> binary,
               std::string* why_not = nullptr) const;

private:
    std::filesystem::path directory_;
    bool root_may_own_ = false;  // a seed's files may be the installer's
};

}  // namespace penumbra::cl_backend
