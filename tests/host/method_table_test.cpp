// The method table (penumbra/methods.h): each method listed once, the CLI's
// help generated from it, every option's out-of-range value refused by the
// tool with the flag named (a loop over the table), and the library's Error
// naming the parameter.
#include <gtest/gtest.h>

#include <any>
#include <cstdlib>
#include <set>
#include <sstream>
#include <string>

#include "penumbra/error.h"
#include "penumbra/exr_io.h"
#include "penumbra/methods.h"
#include "support/cli.h"
#include "support/maps.h"
#include "support/run_cli.h"

namespace penumbra {
namespace {

TEST(MethodTable, ListsEachMethodOnceWithKnownOptions)
{
    std::set<std::string> names;
    for (const Method& m : methods()) {
        EXPECT_TRUE(names.insert(m.name).second) << m.name;
        for (std::string_view option : m.reads) {
            bool known = false;
            for (const MethodOption& o : method_options()) known = known || option == o.name;
            EXPECT_TRUE(known) << m.name << " reads " << option;
        }
    }
    EXPECT_EQ(names, (std::set<std::string>{"vsm", "vssm", "msm", "msm-soft", "evsm2", "evsm4", "pcf", "pcf-gauss",
                                            "pcf-disc", "pcss", "burley", "dsm", "pismo", "pismo-maxdepth"}));
}

// A value just outside the range: below an open or closed lower bound, above an upper one.
std::string outside(const ParameterRange& r)
{
    std::ostringstream text;
    text << (r.low_open ? r.low : r.low - 1.0);
    return text.str();
}

TEST(MethodTable, LibraryErrorsNameTheParameter)
{
    for (const Method& m : methods())
        for (const MethodOption& o : method_options()) {
            if (!o.range) continue;
            std::string text = outside(*o.range);
            if (std::string(o.name) == "exponents" && std::string(m.name) == "evsm4") text += ",1";
            try {
                parse_method_settings(m, {{o.name, text}});
                ADD_FAILURE() << m.name << " accepted " << o.name << " " << text;
            } catch (const Error& e) {
                EXPECT_EQ(option_for_parameter(e.parameter()), &o) << m.name << ": " << e.what();
            }
        }
    Context ctx(ContextOptions{Backend::Scalar, {}});
    const Image map = testing::random_depth(9, 7, 1);
    const Image rx = testing::receivers_on_texels(5, 4, 9, 7, 0.2f, 0.9f, 2);
    MethodSettings s;
    s.radius = 200;
    try {
        find_method("vsm").run(ctx, map, rx, s);
        ADD_FAILURE() << "radius 200 accepted";
    } catch (const Error& e) {
        EXPECT_EQ(e.parameter(), "radius") << e.what();
        EXPECT_EQ(e.operation(), "vsm");
    }
}

// The two steps alone give what run() gives (run is prepare then shade), and
// one prepared table serves every shade call: the benchmarks time each step
// on that assumption. The reference is each method's own public operation
// (vsm(), msm(), ...), called here through run() on a fresh context.
TEST(MethodTable, PrepareThenShadeIsRunAndThePreparedTableIsReused)
{
    Context ctx(ContextOptions{Backend::Scalar, {}});
    const Image map = testing::random_depth(9, 7, 3);
    const Image rx = testing::receivers_on_texels(7, 3, 9, 7, 0.1f, 0.9f, 4);
    for (const Method& m : methods()) {
        if (m.input != MethodInput::ShadowMap) continue;  // DeepMapMethod, PismoMethod (tests/cli)
        MethodSettings s;
        s.radius = 1;
        const Image expected = m.run(ctx, map, rx, s);
        const PreparedMap prepared = m.prepare(ctx, map, s);
        EXPECT_EQ(&prepared.map(), &map) << m.name;
        for (int call = 0; call < 2; ++call) {
            Image out(rx.width(), rx.height(), 1);
            m.shade(ctx, prepared, rx, s, out);
            EXPECT_EQ(testing::difference(out, expected).differing, 0) << m.name << " call " << call;
        }
    }
    const PreparedMap none = prepare_map(ctx, map, {});
    EXPECT_EQ(&none.map(), &map);
    EXPECT_THROW(none.table<MomentTable>(), std::bad_any_cast) << "prepare_map keeps no table";
}

class MethodTableCli : public testing::CliFixture {};

TEST_F(MethodTableCli, HelpIsGeneratedFromTheTable)
{
    const auto usage = testing::run_cli({"--help"});
    EXPECT_NE(usage.out.find("--method " + method_names("|")), std::string::npos) << usage.out;
    const auto help = testing::run_cli({"shade", "--help"});
    for (const Method& m : methods()) EXPECT_NE(help.out.find(std::string("  ") + m.name + " "), std::string::npos);
    for (const MethodOption& o : method_options()) {
        const std::string flag = std::string("  --") + o.name + " ";
        const std::size_t at = help.out.find(flag);
        ASSERT_NE(at, std::string::npos) << flag;
        EXPECT_EQ(help.out.find(flag, at + 1), std::string::npos) << flag << " listed twice";
        if (o.range) {
            EXPECT_NE(help.out.find(describe(*o.range), at), std::string::npos) << flag;
        }
    }
}

TEST_F(MethodTableCli, EveryOutOfRangeOptionExitsTwoNamingTheFlag)
{
    write_exr(path("sm.exr"), testing::random_depth(9, 7, 1), {"Z"});
    write_exr(path("rx.exr"), testing::receivers_on_texels(5, 4, 9, 7, 0.2f, 0.9f, 2), {"u", "v", "z"});
    for (const Method& m : methods())
        for (std::string_view name : m.reads) {
            const MethodOption* o = option_for_parameter(name);
            ASSERT_NE(o, nullptr);
            if (!o->range) continue;
            std::string text = outside(*o->range);
            if (name == "exponents" && std::string(m.name) == "evsm4") text += ",1";
            const std::string flag = "--" + std::string(name);
            // Options are checked before any file is read: the flat map serves every input.
            const std::string input = "--" + std::string(input_info(m.input).flag);
            const auto r = testing::run_cli({"shade", "--method", m.name, input, path("sm.exr"),
                                             "--receivers", path("rx.exr"), "--out", path("out.exr"), "--backend",
                                             "scalar", flag, text});
            EXPECT_EQ(r.exit_code, 2) << m.name << " " << flag << " " << text << ": " << r.err;
            EXPECT_EQ(r.err.rfind("penumbra shade: ", 0), 0u) << r.err;
            EXPECT_NE(r.err.find(flag), std::string::npos) << r.err;
        }
}

}  // namespace
}  // namespace penumbra
