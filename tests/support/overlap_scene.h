// The `overlap` reference scene (docs/reference.md: two slabs overlapping as
// seen from the light, a footprint that holds two blocker depths and the
// receiver) rendered into one frame, and the light-leaking table of the
// moment methods on it: VSM against EVSM2, EVSM4 and MSM (and the soft
// methods), scored against ray-traced ground truth with
// penumbra/reference/metrics.h. Shared by tests/kernels/moments_overlap_test.cpp
// (a check at a small size) and bench/overlap_leak_table.cpp (the table of
// docs/moments.md).
#pragma once

#include <string>
#include <utility>
#include <vector>

#include "penumbra/image.h"
#include "penumbra/reference.h"

namespace penumbra::testing {

struct OverlapFrame {
    reference::Scene scene;
    Image map;
    reference::Receivers receivers;
    Image truth;
    Image two_layers;  // valid receivers whose ray to the light's centre crosses both slabs
};

// The overlap scene at a `map_size`^2 shadow map and `width` x `height`
// receivers, its truth with `strata`^2 rays per receiver.
OverlapFrame render_overlap_frame(int map_size, int width, int height, int strata);

struct LeakScore {
    double leak, leak_two_layers, rmse, dark;
};
using LeakTable = std::vector<std::pair<std::string, LeakScore>>;

// Every method of the table (leak_methods() in overlap_scene.cpp lists them with their
// settings) on the SIMD backend at box radius `radius`.
LeakTable overlap_leak_table(const OverlapFrame& frame, int radius);
void print_leak_table(const LeakTable& rows);

}  // namespace penumbra::testing
