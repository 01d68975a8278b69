// Output files published all-or-nothing, never over an input or a device.
//
// Each file is first written in full into an unnamed temporary (O_TMPFILE) in
// its target's directory, which no interruption can leave behind: the kernel
// frees it when the process dies, even by SIGKILL. publish() then links every
// temporary into the directory under a hidden name and renames each over its
// target; a failure before the first rename leaves every target as it was. Where
// the file system lacks O_TMPFILE (or /proc is not mounted), named temporaries
// ".NAME.penumbra-tmp-PID-N" are used instead and removed on failure and on
// SIGINT, SIGTERM and SIGHUP; PENUMBRA_NO_O_TMPFILE=1 forces them. Every
// temporary is flock()ed by its writer; one left unlocked (its writer killed
// by SIGKILL) is removed by the next stage() into its directory.
// docs/robustness.md describes the whole scheme and its exact guarantee.
#pragma once

#include <functional>
#include <memory>
#include <string>
#include <string_view>
#include <vector>

namespace penumbra {

// Throws Error(Io) naming `operation` when any output
//  - exists and is not a regular file (a device such as /dev/full, a directory,
//    a FIFO): penumbra replaces files, never other things;
//  - is the same file as any input (same st_dev and st_ino, through links), or
//    names the same path as another output.
// Call it before any work, so that a bad OUT costs nothing.
void require_safe_outputs(const std::vector<std::string>& outputs, const std::vector<std::string>& inputs,
                          std::string_view operation);

class OutputFiles {
public:
    explicit OutputFiles(std::string operation);
    ~OutputFiles();  // removes every temporary not yet published
    OutputFiles(const OutputFiles&) = delete;
    OutputFiles& operator=(const OutputFiles&) = delete;

    // Creates the temporary for `path` and calls `write` with a name that opens
    // it (under /proc/self/fd, or the named fallback). `write` must create or
    // truncate that file and write all of it; it may throw. Errors: Error(Io).
    void stage(const std::string& path, const std::function<void(const std::string& temporary)>& write);

    // Flushes every temporary to disk and puts each in place of its target.
    // Throws Error(Io) on failure; if some targets were already replaced, the
    // message says which were and which were not.
    void publish();

    struct Staged;

private:
    void publish_all();

    std::string operation_;
    std::vector<std::unique_ptr<Staged>> staged_;
};

}  // namespace penumbra
