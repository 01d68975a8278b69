// A name or value as error messages quote it: 'name'. Shared by the readers
// and writers that name files and channels in their errors.
#pragma once

#include <string>

namespace penumbra::detail {

inline std::string in_quotes(const std::string& text) { return "'" + text + "'"; }

}  // namespace penumbra::detail
