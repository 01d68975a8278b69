// How `penumbra demo` times a setting: on a stated frame (1920x1080 receivers
// by default) rather than on the small view it scores, with the per-map work
// (the table build, once per light per frame) and the per-receiver work timed
// apart; a warm-up run of every setting first (OpenCL builds, first-touch
// pages, the distance grid's bake), then repetitions interleaved across the
// scene's settings, each round in a new shuffled order, so that a slow moment
// of a shared machine lands on many settings a little instead of on one.
#pragma once

#include <vector>

#include "demo_methods.h"

namespace penumbra::cli {

// One setting's times, medians over the repetitions, in milliseconds per
// frame; min and max are the whole frame's (map + receivers) spread.
struct FrameTimes {
    double map_ms = 0, receiver_ms = 0, frame_ms = 0, frame_min_ms = 0, frame_max_ms = 0;
    int repetitions = 0;
};

// Times each of `settings` on `frame` with `timed` as its receivers.
std::vector<FrameTimes> time_settings(Context& context, const std::vector<const DemoSetting*>& settings,
                                      const DemoFrame& frame, const reference::Receivers& timed, int repetitions);

}  // namespace penumbra::cli
