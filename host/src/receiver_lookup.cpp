// LookupSource and the refusal of a kernel that is no lookup
// (host/backend/backend.h): the parts of the generic per-receiver lookup that
// both backends share.
#include <string>

#include "host/backend/backend.h"
#include "penumbra/error.h"

namespace penumbra::detail {
namespace {

[[noreturn]] void wrong_source(KernelId kernel, const std::string& what)
{
    throw Error(ErrorCategory::InvalidArgument, "receiver_lookup", "source",
                "kernel '" + std::string(kernel_name(kernel)) + "' reads " + what +
                    ", and the source given holds none; pass the table or image its entry names");
}

}  // namespace

template <>
const float* LookupSource::origin<float>(KernelId kernel) const
{
    if (map_) return map_->plane(0);
    if (table_->precision() != Precision::Float) wrong_source(kernel, "float values (a float table or image)");
    return table_->float_origin();
}

template <>
const std::uint32_t* LookupSource::origin<std::uint32_t>(KernelId kernel) const
{
    if (!table_ || table_->precision() != Precision::Exact) wrong_source(kernel, "an exact moment table");
    return table_->exact_origin();
}

void throw_not_a_lookup(KernelId kernel)
{
    const int index = static_cast<int>(kernel);
    const std::string name = index >= 0 && index < kKernelCount ? "'" + std::string(kernel_name(kernel)) + "'"
                                                                : "number " + std::to_string(index);
    throw Error(ErrorCategory::InvalidArgument, "receiver_lookup", "kernel",
                "kernel " + name +
                    " is not a per-receiver lookup (a pixel entry reading source, receivers, out, bad_rows); "
                    "it runs through its own schedule");
}

}  // namespace penumbra::detail
