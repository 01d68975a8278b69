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
