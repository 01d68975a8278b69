// OpenCL launches of the moment family: the encoded table build
// (kernels/encoded_table.h; bands of 32 rows, one work-item each, then the
// join of kernels/moment_table.h, as the moment table's build); the lookups
// (kernels/msm.h, msm_soft.h, evsm.h) run through the generic
// receiver_lookup (cl/opencl_lookup.cpp).
#include <cstdint>

#include "cl/opencl_backend.h"

namespace penumbra::cl_backend {

using detail::KernelId;

void OpenClBackend::build_encoded_table(const Image& depth, const EncodedSatParams& params, MomentTable& table,
                                        int* bad_rows)
{
    translate_cl_errors([&] {
        if (table.precision() == Precision::Exact)
            build_encoded_table_as<KernelId::encoded_bands_exact, std::uint32_t>(depth, params, table, bad_rows);
        else
            build_encoded_table_as<KernelId::encoded_bands_float, float>(depth, params, table, bad_rows);
    });
}

template <KernelId K, class T>
void OpenClBackend::build_encoded_table_as(const Image& depth, const EncodedSatParams& params, MomentTable& table,
                                           int* bad_rows)
{
    const int bands = (depth.height() + kTableBandHeight - 1) / kTableBandHeight;
    const int pitch = padded_pitch(depth.width());
    EncodedSatParams p = params;
    p.band_height = kTableBandHeight;
    p.columns = {depth.width(), bands, pitch, pitch * bands};

    const auto target = table_output<T>(context(), table);
    const Output<T> columns = zeros<T>(context(), std::size_t(p.columns.plane_pitch) * std::size_t(p.channels));
    const Output<int> flags = row_flags(context(), bad_rows, depth.height());
    launch<K>(Tasks{bands}, image_input(context(), depth), target.origin, columns, flags, p);
    join_bands(target.origin, columns, detail::join_params(p), Pixels{depth.width(), depth.height()});
    sync_to_host(queue(), target.storage, table.storage_elements() * 4);
    sync_to_host(queue(), flags);
}

}  // namespace penumbra::cl_backend
