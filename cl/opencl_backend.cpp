#include "cl/opencl_backend.h"

#include "kernels/registry.h"

namespace penumbra::cl_backend {

OpenClBackend::OpenClBackend(bool non_cpu_only)
    : runtime_(non_cpu_only ? DeviceChoice::NonCpuOnly : DeviceChoice::Any)
{
    program_ = runtime_.build(kEmbeddedProgramSource, kProgramOptions);
    build_seconds_ = runtime_.last_build_seconds();
    translate_cl_errors([&] {
        for (const std::string& name : registry_kernel_names()) kernels_[name] = cl::Kernel(program_, name.c_str());
    });
}

std::string OpenClBackend::description() const
{
    const DeviceInfo& d = runtime_.device_info();
    return "opencl (" + d.platform_name + ": " + d.device_name + ", " + d.type + ")";
}

std::size_t image_bytes(const Image& image) { return image.plane_pitch() * image.channels() * sizeof(float); }

cl::Buffer wrap(const cl::Context& context, const void* data, std::size_t bytes, cl_mem_flags access)
{
    return cl::Buffer(context, access | CL_MEM_USE_HOST_PTR, bytes, const_cast<void*>(data));
}

cl::Buffer zeros(const cl::Context& context, std::size_t bytes)
{
    std::vector<unsigned char> zero(bytes, 0);
    return cl::Buffer(context, CL_MEM_READ_WRITE | CL_MEM_COPY_HOST_PTR, bytes, zero.data());
}

cl::Buffer table_origin(cl::Buffer& storage, const MomentTable& table, cl_mem_flags access)
{
    const std::size_t bytes = table.storage_elements() * 4;
    cl_buffer_region region{table.origin_offset_bytes(), bytes - table.origin_offset_bytes()};
    return storage.createSubBuffer(access, CL_BUFFER_CREATE_TYPE_REGION, &region);
}

void sync_to_host(const cl::CommandQueue& queue, const cl::Buffer& buffer, std::size_t bytes)
{
    void* mapped = queue.enqueueMapBuffer(buffer, CL_TRUE, CL_MAP_READ, 0, bytes);
    cl::Event done;
    queue.enqueueUnmapMemObject(buffer, mapped, nullptr, &done);
    done.wait();
}

void launch_pixels(const cl::CommandQueue& queue, cl::Kernel& kernel, int width, int height)
{
    queue.enqueueNDRangeKernel(kernel, cl::NullRange, cl::NDRange(std::size_t(width), std::size_t(height)));
}

std::vector<std::string> registry_kernel_names()
{
    std::vector<std::string> names;
#define PN_NAME(entry) names.emplace_back(#entry);
    PN_KERNEL_REGISTRY(PN_NAME)
#undef PN_NAME
    return names;
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
