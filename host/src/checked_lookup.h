// The host side of every per-receiver lookup (detail::receiver_lookup,
// host/backend/backend.h): the kernels flag rows holding a NaN or infinite
// receiver, and the first one is then reported as the operation's Error (the
// output is left unspecified); the check of a shadow map an entry reads
// itself. Shared by every lookup-shaped family (chebyshev.cpp, moments.cpp,
// pcf.cpp, ...).
#pragma once

#include <algorithm>
#include <string>
#include <vector>

#include "host/backend/backend.h"
#include "host/src/depth_conversion.h"
#include "penumbra/depth_convention.h"
#include "penumbra/image.h"

namespace penumbra::detail {

// lookup(bad_rows) runs the backend's lookup with one zeroed flag per receiver row.
template <class Lookup>
void checked_lookup(const std::string& op, const Image& receivers, Lookup&& lookup)
{
    std::vector<int> bad_rows(std::size_t(receivers.height()), 0);
    lookup(bad_rows.data());
    if (std::find(bad_rows.begin(), bad_rows.end(), 1) != bad_rows.end())
        require_finite(receivers, op, "the receivers image", "receivers");
}

// A shadow map an entry reads itself: one channel of depths in the
// convention's range ([0, 1] by default; Error, parameter "depth", naming the
// first bad texel).
void check_shadow_map(const Image& map, const std::string& op, const DepthConvention& convention = {});

// A box method's window summed directly from the map (the `_direct` entries,
// kernels/box_window.h): the map checked, its dims as the Params' `table`
// (the source's dims), then the checked lookup.
template <KernelId K>
void checked_direct_lookup(BackendImpl& backend, const std::string& op, const Image& map, const Image& receivers,
                           const DepthConvention& convention, typename KernelTraits<K>::Params params, Image& out)
{
    check_shadow_map(map, op, convention);
    params.table = dims_of(map);
    params.direct = DirectMap{params.table, 0, kernel_conversion(convention)};
    checked_lookup(op, receivers,
                   [&](int* bad_rows) { receiver_lookup<K>(backend, map, receivers, params, out, bad_rows); });
}

// A moment table's lookup (Float / Exact twins), checked.
template <KernelId Float, KernelId Exact>
void checked_table_lookup(BackendImpl& backend, const std::string& op, const MomentTable& table,
                          const Image& receivers, const typename KernelTraits<Float>::Params& params, Image& out)
{
    checked_lookup(op, receivers, [&](int* bad_rows) {
        table_lookup<Float, Exact>(backend, table, receivers, params, out, bad_rows);
    });
}

}  // namespace penumbra::detail
