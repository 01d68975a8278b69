#include "cl/opencl_launch.h"

#include "cl/transfer_counts.h"

namespace penumbra::cl_backend {

std::size_t extent_of(const pn_dims& dims, int channels)
{
    return std::size_t(channels - 1) * std::size_t(dims.plane_pitch) +
           std::size_t(dims.height - 1) * std::size_t(dims.pitch) + std::size_t(dims.width);
}

// Up to the last pixel, not the plane pitch times the planes: a borrowed
// image (penumbra/image_view.h) may end there.
std::size_t image_floats(const Image& image) { return image.extent(); }

Input<float> image_input(const cl::Context& context, const Image& image)
{
    return read_only(context, image.plane(0), image_floats(image));
}

Output<float> image_output(const cl::Context& context, Image& image)
{
    return read_write(context, image.plane(0), image_floats(image), CL_MEM_WRITE_ONLY);
}

Output<int> row_flags(const cl::Context& context, int* bad_rows, int rows)
{
    return read_write(context, bad_rows, std::size_t(rows));
}

cl::Buffer table_storage(const cl::Context& context, const MomentTable& table, cl_mem_flags access)
{
    count_upload(table.storage_elements() * 4);
    return cl::Buffer(context, access | CL_MEM_USE_HOST_PTR, table.storage_elements() * 4,
                      const_cast<void*>(static_cast<const void*>(table.storage())));
}

cl::Buffer table_origin(cl::Buffer& storage, const MomentTable& table, cl_mem_flags access)
{
    const std::size_t bytes = table.storage_elements() * 4;
    cl_buffer_region region{table.origin_offset_bytes(), bytes - table.origin_offset_bytes()};
    return storage.createSubBuffer(access, CL_BUFFER_CREATE_TYPE_REGION, &region);
}

void sync_to_host(const cl::CommandQueue& queue, const cl::Buffer& buffer, std::size_t bytes)
{
    count_download(bytes);
    void* mapped = queue.enqueueMapBuffer(buffer, CL_TRUE, CL_MAP_READ, 0, bytes);
    cl::Event done;
    queue.enqueueUnmapMemObject(buffer, mapped, nullptr, &done);
    done.wait();
}

}  // namespace penumbra::cl_backend
