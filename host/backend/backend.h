// The interface every backend implements (simd/cpu_backend.h,
// cl/opencl_backend.h): one generic per-receiver lookup for every
// lookup-shaped entry of the kernel table, and one method per schedule that
// differs (table builds, the bilateral passes, the SDF marches);
// host/src/*.cpp call it. Inputs are validated before these are called; a
// backend trusts its arguments. The kernels it runs are named by KernelId
// (kernel_id.h, beside this file).
#pragma once

#include <cstddef>
#include <cstdint>
#include <span>
#include <string>
#include <tuple>
#include <utility>
#include <vector>

#include "host/backend/kernel_id.h"
#include "kernels/params.h"
#include "penumbra/image.h"
#include "penumbra/moment_table.h"

namespace penumbra::detail {

// The Error a backend throws for a KernelId that is no lookup-shaped entry.
[[noreturn]] void throw_not_a_lookup(KernelId kernel);
// The Error for a source of `given` arrays passed to an entry reading `wanted`.
[[noreturn]] void throw_wrong_arrays(KernelId kernel, std::size_t wanted, std::size_t given);

// One array of a source made of several (a deep shadow map's offsets,
// depths, transmittances), as an entry's PN_IN(float) or PN_IN(uint) reads it.
class SourceArray {
public:
    SourceArray(std::span<const float> values) : data_(values.data()), count_(values.size()), floats_(true) {}
    SourceArray(std::span<const std::uint32_t> values)
        : data_(values.data()), count_(values.size()), floats_(false)
    {
    }
    std::size_t count() const { return count_; }
    // The elements as T; throws Error(InvalidArgument, "source") for the other type.
    template <class T>
    const T* data(KernelId kernel) const;

private:
    const void* data_;
    std::size_t count_;
    bool floats_;
};

template <>
const float* SourceArray::data<float>(KernelId kernel) const;
template <>
const std::uint32_t* SourceArray::data<std::uint32_t>(KernelId kernel) const;

// What a lookup-shaped entry reads per receiver (its PN_IN source buffers):
// the planes of a moment table (float or exact), a plain float image such as
// a raw depth map (the percentage-closer family filters the shadow map
// itself), both one buffer, or several arrays, one per source buffer of the
// entry. The entry's Params carry the source's dims; this carries its storage.
class LookupSource {
public:
    LookupSource(const MomentTable& table) : table_(&table) {}  // NOLINT: a table is a source
    LookupSource(const Image& map) : map_(&map) {}              // NOLINT: so is a float image
    explicit LookupSource(std::vector<SourceArray> arrays) : arrays_(std::move(arrays)) {}

    const MomentTable* table() const { return table_; }
    const Image* map() const { return map_; }
    const std::vector<SourceArray>& arrays() const { return arrays_; }
    // The first element an entry reading T gets (a table's origin, an
    // image's plane 0); throws Error(InvalidArgument, "source") when the
    // source holds no T (an exact table for a float entry, an image for a
    // uint one, arrays for an entry of one buffer).
    template <class T>
    const T* origin(KernelId kernel) const;
    // Array `index` of an entry reading `count` arrays, as T; throws
    // Error(InvalidArgument, "source") unless the source is `count` arrays
    // and that one holds T.
    template <class T>
    const T* array(KernelId kernel, std::size_t index, std::size_t count) const;

private:
    const MomentTable* table_ = nullptr;
    const Image* map_ = nullptr;
    std::vector<SourceArray> arrays_;
};

template <>
const float* LookupSource::origin<float>(KernelId kernel) const;
template <>
const std::uint32_t* LookupSource::origin<std::uint32_t>(KernelId kernel) const;

template <class T>
const T* LookupSource::array(KernelId kernel, std::size_t index, std::size_t count) const
{
    if (arrays_.size() != count) throw_wrong_arrays(kernel, count, arrays_.size());
    return arrays_[index].data<T>(kernel);
}

// The source buffers of lookup-shaped entry K as a tuple of pointers, in its
// argument order: one origin, or one pointer per array.
template <KernelId K>
auto source_buffers(const LookupSource& source)
{
    using Sources = LookupSourcesOf<K>;
    constexpr std::size_t n = std::tuple_size_v<Sources>;
    if constexpr (n == 1) {
        return std::tuple{source.origin<std::tuple_element_t<0, Sources>>(K)};
    } else {
        return [&]<std::size_t... I>(std::index_sequence<I...>) {
            return std::tuple{source.array<std::tuple_element_t<I, Sources>>(K, I, n)...};
        }(std::make_index_sequence<n>{});
    }
}


// Calls visit(KernelConstant<K>{}, params) with `params` as K's Params when
// `kernel` is lookup-shaped (kernel_id.h), throws Error(InvalidArgument,
// "kernel") otherwise: the dispatch each backend's receiver_lookup runs, so
// that a backend has no per-method code.
template <class Visitor>
void visit_lookup(KernelId kernel, const void* params, Visitor&& visit)
{
    visit_kernel(
        kernel,
        [&](auto k) {
            constexpr KernelId K = decltype(k)::value;
            if constexpr (is_lookup_shaped<K>)
                visit(k, *static_cast<const typename KernelTraits<K>::Params*>(params));
            else
                throw_not_a_lookup(K);
        },
        [&] { throw_not_a_lookup(kernel); });
}

// The operations every backend implements, declared once: BackendImpl
// declares them with PN_BACKEND_OPERATIONS(virtual, = 0), each backend's class
// with PN_BACKEND_OPERATIONS(, override), and each backend defines each in its
// own file (simd/cpu_lookup.cpp and cl/opencl_lookup.cpp, ..._moment_table,
// ..._bilateral, ..._sdf, ..._moments).
//
// Kernels check the values they read: `bad_rows` (one int per row of the
// input they check, zeroed) gets a 1 for every row holding a value the
// kernel cannot take; the host then finds and reports the first one.
//
// - receiver_lookup: lookup-shaped entry `kernel` (kernel_id.h) once per
//   receiver: reads `source`, `receivers` (plane 0 onwards: u, v, z), writes
//   out's plane 0; `params` points to the entry's complete Params (use the
//   typed receiver_lookup<K> below, which checks that). Throws Error for a
//   kernel that is not lookup-shaped. bad_rows: per receiver row.
// - build_moment_table: fills `table` from `depth`; bad_rows: per depth row.
// - cross_bilateral: the cross-bilateral filter (kernels/bilateral.h) of
//   `mask` into `out`. `normals` is null unless params.use_normals; `taps`
//   holds the window's offsets as (dx, dy) pairs (separable: (d, d)),
//   `weights` their spatial weights and base-2 exponents as pairs; `params`
//   is complete but for `pass` and `pass_first_row`, which the separable
//   schedule sets. bad_rows: per mask row.
// - sdf_grid, sdf_analytic: SDF soft shadows (kernels/sdf.h) through a
//   distance grid (`data`: the nodes) or analytic primitives (`data`: the
//   packed records, `floats` of them, possibly none). `normals` is
//   `positions` when params.normal_offset is 0; `out` has 1 or 2 planes;
//   `params` is complete; bad_rows: per receiver row.
// - build_encoded_table: the moment family (kernels/encoded_table.h, msm.h,
//   msm_soft.h, evsm.h). Fills `table` (zeroed, params.channels planes) with
//   the sums of encoded texels; `params` is complete but for columns and
//   band_height, which the schedule sets. bad_rows: per depth row.
#define PN_BACKEND_OPERATIONS(VIRTUAL, SPECIFIER)                                                                  \
    VIRTUAL void receiver_lookup(::penumbra::detail::KernelId kernel,                                             \
                                 const ::penumbra::detail::LookupSource& source, const Image& receivers,          \
                                 const void* params, Image& out, int* bad_rows) SPECIFIER;                        \
    VIRTUAL void build_moment_table(const Image& depth, MomentTable& table, int* bad_rows) SPECIFIER;            \
    VIRTUAL void cross_bilateral(const Image& mask, const Image& guide, const Image* normals,                     \
                                 const std::vector<int>& taps, const std::vector<float>& weights, bool separable, \
                                 const BilateralParams& params, Image& out, int* bad_rows) SPECIFIER;             \
    VIRTUAL void sdf_grid(const float* data, std::size_t floats, const Image& positions, const Image& normals,   \
                          const SdfParams& params, Image& out, int* bad_rows) SPECIFIER;                          \
    VIRTUAL void sdf_analytic(const float* data, std::size_t floats, const Image& positions,                     \
                              const Image& normals, const SdfParams& params, Image& out, int* bad_rows) SPECIFIER; \
    VIRTUAL void build_encoded_table(const Image& depth, const EncodedSatParams& params, MomentTable& table,      \
                                     int* bad_rows) SPECIFIER

class DeviceQueue;  // host/backend/device_queue.h

class BackendImpl {
public:
    virtual ~BackendImpl() = default;
    // Device-resident storage and enqueued operations; null on the CPU
    // backends, which run penumbra/device_image.h's operations at once.
    virtual DeviceQueue* device_queue() { return nullptr; }
    virtual std::string description() const = 0;
    virtual std::string isa() const { return {}; }
    virtual double program_build_seconds() const { return 0.0; }

    PN_BACKEND_OPERATIONS(virtual, = 0);
};

// The typed front end of BackendImpl::receiver_lookup: K's own Params, so a
// call site cannot pass another entry's.
template <KernelId K>
void receiver_lookup(BackendImpl& backend, const LookupSource& source, const Image& receivers,
                     const typename KernelTraits<K>::Params& params, Image& out, int* bad_rows)
{
    static_assert(is_lookup_shaped<K>, "receiver_lookup runs a lookup-shaped entry (kernel_id.h)");
    backend.receiver_lookup(K, source, receivers, &params, out, bad_rows);
}

// A moment table's lookup: Float on a float table, Exact on an exact one (the
// two PN_TABLE_VARIANTS of one description, kernels/dialect.h).
template <KernelId Float, KernelId Exact>
void table_lookup(BackendImpl& backend, const MomentTable& table, const Image& receivers,
                  const typename KernelTraits<Float>::Params& params, Image& out, int* bad_rows)
{
    static_assert(std::is_same_v<typename KernelTraits<Float>::Params, typename KernelTraits<Exact>::Params>,
                  "the twins of one lookup share their Params");
    if (table.precision() == Precision::Float)
        receiver_lookup<Float>(backend, table, receivers, params, out, bad_rows);
    else
        receiver_lookup<Exact>(backend, table, receivers, params, out, bad_rows);
}

pn_dims dims_of(const Image& image);
pn_dims dims_of(const MomentTable& table);

// The moment table build's parameters for `depth` into `table`, with
// `column_rows` rows of column totals and bands of `band_height` rows (the
// schedule's choice): both backends' builds start from these.
SatParams sat_params(const Image& depth, const MomentTable& table, int column_rows, int band_height);
// The same from the geometry alone (a device-resident table's, powers z^k).
SatParams sat_params(pn_dims depth, pn_dims table, int moments, int limbs, int column_rows, int band_height);
// The join pass of a banded encoded build (kernels/moment_table.h's
// sat_join_bands_*) reads the encoded table as a one-limb moment table.
SatParams join_params(const EncodedSatParams& p);

}  // namespace penumbra::detail
