// Creating the directory an option names (example --out, demo --out), with a
// one-line error naming the option and the path instead of a filesystem_error.
#pragma once

#include <filesystem>
#include <string>

namespace penumbra::cli {

// Creates `dir` and its parents; throws UsageError when a part of it is a
// regular file, cannot be created (permissions, /proc), or the name is unusable.
void create_output_directory(const std::filesystem::path& dir, const std::string& option);

}  // namespace penumbra::cli
