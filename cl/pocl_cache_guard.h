// Guards PoCL's kernel cache (cache_directory()/pocl, program_cache.h) against
// damage from outside: PoCL trusts its files, and an emptied, truncated or
// zeroed program.bc makes it abort (SIGABRT), a kernel .so with flipped bits
// makes it crash (SIGSEGV), in every later run (issue 11, measured with PoCL 3.1).
//
// After a run, a manifest (cache_directory()/pocl.manifest) records the size
// and a 64-bit FNV-1a hash of every file PoCL wrote. Before the first OpenCL
// call of the next process, every file the manifest lists is checked; on any
// mismatch, or a non-empty folder without a manifest, the whole pocl/ folder is
// moved aside and deleted, so PoCL rebuilds from source, and one warning says so.
// Files that appeared after the manifest was written are not checked until the
// next manifest covers them: PoCL 3.1 appears to write through temporaries
// (its `tempfile_*` files) renamed into place, so only damage after the fact
// should spoil one; that gap remains. PoCL's `last_accessed`
// stamps and `tempfile_*` leftovers change on their own and are not listed.
// Only the folder penumbra chose is guarded: a POCL_CACHE_DIR the user set is
// the user's.
#pragma once

#include <filesystem>
#include <string>

namespace penumbra::cl_backend {

struct PoclCacheCheck {
    bool repaired = false;  // the folder was damaged and has been cleared
    std::string warning;    // what was wrong, for Context::warnings(); empty when all was well
};

// Checks `pocl_dir` against `manifest` and clears it when damaged. Never throws.
PoclCacheCheck check_pocl_cache(const std::filesystem::path& pocl_dir, const std::filesystem::path& manifest) noexcept;

// Records the current files of `pocl_dir` in `manifest` (atomically: a
// temporary, then rename). Files whose size matches the entry the last check
// verified are not hashed again. Never throws; a failure only skips the record.
void record_pocl_cache(const std::filesystem::path& pocl_dir, const std::filesystem::path& manifest) noexcept;

}  // namespace penumbra::cl_backend
