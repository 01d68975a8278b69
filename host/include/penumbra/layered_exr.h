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
// With surface ids (Pismo's, docs/pismo.md "A surface id per layer"), each
// sample also holds the id of the surface its layer crosses, in the channel
// `surface`, 32-bit UINT: exact for every id (a float is exact only to 2^24),
// and the type of OpenEXR's deep ID channels.
//
// Reading takes deep scanline and deep tiled files, with every check of
// penumbra/deep_exr.h's reader (nothing is allocated on the file's word
// alone; the same limits); channels other than Z (ZBack, A, ...) are ignored.
// Errors name the file: Io for a file that is missing, not EXR, flat, corrupt,
// lacks Z or a camera attribute, or claims more samples than it can hold;
// InvalidData, naming the pixel and the layer, for a depth that is not finite
// and > 0 or layers out of order, and for a camera that is no orthonormal
// right-handed frame or whose field of view is not in (0, 180) degrees; the
// channel surface stored other than as UINT is Io, an id above 2^31 - 1
// InvalidData naming the pixel and the layer.
#pragma once

#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "penumbra/exr_io.h"
#include "penumbra/layered_depth_map.h"
#include "penumbra/output_files.h"

namespace penumbra {

inline constexpr const char* kLayeredSurfaceChannel = "surface";

// Writes `map` atomically (penumbra/output_files.h), deep scanline, ZIPS, and
// when `surface_ids` is not empty the channel surface: one id a layer,
// parallel to map.depths(), each >= 0 (else Error(InvalidArgument),
// parameter "surface-ids").
void write_layered_exr(const std::string& path, const LayeredDepthMap& map,
                       std::span<const std::int32_t> surface_ids = {});

// As write_layered_exr, into `output`, which publishes it with its other files at once.
void stage_layered_exr(OutputFiles& output, const std::string& path, const LayeredDepthMap& map,
                       std::span<const std::int32_t> surface_ids = {});

// Reads a layered map; the data window's top-left pixel is the map's (0, 0).
// With `surface_ids`, it is set to the file's channel surface, parallel to the
// map's depths(), or emptied when the file has none (the channel is otherwise
// not read).
LayeredDepthMap read_layered_exr(const std::string& path, const ExrReadLimits& limits = {},
                                 std::vector<std::int32_t>* surface_ids = nullptr);

}  // namespace penumbra
