// LookupSource and the refusal of a kernel that is no lookup
// (host/backend/backend.h): the parts of the generic per-receiver lookup that
// both backends share; the check of a shadow map a lookup reads itself
// (checked_lookup.h).
#include <string>

#include "checked_lookup.h"
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
    if (!table_) wrong_source(kernel, "one float buffer (a float table or image)");
    if (table_->precision() != Precision::Float) wrong_source(kernel, "float values (a float table or image)");
    return table_->float_origin();
}

template <>
const std::uint32_t* LookupSource::origin<std::uint32_t>(KernelId kernel) const
{
    if (!table_ || table_->precision() != Precision::Exact) wrong_source(kernel, "an exact moment table");
    return table_->exact_origin();
}

template <>
const float* SourceArray::data<float>(KernelId kernel) const
{
    if (!floats_) wrong_source(kernel, "a float array at this place");
    return static_cast<const float*>(data_);
}

template <>
const std::uint32_t* SourceArray::data<std::uint32_t>(KernelId kernel) const
{
    if (floats_) wrong_source(kernel, "a uint array at this place");
    return static_cast<const std::uint32_t*>(data_);
}

void throw_wrong_arrays(KernelId kernel, std::size_t wanted, std::size_t given)
{
    throw Error(ErrorCategory::InvalidArgument, "receiver_lookup", "source",
                "kernel '" + std::string(kernel_name(kernel)) + "' reads " + std::to_string(wanted) +
                    " source arrays, and the source given holds " + std::to_string(given) +
                    "; pass the map its entry names");
}

// The map is scanned for values outside its convention's range up front: the
// kernels do not flag them (a NaN depth would silently count as neither
// blocker nor lit in a percentage-closer test, and the direct sums clamp it).
void check_shadow_map(const Image& map, const std::string& op, const DepthConvention& convention)
{
    require(!map.empty(), op, "depth", "the shadow map is empty (0 texels)");
    require(map.channels() == 1, op, "depth",
            "the shadow map must have one channel (depth), got " + std::to_string(map.channels()));
    check_depth_convention(convention, op);
    require_depths_in(map, convention, op);
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
