// penumbra mask: the deferred mask of the Toy Story 3 notes (issue 16) for a
// reference scene's view: one channel per step of mask_steps() (ao, then
// the shadow steps), optionally blurred together in one cross-bilateral
// pass guided by the view depth, written as one EXR.
#include <iostream>
#include <set>
#include <string>
#include <vector>

#include "commands.h"
#include "mask_steps.h"
#include "penumbra/bilateral.h"
#include "penumbra/error.h"
#include "penumbra/exr_io.h"
#include "penumbra/output_files.h"
#include "penumbra/ssao.h"
#include "scene_input.h"

namespace penumbra::cli {

const std::vector<MaskStep>& mask_steps()
{
    static const std::vector<MaskStep> steps = {ao_mask_step(), shadow_mask_step()};
    return steps;
}

namespace {

const std::set<std::string> kValued = {"--scene", "--out", "--view-size", "--backend"};
const std::set<std::string> kFlags = {"--blur", "--help"};

std::string help_text()
{
    std::string text =
        "usage: penumbra mask --scene S --out MASK.exr [--view-size WxH] [--blur] [--backend B] [step options]\n"
        "  S: a built-in scene name or a scene .json; MASK.exr: one float channel per step, in [0, 1].\n"
        "  --view-size WxH  the view's pixels (default 1280x720)\n"
        "  --blur           one 5x5 cross-bilateral pass over all channels, guided by view depth\n"
        "                   (threshold 0.05 of the centre depth: the notes' filter)\n"
        "  --backend B      auto (default), simd, opencl or scalar\n";
    for (const MaskStep& step : mask_steps()) text += step.help;
    return text;
}

Args parse_args(const std::vector<std::string>& argv)
{
    std::set<std::string> valued = kValued, flags = kFlags;
    for (const MaskStep& step : mask_steps()) {
        valued.insert(step.valued.begin(), step.valued.end());
        flags.insert(step.flags.begin(), step.flags.end());
    }
    return Args(argv, valued, flags);
}

// The channels as planes of one image, for the blur and the writer.
Image stack(const std::vector<MaskChannel>& channels)
{
    const Image& first = channels.front().values;
    Image image(first.width(), first.height(), int(channels.size()));
    for (int c = 0; c < image.channels(); ++c)
        for (int y = 0; y < image.height(); ++y)
            for (int x = 0; x < image.width(); ++x) image.at(c, x, y) = channels[std::size_t(c)].values.at(0, x, y);
    return image;
}

// Stacks the channels, blurs them together when a guide is given, writes them.
void write_mask(const std::string& path, const std::vector<MaskChannel>& channels, const Image* guide,
                Context& context)
{
    if (channels.empty() || channels.size() > std::size_t(kBilateralMaxChannels))
        throw Error(ErrorCategory::InvalidArgument, "mask",
                    "the steps made " + std::to_string(channels.size()) + " channels; a mask holds 1 to 4");
    Image mask = stack(channels);
    if (guide) mask = cross_bilateral(context, mask, *guide, ssao_blur_options());
    std::vector<std::string> names;
    for (const MaskChannel& c : channels) names.push_back(c.name);
    write_exr(path, mask, names);
}

}  // namespace

int mask_command(const std::vector<std::string>& argv)
{
    const Args args = parse_args(argv);
    if (args.flag("--help")) {
        std::cout << help_text();
        return 0;
    }
    const std::string out_path = args.required("--out");
    const std::string scene_name = args.required("--scene");
    require_safe_outputs({out_path}, {}, "mask");
    const ViewSize size = parse_view_size(args.text("--view-size", "1280x720"));
    for (const MaskStep& step : mask_steps())
        if (step.check) step.check(args);
    const Backend backend = backend_option(args);
    try {
        const reference::Scene scene = resolve_scene(scene_name);
        Context context(ContextOptions{backend, {}});
        for (const std::string& warning : context.warnings()) std::cerr << "penumbra mask: warning: " << warning << "\n";
        const reference::Receivers receivers = reference::render_receivers(scene, size.width, size.height);
        const MaskView view{scene, receivers, context, args};
        std::vector<MaskChannel> channels;
        for (const MaskStep& step : mask_steps()) step.run(view, channels);
        write_mask(out_path, channels, args.flag("--blur") ? &receivers.view_depth : nullptr, context);
    } catch (const Error& e) {
        if (e.category() == ErrorCategory::Backend) throw;
        throw e.as_operation("mask");
    }
    return 0;
}

}  // namespace penumbra::cli
