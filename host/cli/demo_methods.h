// The methods `penumbra demo` runs, each with a small sweep of its settings.
// A method turns one frame of a scene (shadow map + receivers) into a
// visibility image on the receivers' grid.
#pragma once

#include <functional>
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

struct DemoSetting {
    std::string label;                 // e.g. "r=3 exact"
    std::function<Image(Context&, const DemoFrame&)> run;
};

struct DemoMethod {
    std::string name;                  // e.g. "vsm"
    std::vector<DemoSetting> settings;
    int preview_setting = 0;           // index into settings: the one whose images the demo writes
};

// Every method of the library, its settings chosen for `scene` (light size
// from the scene's geometry) and a map of `map_size` texels.
std::vector<DemoMethod> demo_methods(const reference::Scene& scene, int map_size);

}  // namespace penumbra::cli
