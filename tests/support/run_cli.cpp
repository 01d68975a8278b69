#include "support/run_cli.h"

#include <fcntl.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <thread>

namespace penumbra::testing {
namespace {

std::string read_all(const std::string& path)
{
    std::ifstream in(path, std::ios::binary);
    std::stringstream text;
    text << in.rdbuf();
    return text.str();
}

}  // namespace

bool CliRun::refused_cleanly() const
{
    return !timed_out && signal == 0 && exit_code == 2 && !err.empty() && err.find('\n') == err.size() - 1;
}

CliRun run_cli(const std::vector<std::string>& args, const std::map<std::string, std::string>& environment,
               double timeout_seconds)
{
    static int counter = 0;
    const std::string base = (std::filesystem::temp_directory_path() /
                              ("penumbra-run-" + std::to_string(::getpid()) + "-" + std::to_string(counter++)))
                                 .string();
    const std::string out_path = base + ".out", err_path = base + ".err";
    std::vector<std::string> words{PENUMBRA_CLI_PATH};
    words.insert(words.end(), args.begin(), args.end());
    const pid_t child = ::fork();
    if (child == 0) {
        for (const auto& [name, value] : environment)
            value.empty() ? ::unsetenv(name.c_str()) : ::setenv(name.c_str(), value.c_str(), 1);
        const int out = ::open(out_path.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0600);
        const int err = ::open(err_path.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0600);
        const int null = ::open("/dev/null", O_RDONLY);
        ::dup2(null, 0);
        ::dup2(out, 1);
        ::dup2(err, 2);
        std::vector<char*> argv;
        for (std::string& word : words) argv.push_back(word.data());
        argv.push_back(nullptr);
        ::execv(argv[0], argv.data());
        ::_exit(127);
    }
    CliRun run;
    int status = 0;
    const auto deadline = std::chrono::steady_clock::now() + std::chrono::duration<double>(timeout_seconds);
    while (::waitpid(child, &status, WNOHANG) == 0) {
        if (std::chrono::steady_clock::now() > deadline) {
            run.timed_out = true;
            ::kill(child, SIGKILL);
            ::waitpid(child, &status, 0);
            break;
        }
        std::this_thread::sleep_for(std::chrono::milliseconds(10));
    }
    if (WIFEXITED(status)) run.exit_code = WEXITSTATUS(status);
    if (WIFSIGNALED(status)) run.signal = WTERMSIG(status);
    run.out = read_all(out_path);
    run.err = read_all(err_path);
    std::remove(out_path.c_str());
    std::remove(err_path.c_str());
    return run;
}

}  // namespace penumbra::testing
