// 8-bit PNG previews of images, and a diverging colour map for signed errors.
//
// PNG is for looking at results (the demo's previews, error heatmaps in notes),
// never for data: it holds 8 bits per channel. Data goes to EXR (exr_io.h).
#pragma once

#include <string>

#include "penumbra/image.h"

namespace penumbra {

// How a value in [0, 1] becomes an 8-bit code.
enum class PngTransfer {
    // Linear-light values (visibility, radiance): encoded with the sRGB transfer
    // curve (IEC 61966-2-1), as a display expects, so mid-grey looks mid-grey.
    Srgb,
    // Values already meant for display (colormap_error output, or a quantity such as
    // depth shown as a plain ramp): code = round(255 * value).
    None,
};

// Writes a 1-channel image as 8-bit greyscale or a 3-channel image as 8-bit RGB
// (channels 0, 1, 2 = R, G, B). Values are clamped to [0, 1] (infinities clamp
// too) and then mapped by `transfer`; a NaN is an Error(InvalidData) naming the
// pixel. Other channel counts and empty images are Error(InvalidArgument).
//
// Atomic like write_exr: a temporary file beside `path` replaces it only once
// complete, so a failed write never leaves a partial file or clobbers an old one.
void write_png(const std::string& path, const Image& image, PngTransfer transfer = PngTransfer::Srgb);

// Maps a 1-channel signed error (estimate minus truth) to a 3-channel,
// display-ready heatmap, for write_png with PngTransfer::None: white at 0,
// shading linearly to pure blue at -max_abs (underestimate: too dark, e.g.
// over-darkening) and pure red at +max_abs (overestimate: too bright, e.g.
// light leaking). Errors beyond ±max_abs saturate. The ends are pure primaries
// so that the sign of an error reads at a glance, even in a small preview.
// max_abs must be finite and > 0; a NaN error is Error(InvalidData).
Image colormap_error(const Image& signed_error, float max_abs);

}  // namespace penumbra
