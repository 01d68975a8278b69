// OpenEXR's C++ streams over penumbra's own files, and the translation of its
// exceptions: shared by the flat (exr_io.cpp) and deep (deep_exr_*.cpp) I/O.
#pragma once

#include <OpenEXR/ImfIO.h>

#include <cerrno>
#include <cstdint>
#include <cstdio>
#include <stdexcept>
#include <string>
#include <string_view>
#include <system_error>
#include <utility>

#include "penumbra/error.h"
#include "penumbra/input_file.h"

namespace penumbra::detail {

// OpenEXR's messages end in a period; ours continue after them with advice.
inline std::string without_final_period(std::string text)
{
    if (!text.empty() && text.back() == '.') text.pop_back();
    return text;
}

// Runs `body`, turning whatever OpenEXR throws (Iex::BaseExc, or a standard
// exception from the library beneath it) into an Error(Io) that names the file,
// so that callers only ever see penumbra::Error. Our own Errors pass unchanged.
template <class Body>
auto translating_exr_exceptions(std::string_view operation, const std::string& path, std::string_view advice,
                                Body&& body)
{
    try {
        return body();
    } catch (const Error&) {
        throw;
    } catch (const std::exception& e) {
        throw Error(ErrorCategory::Io, operation,
                    "OpenEXR failed on '" + path + "': " + without_final_period(e.what()) + std::string(advice));
    }
}

// An OpenEXR input stream over a file penumbra opened itself (open_input_file:
// a regular file, opened without blocking), so that OpenEXR never opens a path.
class DescriptorInputStream : public Imf::IStream {
public:
    explicit DescriptorInputStream(const InputFile& file) : Imf::IStream(file.path().c_str()), file_(file) {}

    bool read(char bytes[], int count) override
    {
        if (count < 0 || !file_.read_at(position_, bytes, std::size_t(count)))
            throw std::runtime_error("unexpected end of file");
        position_ += std::uint64_t(count);
        return position_ < file_.size();
    }
    std::uint64_t tellg() override { return position_; }
    void seekg(std::uint64_t position) override { position_ = position; }

private:
    const InputFile& file_;
    std::uint64_t position_ = 0;
};

// An OpenEXR output stream over a stdio file that remembers its first failure.
// OutputFile's destructor writes the table of scanline offsets and swallows any
// exception doing so; without this record a full disk at that moment would
// leave a corrupt file that looks written.
class CheckedOutputStream : public Imf::OStream {
public:
    explicit CheckedOutputStream(const std::string& path)
        : Imf::OStream(path.c_str()), file_(std::fopen(path.c_str(), "wb"))
    {
        if (!file_) fail();
    }
    ~CheckedOutputStream() override
    {
        if (file_) std::fclose(file_);
    }

    void write(const char bytes[], int count) override
    {
        if (std::fwrite(bytes, 1, std::size_t(count), file()) != std::size_t(count)) fail();
    }
    // Must not throw: OutputFile's destructor calls it outside its try block.
    // A failure is recorded, and the next write() or close() reports it.
    std::uint64_t tellp() override
    {
        const off_t position = error_ ? -1 : ::ftello(file_);
        if (position < 0 && !error_) error_ = errno ? errno : EIO;
        return position < 0 ? 0 : std::uint64_t(position);
    }
    void seekp(std::uint64_t position) override
    {
        if (::fseeko(file(), off_t(position), SEEK_SET) != 0) fail();
    }

    // Closes the file; throws unless every write, and the close, succeeded.
    void close()
    {
        if (file_ && std::fclose(std::exchange(file_, nullptr)) != 0 && !error_) error_ = errno;
        if (error_)
            throw std::system_error(error_, std::generic_category(), "writing " + std::string(fileName()));
    }

private:
    std::FILE* file()
    {
        if (error_) throw std::system_error(error_, std::generic_category(), "writing after an error");
        return file_;
    }
    [[noreturn]] void fail()
    {
        if (!error_) error_ = errno ? errno : EIO;
        throw std::system_error(error_, std::generic_category(), "writing " + std::string(fileName()));
    }

    std::FILE* file_ = nullptr;
    int error_ = 0;
};

// OpenEXR compresses (and Imf decodes) chunks on its own thread pool, which
// is empty unless asked for (issue 10: a 2048^2 output written on one thread).
// Sized as TBB sizes its own: the CPUs this process may run on (its affinity
// mask, e.g. under taskset), not every CPU of the machine.
void use_hardware_threads_for_exr();

// Rows per frame buffer where a scanline file is read or written in bands:
// the buffers stay small, and ZIPS chunks are one line, so any band fits.
inline constexpr int kScanlineBand = 64;

}  // namespace penumbra::detail
