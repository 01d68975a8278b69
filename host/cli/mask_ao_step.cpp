// The `ao` channel of `penumbra mask`: ssao-vo (penumbra/ssao.h) on the
// view depth, as the AO term 1 - saturate(2 o - 1). Its options carry the
// prefix --ao- so that the other steps' options never collide with them; the
// library's parameter names (radius, pairs, ...) are their suffixes.
#include <string>

#include "mask_steps.h"
#include "penumbra/error.h"
#include "penumbra/ssao.h"

namespace penumbra::cli {
namespace {

SsaoUnusable parse_unusable(const std::string& text)
{
    if (text == "paired") return SsaoUnusable::Paired;
    if (text == "zero") return SsaoUnusable::Zero;
    if (text == "half") return SsaoUnusable::Half;
    if (text == "renormalise") return SsaoUnusable::Renormalise;
    throw UsageError{"option --ao-unusable: '" + text + "' is not paired, zero, half or renormalise"};
}

SsaoOptions parse(const Args& args)
{
    SsaoOptions o;
    o.radius = args.number("--ao-radius", float(o.radius));
    o.pairs = args.integer("--ao-pairs", o.pairs);
    o.max_screen_radius = args.number("--ao-max-screen-radius", float(o.max_screen_radius));
    o.falloff = args.number("--ao-falloff", float(o.falloff));
    o.unusable = parse_unusable(args.text("--ao-unusable", "paired"));
    o.rotate = !args.flag("--ao-no-rotate");
    return o;
}

// The library's range checks, worded with the option's name.
void check(const Args& args)
{
    const SsaoOptions o = parse(args);
    try {
        check(kSsaoRadiusRange, o.radius, "mask");
        check(kSsaoPairsRange, o.pairs, "mask");
        check(kSsaoMaxScreenRadiusRange, o.max_screen_radius, "mask");
        check(kSsaoFalloffRange, o.falloff, "mask");
    } catch (const Error& e) {
        throw UsageError{"option --ao-" + e.parameter() + ": " + e.message()};
    }
}

void run(const MaskView& view, std::vector<MaskChannel>& out)
{
    out.push_back({"ao", ssao_obscurance(view.context, view.receivers.view_depth, view.scene.view.fov_degrees,
                                         parse(view.args))});
}

}  // namespace

MaskStep ao_mask_step()
{
    return {"ao",
            {"--ao-radius", "--ao-pairs", "--ao-max-screen-radius", "--ao-falloff", "--ao-unusable"},
            {"--ao-no-rotate"},
            "  ao (ssao-vo, volumetric obscurance with paired samples; docs/ssao.md):\n"
            "  --ao-radius R             sphere radius, world units, > 0 (default 0.5)\n"
            "  --ao-pairs N              sample pairs, in [1, 16] (default 3, the notes' 6 samples)\n"
            "  --ao-max-screen-radius F  cap of the screen radius, fraction of the height, (0, 1] (default 0.07)\n"
            "  --ao-falloff K            occluders nearer by K R or more do not occlude, > 1 (default 2)\n"
            "  --ao-unusable U           paired (default), zero, half or renormalise\n"
            "  --ao-no-rotate            one pattern for every pixel instead of the 4x4 rotation tile\n",
            check,
            run};
}

}  // namespace penumbra::cli
