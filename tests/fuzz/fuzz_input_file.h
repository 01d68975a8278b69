// A fuzz input as a file, for the readers that take a path (read_exr,
// read_distance_grid): the bytes go to one scratch file per process in the
// temporary directory ($TMPDIR, else /tmp), rewritten for every input and
// removed at exit. Without an fsync the write stays in the page cache, so it
// costs microseconds. Going through a path rather than a memory stream fuzzes
// the entry point users call, with its own open and file checks.
#pragma once

#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <string>

#include <unistd.h>

namespace penumbra::fuzz {

// Writes data[0, size) to this process's scratch file and returns its path.
// Aborts (a fuzzer crash report, not a silent skip) if the write fails.
inline const std::string& input_as_file(const std::uint8_t* data, std::size_t size, const char* suffix)
{
    static const std::string path = [suffix] {
        std::string p = (std::filesystem::temp_directory_path() /
                         ("penumbra-fuzz-" + std::to_string(getpid()) + suffix)).string();
        static std::string removed_at_exit = p;
        std::atexit([] { std::remove(removed_at_exit.c_str()); });
        return p;
    }();
    std::FILE* f = std::fopen(path.c_str(), "wb");
    if (!f || (size && std::fwrite(data, 1, size, f) != size) || std::fclose(f) != 0) {
        std::perror(path.c_str());
        std::abort();
    }
    return path;
}

}  // namespace penumbra::fuzz
