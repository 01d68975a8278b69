// `penumbra shade --depth-convention normalized|linear|perspective|reversed
// --near N --far F --depth-channel NAME`: the reference scenes' maps and
// receivers (render-scene) written in each convention give the normalised
// files' visibility for every method that reads a shadow map, within the
// tolerance below; a map whose channel is depth.Z or R; and the refusals
// (exit 2, one line naming the option or file, no output left).
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <string>
#include <vector>

#include "penumbra/exr_io.h"
#include "penumbra/methods.h"
#include "support/cli.h"
#include "support/depth_conventions.h"
#include "support/maps.h"
#include "support/run_cli.h"

namespace penumbra {
namespace {

using testing::run_cli;

class DepthConventionCli : public testing::CliFixture {
protected:
    void render(const std::string& scene)
    {
        const testing::CliRun run =
            run_cli({"render-scene", scene, "--map-size", "64", "--view-size", "24x16", "--samples", "1",
                     "--shadow-map", path("sm.exr"), "--receivers", path("rx.exr"), "--truth", path("gt.exr")});
        ASSERT_EQ(run.exit_code, 0) << run.err;
    }
    testing::CliRun shade(const std::string& method, const std::string& map, const std::string& rx,
                          const std::string& out, const std::vector<std::string>& options)
    {
        std::vector<std::string> args{"shade",       "--method",  method,    "--shadow-map", path(map),
                                      "--receivers", path(rx),    "--out",   path(out),      "--backend",
                                      "simd"};
        args.insert(args.end(), options.begin(), options.end());
        return run_cli(args);
    }
    // The rendered files rewritten in convention c (double, stored float32).
    void write_in(const DepthConvention& c, const std::string& map_channel = "Z")
    {
        const Image map = read_exr(path("sm.exr"), {"Z"});
        const Image rx = read_exr(path("rx.exr"), {"u", "v", "z"});
        write_exr(path("sm_c.exr"), testing::in_convention(map, 0, c), {map_channel});
        write_exr(path("rx_c.exr"), testing::in_convention(rx, 2, c), {"u", "v", "z"});
    }
};

std::vector<std::string> convention_flags(const DepthConvention& c)
{
    if (c.kind == DepthConventionKind::Normalized) return {"--depth-convention", "normalized"};
    return {"--depth-convention", to_string(c.kind), "--near", "0.5", "--far", "50"};
}

// The tolerance: the storage's error (at most 6e-6 in normalised depth,
// perspective at the far plane; measured by DepthConventionStorage) moves
// the moment methods smoothly (by their slope in depth: measured up to 2e-4,
// msm-soft's blocker search 4e-3 on 0.3% of the receivers) and moves a
// decision where a percentage-closer tap's depth lies that close to its
// reference or a blocker search's radius crosses a texel edge (burley,
// perspective: one tap of 24 on 0.3 to 0.8% of the receivers). Stated:
// at most 2% of the receivers move by more than 1e-3, none by more than
// 0.25 (one tap's weight of the smallest filter bounds a single flip), and
// the mean moves by less than 2e-3.
struct Change {
    double max = 0.0, mean = 0.0;
    double moved = 0.0;  // share of receivers moved by more than 1e-3
};
Change change(const Image& a, const Image& b)
{
    Change c;
    const int n = a.width() * a.height();
    for (int y = 0; y < a.height(); ++y)
        for (int x = 0; x < a.width(); ++x) {
            const double d = std::abs(double(a.at(0, x, y)) - b.at(0, x, y));
            c.max = std::max(c.max, d);
            c.mean += d / n;
            c.moved += d > 1e-3 ? 1.0 / n : 0.0;
        }
    return c;
}

TEST_F(DepthConventionCli, ReferenceScenesInEachConventionShadeAlike)
{
    std::vector<std::string> shadow_map_methods;
    for (const Method& m : methods())
        if (m.input == MethodInput::ShadowMap) shadow_map_methods.emplace_back(m.name);
    ASSERT_EQ(shadow_map_methods.size(), 11u);
    for (const char* scene : {"contact", "overlap"}) {
        render(scene);
        for (const std::string& method : shadow_map_methods) {
            ASSERT_EQ(shade(method, "sm.exr", "rx.exr", "want.exr", {}).exit_code, 0) << method;
            const Image want = read_exr(path("want.exr"), {"Y"});
            for (DepthConventionKind kind : testing::kAllConventions) {
                const DepthConvention c = testing::convention_of(kind);
                write_in(c);
                const testing::CliRun run = shade(method, "sm_c.exr", "rx_c.exr", "got.exr", convention_flags(c));
                ASSERT_EQ(run.exit_code, 0) << method << " " << to_string(kind) << ": " << run.err;
                const Change d = change(read_exr(path("got.exr"), {"Y"}), want);
                std::printf("%-8s %-9s %-12s max %.3g mean %.3g moved %.3f\n", scene, method.c_str(),
                            to_string(kind).c_str(), d.max, d.mean, d.moved);
                EXPECT_LE(d.max, 0.25) << scene << " " << method << " " << to_string(kind);
                EXPECT_LE(d.mean, 2e-3) << scene << " " << method << " " << to_string(kind);
                EXPECT_LE(d.moved, 0.02) << scene << " " << method << " " << to_string(kind);
            }
        }
    }
}

TEST_F(DepthConventionCli, DepthChannelReadsDepthZAndR)
{
    render("contact");
    const DepthConvention reversed = testing::convention_of(DepthConventionKind::Reversed);
    write_in(reversed);
    ASSERT_EQ(shade("pcf", "sm_c.exr", "rx_c.exr", "want.exr", convention_flags(reversed)).exit_code, 0);
    const Image want = read_exr(path("want.exr"), {"Y"});
    for (const char* channel : {"depth.Z", "R"}) {
        write_in(reversed, channel);
        std::vector<std::string> flags = convention_flags(reversed);
        flags.insert(flags.end(), {"--depth-channel", channel});
        const testing::CliRun run = shade("pcf", "sm_c.exr", "rx_c.exr", "got.exr", flags);
        ASSERT_EQ(run.exit_code, 0) << channel << ": " << run.err;
        EXPECT_EQ(testing::difference(read_exr(path("got.exr"), {"Y"}), want).differing, 0) << channel;
    }
}

TEST_F(DepthConventionCli, HelpListsTheOptions)
{
    const testing::CliRun run = run_cli({"shade", "--help"});
    ASSERT_EQ(run.exit_code, 0);
    for (const char* flag : {"--depth-convention", "--near", "--far", "--depth-channel", "perspective", "reversed"})
        EXPECT_NE(run.out.find(flag), std::string::npos) << flag;
}

TEST_F(DepthConventionCli, BadConventionsAndChannelsAreOneLineAndExitTwo)
{
    render("contact");
    write_in(testing::convention_of(DepthConventionKind::Linear));
    const std::string base = "shade --backend simd --out " + path("out.exr") + " --receivers " + path("rx_c.exr") +
                             " --shadow-map " + path("sm_c.exr") + " --method ";
    expect_bad_inputs([&](const std::string& rest) { return base + rest; },
                      {
                          {"pcf --depth-convention perspective --near 0 --far 5", "option --near"},
                          {"vsm --depth-convention reversed --near 2 --far 1", "option --far"},
                          {"msm --depth-convention linear --near 0.5", "option --far"},
                          {"pcss --depth-convention perspective --near 0.5 --far inf", "option --far"},
                          {"pcf --near 0.5 --far 50", "option --near"},
                          {"evsm4 --depth-convention zbuffer", "option --depth-convention"},
                          {"vssm --depth-convention linear --near 0.5 --far 10", "channel Z at pixel"},
                          {"pcf --depth-convention linear --near 0.5 --far 50 --depth-channel Q", "Q"},
                          {"pcf-gauss --depth-convention linear --near 0.5 --far 50 --depth-channel",
                           "--depth-channel"},
                          {"burley --depth-convention perspective --near 0.5 --far 50", "outside [0, 1]"},
                      });
    expect_bad_input("shade --method dsm --deep-map " + path("sm.exr") + " --receivers " + path("rx.exr") +
                         " --out " + path("out.exr") + " --depth-channel R",
                     "option --depth-channel");
}

}  // namespace
}  // namespace penumbra
