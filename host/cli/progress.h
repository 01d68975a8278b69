// Progress of a long run (penumbra demo), in the form its output can carry:
//  - stdout is not a terminal (a CI log, `| tee`): one line per milestone on
//    stdout, "[12/80] 31.2 s, about 176 s left: contact: vsm", in order with
//    the rest of the output, so that a log shows the run moving;
//  - else a bar on stderr, redrawn in place, when stderr is a terminal, shown
//    once the work has taken more than a second (short runs stay quiet).
// PENUMBRA_PROGRESS=1 forces the bar, =0 turns both off. finish() ends the
// bar's line; call it before printing anything else to the terminal.
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
        const std::string force = forced ? forced : "";
        if (force == "0") return;
        if (force == "1") bar_ = true;
        else if (isatty(STDOUT_FILENO) == 0) lines_ = true;
        else bar_ = isatty(STDERR_FILENO) != 0;
    }
    ~Progress() { finish(); }
    Progress(const Progress&) = delete;
    Progress& operator=(const Progress&) = delete;

    // One unit of work done; the bar shows `what`.
    void step(const std::string& what)
    {
        ++done_;
        if (!bar_) return;
        const double elapsed = seconds();
        if (elapsed < 1.0 && !shown_) return;
        shown_ = true;
        const int width = 30, filled = total_ ? width * done_ / total_ : width;
        std::fprintf(stderr, "\r[%s%s] %3d%% %5.1fs  %-40.40s", std::string(filled, '#').c_str(),
                     std::string(width - filled, ' ').c_str(), total_ ? 100 * done_ / total_ : 100, elapsed,
                     what.c_str());
        std::fflush(stderr);
    }

    // A unit of the log (a scene's truth, a method's settings): its line, with
    // the time so far and a linear estimate of the rest from the units done.
    void milestone(const std::string& what)
    {
        if (!lines_) return;
        const double elapsed = seconds();
        const double left = done_ > 0 ? elapsed * (total_ - done_) / done_ : 0.0;
        std::printf("[%d/%d] %.1f s, about %.0f s left: %s\n", done_, total_, elapsed, left, what.c_str());
        std::fflush(stdout);
    }

    void finish()
    {
        if (shown_) std::fprintf(stderr, "\n");
        shown_ = false;
        bar_ = false;
    }

private:
    double seconds() const
    {
        return std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
    }

    int total_, done_ = 0;
    bool bar_ = false, lines_ = false, shown_ = false;
    std::chrono::steady_clock::time_point start_;
};

}  // namespace penumbra::cli
