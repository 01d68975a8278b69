// A progress bar on stderr, shown only once the work has taken more than a
// second (short runs stay quiet) and only when stderr is a terminal or
// PENUMBRA_PROGRESS=1 (logs of CI runs stay readable).
#pragma once

#include <unistd.h>

#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <string>

namespace penumbra::cli {

class Progress {
public:
    explicit Progress(int total) : total_(total), start_(std::chrono::steady_clock::now())
    {
        const char* forced = std::getenv("PENUMBRA_PROGRESS");
        enabled_ = forced ? std::string(forced) == "1" : isatty(STDERR_FILENO) != 0;
    }
    ~Progress()
    {
        if (shown_) std::fprintf(stderr, "\n");
    }

    void step(const std::string& what)
    {
        ++done_;
        if (!enabled_) return;
        const double elapsed = std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
        if (elapsed < 1.0 && !shown_) return;
        shown_ = true;
        const int width = 30, filled = total_ ? width * done_ / total_ : width;
        std::fprintf(stderr, "\r[%s%s] %3d%% %5.1fs  %-40.40s", std::string(filled, '#').c_str(),
                     std::string(width - filled, ' ').c_str(), total_ ? 100 * done_ / total_ : 100, elapsed,
                     what.c_str());
        std::fflush(stderr);
    }

private:
    int total_, done_ = 0;
    bool enabled_ = false, shown_ = false;
    std::chrono::steady_clock::time_point start_;
};

}  // namespace penumbra::cli
