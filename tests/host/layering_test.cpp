// The layers of docs/architecture.md, checked on the sources: the library
// (host/) names nothing of reference/, and reference/ reaches the library
// only through its public headers (penumbra/*.h), never host/src, kernels/,
// simd/ or cl/. tests/install_test.cmake checks the same on the install.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <regex>
#include <sstream>
#include <string>
#include <vector>

namespace {

namespace fs = std::filesystem;

std::vector<fs::path> sources_under(const std::string& folder)
{
    std::vector<fs::path> files;
    for (const auto& entry : fs::recursive_directory_iterator(fs::path(PENUMBRA_SOURCE_DIR) / folder)) {
        const std::string ext = entry.path().extension().string();
        if (entry.is_regular_file() && (ext == ".h" || ext == ".cpp")) files.push_back(entry.path());
    }
    return files;
}

std::vector<std::string> quoted_includes(const fs::path& file)
{
    std::ifstream in(file);
    std::vector<std::string> includes;
    static const std::regex include(R"(^\s*#\s*include\s*"([^"]+)\")");
    std::smatch m;
    for (std::string line; std::getline(in, line);)
        if (std::regex_search(line, m, include)) includes.push_back(m[1]);
    return includes;
}

std::string text_of(const fs::path& file)
{
    std::ifstream in(file);
    std::ostringstream s;
    s << in.rdbuf();
    return s.str();
}

TEST(Layering, TheLibraryNamesNothingOfTheReference)
{
    for (const char* folder : {"host/include", "host/src"}) {
        const std::vector<fs::path> files = sources_under(folder);
        ASSERT_FALSE(files.empty()) << folder;
        for (const fs::path& file : files) {
            for (const std::string& inc : quoted_includes(file))
                EXPECT_NE(inc.rfind("penumbra/reference", 0), 0u) << file << " includes " << inc;
            EXPECT_EQ(text_of(file).find("reference::"), std::string::npos) << file << " names reference::";
        }
    }
}

// Besides penumbra's public headers, a reference source may include its own
// private headers, the files beside it in reference/src (no path: nothing
// from another layer's folder can be named that way).
TEST(Layering, TheReferenceUsesOnlyPublicHeaders)
{
    const std::vector<fs::path> files = sources_under("reference");
    ASSERT_GE(files.size(), 10u);
    for (const fs::path& file : files)
        for (const std::string& inc : quoted_includes(file)) {
            const bool own = inc.find('/') == std::string::npos && fs::is_regular_file(file.parent_path() / inc);
            EXPECT_TRUE(inc.rfind("penumbra/", 0) == 0 || own) << file << " includes " << inc << ", not a public header";
        }
}

}  // namespace
