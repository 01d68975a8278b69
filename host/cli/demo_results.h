// One row of `penumbra demo`'s results: a method at one setting on one scene,
// its frame times and its errors against the ground truth.
#pragma once

#include <string>

#include "demo_methods.h"
#include "demo_timing.h"

namespace penumbra::cli {

struct DemoRow {
    std::string scene, method, setting;
    DemoTruth truth = DemoTruth::Shadow;  // what the errors are against
    FrameTimes time;
    double rmse = 0, p99 = 0, leak = 0, overdark = 0, flicker = 0;
    double truth_noise = 0;  // the scene's: its truth's RMSE against a truth with 4x the rays
};

}  // namespace penumbra::cli
