// Inputs of penumbra_bench, made once per size and kept for the whole run so
// that no case times their creation.
//
// The scene: a lit ground at depth 0.75..0.85 under a 16 x 16 grid of square
// occluders at depth 0.25..0.30 that cover 36% of the map; the receivers sit at
// z = 0.5..0.6 at every texel centre, so that 36% of them are in shadow, the
// rest lit, with a penumbra band along every occluder edge (both branches of
// the Chebyshev bound run, as in a real frame).
#pragma once

#include <cstddef>
#include <memory>
#include <string>

#include "penumbra/context.h"
#include "penumbra/image.h"
#include "penumbra/moment_table.h"
#include "support/backend_list.h"  // backend_names(): the tests' list

namespace penumbra::bench {

// Bytes the table build moves per texel, by the project's definition: the
// 4-byte depth read plus one 4-byte element written per plane (an exact limb
// table has moments x limbs planes: VSM's 2 x 2 = 20 B/texel; a float table
// one per moment, 12 B). The memcpy case copies the exact table's figure.
constexpr std::size_t table_bytes_per_texel(int planes) { return 4 + 4 * std::size_t(planes); }

const Image& depth_map(int size);   // size x size, 1 channel
const Image& receivers(int size);   // size x size, 3 channels (u, v, z)
// The same receivers in a fixed random order (a permutation of the pixels):
// neighbouring lanes read unrelated windows.
const Image& shuffled_receivers(int size);
// A raster denser than the map, as a renderer's screen often is near the
// camera: kMagnifiedStep texels per receiver about the map's centre, so
// neighbouring lanes read the same or the next window corners.
constexpr float kMagnifiedStep = 0.6f;
const Image& magnified_receivers(int size);
// The best CPU backend here, by name: the last (best) ISA of supported_isas()
// (simd/cpu_kernels.h: built and run by this CPU), or "scalar" where there is
// none. The tables every backend's lookups read are built with it.
std::string best_cpu_backend();
// Built once with best_cpu_backend(); lookups of every backend read it.
const MomentTable& moment_table(int size, Precision precision);

// Two touched, 64-byte aligned buffers of `bytes` each, for the memcpy case.
struct CopyBuffers {
    std::byte* src;
    std::byte* dst;
    std::size_t bytes;
};
const CopyBuffers& copy_buffers(std::size_t bytes);

// One context per backend name (testing::backend_names(): "scalar",
// "sse4.2", "avx2", "avx512", "opencl"), made on first use and kept: the OpenCL program build (seconds
// under PoCL) stays outside every timing. Throws penumbra::Error when the
// backend cannot start.
Context& context(const std::string& backend);

}  // namespace penumbra::bench
