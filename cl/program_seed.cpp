#include "cl/program_seed.h"

#include <dlfcn.h>

#include <cstdlib>
#include <filesystem>

#include "cl/program_cache.h"

namespace penumbra::cl_backend {

std::string seed_directory()
{
    if (const char* chosen = std::getenv("PENUMBRA_CL_SEED_DIR")) return chosen;
    // The library's own file: dladdr of a function it defines.
    Dl_info info{};
    if (::dladdr(reinterpret_cast<void*>(&seed_directory), &info) == 0 || !info.dli_fname) return {};
    std::error_code error;
    const std::filesystem::path library = std::filesystem::canonical(info.dli_fname, error);
    if (error) return {};
    return (library.parent_path() / kSeedFolderName).string();
}

ProgramCache ProgramCache::installed_seed()
{
    const std::string directory = seed_directory();
    return directory.empty() ? ProgramCache() : seed(directory);
}

}  // namespace penumbra::cl_backend
