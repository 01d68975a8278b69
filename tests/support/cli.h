// What every test of the `penumbra` tool needs: a scratch folder per test,
// a run of the tool with what it printed, the check of a refused run, and
// reading back what a run wrote.
#pragma once

#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <initializer_list>
#include <sstream>
#include <string>

#include "support/errors.h"

namespace penumbra::testing {

inline std::string slurp(const std::filesystem::path& path)
{
    std::ifstream in(path, std::ios::binary);
    std::stringstream ss;
    ss << in.rdbuf();
    return ss.str();
}

// What a run of the tool left: its exit status and what it printed.
struct ToolRun {
    int status;
    std::string out, err;
};

// A fixture with a fresh folder named after the process and the test,
// removed afterwards. Derived fixtures call CliFixture::SetUp() first.
class CliFixture : public ::testing::Test {
protected:
    void SetUp() override
    {
        dir_ = std::filesystem::temp_directory_path() /
               ("penumbra_cli_" + std::to_string(::getpid()) + "_" +
                ::testing::UnitTest::GetInstance()->current_test_info()->test_suite_name() + "_" +
                ::testing::UnitTest::GetInstance()->current_test_info()->name());
        std::filesystem::remove_all(dir_);
        std::filesystem::create_directories(dir_);
    }
    void TearDown() override { std::filesystem::remove_all(dir_); }

    std::string path(const std::string& name) const { return (dir_ / name).string(); }

    // `penumbra ARGS` through the shell, after the assignments `env` ("A=1 B=2").
    ToolRun run(const std::string& args, const std::string& env = "") const
    {
        const std::string cmd = env + " " PENUMBRA_CLI_PATH " " + args + " >" + path("stdout") + " 2>" + path("stderr");
        const int raw = std::system(cmd.c_str());
        return {WEXITSTATUS(raw), slurp(path("stdout")), slurp(path("stderr"))};
    }

    // The tool's contract for bad input: status 2, exactly one line on stderr
    // holding `needle`, the existing out.exr untouched and no temporary left.
    void expect_bad_input(const std::string& args, const std::string& needle, const std::string& env = "")
    {
        std::ofstream(path("out.exr")) << "previous contents";
        const ToolRun r = run(args, env);
        EXPECT_EQ(r.status, 2) << args << "\n" << r.err;
        EXPECT_NE(r.err.find(needle), std::string::npos) << args << ": stderr: " << r.err;
        EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << "stderr: " << r.err;
        EXPECT_EQ(slurp(path("out.exr")), "previous contents");
        for (const auto& entry : std::filesystem::directory_iterator(dir_))
            EXPECT_EQ(entry.path().filename().string().find(".tmp"), std::string::npos) << entry.path();
    }

    // expect_bad_input for each row: `command(row.input)` names `row.needle`.
    template <class Command>
    void expect_bad_inputs(Command&& command, std::initializer_list<BadInput> rows)
    {
        for (const BadInput& row : rows) expect_bad_input(command(row.input), row.needle);
    }

    std::filesystem::path dir_;
};

}  // namespace penumbra::testing
