// A small command-line option reader for the penumbra tool: --name value
// pairs and --flag switches, with errors that name the option.
#pragma once

#include <map>
#include <optional>
#include <set>
#include <string>
#include <vector>

#include "penumbra/context.h"

namespace penumbra::cli {

// Thrown for bad usage; main() prints it as one line and exits with 2.
struct UsageError {
    std::string message;
};

class Args {
public:
    // `valued` options take a value, `flags` do not; anything else is an error.
    Args(const std::vector<std::string>& argv, const std::set<std::string>& valued, const std::set<std::string>& flags);

    bool flag(const std::string& name) const { return flags_.count(name) != 0; }
    std::optional<std::string> get(const std::string& name) const;
    std::string required(const std::string& name) const;
    std::string text(const std::string& name, const std::string& fallback) const;
    int integer(const std::string& name, int fallback) const;
    float number(const std::string& name, float fallback) const;

private:
    std::map<std::string, std::string> values_;
    std::set<std::string> flags_;
};

// The --backend option (default auto), its error as a UsageError.
Backend backend_option(const Args& args);

}  // namespace penumbra::cli
