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
#undef PN_OUT
#undef PN_INOUT
#undef PN_UNPAREN

// A lookup-shaped entry reads one source per receiver: a pixel entry whose
// buffers are (PN_IN(T) source, PN_IN(float) receivers, PN_OUT(float) out,
// PN_OUT(int) bad_rows), T the source's element type (float: a float moment
// table or a plain float image such as a raw depth map; uint: an exact moment
// table). Every such entry runs through BackendImpl::receiver_lookup
// (backend.h) with no per-method code in a backend.
template <class Buffers>
struct LookupBuffers : std::false_type {};
template <class T>
struct LookupBuffers<std::tuple<const T*, const float*, float*, int*>> : std::true_type {
    using Source = T;
};

template <KernelId K>
inline constexpr bool is_lookup_shaped =
    KernelTraits<K>::shape == KernelShape::pixel && LookupBuffers<typename KernelTraits<K>::Buffers>::value;

// The source's element type of lookup-shaped entry K.
template <KernelId K>
using LookupSourceOf = typename LookupBuffers<typename KernelTraits<K>::Buffers>::Source;

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
