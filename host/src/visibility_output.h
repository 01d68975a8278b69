// The allocating form of an operation that writes one plane of visibility per
// receiver: the output is made without the zero fill, as the kernel writes
// every pixel or the operation throws (and the image is dropped).
#pragma once

#include "penumbra/image.h"

namespace penumbra::detail {

template <class Write>
Image visibility_output(const Image& receivers, Write write)
{
    Image out(receivers.width(), receivers.height(), 1, Image::Uninitialized{});
    write(out);
    return out;
}

}  // namespace penumbra::detail

// Defines the allocating form of a visibility operation from its form into an
// existing output: `Image NAME(Context&, const SOURCE&, const Image& receivers,
// const OPTIONS&)` calls `NAME(..., out)` on a fresh 1-channel image. Used at
// namespace penumbra scope, once per public operation.
#define PN_ALLOCATING_VISIBILITY(NAME, SOURCE, OPTIONS)                                                   \
    Image NAME(Context& context, const SOURCE& source, const Image& receivers, const OPTIONS& options)    \
    {                                                                                                     \
        return detail::visibility_output(receivers,                                                      \
                                         [&](Image& out) { NAME(context, source, receivers, options, out); }); \
    }
