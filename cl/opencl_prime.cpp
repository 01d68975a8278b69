#include "cl/opencl_prime.h"

#include <array>
#include <string>
#include <tuple>

#include "penumbra/error.h"

namespace penumbra::cl_backend {

namespace {

// Large enough for any one element a kernel might touch; nothing reads it.
constexpr std::size_t kDummyBytes = 64;

// The table's argument list of K bound with dummies (cl/opencl_launch.h binds
// the same list for real): its buffers, its Params, the shape's last int.
template <detail::KernelId K>
void bind_empty(cl::Kernel& kernel, const cl::Buffer& dummy)
{
    using Traits = detail::KernelTraits<K>;
    constexpr cl_uint buffers = std::tuple_size_v<typename Traits::Buffers>;
    for (cl_uint i = 0; i < buffers; ++i) kernel.setArg(i, dummy);
    const std::array<unsigned char, sizeof(typename Traits::Params)> zeros{};
    kernel.setArg(buffers, zeros.size(), zeros.data());
    kernel.setArg(buffers + 1, 0);  // pixel: the first row; task: no tasks
}

}  // namespace

void prime_kernel(const cl::Context& context, const cl::CommandQueue& queue, const cl::Program& program,
                  detail::KernelId id, const WorkGroups& groups)
{
    cl::Kernel kernel(program, std::string(detail::kernel_name(id)).c_str());
    const cl::Buffer dummy(context, CL_MEM_READ_WRITE, kDummyBytes);
    const bool pixel = detail::visit_kernel(
        id,
        [&](auto k) {
            bind_empty<decltype(k)::value>(kernel, dummy);
            return detail::KernelTraits<decltype(k)::value>::shape == detail::KernelShape::pixel;
        },
        []() -> bool { throw Error(ErrorCategory::InvalidArgument, "opencl", "prime_kernel: no kernel entry"); });
    const cl::NDRange group = pixel ? groups.pixel() : groups.tasks();
    queue.enqueueNDRangeKernel(kernel, cl::NullRange, group, group);
    queue.finish();
}

}  // namespace penumbra::cl_backend
