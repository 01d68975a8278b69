// Range checks of the shading options (penumbra/parameter_range.h).
#include "penumbra/parameter_range.h"

#include <cmath>
#include <sstream>

#include "penumbra/error.h"

namespace penumbra {
namespace {

// Shortest round-trip-ish text: 127, 0.5, 2e-05.
std::string number(double v)
{
    std::ostringstream text;
    text << v;
    return text.str();
}

std::string lower_bound(const ParameterRange& r) { return (r.low_open ? "> " : ">= ") + number(r.low); }

}  // namespace

std::string describe(const ParameterRange& r)
{
    if (std::isinf(r.high)) return lower_bound(r);
    return std::string(r.low_open ? "(" : "[") + number(r.low) + ", " + number(r.high) + (r.high_open ? ")" : "]");
}

bool contains(const ParameterRange& r, double v)
{
    const bool above_low = r.low_open ? v > r.low : v >= r.low;
    const bool below_high = r.high_open ? v < r.high : v <= r.high;
    return above_low && below_high;  // both false for NaN
}

void check(const ParameterRange& r, double v, std::string_view operation)
{
    if (contains(r, v)) return;
    const bool storage_bound = *r.why_high != '\0';
    std::string message;
    if (storage_bound && v > r.high)
        message = std::string(r.label) + " " + number(v) + " exceeds " + number(r.high) + r.why_high;
    else if (storage_bound || std::isinf(r.high))  // below a storage bound, only the lower one is news
        message = std::string(r.label) + " must be " + lower_bound(r) + " (got " + number(v) + ")";
    else
        message = std::string(r.label) + " must be in " + describe(r) + " (got " + number(v) + ")";
    throw Error(ErrorCategory::InvalidArgument, operation, r.name, message);
}

}  // namespace penumbra
