#include "cl/opencl_backend.h"

namespace penumbra::cl_backend {

OpenClBackend::OpenClBackend(bool non_cpu_only)
    : runtime_(non_cpu_only ? DeviceChoice::NonCpuOnly : DeviceChoice::Any)
{
}

std::string OpenClBackend::description() const
{
    const DeviceInfo& d = runtime_.device_info();
    return "opencl (" + d.platform_name + ": " + d.device_name + ", " + d.type + ")";
}

bool has_non_cpu_device()
{
    for (const DeviceInfo& device : list_devices().devices)
        if (!device.is_cpu) return true;
    return false;
}

std::unique_ptr<detail::BackendImpl> make_opencl_backend(bool non_cpu_only)
{
    return std::make_unique<OpenClBackend>(non_cpu_only);
}

}  // namespace penumbra::cl_backend
