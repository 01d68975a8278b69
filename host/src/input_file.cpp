// Regular-file inputs (penumbra/input_file.h).
#include "penumbra/input_file.h"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <system_error>
#include <utility>

#include "penumbra/error.h"
#include "quoted.h"

namespace penumbra {
namespace {

using detail::in_quotes;

[[noreturn]] void refuse(std::string_view operation, const std::string& path, const std::string& why)
{
    throw Error(ErrorCategory::Io, operation, in_quotes(path) + " " + why);
}

std::string open_failure(int error)
{
    switch (error) {
    case ENOENT: return "does not exist; check the path";
    case EACCES: return "cannot be opened for reading (permission denied); check its permissions";
    case ELOOP: return "cannot be opened: too many levels of symbolic links (a link loop?)";
    case ENAMETOOLONG: return "cannot be opened: the name is too long";
    case ENOTDIR: return "cannot be opened: a part of the path is not a directory";
    default: return "cannot be opened for reading (" + std::generic_category().message(error) + ")";
    }
}


}  // namespace

const char* file_type_name(unsigned mode)
{
    if (S_ISDIR(mode)) return "a directory";
    if (S_ISFIFO(mode)) return "a FIFO (named pipe)";
    if (S_ISCHR(mode)) return "a character device";
    if (S_ISBLK(mode)) return "a block device";
    if (S_ISSOCK(mode)) return "a socket";
    return "not a regular file";
}

InputFile::InputFile(InputFile&& other) noexcept
    : fd_(std::exchange(other.fd_, -1)), size_(other.size_), path_(std::move(other.path_))
{
}

InputFile& InputFile::operator=(InputFile&& other) noexcept
{
    if (this != &other) {
        if (fd_ >= 0) ::close(fd_);
        fd_ = std::exchange(other.fd_, -1);
        size_ = other.size_;
        path_ = std::move(other.path_);
    }
    return *this;
}

InputFile::~InputFile()
{
    if (fd_ >= 0) ::close(fd_);
}

bool InputFile::read_at(std::uint64_t offset, void* buffer, std::size_t count) const
{
    auto* bytes = static_cast<char*>(buffer);
    while (count > 0) {
        const ssize_t got = ::pread(fd_, bytes, count, off_t(offset));
        if (got < 0 && errno == EINTR) continue;
        if (got <= 0) return false;
        bytes += got;
        offset += std::uint64_t(got);
        count -= std::size_t(got);
    }
    return true;
}

InputFile open_input_file(const std::string& path, std::string_view operation)
{
    if (path.empty()) throw Error(ErrorCategory::Io, operation, "an input file name is empty");
    // O_NONBLOCK: open(2) of a FIFO without a writer would otherwise wait forever.
    const int fd = ::open(path.c_str(), O_RDONLY | O_NONBLOCK | O_CLOEXEC);
    if (fd < 0) refuse(operation, path, open_failure(errno));
    InputFile file(fd, 0, path);  // closes fd on every refusal below
    struct stat status {};
    if (::fstat(fd, &status) != 0) refuse(operation, path, "cannot be examined (fstat failed)");
    if (!S_ISREG(status.st_mode))
        refuse(operation, path, std::string("is ") + file_type_name(status.st_mode) + ", not a regular file; give a file");
    // Back to blocking reads: a regular file never blocks, but be explicit.
    ::fcntl(fd, F_SETFL, ::fcntl(fd, F_GETFL) & ~O_NONBLOCK);
    file.size_ = std::uint64_t(status.st_size);
    return file;
}

std::string read_input_file(const std::string& path, std::string_view operation, std::uint64_t max_bytes)
{
    const InputFile file = open_input_file(path, operation);
    if (file.size() > max_bytes)
        refuse(operation, path,
               "is " + std::to_string(file.size()) + " bytes, more than the limit of " + std::to_string(max_bytes) +
                   "; it cannot be the kind of file expected here");
    std::string bytes(std::size_t(file.size()), '\0');
    if (!file.read_at(0, bytes.data(), bytes.size()))
        refuse(operation, path, "could not be read in full (it shrank while being read, or an I/O error)");
    return bytes;
}

}  // namespace penumbra
