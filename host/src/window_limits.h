// The window limits shared by the Chebyshev (chebyshev.cpp) and moment
// (moments.cpp) lookups: one check of the box radius and one of the blocker
// search of the soft methods (vssm, msm_soft), each naming its parameter.
#pragma once

#include <string>

#include "penumbra/moment_table.h"

namespace penumbra::detail {

// kRadiusRange; a float table keeps any window (no upper bound).
void check_radius(const std::string& operation, int radius, Precision precision);

// The largest filter radius of a soft method's search on `table`: the window
// is clamped to it; an exact table needs the window and its one-texel
// interpolation slivers within 255 texels, so light-size is refused where
// the blocker search would need more. Checks kLightSizeRange first.
int checked_search_radius(const std::string& operation, float light_size, const MomentTable& table);
// The same from the table's shape (a device-resident table's).
int checked_search_radius(const std::string& operation, float light_size, int width, int height, Precision precision);

}  // namespace penumbra::detail
