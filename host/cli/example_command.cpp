// penumbra example: a small synthetic shadow map and receivers, so that a new
// user can run `penumbra shade` at once (the reference scenes of
// `penumbra render-scene` are the measured cases).
//
// Light-space picture, looking down the light: a ground plane at depth 0.9, a
// disk occluder at depth 0.35 and a square post at depth 0.6 over it; the
// receivers are the ground seen straight down, on a grid of their own size.
#include <filesystem>
#include <iostream>

#include "args.h"
#include "commands.h"
#include "output_directory.h"
#include "penumbra/exr_io.h"
#include "penumbra/image.h"

namespace penumbra::cli {
namespace {

constexpr float kGroundDepth = 0.9f;

float example_depth(float u, float v)
{
    const float du = u - 0.38f, dv = v - 0.45f;
    if (du * du + dv * dv < 0.16f * 0.16f) return 0.35f;
    if (u > 0.62f && u < 0.78f && v > 0.55f && v < 0.71f) return 0.6f;
    return kGroundDepth;
}

Image example_shadow_map(int size)
{
    Image map(size, size, 1);
    for (int y = 0; y < size; ++y)
        for (int x = 0; x < size; ++x) map.at(0, x, y) = example_depth((x + 0.5f) / size, (y + 0.5f) / size);
    return map;
}

Image example_receivers(int width, int height)
{
    Image rx(width, height, 3);
    for (int y = 0; y < height; ++y)
        for (int x = 0; x < width; ++x) {
            rx.at(0, x, y) = (x + 0.5f) / width;
            rx.at(1, x, y) = (y + 0.5f) / height;
            rx.at(2, x, y) = kGroundDepth;
        }
    return rx;
}

}  // namespace

int example_command(const std::vector<std::string>& argv)
{
    const Args args(argv, {"--out", "--map-size"}, {"--help"});
    if (args.flag("--help")) {
        std::cout << "usage: penumbra example --out DIR [--map-size N]\n"
                     "  writes DIR/shadow_map.exr (Z) and DIR/receivers.exr (u, v, z)\n";
        return 0;
    }
    const std::filesystem::path dir = args.required("--out");
    const int size = args.integer("--map-size", 256);
    if (size < 1 || size > 16384) throw UsageError{"option --map-size: must be in [1, 16384]"};
    create_output_directory(dir, "--out");
    // Both or neither (a full disk used to leave a new map beside old receivers).
    OutputFiles outputs("example");
    stage_exr(outputs, (dir / "shadow_map.exr").string(), example_shadow_map(size), {"Z"});
    stage_exr(outputs, (dir / "receivers.exr").string(), example_receivers(320, 240), {"u", "v", "z"});
    outputs.publish();
    std::cout << "wrote " << (dir / "shadow_map.exr").string() << " and " << (dir / "receivers.exr").string() << "\n";
    return 0;
}

}  // namespace penumbra::cli
