// The per-pixel lookups over a moment table (kernels/vsm.h, vssm.h, msm.h,
// msm_soft.h, evsm.h): one work-item per receiver. Their entries share one
// argument list (table origin, receivers, output, row flags, params) and come
// in twins by the table's element type; this picks the twin and launches it.
#pragma once

#include <cstdint>

#include "cl/opencl_backend.h"

namespace penumbra::cl_backend {

template <detail::KernelId FloatK, detail::KernelId ExactK, class Params>
void OpenClBackend::table_lookup(const MomentTable& table, const Image& receivers, const Params& params, Image& out,
                                 int* bad_rows)
{
    if (table.precision() == Precision::Exact)
        table_lookup_as<ExactK, std::uint32_t>(table, receivers, params, out, bad_rows);
    else
        table_lookup_as<FloatK, float>(table, receivers, params, out, bad_rows);
}

template <detail::KernelId K, class T, class Params>
void OpenClBackend::table_lookup_as(const MomentTable& table, const Image& receivers, const Params& params, Image& out,
                                    int* bad_rows)
{
    translate_cl_errors([&] {
        const auto source = table_input<T>(context(), table);
        const Output<float> result = image_output(context(), out);
        const Output<int> flags = row_flags(context(), bad_rows, receivers.height());
        launch<K>(Pixels{out.width(), out.height()}, source.origin, image_input(context(), receivers), result, flags,
                  params);
        sync_to_host(queue(), result);
        sync_to_host(queue(), flags);
    });
}

}  // namespace penumbra::cl_backend
