#include "window_limits.h"

#include <algorithm>
#include <cmath>

#include "penumbra/error.h"
#include "penumbra/parameter_range.h"

namespace penumbra::detail {

void check_radius(const std::string& operation, int radius, Precision precision)
{
    ParameterRange range = kRadiusRange;
    if (precision == Precision::Float) {
        range.high = kNoUpperBound;
        range.why_high = "";
    }
    check(range, radius, operation);
}

int checked_search_radius(const std::string& operation, float light_size, const MomentTable& table)
{
    return checked_search_radius(operation, light_size, table.width(), table.height(), table.precision());
}

int checked_search_radius(const std::string& operation, float light_size, int width, int height, Precision precision)
{
    check(kLightSizeRange, light_size, operation);
    const int extent = std::max(width, height);
    if (precision == Precision::Float) return extent;
    const int max_radius = kExactMaxRadius - 1;
    const float search_half = light_size * 0.5f * float(extent);
    require(search_half <= float(max_radius), operation, kLightSizeRange.name,
            "light-size " + std::to_string(light_size) + " needs a blocker search of " +
                std::to_string(int(std::ceil(2 * search_half))) + " texels, more than an exact table keeps exact (" +
                std::to_string(2 * max_radius + 1) + "); use a smaller light");
    return max_radius;
}

}  // namespace penumbra::detail
