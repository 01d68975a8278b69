// OpenCL launch of every lookup-shaped entry of the kernel table (VSM, VSSM,
// MSM, moment soft shadows, EVSM, the deep shadow map lookup, and any entry
// of the same shape added later): one work-item per receiver through
// launch<K>, the run-time KernelId made compile-time by the table's one
// switch (detail::visit_lookup). No method is named here: a new
// lookup-shaped entry runs with no edit of this file.
#include <tuple>
#include <type_traits>
#include <utility>

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

// Array `I` of a source of several, in host memory (OpenCL has no empty
// buffer: an empty array is one zero, which a valid entry never reads).
template <class T>
Input<T> array_input(const cl::Context& context, const detail::LookupSource& source, KernelId kernel,
                     std::size_t index, std::size_t count)
{
    const T* data = source.array<T>(kernel, index, count);
    const std::size_t elements = source.arrays()[index].count();
    return elements == 0 ? as_input(zeros<T>(context, 1)) : read_only(context, data, elements);
}

// Entry K's source buffers, in its argument order, and what keeps them alive.
template <KernelId K>
auto source_inputs(const cl::Context& context, const detail::LookupSource& source)
{
    using Sources = detail::LookupSourcesOf<K>;
    constexpr std::size_t n = std::tuple_size_v<Sources>;
    if constexpr (n == 1) {
        TableBuffers<const std::tuple_element_t<0, Sources>*> one =
            source_input<std::tuple_element_t<0, Sources>>(context, source, K);
        return std::pair{one.storage, std::tuple{one.origin}};
    } else {
        return [&]<std::size_t... I>(std::index_sequence<I...>) {
            return std::pair{cl::Buffer(),
                             std::tuple{array_input<std::tuple_element_t<I, Sources>>(context, source, K, I, n)...}};
        }(std::make_index_sequence<n>{});
    }
}

}  // namespace

void OpenClBackend::receiver_lookup(KernelId kernel, const detail::LookupSource& source, const Image& receivers,
                                    const void* params, Image& out, int* bad_rows)
{
    detail::visit_lookup(kernel, params, [&](auto k, const auto& p) {
        constexpr KernelId K = decltype(k)::value;
        translate_cl_errors([&] {
            const auto inputs = source_inputs<K>(context(), source);
            const Output<float> result = image_output(context(), out);
            const Output<int> flags = row_flags(context(), bad_rows, receivers.height());
            std::apply(
                [&](const auto&... buffers) {
                    launch<K>(Pixels{out.width(), out.height()}, buffers..., image_input(context(), receivers),
                              result, flags, p);
                },
                inputs.second);
            sync_to_host(queue(), result);
            sync_to_host(queue(), flags);
        });
    });
}

}  // namespace penumbra::cl_backend
