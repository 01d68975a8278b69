// The methods `penumbra demo` runs, each with a small sweep of its settings.
// A method turns one frame of a scene (shadow map + receivers) into a
// visibility image on the receivers' grid.
#pragma once

#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "penumbra/context.h"
#include "penumbra/image.h"
#include "penumbra/reference/render.h"
#include "penumbra/reference/scene.h"

namespace penumbra::cli {

struct DemoFrame {
    reference::Scene scene;            // this frame's scene (the light may be shifted)
    Image shadow_map;                  // channel Z
    reference::Receivers receivers;    // light_uvz etc.
    Image truth;                       // channel Y
};

// What a setting's per-map step made for its per-receiver step (a method's
// PreparedMap), or null for a setting with no per-map work.
using DemoPrepared = std::shared_ptr<const void>;

// A setting's two steps, which the demo times apart: the per-map work (the
// table built from the shadow map, once per light per frame) and the
// per-receiver work (the shade step, and any screen-space pass after it), on
// whichever receivers it is given (the scored view or the timed frame).
struct DemoSetting {
    std::string label;                 // e.g. "r=3"
    std::function<DemoPrepared(Context&, const DemoFrame&)> prepare;
    std::function<Image(Context&, const DemoFrame&, const reference::Receivers&, const DemoPrepared&)> shade;
};

// Both steps on the frame's own receivers.
Image run_setting(Context& context, const DemoSetting& setting, const DemoFrame& frame);

struct DemoMethod {
    std::string name;                  // e.g. "vsm"
    std::vector<DemoSetting> settings;
    int preview_setting = 0;           // index into settings: the one whose images the demo writes
};

// Every method of the library, its settings chosen for `scene` (light size
// from the scene's geometry) and a map of `map_size` texels.
std::vector<DemoMethod> demo_methods(const reference::Scene& scene, int map_size);

}  // namespace penumbra::cli
