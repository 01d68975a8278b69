// The `penumbra` tool's contracts, run as a user would: exit status, one line
// on stderr naming the file, channel or option, and nothing lost on failure.
#include <gtest/gtest.h>

#include <cmath>
#include <algorithm>
#include <cstdlib>
#include <unistd.h>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
#include <string_view>
#include <vector>

#include "penumbra/chebyshev.h"
#include "penumbra/exr_io.h"
#include "penumbra/moment_table.h"
#include "simd/cpu_kernels.h"
#include "support/cli.h"
#include "support/maps.h"
#include "support/shade_inputs.h"

namespace penumbra {
namespace {

namespace fs = std::filesystem;

struct CliRun {
    int status;
    std::string out, err;
};

using testing::slurp;

class CliTest : public testing::ShadeInputs {
protected:
    CliRun run(const std::string& args, const std::string& env = "") const
    {
        const std::string cmd = env + " " PENUMBRA_CLI_PATH " " + args + " >" + path("stdout") + " 2>" + path("stderr");
        const int raw = std::system(cmd.c_str());
        return {WEXITSTATUS(raw), slurp(path("stdout")), slurp(path("stderr"))};
    }

    std::string shade(const std::string& extra) const
    {
        return "shade --shadow-map " + path("sm.exr") + " --receivers " + path("rx.exr") + " --out " + path("out.exr") +
               " " + extra;
    }

    // A failed run: status 2, exactly one line on stderr containing `needle`,
    // and the pre-existing output untouched.
    void expect_bad_input(const std::string& args, const std::string& needle, const std::string& env = "")
    {
        std::ofstream(path("out.exr")) << "previous contents";
        const CliRun r = run(args, env);
        EXPECT_EQ(r.status, 2) << args << "\n" << r.err;
        EXPECT_NE(r.err.find(needle), std::string::npos) << "stderr: " << r.err;
        EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << "stderr: " << r.err;
        EXPECT_EQ(slurp(path("out.exr")), "previous contents");
        for (const auto& entry : fs::directory_iterator(dir_))
            EXPECT_EQ(entry.path().filename().string().find(".tmp"), std::string::npos) << entry.path();
    }

};

TEST_F(CliTest, ShadeWritesVisibilityMatchingTheLibrary)
{
    for (const std::string method : {"vsm", "vssm"}) {
        const CliRun r = run(shade("--method " + method + " --radius 3 --light-size 0.1 --backend scalar"));
        ASSERT_EQ(r.status, 0) << r.err;
        const Image out = read_exr(path("out.exr"), {"Y"});
        ASSERT_EQ(out.width(), rx_.width());
        ASSERT_EQ(out.height(), rx_.height());
        Context ctx(ContextOptions{Backend::Scalar, {}});
        const MomentTable table = build_moment_table(ctx, map_);
        const Image expected = method == "vsm" ? vsm(ctx, table, rx_, VsmOptions{3, kDefaultMinVariance, 0.0f})
                                               : vssm(ctx, table, rx_, VssmOptions{0.1f, kDefaultMinVariance, 0.0f});
        for (int y = 0; y < out.height(); ++y)
            for (int x = 0; x < out.width(); ++x) ASSERT_EQ(out.at(0, x, y), expected.at(0, x, y));
    }
}

TEST_F(CliTest, ShadeRejectsBadFiles)
{
    std::ofstream(path("text.exr")) << "not an image";
    expect_bad_input("shade --method vsm --shadow-map " + path("text.exr") + " --receivers " + path("rx.exr") +
                         " --out " + path("out.exr"),
                     "text.exr");
    expect_bad_input("shade --method vsm --shadow-map " + path("missing.exr") + " --receivers " + path("rx.exr") +
                         " --out " + path("out.exr"),
                     "missing.exr");
    write_exr(path("wrong_channel.exr"), map_, {"Y"});
    expect_bad_input("shade --method vsm --shadow-map " + path("wrong_channel.exr") + " --receivers " +
                         path("rx.exr") + " --out " + path("out.exr"),
                     "Z");
    Image two = testing::receivers_on_texels(5, 4, 37, 23, 0.2f, 0.9f, 1);
    Image uv(5, 4, 2);
    write_exr(path("rx_uv.exr"), uv, {"u", "z"});
    expect_bad_input("shade --method vsm --shadow-map " + path("sm.exr") + " --receivers " + path("rx_uv.exr") +
                         " --out " + path("out.exr"),
                     "v");
}

TEST_F(CliTest, ShadeRejectsBadValues)
{
    Image nan_map = map_;
    nan_map.at(0, 3, 2) = NAN;
    write_exr(path("nan.exr"), nan_map, {"Z"});
    expect_bad_input("shade --method vsm --shadow-map " + path("nan.exr") + " --receivers " + path("rx.exr") +
                         " --out " + path("out.exr"),
                     "nan.exr: channel Z at pixel (3, 2)");
    Image far_map = map_;
    far_map.at(0, 1, 1) = 1.5f;
    write_exr(path("far.exr"), far_map, {"Z"});
    expect_bad_input("shade --method vsm --shadow-map " + path("far.exr") + " --receivers " + path("rx.exr") +
                         " --out " + path("out.exr"),
                     "outside [0, 1]");
    Image inf_rx = rx_;
    inf_rx.at(2, 4, 4) = INFINITY;
    write_exr(path("inf_rx.exr"), inf_rx, {"u", "v", "z"});
    expect_bad_input("shade --method vsm --shadow-map " + path("sm.exr") + " --receivers " + path("inf_rx.exr") +
                         " --out " + path("out.exr"),
                     "inf_rx.exr: channel z");
}

TEST_F(CliTest, ShadeRejectsBadOptions)
{
    expect_bad_input(shade("--method vsm --radius -1"), "--radius");
    expect_bad_input(shade("--method vsm --min-variance -0.5"), "--min-variance");
    expect_bad_input(shade("--method vsm --bleed 1"), "--bleed");
    expect_bad_input(shade("--method vsm --bleed -0.1"), "--bleed");
    expect_bad_input(shade("--method vssm --light-size 0"), "--light-size");
    expect_bad_input(shade("--method pcf-box"), "--method");
    expect_bad_input(shade("--method vsm --radius three"), "--radius");
    expect_bad_input(shade("--method vsm --precision float"), "--precision");
    expect_bad_input(shade("--method vsm --backend cuda"), "backend");
    expect_bad_input(shade("--method vsm --radius 128"), "radius");
    expect_bad_input(shade("--method vsm --frobnicate 1"), "--frobnicate");
    expect_bad_input("shade --method vsm --receivers " + path("rx.exr") + " --out " + path("out.exr"), "--shadow-map");
}

TEST_F(CliTest, ExplicitOpenClWithoutDeviceIsAnError)
{
    fs::create_directories(dir_ / "no_icds");
    expect_bad_input(shade("--method vsm --backend opencl"), "OpenCL", "OCL_ICD_VENDORS=" + path("no_icds"));
}

TEST_F(CliTest, InfoJsonListsBackendsAndHonoursTheIsaOverride)
{
    // The worst ISA of this build this CPU runs: not the default (the best) where there are two.
    const std::vector<std::string_view> isas = cpu::supported_isas();
    const std::string forced = isas.empty() ? "scalar" : std::string(isas.front());
    const CliRun r = run("info --json", "PENUMBRA_SIMD_ISA=" + forced);
    ASSERT_EQ(r.status, 0) << r.err;
    const nlohmann::json j = nlohmann::json::parse(r.out);
    EXPECT_EQ(j["cpu"]["chosen_isa"], forced);
    EXPECT_EQ(j["cpu"]["isas"].get<std::vector<std::string>>(), std::vector<std::string>(isas.begin(), isas.end()));
    EXPECT_EQ(j["auto"]["backend"], "simd");  // no GPU on this machine's kind; see context.h for the rule
    EXPECT_FALSE(j["auto"]["reason"].get<std::string>().empty());
    EXPECT_TRUE(j["opencl"].contains("devices"));
    EXPECT_TRUE(j["backends"].is_array());
    const CliRun bad = run("info", "PENUMBRA_SIMD_ISA=avx9000");
    EXPECT_EQ(bad.status, 2);
    EXPECT_NE(bad.err.find("avx9000"), std::string::npos);
}

TEST_F(CliTest, BackendEnvironmentOverride)
{
    const CliRun r = run("info --json", "PENUMBRA_BACKEND=scalar");
    ASSERT_EQ(r.status, 0) << r.err;
    EXPECT_EQ(nlohmann::json::parse(r.out)["auto"]["backend"], "scalar");
}

}  // namespace
}  // namespace penumbra
