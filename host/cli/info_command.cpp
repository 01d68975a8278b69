// penumbra info: what this machine offers and what Auto chooses, as text or JSON.
#include <iostream>
#include <nlohmann/json.hpp>

#include "args.h"
#include "commands.h"
#include "penumbra/system_info.h"

namespace penumbra::cli {
namespace {

nlohmann::json to_json(const SystemInfo& info)
{
    nlohmann::json devices = nlohmann::json::array();
    for (const OpenClDeviceSummary& d : info.opencl_devices)
        devices.push_back({{"platform", d.platform}, {"platform_version", d.platform_version}, {"name", d.name},
                           {"version", d.version}, {"driver", d.driver}, {"type", d.type},
                           {"compute_units", d.compute_units}});
    nlohmann::json j = {
        {"version", info.version},
        {"backends", info.backends},
        {"auto", {{"backend", info.auto_backend}, {"description", info.auto_description}, {"reason", info.auto_reason},
                  {"warnings", info.auto_warnings}}},
        {"cpu", {{"isas", info.cpu_isas}, {"chosen_isa", info.chosen_isa}, {"isa_reason", info.isa_reason}}},
        {"opencl", {{"built", info.opencl_built}, {"devices", devices}, {"problem", info.opencl_problem},
                    {"cache_directory", info.cache_directory}, {"seed_directory", info.seed_directory},
                    {"seed_programs", info.seed_programs}}},
    };
    if (info.opencl_build_seconds >= 0) j["opencl"]["program_build_seconds"] = info.opencl_build_seconds;
    if (!info.opencl_build_error.empty()) j["opencl"]["program_build_error"] = info.opencl_build_error;
    return j;
}

void print_text(const SystemInfo& info)
{
    std::cout << "penumbra " << info.version << "\n";
    std::cout << "backends available: ";
    for (std::size_t i = 0; i < info.backends.size(); ++i) std::cout << (i ? ", " : "") << info.backends[i];
    std::cout << "\nauto chooses: " << info.auto_description << "\n  because " << info.auto_reason << "\n";
    for (const std::string& w : info.auto_warnings) std::cout << "  warning: " << w << "\n";
    std::cout << "cpu ISAs: ";
    for (std::size_t i = 0; i < info.cpu_isas.size(); ++i) std::cout << (i ? ", " : "") << info.cpu_isas[i];
    std::cout << "\nsimd ISA in use: " << info.chosen_isa << " (" << info.isa_reason << ")\n";
    std::cout << "opencl devices:" << (info.opencl_devices.empty() ? " none (" + info.opencl_problem + ")" : "") << "\n";
    for (const OpenClDeviceSummary& d : info.opencl_devices)
        std::cout << "  " << d.platform << " (" << d.platform_version << "): " << d.name << " [" << d.type << ", "
                  << d.compute_units << " compute units, " << d.version << ", driver " << d.driver << "]\n";
    if (!info.cache_directory.empty()) std::cout << "opencl program cache: " << info.cache_directory << "\n";
    if (!info.seed_directory.empty())
        std::cout << "opencl program seed: " << info.seed_directory << " (" << info.seed_programs << " programs)\n";
    if (info.opencl_build_seconds >= 0)
        std::cout << "opencl program build: " << info.opencl_build_seconds << " s\n";
    if (!info.opencl_build_error.empty()) std::cout << "opencl program build failed: " << info.opencl_build_error << "\n";
}

}  // namespace

int info_command(const std::vector<std::string>& argv)
{
    const Args args(argv, {}, {"--json", "--verbose", "--help"});
    if (args.flag("--help")) {
        std::cout << "usage: penumbra info [--json] [--verbose]\n"
                     "  --verbose also starts the OpenCL backend and reports its program build time\n";
        return 0;
    }
    const SystemInfo info = describe_system(args.flag("--verbose"));
    if (args.flag("--json")) std::cout << to_json(info).dump(2) << "\n";
    else print_text(info);
    return 0;
}

}  // namespace penumbra::cli
