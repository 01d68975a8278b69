// Runs the `penumbra` tool without a shell (argv passed as is, so no test
// depends on quoting), with a time limit and extra environment variables.
#pragma once

#include <map>
#include <string>
#include <vector>

namespace penumbra::testing {

struct CliRun {
    int exit_code = -1;    // when it exited
    int signal = 0;        // when a signal ended it
    bool timed_out = false;
    std::string out, err;  // what it wrote

    bool refused_cleanly() const;  // exit 2, exactly one line on stderr
};

// `environment` entries are set (or, with an empty value, unset) in the child.
CliRun run_cli(const std::vector<std::string>& args, const std::map<std::string, std::string>& environment = {},
               double timeout_seconds = 60.0);

}  // namespace penumbra::testing
