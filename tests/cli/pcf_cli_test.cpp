// `penumbra shade --method pcf|pcf-gauss|pcf-disc`: the window contract
// checked exactly as issue 12 writes it (`--method pcf --radius R
// --depth-bias B` against a brute-force loop over the files' values), every
// bias mode and option through the tool, and the refusals (exit 2, one line
// on stderr naming the option or file).
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "penumbra/exr_io.h"
#include "support/cli.h"
#include "support/pcf_reference.h"
#include "support/run_cli.h"

namespace penumbra {
namespace {

using testing::run_cli;

class PcfCli : public testing::CliFixture {
protected:
    void SetUp() override
    {
        CliFixture::SetUp();
        ASSERT_EQ(run_cli({"example", "--out", path("ex")}).exit_code, 0);
    }
    testing::CliRun shade(const std::string& method, const std::vector<std::string>& options,
                          const std::string& receivers = "ex/receivers.exr")
    {
        std::vector<std::string> args{"shade", "--method", method, "--shadow-map", path("ex/shadow_map.exr"),
                                      "--receivers", path(receivers), "--out", path("out.exr")};
        args.insert(args.end(), options.begin(), options.end());
        return run_cli(args);
    }
    // The example's receivers with channels dzdu, dzdv of a gentle slope.
    std::string receivers_with_slopes()
    {
        const Image rx = read_exr(path("ex/receivers.exr"), {"u", "v", "z"});
        Image with(rx.width(), rx.height(), 5);
        for (int y = 0; y < rx.height(); ++y)
            for (int x = 0; x < rx.width(); ++x) {
                for (int c = 0; c < 3; ++c) with.at(c, x, y) = rx.at(c, x, y);
                with.at(3, x, y) = 0.05f;
                with.at(4, x, y) = -0.02f;
            }
        write_exr(path("rx5.exr"), with, {"u", "v", "z", "dzdu", "dzdv"});
        return "rx5.exr";
    }
};

TEST_F(PcfCli, BoxWindowContractHoldsExactly)
{
    const Image map = read_exr(path("ex/shadow_map.exr"), {"Z"});
    const Image rx = read_exr(path("ex/receivers.exr"), {"u", "v", "z"});
    for (const int radius : {0, 1, 3})
        for (const double bias : {0.0, 0.01}) {
            const testing::CliRun run =
                shade("pcf", {"--radius", std::to_string(radius), "--depth-bias", std::to_string(bias)});
            ASSERT_EQ(run.exit_code, 0) << run.err;
            const Image out = read_exr(path("out.exr"), {"Y"});
            const testing::RefBias b{testing::RefBiasMode::Constant, double(float(bias))};
            for (int y = 0; y < rx.height(); ++y)
                for (int x = 0; x < rx.width(); ++x) {
                    const testing::RefResult want =
                        testing::pcf_box_reference(map, testing::ref_receiver(rx, x, y), b, radius);
                    if (want.margin < 1e-6) continue;  // a tie float32 may take either way
                    ASSERT_NEAR(out.at(0, x, y), want.visibility, 1e-6)
                        << "r=" << radius << " bias=" << bias << " at (" << x << ", " << y << ")";
                }
        }
}

TEST_F(PcfCli, EveryMethodAndBiasModeShades)
{
    const std::string slopes = receivers_with_slopes();
    const std::vector<std::pair<std::string, std::vector<std::string>>> cases = {
        {"pcf", {"--bias-mode", "slope", "--slope-scale", "2"}},
        {"pcf", {"--bias-mode", "receiver-plane", "--bias-min", "0.0001", "--bias-max", "0.01"}},
        {"pcf-gauss", {}},
        {"pcf-gauss", {"--grid", "6", "--sigma", "1.5", "--bias-mode", "receiver-plane"}},
        {"pcf-disc", {}},
        {"pcf-disc", {"--taps", "64", "--disc-radius", "4", "--rotation", "none", "--bias-mode", "slope"}},
    };
    for (const auto& [method, options] : cases) {
        const testing::CliRun run = shade(method, options);
        ASSERT_EQ(run.exit_code, 0) << method << ": " << run.err;
        const Image out = read_exr(path("out.exr"), {"Y"});
        for (int y = 0; y < out.height(); ++y)
            for (int x = 0; x < out.width(); ++x) ASSERT_TRUE(out.at(0, x, y) >= 0.0f && out.at(0, x, y) <= 1.0f);
    }
    const testing::CliRun run =
        shade("pcf", {"--bias-mode", "receiver-plane", "--bias-derivatives", "channels"}, slopes);
    EXPECT_EQ(run.exit_code, 0) << run.err;
}

TEST_F(PcfCli, BadValuesAreOneLineAndExitTwo)
{
    const std::vector<std::tuple<std::string, std::vector<std::string>, std::string>> cases = {
        {"pcf", {"--radius", "-1"}, "--radius"},
        {"pcf", {"--radius", "128"}, "the widest box pcf filters"},  // not a table's limit: pcf has none
        {"pcf-disc", {"--taps", "-1"}, "--taps"},
        {"pcf-disc", {"--taps", "0"}, "--taps"},
        {"pcf-disc", {"--taps", "257"}, "--taps"},
        {"pcf-gauss", {"--grid", "17"}, "--grid"},
        {"pcf-gauss", {"--grid", "-4"}, "--grid"},
        {"pcf-gauss", {"--sigma", "0"}, "--sigma"},
        {"pcf-disc", {"--disc-radius", "0"}, "--disc-radius"},
        {"pcf-disc", {"--rotation", "spin"}, "--rotation"},
        {"pcf", {"--bias-mode", "sloped"}, "--bias-mode"},
        {"pcf", {"--bias-mode", "slope", "--bias-min", "0.1", "--bias-max", "0.05"}, "--bias-min"},
        {"pcf", {"--bias-max", "2"}, "--bias-max"},
        {"pcf", {"--slope-scale", "-1"}, "--slope-scale"},
        {"pcf", {"--depth-bias", "nan"}, "--depth-bias"},
        {"pcf", {"--taps", "16"}, "--taps"},  // another method's option
        {"pcf", {"--bias-mode", "receiver-plane", "--bias-derivatives", "channels"}, "dzdu"},
    };
    for (const auto& [method, options, needle] : cases) {
        const testing::CliRun run = shade(method, options);
        EXPECT_TRUE(run.refused_cleanly()) << method << " " << options[0] << ": exit " << run.exit_code << ", "
                                           << run.err;
        EXPECT_NE(run.err.find(needle), std::string::npos) << run.err;
    }
}

}  // namespace
}  // namespace penumbra
