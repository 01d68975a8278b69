// start_context (penumbra/context.h) and Method::warm_up (penumbra/methods.h):
// the prepare step runs on the new context before get() returns it, and an
// Error it throws is dropped; on OpenCL, a method's warm-up on one texel
// builds every program that method's run launches, so that the run itself
// builds none (the warm start of docs/opencl_startup.md).
#include <gtest/gtest.h>

#include <future>
#include <optional>
#include <vector>

#include "penumbra/context.h"
#include "penumbra/deep_shadow_map.h"
#include "penumbra/error.h"
#include "penumbra/methods.h"
#include "penumbra/reference/pismo_maps.h"
#include "support/pismo_scenes.h"

namespace penumbra {
namespace {

TEST(StartContext, PrepareRunsOnTheNewContextBeforeGetReturnsIt)
{
    Backend seen = Backend::Auto;
    std::future<Context> starting =
        start_context(ContextOptions{Backend::Scalar, {}}, [&seen](Context& c) { seen = c.backend(); });
    const Context context = starting.get();  // the thread's write to `seen` happens before get() returns
    EXPECT_EQ(seen, Backend::Scalar);
    EXPECT_EQ(context.backend(), Backend::Scalar);
}

TEST(StartContext, AnErrorOfPrepareIsDroppedAndTheContextKept)
{
    std::future<Context> starting = start_context(ContextOptions{Backend::Scalar, {}}, [](Context&) {
        throw Error(ErrorCategory::InvalidArgument, "warm-up", "a one-texel input this method refuses");
    });
    std::optional<Context> context;
    EXPECT_NO_THROW(context.emplace(starting.get()));
    ASSERT_TRUE(context);
    EXPECT_EQ(context->backend(), Backend::Scalar);
}

// A 37 x 29 map (a ramp of depths in [0.3, 0.7]) and 23 x 17 receivers on it.
Image ramp_map()
{
    Image map(37, 29, 1);
    for (int y = 0; y < map.height(); ++y)
        for (int x = 0; x < map.width(); ++x) map.at(0, x, y) = 0.3f + 0.4f * float(x) / float(map.width());
    return map;
}

Image receivers_over(int width, int height)
{
    Image rx(width, height, 3);
    for (int y = 0; y < height; ++y)
        for (int x = 0; x < width; ++x) {
            rx.at(0, x, y) = (x + 0.5f) / float(width);
            rx.at(1, x, y) = (y + 0.5f) / float(height);
            rx.at(2, x, y) = 0.6f;
        }
    return rx;
}

// A deep map whose every pixel has a sheet of opacity 1/2 at depth 0.4.
DeepShadowMap half_shadowing_deep_map()
{
    DeepShadowMapBuilder builder(5, 3);
    for (int p = 0; p < 15; ++p) builder.add_pixel(std::vector<float>{0.4f, 0.4f}, std::vector<float>{1.0f, 0.5f});
    return builder.build();
}

TEST(MethodWarmUp, BuildsEveryProgramTheRunOfEachMethodLaunches)
{
    std::optional<Context> context;
    try {
        context.emplace(ContextOptions{Backend::OpenCL, {}});  // a context of its own: no program built yet
    } catch (const Error& e) {
        GTEST_SKIP() << "no OpenCL here: " << e.what();
    }
    const Image map = ramp_map(), receivers = receivers_over(23, 17);
    reference::LayeredMapOptions small;
    small.size = 8;
    const PismoMapSet pismo_set = reference::render_pismo_map_set(testing::half_plane_scene(), 0, small);
    Image pismo_receivers(23, 17, 3);  // ground points under the light, world positions
    for (int y = 0; y < 17; ++y)
        for (int x = 0; x < 23; ++x) {
            pismo_receivers.at(0, x, y) = -1.5f + 3.0f * float(x) / 22;
            pismo_receivers.at(2, x, y) = -0.5f + float(y) / 16;
        }
    for (const Method& method : methods()) {
        const MethodSettings settings{};
        method.warm_up(*context, settings);  // builds what this method adds to the methods before it
        const double warmed = context->program_build_seconds();
        if (method.input == MethodInput::DeepMap)
            (void)method.run(*context, half_shadowing_deep_map(), receivers, settings);
        else if (method.input == MethodInput::PismoMapSet)
            (void)method.run(*context, pismo_set, pismo_receivers, settings);
        else
            (void)method.run(*context, map, receivers, settings);
        EXPECT_EQ(context->program_build_seconds(), warmed) << method.name << ": the run built a program "
                                                               "its warm-up had not";
    }
}

TEST(MethodWarmUp, DoesNothingOnTheCpu)
{
    Context context(ContextOptions{Backend::Scalar, {}});
    for (const Method& method : methods()) EXPECT_NO_THROW(method.warm_up(context, MethodSettings{})) << method.name;
}

}  // namespace
}  // namespace penumbra
