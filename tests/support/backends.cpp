#include "support/backends.h"

#include <map>
#include <memory>
#include <set>
#include <stdexcept>

#include "penumbra/error.h"
#include "simd/cpu_kernels.h"

namespace penumbra::testing {

std::vector<std::string> backend_names()
{
    std::vector<std::string> names{"scalar"};
    for (std::string_view isa : cpu::supported_isas()) names.emplace_back(isa);
    names.emplace_back("opencl");
    return names;
}

std::vector<std::string> non_scalar_backends()
{
    std::vector<std::string> names = backend_names();
    names.erase(names.begin());  // "scalar", the oracle
    return names;
}

int backend_lanes(const std::string& name)
{
    if (name == "scalar" || name == "opencl") return 1;
    return cpu::kernels_for(name).lanes;
}

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
        ContextOptions options;
        if (name == "scalar") options.backend = Backend::Scalar;
        else if (name == "opencl") options.backend = Backend::OpenCL;
        else {
            options.backend = Backend::Simd;
            options.simd_isa = name;
        }
        try {
            it->second.context = std::make_unique<Context>(options);
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

std::vector<int> lane_edge_widths()
{
    std::set<int> widths{1};
    for (std::string_view isa : cpu::supported_isas()) {
        const int n = cpu::kernels_for(isa).lanes;
        for (int w : {n - 1, n, n + 1, 3 * n + 1})
            if (w > 0) widths.insert(w);
    }
    return {widths.begin(), widths.end()};
}

}  // namespace penumbra::testing
