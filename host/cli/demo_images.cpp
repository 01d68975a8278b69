#include "demo_images.h"

#include "penumbra/png_io.h"

namespace penumbra::cli {
namespace {

struct Rgb {
    float r, g, b;
};
// #2e8b57 as display values (for PngTransfer::None) and as linear light (Srgb).
constexpr Rgb kBackFaceDisplay{0.180f, 0.545f, 0.341f};
constexpr Rgb kBackFaceLinear{0.027f, 0.258f, 0.095f};

bool faces_away(const Image& valid, const Image& scored, int x, int y)
{
    return valid.at(0, x, y) > 0.5f && scored.at(0, x, y) <= 0.5f;
}

// `image` (one channel, or three) as RGB, with the back faces in `colour`.
Image with_back_faces(const Image& image, const Image& valid, const Image& scored, Rgb colour)
{
    Image rgb(image.width(), image.height(), 3);
    for (int y = 0; y < image.height(); ++y)
        for (int x = 0; x < image.width(); ++x) {
            const bool away = faces_away(valid, scored, x, y);
            for (int c = 0; c < 3; ++c) {
                const float value = image.at(image.channels() == 3 ? c : 0, x, y);
                const float back = c == 0 ? colour.r : c == 1 ? colour.g : colour.b;
                rgb.at(c, x, y) = away ? back : value;
            }
        }
    return rgb;
}

}  // namespace

void write_visibility_png(const std::string& path, const Image& visibility, const Image& valid, const Image& scored)
{
    write_png(path, with_back_faces(visibility, valid, scored, kBackFaceLinear), PngTransfer::Srgb);
}

void write_error_png(const std::string& path, const Image& estimate, const Image& truth, const Image& valid,
                     const Image& scored)
{
    Image error(estimate.width(), estimate.height(), 1);
    for (int y = 0; y < error.height(); ++y)
        for (int x = 0; x < error.width(); ++x)
            error.at(0, x, y) = scored.at(0, x, y) > 0.5f ? estimate.at(0, x, y) - truth.at(0, x, y) : 0.0f;
    write_png(path, with_back_faces(colormap_error(error, kDemoErrorScale), valid, scored, kBackFaceDisplay),
              PngTransfer::None);
}

void write_error_scale_png(const std::string& path)
{
    constexpr int width = 256, height = 12;
    Image ramp(width, height, 1);
    for (int y = 0; y < height; ++y)
        for (int x = 0; x < width; ++x) ramp.at(0, x, y) = kDemoErrorScale * (2.0f * (x + 0.5f) / width - 1.0f);
    write_png(path, colormap_error(ramp, kDemoErrorScale), PngTransfer::None);
}

}  // namespace penumbra::cli
