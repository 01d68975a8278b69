// OpenCL launches of the kernel descriptions.
//
// Schedule: per-pixel kernels run one work-item per pixel (the driver picks the
// work-group size); the summed-area table runs bands of rows in parallel (one
// work-item scans a band) and then adds the bands' column totals below them
// (kernels/moment_table.h). Host images are wrapped with CL_MEM_USE_HOST_PTR so
// that a CPU driver such as PoCL works in place; results are read back
// through a map, which is free in that case.
#include "cl/opencl_backend.h"

#include <chrono>
#include <map>

#include "cl/opencl_runtime.h"
#include "kernels/registry.h"
#include "penumbra/error.h"

namespace penumbra::cl_backend {
namespace {

constexpr int kBandHeight = 32;

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

// Makes the host copy of a USE_HOST_PTR buffer current.
void sync_to_host(const cl::CommandQueue& queue, const cl::Buffer& buffer, std::size_t bytes)
{
    void* mapped = queue.enqueueMapBuffer(buffer, CL_TRUE, CL_MAP_READ, 0, bytes);
    cl::Event done;
    queue.enqueueUnmapMemObject(buffer, mapped, nullptr, &done);
    done.wait();
}

class OpenClBackend final : public detail::BackendImpl {
public:
    explicit OpenClBackend(bool non_cpu_only)
        : runtime_(non_cpu_only ? DeviceChoice::NonCpuOnly : DeviceChoice::Any)
    {
        program_ = runtime_.build(kEmbeddedProgramSource, kProgramOptions);
        build_seconds_ = runtime_.last_build_seconds();
        translate_cl_errors([&] {
            for (const std::string& name : registry_kernel_names()) kernels_[name] = cl::Kernel(program_, name.c_str());
        });
    }

    std::string description() const override
    {
        const DeviceInfo& d = runtime_.device_info();
        return "opencl (" + d.platform_name + ": " + d.device_name + ", " + d.type + ")";
    }
    double program_build_seconds() const override { return build_seconds_; }

    void build_moment_table(const Image& depth, MomentTable& table) override
    {
        translate_cl_errors([&] { build_table(depth, table); });
    }

    void chebyshev(detail::ChebyshevMethod method, const MomentTable& table, const Image& receivers,
                   const ChebyshevParams& p, Image& out) override
    {
        translate_cl_errors([&] { run_chebyshev(method, table, receivers, p, out); });
    }

private:
    cl::Kernel& kernel(const char* name) { return kernels_.at(name); }

    void build_table(const Image& depth, MomentTable& table)
    {
        const cl::Context& ctx = runtime_.context();
        const cl::CommandQueue& queue = runtime_.queue();
        const bool exact = table.precision() == Precision::Exact;
        const int bands = (depth.height() + kBandHeight - 1) / kBandHeight;
        SatParams p{};
        p.depth = detail::dims_of(depth);
        p.table = detail::dims_of(table);
        p.moments = table.moments();
        p.band_height = kBandHeight;
        p.columns = {depth.width(), bands, padded_pitch(depth.width()), padded_pitch(depth.width()) * bands};

        const std::size_t table_bytes = table.storage_elements() * 4;
        cl::Buffer depth_buf = wrap(ctx, depth.plane(0), image_bytes(depth), CL_MEM_READ_ONLY);
        cl::Buffer storage = wrap(ctx, table.storage(), table_bytes, CL_MEM_READ_WRITE);
        cl_buffer_region region{table.origin_offset_bytes(), table_bytes - table.origin_offset_bytes()};
        cl::Buffer origin = storage.createSubBuffer(CL_MEM_READ_WRITE, CL_BUFFER_CREATE_TYPE_REGION, &region);
        cl::Buffer carry = zeros(ctx, std::size_t(depth.height()) * p.moments * 4);
        cl::Buffer columns = zeros(ctx, std::size_t(p.columns.plane_pitch) * p.moments * 4);

        cl::Kernel& bands_kernel = kernel(exact ? "sat_bands_exact" : "sat_bands_float");
        bands_kernel.setArg(0, depth_buf);
        bands_kernel.setArg(1, origin);
        bands_kernel.setArg(2, carry);
        bands_kernel.setArg(3, columns);
        bands_kernel.setArg(4, sizeof(SatParams), &p);
        bands_kernel.setArg(5, bands);
        queue.enqueueNDRangeKernel(bands_kernel, cl::NullRange, cl::NDRange(std::size_t(bands)));

        cl::Kernel& join = kernel(exact ? "sat_join_bands_exact" : "sat_join_bands_float");
        join.setArg(0, origin);
        join.setArg(1, columns);
        join.setArg(2, sizeof(SatParams), &p);
        join.setArg(3, 0);
        queue.enqueueNDRangeKernel(join, cl::NullRange,
                                   cl::NDRange(std::size_t(depth.width()), std::size_t(depth.height())));
        sync_to_host(queue, storage, table_bytes);
    }

    void run_chebyshev(detail::ChebyshevMethod method, const MomentTable& table, const Image& receivers,
                       const ChebyshevParams& p, Image& out)
    {
        const cl::Context& ctx = runtime_.context();
        const cl::CommandQueue& queue = runtime_.queue();
        const bool exact = table.precision() == Precision::Exact;
        const bool vsm = method == detail::ChebyshevMethod::Vsm;
        const char* name = vsm ? (exact ? "vsm_exact" : "vsm_float") : (exact ? "vssm_exact" : "vssm_float");

        const std::size_t table_bytes = table.storage_elements() * 4;
        cl::Buffer storage = wrap(ctx, table.storage(), table_bytes, CL_MEM_READ_ONLY);
        cl_buffer_region region{table.origin_offset_bytes(), table_bytes - table.origin_offset_bytes()};
        cl::Buffer origin = storage.createSubBuffer(CL_MEM_READ_ONLY, CL_BUFFER_CREATE_TYPE_REGION, &region);
        cl::Buffer rx = wrap(ctx, receivers.plane(0), image_bytes(receivers), CL_MEM_READ_ONLY);
        cl::Buffer result = wrap(ctx, out.plane(0), image_bytes(out), CL_MEM_WRITE_ONLY);

        cl::Kernel& k = kernel(name);
        k.setArg(0, origin);
        k.setArg(1, rx);
        k.setArg(2, result);
        k.setArg(3, sizeof(ChebyshevParams), &p);
        k.setArg(4, 0);
        queue.enqueueNDRangeKernel(k, cl::NullRange, cl::NDRange(std::size_t(out.width()), std::size_t(out.height())));
        sync_to_host(queue, result, image_bytes(out));
    }

    Runtime runtime_;
    cl::Program program_;
    double build_seconds_ = 0.0;
    std::map<std::string, cl::Kernel> kernels_;
};

}  // namespace

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
