// A damaged PoCL kernel cache (issue 11, defect 3) and an unusable cache folder
// (defect 11), through the real tool in fresh processes: PoCL reads its cache
// folder once per process, and a damaged file used to abort (SIGABRT) or crash
// (SIGSEGV) it. Each test works in its own PENUMBRA_CACHE_DIR.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <functional>

#include "support/cli.h"
#include "support/run_cli.h"

namespace penumbra {
namespace {

namespace fs = std::filesystem;
using testing::run_cli;

class OpenClCacheRepair : public testing::CliFixture {
protected:
    void SetUp() override
    {
        CliFixture::SetUp();
        ASSERT_EQ(run_cli({"example", "--out", path("ex"), "--map-size", "64"}).exit_code, 0);
    }
    // POCL_CACHE_DIR unset: a user's own setting would bypass penumbra's folder.
    testing::CliRun shade(const std::string& cache) const
    {
        return run_cli({"shade", "--method", "vsm", "--backend", "opencl", "--shadow-map", path("ex/shadow_map.exr"),
                        "--receivers", path("ex/receivers.exr"), "--out", path("out.exr")},
                       {{"PENUMBRA_CACHE_DIR", cache}, {"POCL_CACHE_DIR", ""}}, 120);
    }
    static std::vector<fs::path> files_named(const fs::path& root, const std::string& suffix)
    {
        std::vector<fs::path> found;
        for (const auto& entry : fs::recursive_directory_iterator(root))
            if (entry.is_regular_file() && entry.path().string().ends_with(suffix)) found.push_back(entry.path());
        return found;
    }
};

void rewrite(const fs::path& file, const std::function<void(std::string&)>& change)
{
    std::string bytes = testing::slurp(file);
    change(bytes);
    std::ofstream(file, std::ios::binary | std::ios::trunc) << bytes;
}

TEST_F(OpenClCacheRepair, EveryKindOfDamageIsRepairedBeforeUse)
{
    const std::string cache = path("cache");
    const auto first = shade(cache);
    if (first.exit_code == 2 && first.err.find("OpenCL") != std::string::npos)
        GTEST_SKIP() << "no OpenCL device here: " << first.err;
    ASSERT_EQ(first.exit_code, 0) << first.err;
    ASSERT_TRUE(fs::exists(fs::path(cache) / "pocl.manifest"));

    const std::vector<std::pair<std::string, std::function<void(std::string&)>>> damages = {
        {"program.bc", [](std::string& b) { b.clear(); }},
        {"program.bc", [](std::string& b) { b.resize(b.size() / 2); }},
        {"program.bc", [](std::string& b) { b.assign(b.size(), '\0'); }},
        {".so", [](std::string& b) {
             for (std::size_t i = 64; i < b.size(); i += 97) b[i] = char(b[i] ^ 0x5a);
         }},
    };
    for (const auto& [suffix, damage] : damages) {
        const auto files = files_named(fs::path(cache) / "pocl", suffix);
        ASSERT_FALSE(files.empty()) << "PoCL wrote no " << suffix;
        for (const fs::path& file : files) rewrite(file, damage);
        const auto repaired = shade(cache);
        EXPECT_EQ(repaired.signal, 0) << suffix << ": the driver crashed: " << repaired.err;
        EXPECT_EQ(repaired.exit_code, 0) << suffix << ": " << repaired.err;
        EXPECT_NE(repaired.err.find("was damaged"), std::string::npos) << suffix << ": no warning: " << repaired.err;
        const auto next = shade(cache);
        EXPECT_EQ(next.exit_code, 0) << next.err;
        EXPECT_EQ(next.err.find("damaged"), std::string::npos) << "warned twice: " << next.err;
    }
}

// Defect 11: PoCL drops its device when it cannot create its folder, which was
// reported as "no OpenCL device ... install pocl-opencl-icd".
TEST_F(OpenClCacheRepair, UnusableCacheFolderIsNamedAsSuch)
{
    { std::ofstream(path("plain")) << "x"; }
    for (const std::string& cache : {path("plain"), std::string("/proc/penumbra-cache")}) {
        const auto run = shade(cache);
        if (run.exit_code == 0) continue;  // a driver that needs no cache folder
        EXPECT_TRUE(run.refused_cleanly()) << run.err;
        EXPECT_NE(run.err.find(cache), std::string::npos) << run.err;
        EXPECT_NE(run.err.find("PENUMBRA_CACHE_DIR"), std::string::npos) << run.err;
        EXPECT_EQ(run.err.find("install pocl"), std::string::npos) << run.err;
        const auto info = run_cli({"info"}, {{"PENUMBRA_CACHE_DIR", cache}, {"POCL_CACHE_DIR", ""}});
        EXPECT_EQ(info.exit_code, 0) << info.err;
        EXPECT_NE(info.out.find("cannot be used"), std::string::npos) << info.out;
    }
}

}  // namespace
}  // namespace penumbra
