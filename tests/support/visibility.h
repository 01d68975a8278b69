// The check every shading test makes of a kernel's output: channel 0 is a
// visibility, finite and in [0, 1] at every pixel (never NaN: the project's
// rule for any input).
#pragma once

#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "penumbra/image.h"

namespace penumbra::testing {

// `where` names the case in the failure message.
inline void expect_visibility(const Image& out, const std::string& where = "visibility")
{
    for (int y = 0; y < out.height(); ++y)
        for (int x = 0; x < out.width(); ++x) {
            const float v = out.at(0, x, y);
            ASSERT_TRUE(std::isfinite(v) && v >= 0.0f && v <= 1.0f) << where << ": " << v << " at " << x << "," << y;
        }
}

}  // namespace penumbra::testing
