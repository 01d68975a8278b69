// Measures the opt-in 16-bit optimized MSM quantization (Peters & Klein, I3D
// 2015; kernels/moment_quantize.h) against MSM on the unquantized depths
// (the default exact limb table, which computes the method's float64
// mathematics to within its tolerance, docs/moments.md): the quantization's
// own error in visibility. docs/moments.md and `penumbra shade --help` quote
// the output.
//
// Maps: a smooth one (a tilted plane with a gentle bump) and a two-layer one
// (an occluder at 0.3 over half the map, a floor at 0.7). Receivers on every
// texel: on the surface, 1e-3 in front of it and 1e-2 behind it. Default
// biases; radius 0 .. 8.
// usage: msm_quantization_error [size]
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <vector>

#include "penumbra/moments.h"

using namespace penumbra;

namespace {

Image smooth_map(int n)
{
    Image m(n, n, 1);
    for (int y = 0; y < n; ++y)
        for (int x = 0; x < n; ++x) {
            const double u = (x + 0.5) / n, v = (y + 0.5) / n;
            m.at(0, x, y) = float(0.3 + 0.4 * u + 0.1 * v + 0.05 * std::exp(-20.0 * ((u - 0.5) * (u - 0.5) + (v - 0.5) * (v - 0.5))));
        }
    return m;
}

Image two_layer_map(int n)
{
    Image m(n, n, 1);
    for (int y = 0; y < n; ++y)
        for (int x = 0; x < n; ++x) m.at(0, x, y) = (x + y) % 7 < 3 || x < n / 2 ? 0.3f : 0.7f;
    return m;
}

Image receivers_over(const Image& map, float offset)
{
    const int n = map.width();
    Image rx(n, n, 3);
    for (int y = 0; y < n; ++y)
        for (int x = 0; x < n; ++x) {
            rx.at(0, x, y) = (x + 0.5f) / n;
            rx.at(1, x, y) = (y + 0.5f) / n;
            rx.at(2, x, y) = map.at(0, x, y) + offset;
        }
    return rx;
}

}  // namespace

int main(int argc, char** argv)
{
    const int n = argc > 1 ? std::atoi(argv[1]) : 256;
    Context ctx;
    std::printf("map receivers radius worst p99 share>1e-2\n");
    for (int which = 0; which < 2; ++which) {
        const Image map = which == 0 ? smooth_map(n) : two_layer_map(n);
        const MsmTable exact = build_msm_table(ctx, map);
        const MsmTable bits16 = build_msm_table(ctx, map, Quantization::Bits16);
        for (float offset : {0.0f, -1e-3f, 1e-2f}) {
            const Image rx = receivers_over(map, offset);
            for (int radius : {0, 1, 2, 4, 8}) {
                const Image a = msm(ctx, exact, rx, MsmOptions{radius, {}, {}});
                const Image b = msm(ctx, bits16, rx, MsmOptions{radius, {}, {}});
                std::vector<double> e;
                for (int y = 0; y < n; ++y)
                    for (int x = 0; x < n; ++x) e.push_back(std::abs(double(a.at(0, x, y)) - b.at(0, x, y)));
                std::sort(e.begin(), e.end());
                const double share = double(e.end() - std::upper_bound(e.begin(), e.end(), 1e-2)) / double(e.size());
                std::printf("%s %+g %d %.4f %.4f %.4f\n", which == 0 ? "smooth" : "two-layer", offset, radius,
                            e.back(), e[std::size_t(0.99 * double(e.size() - 1))], share);
            }
        }
    }
    return 0;
}
