// The methods `penumbra demo` runs, each with a small sweep of its settings.
// A method turns one frame of a scene (shadow map + receivers) into a
// visibility image on the receivers' grid.
#pragma once

#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "penumbra/context.h"
#include "penumbra/deep_shadow_map.h"
#include "penumbra/image.h"
#include "penumbra/methods.h"
#include "penumbra/pismo_files.h"
#include "penumbra/reference/render.h"
#include "penumbra/reference/scene.h"

namespace penumbra::cli {

struct DemoFrame {
    reference::Scene scene;            // this frame's scene (the light may be shifted)
    Image shadow_map;                  // channel Z
    reference::Receivers receivers;    // light_uvz etc.
    Image truth;                       // channel Y
    // The frame's deep shadow map, rendered (not timed, as the shadow map's
    // render is not) only when a wanted method reads one; null otherwise.
    std::shared_ptr<const DeepShadowMap> deep_map;
    // The frame's Pismo maps (light mesh and layered maps), rendered (not
    // timed, as the shadow map's render is not) only when a wanted method
    // reads them; null otherwise.
    std::shared_ptr<const PismoMapSet> pismo_maps;
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
    MethodInput input = MethodInput::ShadowMap;  // what its settings read from a frame
};

// The deep map the demo renders per frame for a method that reads one: half
// the shadow map's side, at most 512 (a pixel holds 2 x 2 texels' worth of
// 16 samples: 4 M rays a frame at 512^2), 16 samples per pixel, the default
// tolerance and box filter of `penumbra dsm-build`.
int demo_deep_map_size(int map_size);
inline constexpr int kDemoDeepSamples = 16;

// Pismo's maps in the demo: the light mesh at level 2 (25 maps on a
// rectangle, 37 on a disk), each half the shadow map's side, at most 512 and
// at least 64, cameras fitted to the frame's receivers (docs/pismo.md, "The
// demo rows"). A point light (the deep scenes') is meshed as the soft
// methods' one-texel square stand-in (demo_methods.cpp, SoftLight).
inline constexpr int kDemoPismoLevel = 2;
int demo_pismo_map_size(int map_size);
// The frame's maps: of `scene`, or of its stand-in light under a point light.
std::shared_ptr<const PismoMapSet> demo_pismo_maps(const reference::Scene& scene, int map_size,
                                                   const reference::Receivers& receivers);

// Every method of the library, its settings chosen for `scene` (light size
// from the scene's geometry) and a map of `map_size` texels.
std::vector<DemoMethod> demo_methods(const reference::Scene& scene, int map_size);

}  // namespace penumbra::cli
