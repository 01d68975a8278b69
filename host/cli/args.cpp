#include "args.h"

#include <cmath>
#include <cstdlib>

#include "penumbra/error.h"

namespace penumbra::cli {

Args::Args(const std::vector<std::string>& argv, const std::set<std::string>& valued,
           const std::set<std::string>& flags)
{
    for (std::size_t i = 0; i < argv.size(); ++i) {
        const std::string& word = argv[i];
        if (flags.count(word)) {
            flags_.insert(word);
        } else if (valued.count(word)) {
            if (i + 1 >= argv.size()) throw UsageError{"option " + word + " needs a value"};
            if (values_.count(word)) throw UsageError{"option " + word + " is given twice"};
            values_[word] = argv[++i];
        } else {
            throw UsageError{"unknown option or argument '" + word + "' (see --help)"};
        }
    }
}

std::optional<std::string> Args::get(const std::string& name) const
{
    auto it = values_.find(name);
    if (it == values_.end()) return std::nullopt;
    return it->second;
}

std::string Args::required(const std::string& name) const
{
    auto value = get(name);
    if (!value || value->empty()) throw UsageError{"option " + name + " is required"};
    return *value;
}

std::string Args::text(const std::string& name, const std::string& fallback) const
{
    return get(name).value_or(fallback);
}

int Args::integer(const std::string& name, int fallback) const
{
    auto value = get(name);
    if (!value) return fallback;
    char* end = nullptr;
    const long parsed = std::strtol(value->c_str(), &end, 10);
    if (value->empty() || *end != '\0' || parsed < -1000000000L || parsed > 1000000000L)
        throw UsageError{"option " + name + ": '" + *value + "' is not an integer"};
    return int(parsed);
}

float Args::number(const std::string& name, float fallback) const
{
    auto value = get(name);
    if (!value) return fallback;
    char* end = nullptr;
    const float parsed = std::strtof(value->c_str(), &end);
    if (value->empty() || *end != '\0' || !std::isfinite(parsed))
        throw UsageError{"option " + name + ": '" + *value + "' is not a finite number"};
    return parsed;
}

Backend backend_option(const Args& args)
{
    try {
        return parse_backend(args.text("--backend", "auto"));
    } catch (const Error& e) {
        throw UsageError{std::string(e.what())};
    }
}

}  // namespace penumbra::cli
