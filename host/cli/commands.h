// The subcommands of the `penumbra` tool. Each returns the process exit status;
// bad input throws penumbra::Error or cli::UsageError, which main() reports.
#pragma once

#include <string>
#include <vector>

namespace penumbra::cli {

int info_command(const std::vector<std::string>& args);
int shade_command(const std::vector<std::string>& args);
int example_command(const std::vector<std::string>& args);

}  // namespace penumbra::cli
