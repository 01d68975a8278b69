#include "penumbra/error.h"

namespace penumbra {

std::string_view to_string(ErrorCategory category)
{
    switch (category) {
    case ErrorCategory::InvalidArgument: return "invalid argument";
    case ErrorCategory::InvalidData: return "invalid data";
    case ErrorCategory::Io: return "i/o";
    case ErrorCategory::Unavailable: return "unavailable";
    case ErrorCategory::Backend: return "backend";
    }
    return "unknown";
}

static std::string compose(std::string_view operation, std::string_view message)
{
    std::string text(operation);
    text += ": ";
    text += message;
    return text;
}

Error::Error(ErrorCategory category, std::string_view operation, std::string_view message)
    : Error(category, operation, {}, message)
{
}

Error::Error(ErrorCategory category, std::string_view operation, std::string_view parameter,
             std::string_view message, std::optional<BadPixel> pixel)
    : std::runtime_error(compose(operation, message)), category_(category), operation_(operation),
      parameter_(parameter), message_(message), pixel_(pixel)
{
}

Error Error::as_operation(std::string_view operation) const
{
    return Error(category_, operation, parameter_, message_, pixel_);
}

void require(bool condition, std::string_view operation, std::string_view message)
{
    if (!condition) throw Error(ErrorCategory::InvalidArgument, operation, message);
}

void require(bool condition, std::string_view operation, std::string_view parameter, std::string_view message)
{
    if (!condition) throw Error(ErrorCategory::InvalidArgument, operation, parameter, message);
}

}  // namespace penumbra
