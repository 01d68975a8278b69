#include "support/backend_list.h"

#include <set>

#include "simd/cpu_kernels.h"

namespace penumbra::testing {

std::vector<std::string> cpu_backend_names()
{
    std::vector<std::string> names{"scalar"};
    for (std::string_view isa : cpu::supported_isas()) names.emplace_back(isa);
    return names;
}

std::vector<std::string> backend_names()
{
    std::vector<std::string> names = cpu_backend_names();
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

ContextOptions backend_options(const std::string& name)
{
    if (name == "scalar") return ContextOptions{Backend::Scalar, {}};
    if (name == "opencl") return ContextOptions{Backend::OpenCL, {}};
    return ContextOptions{Backend::Simd, name};
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
