// Layered depth maps (penumbra/layered_depth_map.h) to and from OpenEXR deep
// images: Pismo's maps as files (`penumbra pismo-build`, docs/pismo.md "Files").
//
// One pixel's layers d_0 < d_1 < ... are its deep samples, one point sample
// per layer, in the standard channel Z (32-bit FLOAT, the radial distance from
// the camera, in world units). There is no A: every layer is an opaque
// surface crossing, and the file says nothing about opacity. The header holds
// the map's camera, exactly (double attributes):
//   penumbra.cameraPosition, penumbra.cameraRight, penumbra.cameraDown,
//   penumbra.cameraForward (v3d) and penumbra.tanHalfFov (double).
// An empty pixel has no samples. The samples are tidy, and the header says so.
//
// Reading takes deep scanline and deep tiled files, with every check of
// penumbra/deep_exr.h's reader (nothing is allocated on the file's word
// alone; the same limits); channels other than Z (ZBack, A, ...) are ignored.
// Errors name the file: Io for a file that is missing, not EXR, flat, corrupt,
// lacks Z or a camera attribute, or claims more samples than it can hold;
// InvalidData, naming the pixel and the layer, for a depth that is not finite
// and > 0 or layers out of order, and for a camera that is no orthonormal
// right-handed frame or whose field of view is not in (0, 180) degrees.
#pragma once

#include <string>

#include "penumbra/exr_io.h"
#include "penumbra/layered_depth_map.h"
#include "penumbra/output_files.h"

namespace penumbra {

// Writes `map` atomically (penumbra/output_files.h), deep scanline, ZIPS.
void write_layered_exr(const std::string& path, const LayeredDepthMap& map);

// As write_layered_exr, into `output`, which publishes it with its other files at once.
void stage_layered_exr(OutputFiles& output, const std::string& path, const LayeredDepthMap& map);

// Reads a layered map; the data window's top-left pixel is the map's (0, 0).
LayeredDepthMap read_layered_exr(const std::string& path, const ExrReadLimits& limits = {});

}  // namespace penumbra
