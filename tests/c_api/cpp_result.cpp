// The C++ API's result for the C test (cpp_result.h): Images filled from the
// C test's planar arrays, run through the method table and the blur.
#include "cpp_result.h"

#include <cstdio>
#include <exception>
#include <string>
#include <utility>
#include <vector>

#include "penumbra/bilateral.h"
#include "penumbra/error.h"
#include "penumbra/methods.h"

namespace {

penumbra::Image planar(const float* values, int width, int height, int channels)
{
    penumbra::Image image(width, height, channels);
    for (int c = 0; c < channels; ++c)
        for (int y = 0; y < height; ++y)
            for (int x = 0; x < width; ++x)
                image.at(c, x, y) = values[(std::size_t(c) * height + y) * width + x];
    return image;
}

void copy_out(const penumbra::Image& image, float* out)
{
    for (int c = 0; c < image.channels(); ++c)
        for (int y = 0; y < image.height(); ++y)
            for (int x = 0; x < image.width(); ++x)
                out[(std::size_t(c) * image.height() + y) * image.width() + x] = image.at(c, x, y);
}

template <class Body>
int guarded(Body body)
{
    try {
        body();
        return 0;
    } catch (const penumbra::Error& e) {
        if (e.category() == penumbra::ErrorCategory::Unavailable) return 1;
        std::fprintf(stderr, "C++ reference: %s\n", e.what());
    } catch (const std::exception& e) {
        std::fprintf(stderr, "C++ reference: %s\n", e.what());
    }
    return 2;
}

penumbra::Context context(const char* backend)
{
    return penumbra::Context(penumbra::ContextOptions{penumbra::parse_backend(backend), {}});
}

}  // namespace

extern "C" int cpp_shade(const char* backend, const char* method, const char* const* names,
                         const char* const* values, size_t count, const float* map, int map_width, int map_height,
                         const float* receivers, int receiver_channels, int width, int height, float* out)
{
    return guarded([&] {
        penumbra::Context ctx = context(backend);
        std::vector<std::pair<std::string, std::string>> given;
        for (size_t i = 0; i < count; ++i) given.emplace_back(names[i], values[i]);
        const penumbra::Method& m = penumbra::find_method(method);
        copy_out(m.run(ctx, planar(map, map_width, map_height, 1), planar(receivers, width, height, receiver_channels),
                       penumbra::parse_method_settings(m, given)),
                 out);
    });
}

extern "C" int cpp_blur(const char* backend, const float* mask, int channels, const float* guide, int width,
                        int height, int radius, float* out)
{
    return guarded([&] {
        penumbra::Context ctx = context(backend);
        penumbra::BilateralOptions options;
        options.radius = radius;
        copy_out(penumbra::cross_bilateral(ctx, planar(mask, width, height, channels), planar(guide, width, height, 1),
                                           options),
                 out);
    });
}
