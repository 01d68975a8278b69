// penumbra::DepthConvention as the kernels read it (kernels/params.h,
// DepthConversion; kernels/depth_convention.h converts with it).
#pragma once

#include <string>

#include "kernels/params.h"
#include "penumbra/depth_convention.h"

namespace penumbra::detail {

// The kernels' block of a checked convention; the scale in double, rounded once.
DepthConversion kernel_conversion(const DepthConvention& convention);

// A table lookup's receivers are in the map's convention: the options' must
// be the table's (Error(InvalidArgument), parameter "depth-convention").
DepthConversion receivers_conversion(const std::string& operation, const DepthConvention& table,
                                     const DepthConvention& options);

}  // namespace penumbra::detail
