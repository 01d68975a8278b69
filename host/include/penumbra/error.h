// penumbra::Error — the one exception type of the library.
//
// Three kinds of failure (STYLE.md item 10): user errors (bad parameters,
// sizes, files) throw Error naming the operation and the parameter; internal
// invariants are assertions; backend failures name the API call, the OpenCL
// error name and, for program builds, the whole build log.
#pragma once

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

class Error : public std::runtime_error {
public:
    // `operation` is the API entry point or command ("vsm", "read_exr"), `message`
    // says what was wrong and, where it can, what to do about it.
    Error(ErrorCategory category, std::string_view operation, std::string_view message);

    ErrorCategory category() const noexcept { return category_; }
    const std::string& operation() const noexcept { return operation_; }

private:
    ErrorCategory category_;
    std::string operation_;
};

// Throws Error(InvalidArgument) when `condition` is false. For checks at the API
// boundary, where the caller's mistake is the only possible cause.
void require(bool condition, std::string_view operation, std::string_view message);

}  // namespace penumbra
