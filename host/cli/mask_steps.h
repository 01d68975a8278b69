// The steps of `penumbra mask` (mask_command.cpp): each computes some
// channels of the deferred mask from the view of a reference scene. A new
// channel (the cascaded `shadow`, a character's `shadow2`) is one more
// MaskStep in mask_steps() and its own file; the command itself, its
// option parsing, the blur over all channels and the output stay as they are.
#pragma once

#include <string>
#include <vector>

#include "args.h"
#include "penumbra/context.h"
#include "penumbra/image.h"
#include "penumbra/reference/render.h"
#include "penumbra/reference/scene.h"

namespace penumbra::cli {

// What every step sees: the scene, its receivers on the view grid (view
// depth, world positions, normals, hit), the started backend and the options.
struct MaskView {
    const reference::Scene& scene;
    const reference::Receivers& receivers;
    Context& context;
    const Args& args;
};

struct MaskChannel {
    std::string name;  // the EXR channel: "ao", "shadow", "shadow2"
    Image values;      // 1 channel, the view's size, in [0, 1]
};

struct MaskStep {
    std::string name;                 // in messages: "ao"
    std::vector<std::string> valued;  // the step's options taking a value
    std::vector<std::string> flags;   // and its switches
    std::string help;                 // its lines of `mask --help`
    // Checks its options before anything is rendered (UsageError naming the
    // option); may be empty.
    void (*check)(const Args& args);
    // Appends the step's channels (none if the scene has nothing for it).
    void (*run)(const MaskView& view, std::vector<MaskChannel>& out);
};

// In the order their channels are written.
const std::vector<MaskStep>& mask_steps();

// The ssao-vo step: channel `ao`, the accessibility term (1 open).
MaskStep ao_mask_step();

// The cascaded shadow step: channels `shadow` (the world light) and `shadow2`
// (the character light) where the scene has them (mask_shadow_step.cpp).
MaskStep shadow_mask_step();

}  // namespace penumbra::cli
