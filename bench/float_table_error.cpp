// Measures the float summed-area table's error against exact sums, at map
// sizes 1024^2, 4096^2 and 16384^2 (docs/moment_table.md quotes the output).
//
// Depths are random multiples of 1/65535 in [0, 1] (what a 16-bit depth buffer
// holds), so the reference — double-precision sums over each window — is exact.
// Windows of radius 1, 4 and 16 at random positions; the float table's error
// grows with its entries, so the worst cases sit towards the far corner.
// usage: float_table_error [sizes...]
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <random>
#include <vector>

#include "penumbra/moment_table.h"

using namespace penumbra;

int main(int argc, char** argv)
{
    std::vector<int> sizes;
    for (int i = 1; i < argc; ++i) sizes.push_back(std::atoi(argv[i]));
    if (sizes.empty()) sizes = {1024, 4096, 16384};
    Context ctx;
    std::printf("size radius windows worst_rel_mean worst_rel_var(var>1e-3) worst_abs_var\n");
    for (int n : sizes) {
        Image depth(n, n, 1);
        std::mt19937 rng(n);
        std::uniform_int_distribution<int> level(0, 65535);
        for (int y = 0; y < n; ++y)
            for (int x = 0; x < n; ++x) depth.at(0, x, y) = float(level(rng)) / 65535.0f;
        const MomentTable table = build_moment_table(ctx, depth, 2, Precision::Float);
        for (int r : {1, 4, 16}) {
            double worst_mean = 0, worst_var = 0, worst_abs_var = 0;
            const int windows = 20000;
            std::uniform_int_distribution<int> pos(r, n - r - 1);
            for (int i = 0; i < windows; ++i) {
                // Half the windows near the far corner, where the entries are largest.
                const int cx = i % 2 ? pos(rng) : n - 1 - r - (pos(rng) % 64);
                const int cy = i % 2 ? pos(rng) : n - 1 - r - (pos(rng) % 64);
                const int x0 = cx - r, x1 = cx + r + 1, y0 = cy - r, y1 = cy + r + 1;
                double s1 = 0, s2 = 0;
                for (int y = y0; y < y1; ++y)
                    for (int x = x0; x < x1; ++x) {
                        const double z = depth.at(0, x, y);
                        s1 += z;
                        s2 += z * z;
                    }
                const double area = double(x1 - x0) * (y1 - y0);
                const double mean = s1 / area, var = s2 / area - mean * mean;
                const double fmean = table.box_sum(1, x0, x1, y0, y1) / area;
                const double fvar = table.box_sum(2, x0, x1, y0, y1) / area - fmean * fmean;
                worst_mean = std::max(worst_mean, std::abs(fmean - mean) / std::max(mean, 1e-3));
                worst_abs_var = std::max(worst_abs_var, std::abs(fvar - var));
                if (var > 1e-3) worst_var = std::max(worst_var, std::abs(fvar - var) / var);
            }
            std::printf("%d %d %d %.3g %.3g %.3g\n", n, r, windows, worst_mean, worst_var, worst_abs_var);
            std::fflush(stdout);
        }
    }
}
