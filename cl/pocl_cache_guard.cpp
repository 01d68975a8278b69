// PoCL cache manifest: check before use, record after (pocl_cache_guard.h).
#include "cl/pocl_cache_guard.h"

#include <unistd.h>

#include <cstdint>
#include <cstdio>
#include <fstream>
#include <map>
#include <mutex>
#include <sstream>
#include <system_error>

namespace penumbra::cl_backend {
namespace {

namespace fs = std::filesystem;

struct Entry {
    std::uintmax_t size = 0;
    std::uint64_t hash = 0;
};
using Manifest = std::map<std::string, Entry>;  // path relative to the pocl folder

// 64-bit FNV-1a of a file's bytes; nullopt-like false when it cannot be read.
bool hash_file(const fs::path& file, std::uint64_t& hash)
{
    std::ifstream in(file, std::ios::binary);
    if (!in) return false;
    hash = 14695981039346656037ull;
    char buffer[1 << 16];
    while (in) {
        in.read(buffer, sizeof buffer);
        for (std::streamsize i = 0; i < in.gcount(); ++i) {
            hash ^= static_cast<unsigned char>(buffer[i]);
            hash *= 1099511628211ull;
        }
    }
    return !in.bad();
}

bool listed(const fs::path& relative)
{
    const std::string name = relative.filename().string();
    return name != "last_accessed" && name.rfind("tempfile_", 0) != 0;
}

bool read_manifest(const fs::path& manifest, Manifest& entries)
{
    std::ifstream in(manifest);
    if (!in) return false;
    std::string line;
    if (!std::getline(in, line) || line != "penumbra pocl manifest v1") return false;
    while (std::getline(in, line)) {
        std::istringstream fields(line);
        Entry entry;
        std::string path;
        fields >> entry.size >> std::hex >> entry.hash >> std::ws;
        std::getline(fields, path);
        if (!fields.eof() && fields.fail()) return false;
        if (path.empty()) return false;
        entries[path] = entry;
    }
    return true;
}

// Why `pocl_dir` does not match `entries`, or empty when it does.
std::string first_mismatch(const fs::path& pocl_dir, const Manifest& entries)
{
    for (const auto& [path, entry] : entries) {
        const fs::path file = pocl_dir / path;
        std::error_code error;
        const std::uintmax_t size = fs::file_size(file, error);
        if (error) return file.string() + " is missing";
        if (size != entry.size)
            return file.string() + " is " + std::to_string(size) + " bytes, was " + std::to_string(entry.size);
        std::uint64_t hash = 0;
        if (!hash_file(file, hash)) return file.string() + " cannot be read";
        if (hash != entry.hash) return file.string() + " has changed (its checksum differs)";
    }
    return {};
}

bool has_files(const fs::path& dir)
{
    std::error_code error;
    for (fs::recursive_directory_iterator it(dir, error), end; !error && it != end; it.increment(error))
        if (it->is_regular_file(error) && listed(it->path().lexically_relative(dir))) return true;
    return false;
}

// Moves the folder aside first, so that another process never sees it half deleted.
void clear_folder(const fs::path& pocl_dir)
{
    std::error_code error;
    fs::path aside = pocl_dir;
    aside += ".damaged-" + std::to_string(::getpid());
    fs::rename(pocl_dir, aside, error);
    // If the rename failed, another process has just moved it aside itself.
    if (!error) fs::remove_all(aside, error);
    fs::create_directories(pocl_dir, error);
    fs::permissions(pocl_dir, fs::perms::owner_all, error);
}

// True when `manifest` already holds `text`.
bool unchanged(const fs::path& manifest, const std::string& text)
{
    std::ifstream in(manifest, std::ios::binary);
    std::string held(text.size() + 1, '\0');  // one byte more: a longer file differs
    in.read(held.data(), std::streamsize(held.size()));
    return in.gcount() == std::streamsize(text.size()) && held.compare(0, text.size(), text) == 0;
}

// The entries the last check verified, so that recording need not hash them again.
std::mutex g_mutex;
Manifest g_verified;

}  // namespace

PoclCacheCheck check_pocl_cache(const fs::path& pocl_dir, const fs::path& manifest) noexcept
{
    PoclCacheCheck result;
    try {
        Manifest entries;
        std::string problem;
        const bool had_manifest = read_manifest(manifest, entries);
        if (had_manifest) problem = first_mismatch(pocl_dir, entries);
        else if (has_files(pocl_dir)) problem = "it has no valid manifest " + manifest.string();
        if (problem.empty()) {
            {
                const std::lock_guard lock(g_mutex);
                g_verified = std::move(entries);
            }
            // A manifest at once, even an empty one: a process starting while
            // this one fills the folder must not take it for an unrecorded one.
            if (!had_manifest) record_pocl_cache(pocl_dir, manifest);
            return result;
        }
        clear_folder(pocl_dir);
        record_pocl_cache(pocl_dir, manifest);
        result.repaired = true;
        result.warning = "the PoCL kernel cache " + pocl_dir.string() + " was damaged (" + problem +
                         ") and has been cleared; OpenCL programs are rebuilt from source this once";
    } catch (...) {
        // Out of memory composing a message: leave the cache as it is.
    }
    return result;
}

void record_pocl_cache(const fs::path& pocl_dir, const fs::path& manifest) noexcept
{
    try {
        Manifest verified;
        {
            const std::lock_guard lock(g_mutex);
            verified = g_verified;
        }
        std::ostringstream text;
        text << "penumbra pocl manifest v1\n";
        std::error_code error;
        for (fs::recursive_directory_iterator it(pocl_dir, error), end; !error && it != end; it.increment(error)) {
            std::error_code status_error;
            if (!it->is_regular_file(status_error)) continue;
            const fs::path relative = it->path().lexically_relative(pocl_dir);
            if (!listed(relative)) continue;
            Entry entry;
            entry.size = it->file_size(status_error);
            if (status_error) continue;
            const auto known = verified.find(relative.string());
            if (known != verified.end() && known->second.size == entry.size) entry.hash = known->second.hash;
            else if (!hash_file(it->path(), entry.hash)) continue;
            text << entry.size << ' ' << std::hex << entry.hash << std::dec << ' ' << relative.string() << '\n';
        }
        if (error || unchanged(manifest, text.str())) return;  // a warm run: nothing to write
        fs::path temporary = manifest;
        temporary += ".tmp-" + std::to_string(::getpid());
        {
            std::ofstream out(temporary, std::ios::binary | std::ios::trunc);
            out << text.str();
            out.close();
            if (!out) {
                fs::remove(temporary, error);
                return;
            }
        }
        fs::rename(temporary, manifest, error);
        if (error) fs::remove(temporary, error);
    } catch (...) {
        // Best effort: without a record the next run checks the older one.
    }
}

}  // namespace penumbra::cl_backend
