#include "cl/opencl_backend.h"

#include "cl/opencl_device_queue.h"

namespace penumbra::cl_backend {

OpenClBackend::OpenClBackend(bool non_cpu_only)
    : runtime_(non_cpu_only ? DeviceChoice::NonCpuOnly : DeviceChoice::Any)
{
}

OpenClBackend::OpenClBackend(cl_context context, cl_command_queue queue) : runtime_(context, queue) {}

OpenClBackend::~OpenClBackend() = default;

detail::DeviceQueue* OpenClBackend::device_queue()
{
    if (!device_queue_) device_queue_ = std::make_unique<OpenClDeviceQueue>(*this);
    return device_queue_.get();
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

std::unique_ptr<detail::BackendImpl> make_opencl_backend(cl_context context, cl_command_queue queue)
{
    return std::make_unique<OpenClBackend>(context, queue);
}

}  // namespace penumbra::cl_backend
