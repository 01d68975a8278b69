// penumbra::Error — the one exception type of the library.
//
// Three kinds of failure (STYLE.md item 10): user errors (bad parameters,
// sizes, files) throw Error naming the operation and the parameter; internal
// invariants are assertions; backend failures name the API call, the OpenCL
// error name and, for program builds, the whole build log.
#pragma once

#include <optional>
#include <stdexcept>
#include <string>
#include <string_view>

namespace penumbra {

enum class ErrorCategory {
    InvalidArgument,  // a parameter, size or value the caller passed is out of range
    InvalidData,      // NaN / infinite / out-of-range values inside an image
    Io,               // a file could not be read or written, or is not what it should be
    Unavailable,      // a requested backend, ISA or device does not exist on this machine
    Backend,          // a backend call failed (OpenCL error, program build failure)
};

std::string_view to_string(ErrorCategory category);

// The first bad value of an image parameter (InvalidData): where it is and what it is,
// so that a caller can name its own file and channel (the CLI does).
struct BadPixel {
    int channel = 0, x = 0, y = 0;
    float value = 0.0f;
};

class Error : public std::runtime_error {
public:
    // `operation` is the API entry point or command ("vsm", "read_exr"), `message`
    // says what was wrong and, where it can, what to do about it.
    Error(ErrorCategory category, std::string_view operation, std::string_view message);
    // The same naming the parameter at fault: the API's name for it ("radius",
    // "light-size", "depth", "receivers"), never a command-line flag; for a bad
    // value inside an image parameter also the pixel.
    Error(ErrorCategory category, std::string_view operation, std::string_view parameter, std::string_view message,
          std::optional<BadPixel> pixel = std::nullopt);

    ErrorCategory category() const noexcept { return category_; }
    const std::string& operation() const noexcept { return operation_; }
    // Empty when the error is about no one parameter (a file, a backend).
    const std::string& parameter() const noexcept { return parameter_; }
    // what() without the leading "operation: ".
    const std::string& message() const noexcept { return message_; }
    const std::optional<BadPixel>& pixel() const noexcept { return pixel_; }

    // This error as one of `operation`'s (an operation that reports a step's failure as its own).
    Error as_operation(std::string_view operation) const;

private:
    ErrorCategory category_;
    std::string operation_, parameter_, message_;
    std::optional<BadPixel> pixel_;
};

// Throws Error(InvalidArgument) when `condition` is false. For checks at the API
// boundary, where the caller's mistake is the only possible cause.
void require(bool condition, std::string_view operation, std::string_view message);
// The same naming the parameter.
void require(bool condition, std::string_view operation, std::string_view parameter, std::string_view message);

}  // namespace penumbra
