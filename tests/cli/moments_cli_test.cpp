// `penumbra shade --method msm|msm-soft|evsm2|evsm4`, run as a user would:
// the output matches the library, and bad options exit with status 2 and one
// line on stderr naming the option, leaving an existing output untouched.
#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <functional>
#include <sstream>
#include <string>

#include "penumbra/exr_io.h"
#include "penumbra/moments.h"
#include "support/cli.h"
#include "support/maps.h"
#include "support/shade_inputs.h"

namespace penumbra {
namespace {

namespace fs = std::filesystem;

using testing::slurp;

class MomentsCli : public testing::ShadeInputs {
protected:
    int run(const std::string& args, std::string* err = nullptr) const
    {
        const std::string cmd = std::string(PENUMBRA_CLI_PATH) + " shade --shadow-map " + path("sm.exr") +
                                " --receivers " + path("rx.exr") + " --out " + path("out.exr") + " --backend scalar " +
                                args + " >" + path("stdout") + " 2>" + path("stderr");
        const int raw = std::system(cmd.c_str());
        if (err) *err = slurp(path("stderr"));
        return WEXITSTATUS(raw);
    }

    void expect_same(const std::string& args, const std::function<Image(Context&)>& library)
    {
        std::string err;
        ASSERT_EQ(run(args, &err), 0) << args << "\n" << err;
        const Image out = read_exr(path("out.exr"), {"Y"});
        Context ctx(ContextOptions{Backend::Scalar, {}});
        const Image want = library(ctx);
        ASSERT_EQ(out.width(), want.width());
        for (int y = 0; y < out.height(); ++y)
            for (int x = 0; x < out.width(); ++x) ASSERT_EQ(out.at(0, x, y), want.at(0, x, y)) << args;
    }

    void expect_bad_option(const std::string& args, const std::string& needle)
    {
        std::ofstream(path("out.exr")) << "previous contents";
        std::string err;
        EXPECT_EQ(run(args, &err), 2) << args << "\n" << err;
        EXPECT_NE(err.find(needle), std::string::npos) << args << ": stderr: " << err;
        EXPECT_EQ(std::count(err.begin(), err.end(), '\n'), 1) << "stderr: " << err;
        EXPECT_EQ(slurp(path("out.exr")), "previous contents");
    }

};

TEST_F(MomentsCli, EveryMethodMatchesTheLibrary)
{
    expect_same("--method msm --radius 3", [&](Context& c) {
        return msm(c, build_msm_table(c, map_), rx_, MsmOptions{3, {}, {}});
    });
    expect_same("--method msm --radius 1 --moment-bias 1e-4 --depth-bias 1e-3", [&](Context& c) {
        return msm(c, build_msm_table(c, map_, Quantization::None), rx_, MsmOptions{1, 1e-4f, 1e-3f});
    });
    expect_same("--method msm --quantize 16", [&](Context& c) {
        return msm(c, build_msm_table(c, map_, Quantization::Bits16), rx_, MsmOptions{});
    });
    expect_same("--method msm-soft --light-size 0.1", [&](Context& c) {
        return msm_soft(c, build_msm_table(c, map_), rx_, MsmSoftOptions{0.1f, {}, {}});
    });
    expect_same("--method msm-soft --light-size 0.1 --quantize 16", [&](Context& c) {
        return msm_soft(c, build_msm_table(c, map_, Quantization::Bits16), rx_, MsmSoftOptions{0.1f, {}, {}});
    });
    expect_same("--method evsm2 --exponents 3", [&](Context& c) {
        return evsm(c, build_evsm_table(c, map_, EvsmWarp{2, 3.0f, {}, Quantization::None}), rx_, EvsmOptions{});
    });
    expect_same("--method evsm4 --exponents 9,4 --min-variance 1e-5 --bleed 0.2 --radius 1 --depth-bias 0.001",
                [&](Context& c) {
                    return evsm(c, build_evsm_table(c, map_, EvsmWarp{4, 9.0f, 4.0f, Quantization::None}), rx_,
                                EvsmOptions{1, 1e-5f, 0.2f, 0.001f});
                });
}

TEST_F(MomentsCli, BadOptionsNameTheOption)
{
    expect_bad_option("--method msm --moment-bias 1", "--moment-bias");
    expect_bad_option("--method msm --moment-bias -0.1", "--moment-bias");
    expect_bad_option("--method msm-soft --depth-bias 1.5", "--depth-bias");
    expect_bad_option("--method evsm4 --depth-bias -1e-3", "--depth-bias");
    expect_bad_option("--method msm --quantize 8", "--quantize");
    expect_bad_option("--method msm --quantize 32", "--quantize: '32' is not 16");
    expect_bad_option("--method evsm2 --quantize 16", "--quantize: applies to msm and msm-soft only");
    expect_bad_option("--method msm --precision float", "--precision");
    expect_bad_option("--method evsm4 --exponents 11,5", "positive exponent 11");
    expect_bad_option("--method evsm4 --exponents 5,11", "negative exponent 11");
    expect_bad_option("--method evsm2 --exponents 43", "exceeds 10");
    expect_bad_option("--method evsm4 --exponents 3", "--exponents: evsm4 needs two");
    expect_bad_option("--method evsm2 --exponents 3,2", "--exponents: evsm2 has only the positive warp");
    expect_bad_option("--method evsm4 --exponents a,b", "--exponents");
    expect_bad_option("--method evsm4 --exponents 0,1", "--exponents");
    expect_bad_option("--method evsm2 --moment-bias 1e-4", "--moment-bias: applies to msm and msm-soft");
    expect_bad_option("--method msm --exponents 3,2", "--exponents: applies to evsm2 and evsm4");
    expect_bad_option("--method vsm --depth-bias 1e-3", "--depth-bias: applies to msm, msm-soft, evsm2, evsm4");
    expect_bad_option("--method msm-shadows", "--method");
    expect_bad_option("--method msm --radius 200", "radius 200 exceeds 127");
}

}  // namespace
}  // namespace penumbra
