// Limits on what the tool reads, shared by every command that reads images.
// main() sets them from `--max-pixels N`, accepted on any command line.
#pragma once

#include "penumbra/exr_io.h"

namespace penumbra::cli {

inline ExrReadLimits& exr_limits()
{
    static ExrReadLimits limits;
    return limits;
}

}  // namespace penumbra::cli
