// Deep shadow maps to and from OpenEXR deep images (deep scanline or deep
// tiled, OpenEXR 2.0 and later), docs/deep_shadow_maps.md "Files".
//
// One pixel's function (z_i, t_i), i = 0..n-1, is written as n - 1 deep
// samples, sample k spanning the segment from vertex k to vertex k+1:
//   Z = z_k, ZBack = z_{k+1}     a volume sample, or a point sample (Z == ZBack)
//                                for a step
//   A = 1 - t_{k+1} / t_k        the sample's own (not accumulated) opacity, so
//                                that compositing the samples front to back, as
//                                OpenEXR's "Interpreting Deep Pixels" defines,
//                                gives 1 - A_total = t at every vertex (A = 0
//                                once t_k = 0)
//   penumbra.T = t_{k+1}         the transmittance behind the sample, exactly
// A, Z and ZBack are the standard channels (32-bit FLOAT), so any deep-aware
// tool reads the file as the opacity it is; penumbra.T exists because a float
// A cannot carry every float t: t_k (1 - A) reaches only multiples of
// t_k 2^-24 when t_{k+1} < t_k / 2, so without it a round trip would not be
// exact. The samples are tidy (sorted, non-overlapping, adjacent), and the
// header says so (deepImageState = tidy). An empty pixel has no samples.
//
// Reading takes deep scanline and deep tiled files (level 0 of a tiled one,
// the first part of a multi-part one), with or without ZBack (a sample without
// it is a point sample, Z == ZBack) and penumbra.T (then t_{k+1} = t_k (1 - A_k),
// in double, rounded to float). Gaps between samples are flat stretches. What
// a file from another renderer may also hold (R, G, B, ...) is ignored.
//
// Every failure is Error naming the file: Io for a file that is missing, not
// EXR, flat (not deep), truncated or corrupt, lacks Z or A, or claims more
// samples than its size can hold (checked before anything is allocated for
// them); InvalidData, naming the pixel (file coordinates) and the sample, for
// a NaN or infinite depth, ZBack before Z, samples out of depth order or
// overlapping, an A or penumbra.T that is NaN or outside [0, 1], or a
// penumbra.T that rises or disagrees with A.
#pragma once

#include <string>

#include "penumbra/deep_shadow_map.h"
#include "penumbra/exr_io.h"
#include "penumbra/output_files.h"

namespace penumbra {

enum class DeepExrLayout { Scanline, Tiled };

struct DeepExrWriteOptions {
    DeepExrLayout layout = DeepExrLayout::Scanline;  // every deep reader takes scanline files
    int tile_size = 64;                              // square tiles in [1, 2048], for DeepExrLayout::Tiled
};

// Writes `map` atomically (penumbra/output_files.h): a failed write leaves no
// partial file and an existing target as it was. ZIPS compression
// (lossless; OpenEXR 3.1 takes only NONE, RLE and ZIPS for deep data).
void write_deep_exr(const std::string& path, const DeepShadowMap& map, const DeepExrWriteOptions& options = {});

// As write_deep_exr, into `output`, which publishes it with its other files at once.
void stage_deep_exr(OutputFiles& output, const std::string& path, const DeepShadowMap& map,
                    const DeepExrWriteOptions& options = {});

// Reads a deep map; the data window's top-left pixel is the map's (0, 0).
// `limits.max_pixels` bounds the data window, as for read_exr.
DeepShadowMap read_deep_exr(const std::string& path, const ExrReadLimits& limits = {});

// The name of the exact-transmittance channel (above).
inline constexpr const char* kDeepTransmittanceChannel = "penumbra.T";

}  // namespace penumbra
