// `penumbra shade --method pcss|burley`: the options, the presets and the
// refusals (exit 2, one line on stderr naming the option).
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "penumbra/exr_io.h"
#include "support/cli.h"
#include "support/run_cli.h"

namespace penumbra {
namespace {

using testing::run_cli;

class SoftPcfCli : public testing::CliFixture {
protected:
    void SetUp() override
    {
        CliFixture::SetUp();
        ASSERT_EQ(run_cli({"example", "--out", path("ex")}).exit_code, 0);
    }
    testing::CliRun shade(const std::string& method, const std::vector<std::string>& options)
    {
        std::vector<std::string> args{"shade", "--method", method, "--shadow-map", path("ex/shadow_map.exr"),
                                      "--receivers", path("ex/receivers.exr"), "--out", path("out.exr")};
        args.insert(args.end(), options.begin(), options.end());
        return run_cli(args);
    }
};

TEST_F(SoftPcfCli, BothShadeWithTheirOptionsAndPresets)
{
    for (const auto& [method, options] :
         std::vector<std::pair<std::string, std::vector<std::string>>>{
             {"pcss", {}},
             {"pcss", {"--preset", "hdrp"}},
             {"pcss", {"--preset", "godot-ultra", "--light-size", "0.03", "--depth-bias", "0.001"}},
             {"burley", {}},
             {"burley", {"--min-radius", "0.001", "--max-radius", "0.02", "--bias-slope", "1", "--falloff", "0.5",
                         "--blocker-samples", "32", "--filter-samples", "32"}},
             {"burley", {"--bias-slope", "0.01", "--bias-slope-per-depth", "2.3"}}}) {
        const testing::CliRun run = shade(method, options);
        ASSERT_EQ(run.exit_code, 0) << method << ": " << run.err;
        const Image out = read_exr(path("out.exr"), {"Y"});
        for (int y = 0; y < out.height(); ++y)
            for (int x = 0; x < out.width(); ++x) {
                const float v = out.at(0, x, y);
                ASSERT_TRUE(v >= 0.0f && v <= 1.0f) << method << " " << v;
            }
    }
}

// Light size 0 is a point light: PCSS's filter shrinks to the receiver's
// texel, the hard shadow of pcf r=0 (the library's rule, reached from the tool).
TEST_F(SoftPcfCli, PcssWithLightSizeZeroIsPcfRadiusZero)
{
    ASSERT_EQ(shade("pcss", {"--light-size", "0", "--depth-bias", "0.001"}).exit_code, 0);
    const Image soft = read_exr(path("out.exr"), {"Y"});
    const testing::CliRun hard = shade("pcf", {"--radius", "0", "--depth-bias", "0.001"});
    ASSERT_EQ(hard.exit_code, 0) << hard.err;
    const Image pcf = read_exr(path("out.exr"), {"Y"});
    for (int y = 0; y < pcf.height(); ++y)
        for (int x = 0; x < pcf.width(); ++x) ASSERT_EQ(soft.at(0, x, y), pcf.at(0, x, y)) << x << "," << y;
}

TEST_F(SoftPcfCli, BadValuesAreOneLineAndExitTwo)
{
    const std::vector<std::pair<std::string, std::vector<std::string>>> cases = {
        {"pcss", {"--blocker-samples", "-1"}},     {"pcss", {"--filter-samples", "1025"}},
        {"pcss", {"--blocker-samples", "0"}},      {"pcss", {"--preset", "ultra"}},
        {"pcss", {"--light-size", "-0.5"}},        {"pcss", {"--max-radius", "0.1"}},
        {"burley", {"--min-radius", "0.02", "--max-radius", "0.01"}},
        {"burley", {"--bias-slope", "-2"}},        {"burley", {"--falloff", "nan"}},
        {"burley", {"--preset", "hdrp"}},          {"burley", {"--filter-samples", "x"}},
        {"burley", {"--bias-slope-per-depth", "-2000"}},
        // Each in range, but the slope at z = 1 (1 - 3) is negative.
        {"burley", {"--bias-slope-per-depth", "-3", "--bias-slope", "1"}},
    };
    for (const auto& [method, options] : cases) {
        const testing::CliRun run = shade(method, options);
        EXPECT_TRUE(run.refused_cleanly()) << method << " " << options[0] << ": exit " << run.exit_code << ", "
                                           << run.err;
        EXPECT_NE(run.err.find(options[0].substr(2)), std::string::npos) << run.err;
    }
}

}  // namespace
}  // namespace penumbra
