// What this machine offers penumbra: for `penumbra info` and for users who
// want to log their configuration.
#pragma once

#include <string>
#include <vector>

namespace penumbra {

struct OpenClDeviceSummary {
    std::string platform, platform_version, name, version, driver, type;
    unsigned compute_units = 0;
};

struct SystemInfo {
    std::string version;
    std::vector<std::string> cpu_isas;   // ISAs this CPU runs (sse4.2, avx2, avx512)
    std::string chosen_isa;              // the SIMD backend's (PENUMBRA_SIMD_ISA or the best)
    std::string isa_reason;
    std::vector<OpenClDeviceSummary> opencl_devices;
    std::string opencl_problem;          // why there are none, if so
    bool opencl_built = false;           // this build has the OpenCL backend
    std::vector<std::string> backends;   // available here: scalar, simd, opencl
    std::string auto_backend, auto_description, auto_reason;
    std::vector<std::string> auto_warnings;
    std::string cache_directory;         // OpenCL program binaries (and PoCL's cache)
    std::string seed_directory;          // OpenCL binaries made at build time, read when the cache misses
    int seed_programs = 0;               // how many it holds
    // With `measure_opencl_build`: an OpenCL context was started and its
    // program built; the time in seconds (or the error that stopped it).
    double opencl_build_seconds = -1.0;
    std::string opencl_build_error;
};

SystemInfo describe_system(bool measure_opencl_build);

}  // namespace penumbra
