// Opening input files without hanging, and reading them with a size limit.
//
// Every file penumbra reads (EXR images, scene JSON, distance grids) goes through
// open_input_file: it opens with O_NONBLOCK, so that a FIFO or a device without a
// writer cannot block open(2) forever, then fstat()s the descriptor and refuses
// anything but a regular file (a FIFO, a character device such as /dev/zero, a
// directory, a socket) before a byte is read. The size it reports is the size of
// the file that was opened, not of whatever the path names a moment later.
// docs/robustness.md lists where each limit applies.
#pragma once

#include <cstdint>
#include <string>
#include <string_view>

namespace penumbra {

// An open, regular, readable file. Move-only; closes its descriptor.
class InputFile {
public:
    InputFile() = default;
    InputFile(int fd, std::uint64_t size, std::string path) : fd_(fd), size_(size), path_(std::move(path)) {}
    InputFile(InputFile&& other) noexcept;
    InputFile& operator=(InputFile&& other) noexcept;
    InputFile(const InputFile&) = delete;
    InputFile& operator=(const InputFile&) = delete;
    ~InputFile();

    int fd() const noexcept { return fd_; }
    std::uint64_t size() const noexcept { return size_; }
    const std::string& path() const noexcept { return path_; }

    // Reads exactly `count` bytes at `offset` (pread, so several readers of one
    // descriptor do not share a file position); false when the file is shorter.
    bool read_at(std::uint64_t offset, void* buffer, std::size_t count) const;

private:
    friend InputFile open_input_file(const std::string& path, std::string_view operation);
    int fd_ = -1;
    std::uint64_t size_ = 0;
    std::string path_;
};

// Opens `path` for reading. Throws Error(Io) naming `operation` and the path
// when it does not exist, cannot be opened (permissions, a symbolic-link loop,
// a name too long), or is not a regular file.
InputFile open_input_file(const std::string& path, std::string_view operation);

// Reads the whole of a regular file of at most `max_bytes` bytes; a larger one
// is refused by its size (Error(Io)) before anything is read.
std::string read_input_file(const std::string& path, std::string_view operation, std::uint64_t max_bytes);

// "a directory", "a FIFO (named pipe)", "a character device"...: what an
// st_mode names, for messages that refuse it.
const char* file_type_name(unsigned mode);

// The limit load_scene applies to scene JSON: a scene is a few kilobytes; 64 MiB
// leaves room for generated scenes with many primitives.
inline constexpr std::uint64_t kMaxSceneFileBytes = std::uint64_t(64) << 20;

}  // namespace penumbra
