// The `shadow` and `shadow2` channels of `penumbra mask`: the cascaded shadow
// mask (penumbra/cascades.h; docs/cascades.md) of the scene's directional
// lights, the world light then the character light, each with its own
// cascades fitted to the view (penumbra/reference/cascades.h). A scene
// without a directional light gets no shadow channel, and any cascade option
// given for it is an error. Options carry the prefix --cascade(s)/--shadow-.
#include <string>

#include "mask_steps.h"
#include "penumbra/cascades.h"
#include "penumbra/error.h"
#include "penumbra/reference/cascades.h"

namespace penumbra::cli {
namespace {

const std::vector<std::string> kValued = {"--cascades",         "--cascade-size", "--cascade-select",
                                          "--cascade-near-plane", "--shadow-near",  "--shadow-far"};

reference::CascadeSetup parse_setup(const Args& args)
{
    reference::CascadeSetup s;
    s.count = args.integer("--cascades", s.count);
    s.map_size = args.integer("--cascade-size", s.map_size);
    s.near = args.number("--shadow-near", 0);
    s.far = args.number("--shadow-far", 0);
    const std::string plane = args.text("--cascade-near-plane", "pancake");
    if (plane != "pancake" && plane != "clip")
        throw UsageError{"option --cascade-near-plane: '" + plane + "' is not pancake or clip"};
    s.near_plane = plane == "clip" ? reference::NearPlane::Clip : reference::NearPlane::Pancake;
    return s;
}

CascadeOptions parse_options(const Args& args)
{
    CascadeOptions o;
    const std::string select = args.text("--cascade-select", "box");
    if (select != "box" && select != "split")
        throw UsageError{"option --cascade-select: '" + select + "' is not box or split"};
    o.selection = select == "split" ? CascadeSelection::SplitDepth : CascadeSelection::BoundingBox;
    return o;
}

void check(const Args& args)
{
    const reference::CascadeSetup s = parse_setup(args);
    parse_options(args);
    if (s.count < 1 || s.count > kMaxCascades)
        throw UsageError{"option --cascades: " + std::to_string(s.count) + " cascades asked for; give 1 to " +
                         std::to_string(kMaxCascades)};
    if (s.map_size < 8 || s.map_size > 8192)
        throw UsageError{"option --cascade-size: " + std::to_string(s.map_size) + " is outside [8, 8192]"};
    if (s.near < 0 || s.far < 0 || (s.far > 0 && s.far <= s.near))
        throw UsageError{"options --shadow-near, --shadow-far: need 0 <= near < far (or both unset)"};
}

bool cascades_asked_for(const Args& args)
{
    for (const std::string& option : kValued)
        if (args.get(option)) return true;
    return false;
}

void run(const MaskView& view, std::vector<MaskChannel>& out)
{
    const int lights = int(view.scene.directional_lights.size());
    if (lights == 0 && cascades_asked_for(view.args))
        throw UsageError{"scene '" + view.scene.name +
                         "' has no directional light, which cascades need (add \"directional_lights\" to it)"};
    const reference::CascadeSetup setup = parse_setup(view.args);
    const CascadeOptions options = parse_options(view.args);
    const Image rx = reference::cascade_receivers(view.receivers);
    for (int light = 0; light < lights; ++light) {
        const CascadeShadows shadows = reference::render_cascades(view.scene, light, view.receivers, setup);
        const Image mask = cascade_mask(view.context, shadows, rx, options);
        Image visibility(mask.width(), mask.height(), 1);
        for (int y = 0; y < mask.height(); ++y)
            for (int x = 0; x < mask.width(); ++x) visibility.at(0, x, y) = mask.at(0, x, y);
        out.push_back({light == 0 ? "shadow" : "shadow2", std::move(visibility)});
    }
}

}  // namespace

MaskStep shadow_mask_step()
{
    return {"shadow",
            kValued,
            {},
            "  shadow, shadow2 (cascaded shadow maps of the scene's directional lights; docs/cascades.md):\n"
            "  --cascades K              cascades per light, 1 to 4 (default 3, the notes')\n"
            "  --cascade-size N          each cascade's side in texels, [8, 8192] (default 640)\n"
            "  --cascade-select S        box (default: the finest box holding the pixel, Zhang 2009) or split\n"
            "  --cascade-near-plane P    pancake (default: casters clamped to the near plane) or clip\n"
            "  --shadow-near D, --shadow-far D  the shadowed view depths (default: the surfaces seen)\n",
            check,
            run};
}

}  // namespace penumbra::cli
