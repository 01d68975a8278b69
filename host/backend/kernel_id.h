// The typed names of the kernel table (kernels/kernel_table.h): the host and
// both backends name a kernel by KernelId, never by a string; kernel_name()
// is the one place an entry's name becomes text (the OpenCL kernel object's
// name, messages). KernelTraits<K> gives an entry's parameter struct, shape
// and buffer pointer types, from which each backend derives its signature.
#pragma once

#include <array>
#include <cstdint>
#include <string_view>
#include <tuple>
#include <type_traits>
#include <utility>

#include "kernels/kernel_table.h"
#include "kernels/params.h"

namespace penumbra::detail {

enum class KernelFamily {
#define PN_FAMILY_ENUM(family) family,
    PN_KERNEL_FAMILIES(PN_FAMILY_ENUM)
#undef PN_FAMILY_ENUM
};

enum class KernelId {
#define PN_KERNEL_ENUM(family, name, shape, Params, buffers) name,
    PN_KERNEL_TABLE(PN_KERNEL_ENUM)
#undef PN_KERNEL_ENUM
};

enum class KernelShape { pixel, task };

inline constexpr int kKernelCount = 0
#define PN_KERNEL_COUNT(family, name, shape, Params, buffers) +1
    PN_KERNEL_TABLE(PN_KERNEL_COUNT)
#undef PN_KERNEL_COUNT
    ;

inline constexpr int kFamilyCount = 0
#define PN_FAMILY_COUNT(family) +1
    PN_KERNEL_FAMILIES(PN_FAMILY_COUNT)
#undef PN_FAMILY_COUNT
    ;

constexpr std::string_view kernel_name(KernelId id)
{
    constexpr std::array<std::string_view, kKernelCount> names{
#define PN_KERNEL_NAME(family, name, shape, Params, buffers) #name,
        PN_KERNEL_TABLE(PN_KERNEL_NAME)
#undef PN_KERNEL_NAME
    };
    return names[static_cast<int>(id)];
}

constexpr KernelFamily kernel_family(KernelId id)
{
    constexpr std::array<KernelFamily, kKernelCount> families{
#define PN_KERNEL_FAMILY(family, name, shape, Params, buffers) KernelFamily::family,
        PN_KERNEL_TABLE(PN_KERNEL_FAMILY)
#undef PN_KERNEL_FAMILY
    };
    return families[static_cast<int>(id)];
}

constexpr std::string_view family_name(KernelFamily family)
{
    constexpr std::array<std::string_view, kFamilyCount> names{
#define PN_FAMILY_NAME(family) #family,
        PN_KERNEL_FAMILIES(PN_FAMILY_NAME)
#undef PN_FAMILY_NAME
    };
    return names[static_cast<int>(family)];
}

// The buffer element types of the table, as the host passes them.
using kernel_buffer_float = float;
using kernel_buffer_uint = std::uint32_t;
using kernel_buffer_int = int;

template <KernelId K>
struct KernelTraits;

#define PN_UNPAREN(...) __VA_ARGS__
#define PN_IN(T) const kernel_buffer_##T*
#define PN_SOURCE(T) const kernel_buffer_##T*
#define PN_OUT(T) kernel_buffer_##T*
#define PN_INOUT(T) kernel_buffer_##T*
#define PN_KERNEL_TRAITS(family_, name, shape_, Params_, buffers)      \
    template <>                                                       \
    struct KernelTraits<KernelId::name> {                             \
        using Params = ::penumbra::Params_;                           \
        static constexpr KernelShape shape = KernelShape::shape_;     \
        static constexpr KernelFamily family = KernelFamily::family_; \
        using Buffers = std::tuple<PN_UNPAREN buffers>;               \
    };
PN_KERNEL_TABLE(PN_KERNEL_TRAITS)
#undef PN_KERNEL_TRAITS
#undef PN_IN
#undef PN_SOURCE
#undef PN_OUT
#undef PN_INOUT

// Which of an entry's buffers the table marks PN_SOURCE (std::true_type) and
// which it does not: the same list expanded once more.
template <KernelId K>
struct KernelSourceMarks;
#define PN_IN(T) std::false_type
#define PN_SOURCE(T) std::true_type
#define PN_OUT(T) std::false_type
#define PN_INOUT(T) std::false_type
#define PN_KERNEL_MARKS(family_, name, shape_, Params_, buffers) \
    template <>                                                   \
    struct KernelSourceMarks<KernelId::name> {                    \
        using type = std::tuple<PN_UNPAREN buffers>;              \
    };
PN_KERNEL_TABLE(PN_KERNEL_MARKS)
#undef PN_KERNEL_MARKS
#undef PN_IN
#undef PN_SOURCE
#undef PN_OUT
#undef PN_INOUT
#undef PN_UNPAREN

// A lookup-shaped entry reads its source per receiver: a pixel entry whose
// buffers are (PN_SOURCE(S)... sources, PN_IN(float) receivers,
// PN_OUT(float) out, PN_OUT(int) bad_rows), the sources marked so in the
// table (the types alone cannot tell a source from an SDF's normals). One
// source buffer (float: a float moment table or a plain float image such as
// a raw depth map; uint: an exact moment table) or several arrays (a deep
// shadow map's offsets, depths and transmittances). Every such entry runs
// through BackendImpl::receiver_lookup (backend.h) with no per-method code in
// a backend.
namespace lookup_detail {
template <class Pointer>
struct SourcePointer {
    using Element = void;
};
template <class T>
struct SourcePointer<const T*> {
    using Element = T;
};
template <class Buffers, class Marks, class Indices>
struct Split : std::false_type {};
template <class... B, class... M, std::size_t... I>
    requires(sizeof...(B) == sizeof...(I) + 3)
struct Split<std::tuple<B...>, std::tuple<M...>, std::index_sequence<I...>> {
    using All = std::tuple<B...>;
    using Marks = std::tuple<M...>;
    static constexpr std::size_t kSources = sizeof...(I);
    static constexpr bool value =
        kSources >= 1 && (std::tuple_element_t<I, Marks>::value && ...) &&
        std::is_same_v<std::tuple<std::tuple_element_t<kSources, All>, std::tuple_element_t<kSources + 1, All>,
                                  std::tuple_element_t<kSources + 2, All>>,
                       std::tuple<const float*, float*, int*>>;
    using Sources = std::tuple<typename SourcePointer<std::tuple_element_t<I, All>>::Element...>;
};
template <class Marks>
inline constexpr std::size_t kMarkedSources = 0;
template <class... M>
inline constexpr std::size_t kMarkedSources<std::tuple<M...>> = (std::size_t(M::value) + ... + 0);
}  // namespace lookup_detail

// The entry's buffers split after its marked sources (false when they are not
// sources followed by receivers, out and bad_rows).
template <KernelId K>
using LookupBuffers =
    lookup_detail::Split<typename KernelTraits<K>::Buffers, typename KernelSourceMarks<K>::type,
                         std::make_index_sequence<lookup_detail::kMarkedSources<typename KernelSourceMarks<K>::type>>>;

template <KernelId K>
inline constexpr bool is_lookup_shaped = KernelTraits<K>::shape == KernelShape::pixel && LookupBuffers<K>::value;

// The element types of lookup-shaped entry K's source buffers, in order
// (std::tuple<float>, std::tuple<std::uint32_t, float, float>, ...).
template <KernelId K>
using LookupSourcesOf = typename LookupBuffers<K>::Sources;

template <KernelId K>
using KernelConstant = std::integral_constant<KernelId, K>;

// Calls visit(KernelConstant<id>{}), or otherwise() for a value that is no
// entry (an int cast to KernelId): the one switch that turns a run-time
// KernelId into a compile-time one, generated from the table.
template <class Visitor, class Otherwise>
decltype(auto) visit_kernel(KernelId id, Visitor&& visit, Otherwise&& otherwise)
{
    switch (id) {
#define PN_KERNEL_VISIT(family, name, shape, Params, buffers) \
    case KernelId::name:                                       \
        return visit(KernelConstant<KernelId::name>{});
        PN_KERNEL_TABLE(PN_KERNEL_VISIT)
#undef PN_KERNEL_VISIT
    }
    return otherwise();
}

}  // namespace penumbra::detail
