#include "output_directory.h"

#include <system_error>

#include "args.h"

namespace penumbra::cli {

void create_output_directory(const std::filesystem::path& dir, const std::string& option)
{
    namespace fs = std::filesystem;
    const std::string where = "option " + option + ": '" + dir.string() + "'";
    std::error_code error;
    if (fs::is_directory(dir, error)) return;
    if (fs::exists(fs::symlink_status(dir, error)))
        throw UsageError{where + " exists and is not a directory; give a directory"};
    fs::create_directories(dir, error);
    if (error || !fs::is_directory(dir))
        throw UsageError{where + " cannot be created as a directory (" +
                         (error ? error.message() : std::string("not a directory")) +
                         "); give a directory you may write to"};
}

}  // namespace penumbra::cli
