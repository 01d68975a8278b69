// OpenCL C sources for the runtime's tests (tests/host/opencl_runtime_test.cpp,
// opencl_seed_test.cpp): a kernel whose result is easy to check, and sources
// no cache has seen, so that their first build is a cold one; and the reason
// those tests skip on a machine without a device.
#pragma once

#include <unistd.h>

#include <chrono>
#include <string>

#include "cl/opencl_runtime.h"

namespace penumbra::testing {

inline const std::string add1_source = "kernel void add1(global float* a){ a[get_global_id(0)] += 1.0f; }\n";

// A first line unique per process and call. A declaration, not a comment:
// PoCL keys its cache on the preprocessed source, which has no comments.
inline std::string unique_line()
{
    static int counter = 0;
    const auto now = std::chrono::system_clock::now().time_since_epoch().count();
    return "constant int pn_unique_" + std::to_string(::getpid()) + "_" + std::to_string(now) + "_" +
           std::to_string(++counter) + " = 0;\n";
}

// add1 under a text that no cache (ours or PoCL's) holds yet.
inline std::string never_built_source() { return unique_line() + add1_source; }

// Empty when this machine has an OpenCL device, else the skip message.
inline std::string why_no_opencl_device()
{
    static const cl_backend::DeviceList list = cl_backend::list_devices();
    return list.devices.empty() ? "no OpenCL device on this machine (" + list.problem + "); test not run" : "";
}

}  // namespace penumbra::testing
