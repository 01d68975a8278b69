#include "output_directory.h"

#include <system_error>

#include "args.h"

namespace penumbra::cli {

void create_output_directory(const std::filesystem::path& dir, const std::string& option)
{
    namespace fs = std::filesystem;
    const std::string where = "option " + option + ": '" + dir.string() + "'";
    // Create first, then look: a check before creating races with a
    // concurrent run that creates the same folder between the two (it then
    // looked like "exists and is not a directory").
    std::error_code error;
    fs::create_directories(dir, error);
    std::error_code ignored;
    if (fs::is_directory(dir, ignored)) return;  // made here, by a concurrent run, or already there
    if (fs::exists(fs::symlink_status(dir, ignored)))
        throw UsageError{where + " exists and is not a directory; give a directory"};
    throw UsageError{where + " cannot be created as a directory (" +
                     (error ? error.message() : std::string("not a directory")) +
                     "); give a directory you may write to"};
}

}  // namespace penumbra::cli
