// The one launch path of the OpenCL backend: launch<K>(programs, queue, range,
// buffers..., params) binds the buffers and then the parameter struct of the
// kernel table's entry K (kernels/kernel_table.h) by a fold over the
// arguments, then the shape's last argument (pixel: the first row, 0; task:
// the task count), and enqueues one work-item per pixel or per task, in
// work-groups of the device's fixed size (cl/opencl_work_groups.h says why).
//
// A DeviceBuffer<P> is a cl::Buffer that the kernel sees as the pointer type P
// the table gives the argument (PN_IN(T) -> const T*, PN_OUT(T) and
// PN_INOUT(T) -> T*, KernelTraits<K>::Buffers); launch<K> refuses at compile
// time any argument list that is not the table's, in order. Host memory is
// wrapped with CL_MEM_USE_HOST_PTR so that a CPU driver such as PoCL works in
// place; results are made current through a map, which is free in that case.
#pragma once

#include <CL/opencl.hpp>

#include <cstddef>
#include <mutex>
#include <tuple>
#include <type_traits>
#include <vector>

#include "cl/opencl_programs.h"
#include "cl/opencl_work_groups.h"
#include "host/backend/kernel_id.h"
#include "kernels/params.h"
#include "penumbra/image.h"
#include "penumbra/moment_table.h"

namespace penumbra::cl_backend {

// Every host <-> device transfer the backend makes, counted for
// penumbra::host_transfers() (penumbra/device_image.h): a buffer over or
// copied from host memory is one upload, a map or read back one download.
void count_upload(std::size_t bytes);
void count_download(std::size_t bytes);

// Elements from plane 0 to just past the last pixel of an image of `channels` planes of these dims.
std::size_t extent_of(const pn_dims& dims, int channels);

template <class Pointer>
struct DeviceBuffer {
    cl::Buffer buffer;
    std::size_t bytes = 0;
};

template <class T>
using Input = DeviceBuffer<const T*>;
template <class T>
using Output = DeviceBuffer<T*>;

// Host memory, shared with the device (see the header comment).
template <class T>
Input<T> read_only(const cl::Context& context, const T* data, std::size_t count)
{
    const std::size_t bytes = count * sizeof(T);
    count_upload(bytes);
    return {cl::Buffer(context, CL_MEM_READ_ONLY | CL_MEM_USE_HOST_PTR, bytes, const_cast<T*>(data)), bytes};
}
template <class T>
Output<T> read_write(const cl::Context& context, T* data, std::size_t count, cl_mem_flags access = CL_MEM_READ_WRITE)
{
    const std::size_t bytes = count * sizeof(T);
    count_upload(bytes);
    return {cl::Buffer(context, access | CL_MEM_USE_HOST_PTR, bytes, data), bytes};
}
// Device memory: a copy of `values`, zeros, or uninitialised scratch.
template <class T>
Input<T> copy_of(const cl::Context& context, const std::vector<T>& values)
{
    const std::size_t bytes = values.size() * sizeof(T);
    count_upload(bytes);
    return {cl::Buffer(context, CL_MEM_READ_ONLY | CL_MEM_COPY_HOST_PTR, bytes, const_cast<T*>(values.data())), bytes};
}
template <class T>
Output<T> zeros(const cl::Context& context, std::size_t count)
{
    std::vector<T> zero(count, T(0));
    const std::size_t bytes = count * sizeof(T);
    count_upload(bytes);
    return {cl::Buffer(context, CL_MEM_READ_WRITE | CL_MEM_COPY_HOST_PTR, bytes, zero.data()), bytes};
}
template <class T>
Output<T> scratch(const cl::Context& context, std::size_t count)
{
    return {cl::Buffer(context, CL_MEM_READ_WRITE, count * sizeof(T)), count * sizeof(T)};
}
// What one launch wrote, as the next one's input (the in-order queue orders them).
template <class T>
Input<T> as_input(const Output<T>& written)
{
    return {written.buffer, written.bytes};
}

std::size_t image_floats(const Image& image);
Input<float> image_input(const cl::Context& context, const Image& image);
Output<float> image_output(const cl::Context& context, Image& image);
// One int per row, zeroed by the host; kernels raise a row's flag.
Output<int> row_flags(const cl::Context& context, int* bad_rows, int rows);

// A moment table's storage and its origin (its zero row) as a sub-buffer, in
// the table's element type T (float, or std::uint32_t for an exact table).
template <class Pointer>
struct TableBuffers {
    cl::Buffer storage;
    DeviceBuffer<Pointer> origin;
};
cl::Buffer table_storage(const cl::Context& context, const MomentTable& table, cl_mem_flags access);
cl::Buffer table_origin(cl::Buffer& storage, const MomentTable& table, cl_mem_flags access);
template <class T>
TableBuffers<const T*> table_input(const cl::Context& context, const MomentTable& table)
{
    cl::Buffer storage = table_storage(context, table, CL_MEM_READ_ONLY);
    cl::Buffer origin = table_origin(storage, table, CL_MEM_READ_ONLY);
    return {storage, {origin, table.storage_elements() * 4 - table.origin_offset_bytes()}};
}
template <class T>
TableBuffers<T*> table_output(const cl::Context& context, MomentTable& table)
{
    cl::Buffer storage = table_storage(context, table, CL_MEM_READ_WRITE);
    cl::Buffer origin = table_origin(storage, table, CL_MEM_READ_WRITE);
    return {storage, {origin, table.storage_elements() * 4 - table.origin_offset_bytes()}};
}

// Makes the host copy of a USE_HOST_PTR buffer current.
void sync_to_host(const cl::CommandQueue& queue, const cl::Buffer& buffer, std::size_t bytes);
template <class Pointer>
void sync_to_host(const cl::CommandQueue& queue, const DeviceBuffer<Pointer>& buffer)
{
    sync_to_host(queue, buffer.buffer, buffer.bytes);
}

// The ranges of the two shapes of kernels/kernel_table.h.
struct Pixels {
    int width, height;
};
struct Tasks {
    int count;
};

namespace launch_detail {

template <class Buffers>
struct DeviceBuffersOf;
template <class... Pointers>
struct DeviceBuffersOf<std::tuple<Pointers...>> {
    using type = std::tuple<DeviceBuffer<Pointers>...>;
};

// K's argument list as the host passes it: its buffers, then its Params.
template <detail::KernelId K>
using HostArguments = decltype(std::tuple_cat(
    std::declval<typename DeviceBuffersOf<typename detail::KernelTraits<K>::Buffers>::type>(),
    std::declval<std::tuple<typename detail::KernelTraits<K>::Params>>()));

template <class Pointer>
void bind(cl::Kernel& kernel, cl_uint index, const DeviceBuffer<Pointer>& buffer)
{
    kernel.setArg(index, buffer.buffer);
}
template <class Params>
void bind(cl::Kernel& kernel, cl_uint index, const Params& params)
{
    static_assert(std::is_trivially_copyable_v<Params>, "a kernel's parameters pass by value");
    kernel.setArg(index, sizeof(Params), &params);
}

// The range rounded up to whole work-groups (cl/opencl_work_groups.h).
inline cl::NDRange global_range(Pixels pixels, const WorkGroups& groups)
{
    return cl::NDRange(round_up(std::size_t(pixels.width), groups.pixel_width),
                       round_up(std::size_t(pixels.height), groups.pixel_height));
}
inline cl::NDRange global_range(Tasks tasks, const WorkGroups& groups)
{
    return cl::NDRange(round_up(std::size_t(tasks.count), groups.task));
}
inline cl::NDRange local_range(Pixels, const WorkGroups& groups) { return groups.pixel(); }
inline cl::NDRange local_range(Tasks, const WorkGroups& groups) { return groups.tasks(); }
// The shape's last argument: PN_PIXEL_ARGS (the launch's first row) or PN_TASK_ARGS.
inline int shape_argument(Pixels) { return 0; }
inline int shape_argument(Tasks tasks) { return tasks.count; }

}  // namespace launch_detail

template <detail::KernelId K, class Range, class... A>
void launch(KernelPrograms& programs, const cl::CommandQueue& queue, Range range, const A&... args)
{
    using Traits = detail::KernelTraits<K>;
    static_assert(std::is_same_v<std::tuple<A...>, launch_detail::HostArguments<K>>,
                  "the arguments are not the kernel table's buffers and parameters of this kernel, in order");
    static_assert(std::is_same_v<Range, Pixels> == (Traits::shape == detail::KernelShape::pixel),
                  "a per-pixel kernel launches over Pixels, a per-task kernel over Tasks");
    cl::Kernel& kernel = programs.kernel(K);
    std::lock_guard lock(programs.launch_lock());
    cl_uint index = 0;
    (launch_detail::bind(kernel, index++, args), ...);
    kernel.setArg(index, launch_detail::shape_argument(range));
    const WorkGroups& groups = programs.work_groups();
    queue.enqueueNDRangeKernel(kernel, cl::NullRange, launch_detail::global_range(range, groups),
                               launch_detail::local_range(range, groups));
}

}  // namespace penumbra::cl_backend
