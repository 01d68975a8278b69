#include "support/backends.h"

#include <map>
#include <memory>
#include <stdexcept>

#include "penumbra/error.h"

namespace penumbra::testing {

Context* shared_context(const std::string& name, std::string* why)
{
    struct Entry {
        std::unique_ptr<Context> context;
        std::string why;    // unavailable here: tests skip
        std::string error;  // failed to start for another reason: tests fail
    };
    static std::map<std::string, Entry> contexts;
    auto [it, inserted] = contexts.try_emplace(name);
    if (inserted) {
        try {
            it->second.context = std::make_unique<Context>(backend_options(name));
        } catch (const Error& e) {
            (e.category() == ErrorCategory::Unavailable ? it->second.why : it->second.error) = e.what();
        }
    }
    if (!it->second.error.empty()) throw std::runtime_error("backend " + name + " failed to start: " + it->second.error);
    if (why) *why = it->second.why;
    return it->second.context.get();
}

std::string backend_test_name(const ::testing::TestParamInfo<std::string>& info)
{
    std::string name = info.param;
    for (char& c : name)
        if (c == '.') c = '_';
    return name;
}

}  // namespace penumbra::testing
