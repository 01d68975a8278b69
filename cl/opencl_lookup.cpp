// OpenCL launch of every lookup-shaped entry of the kernel table (VSM, VSSM,
// MSM, moment soft shadows, EVSM, and any entry of the same shape added
// later): one work-item per receiver through launch<K>, the run-time KernelId
// made compile-time by the table's one switch (detail::visit_lookup). No
// method is named here: a new lookup-shaped entry runs with no edit of this file.
#include <type_traits>

#include "cl/opencl_backend.h"

namespace penumbra::cl_backend {

using detail::KernelId;

namespace {

// The source as entry K (reading T) sees it: a moment table's origin, a
// sub-buffer that `storage` keeps alive, or a float image's planes.
template <class T>
TableBuffers<const T*> source_input(const cl::Context& context, const detail::LookupSource& source, KernelId kernel)
{
    source.origin<T>(kernel);  // refuses a source that holds no T
    if constexpr (std::is_same_v<T, float>) {
        if (const Image* map = source.map()) {
            const Input<float> planes = image_input(context, *map);
            return {planes.buffer, planes};
        }
    }
    return table_input<T>(context, *source.table());
}

}  // namespace

void OpenClBackend::receiver_lookup(KernelId kernel, const detail::LookupSource& source, const Image& receivers,
                                    const void* params, Image& out, int* bad_rows)
{
    detail::visit_lookup(kernel, params, [&](auto k, const auto& p) {
        constexpr KernelId K = decltype(k)::value;
        translate_cl_errors([&] {
            const auto input = source_input<detail::LookupSourceOf<K>>(context(), source, K);
            const Output<float> result = image_output(context(), out);
            const Output<int> flags = row_flags(context(), bad_rows, receivers.height());
            launch<K>(Pixels{out.width(), out.height()}, input.origin, image_input(context(), receivers), result,
                      flags, p);
            sync_to_host(queue(), result);
            sync_to_host(queue(), flags);
        });
    });
}

}  // namespace penumbra::cl_backend
