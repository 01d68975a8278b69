// The cases of the fidelity measurements (issue 9): the maps, the receivers
// on, in front of and behind them, and the library calls of every method in
// each mode, shared by tests/kernels/moment_fidelity_test.cpp and
// bench/moment_fidelity.cpp so that the test asserts on the cases the
// deviation table measures.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "penumbra/context.h"
#include "penumbra/image.h"
#include "support/fidelity_reference.h"

namespace penumbra::testing::fidelity {

// Depth maps, one channel, float32 depths in [0, 1].
Image smooth_map(int width, int height);     // a gently curved, sloped surface in [0.2, 0.8]
Image two_layer_map(int width, int height);  // a sloped ground near 0.8 under occluder patches near 0.3
Image constant_map(int width, int height, float z);        // one depth
Image checker_map(int width, int height, float a, float b); // two depths (0 and 1: "only 0 and 1")

// `count` receivers (an image of count x 1 texels, channels u, v, z) at
// random positions: a quarter exactly on the surface (the depth of the texel
// containing (u, v)), a quarter in front (1e-3 to 3e-2), half behind (1e-4
// to 5e-2, log-uniform: the penumbra regime and beyond).
Image receivers_for(const Image& map, int count, std::uint32_t seed);
// One receiver per texel centre at depth offset `dz` from the texel's own depth.
Image receivers_at_texels(const Image& map, float dz);

// A mode of the tool: how the tables are built. (The float tables that
// `--precision float` and `--quantize 32` built before issue 9 left the
// tool; the before table was measured at commit 94e0387, whose Mode::Float
// built them.)
enum class Mode {
    Default,  // the tables `penumbra shade` builds with no precision or quantization option
    Msm16,    // msm, msm-soft: the opt-in I3D 2015 16-bit quantization (--quantize 16)
    Direct,   // vsm, msm, evsm2, evsm4: the window summed from the map, no table (the
              // `Image depth` overloads; what `penumbra shade` runs at radii up to the
              // method's cut, docs/moment_table.md)
};
std::string mode_name(Method m, Mode mode);
std::vector<Mode> modes_of(Method m);

// The window setting of a case: the radius of box methods, the light size of
// vssm and msm-soft.
struct Setting {
    int radius = 2;
    float light_size = 0.02f;
};
bool is_soft(Method m);

// Runs the library: one table for the method and mode, then a lookup per
// setting; each run has the library's visibility and the reference's
// parameters (those the library used). Mode::Msm16 also fills `stored` with
// the table's dequantized per-texel moments and points the parameters at
// them (the reference of the arithmetic after the quantization).
struct LibraryRun {
    Image out;
    Params params;
};
std::vector<LibraryRun> run_library(Context& ctx, Method m, Mode mode, const Image& map, const Image& receivers,
                             const std::vector<Setting>& settings, StoredMoments* stored = nullptr);

inline Receiver receiver_at(const Image& rx, int x, int y)
{
    return {rx.at(0, x, y), rx.at(1, x, y), rx.at(2, x, y)};
}

// Judges every receiver; `fails` gets a line per failure (at most `max_lines`).
struct Tally {
    int receivers = 0, beyond = 0, failed = 0, ill = 0, beyond_1e2 = 0;
    std::vector<double> deviations;
    double worst = 0;
    std::string first_failures;
};
// `references`: the reference answers per receiver when already known.
Tally judge_all(Method m, const Image& map, const Image& receivers, const Image& library, const Params& p,
                int max_lines = 5, const std::vector<double>* references = nullptr);
// The reference answers of every receiver (in parallel).
std::vector<double> reference_all(Method m, const Image& map, const Image& receivers, const Params& p);

}  // namespace penumbra::testing::fidelity
