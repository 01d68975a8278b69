// The methods `penumbra demo` runs, each with a small sweep of its settings.
// A method turns one frame of a scene (shadow map + receivers) into a
// visibility image on the receivers' grid.
#pragma once

#include <functional>
#include <map>
#include <memory>
#include <mutex>
#include <string>
#include <vector>

#include "penumbra/cascades.h"
#include "penumbra/context.h"
#include "penumbra/deep_shadow_map.h"
#include "penumbra/image.h"
#include "penumbra/methods.h"
#include "penumbra/pismo_files.h"
#include "penumbra/reference/render.h"
#include "penumbra/reference/scene.h"

namespace penumbra::cli {

// What a method's rows are scored against. The shadow rows estimate the
// visibility of the scene's own light; the ssao-vo rows another quantity
// (obscurance), the cascaded rows another light (the scene's first
// directional light, the sun): each kind has its own chart panels and table.
enum class DemoTruth {
    Shadow,      // the frame's truth: the scene's area (or point) light
    Obscurance,  // volumetric obscurance, ball of SsaoOptions{}.radius (reference/obscurance_truth.h)
    Sun,         // the hard shadow of directional light 0 (reference/cascades.h)
};
const char* truth_name(DemoTruth truth);  // "shadow", "obscurance", "sun": the CSV's `truth` column

// The sun's inputs, rendered once per scene (the frames move only the scene's
// own light, so every frame shares them) when a wanted method reads them: the
// cascades, one map of the same light at their total texels, and the truth.
struct DemoFrame;
struct SunInputs {
    CascadeShadows cascades;  // kDemoCascades of demo_cascade_size, fitted to the view
    // One cascade of sqrt(kDemoCascades) x the side (the same texels), fitted
    // to the whole view, as a frame whose shadow map it is: the shadow-map
    // methods read it as they read the scene's own.
    CascadeFrame single;
    std::shared_ptr<const DemoFrame> single_map_frame;
    Image truth;              // reference::directional_truth on the view
    // The receivers' light-space forms, derived once per receiver set (a
    // frame's view, the timed frame; they outlive the scene's run) when first
    // shaded, i.e. in the untimed scoring or warm-up: the renderer derives
    // light_uvz for the other rows untimed too.
    const Image& cascade_receivers(const reference::Receivers& rx) const;
    const reference::Receivers& single_map_receivers(const reference::Receivers& rx) const;

private:
    mutable std::mutex mutex_;
    mutable std::map<const reference::Receivers*, Image> cascade_rx_;
    mutable std::map<const reference::Receivers*, reference::Receivers> single_rx_;
};
inline constexpr int kDemoCascades = 3;  // the notes' count, reference::CascadeSetup's default
int demo_cascade_size(int map_size);     // the notes' 640, at most the demo's map size
std::shared_ptr<const SunInputs> render_sun_inputs(const reference::Scene& scene, int map_size,
                                                   const reference::Receivers& view);

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
    // The volumetric-obscurance truth and the sun's inputs, rendered only
    // when a wanted method is scored against them (shared by the frames).
    std::shared_ptr<const Image> obscurance_truth;
    std::shared_ptr<const SunInputs> sun;
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
    DemoTruth truth = DemoTruth::Shadow;          // what its rows are scored against
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
