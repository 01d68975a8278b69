// The table of docs/moments.md, "Biases": the worst excess of MSM over the
// interval [bound(z - delta), truth(z + delta)] of random few-depth windows
// (tests/support/msm_windows.h, the windows tests/kernels/msm_test.cpp
// checks), per moment bias alpha, storage and depth uncertainty delta. A
// measurement, not a check: it prints the table and asserts nothing.
// usage: msm_bias_excess [trials]   (default 300, the figures of the doc)
#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <random>

#include "penumbra/moments.h"
#include "support/msm_windows.h"

using namespace penumbra;

int main(int argc, char** argv)
{
    const int trials = argc > 1 ? std::atoi(argv[1]) : 300;
    if (trials < 1 || argc > 2) {
        std::fprintf(stderr, "usage: msm_bias_excess [trials >= 1]\n");
        return 2;
    }
    Context ctx(ContextOptions{Backend::Scalar, {}});
    const double deltas[3] = {1e-4, 1e-3, 1e-2};
    std::printf("%-8s %-6s %12s %12s %12s\n", "alpha", "bits", "delta 1e-4", "delta 1e-3", "delta 1e-2");
    for (float alpha : {3e-7f, 3e-6f, 1e-5f, 3e-5f, 6e-5f, 1e-4f, 1e-3f})
        for (Quantization q : {Quantization::Bits16, Quantization::Bits32}) {
            std::mt19937 rng(7);
            double worst[3] = {0, 0, 0};
            for (int trial = 0; trial < trials; ++trial) {
                const testing::FewDepthWindow c = testing::few_depth_window(rng, trial);
                const Image out = msm(ctx, testing::msm_table_for(ctx, c.depth, q), c.receivers,
                                      MsmOptions{c.radius, alpha, 0.0f});
                for (int y = 0; y < out.height(); ++y)
                    for (int x = 0; x < out.width(); ++x) {
                        const auto atoms = testing::window_atoms(c.depth, x, y, c.radius);
                        const double z = c.receivers.at(2, x, y), shadow = 1.0 - out.at(0, x, y);
                        for (int k = 0; k < 3; ++k)
                            worst[k] = std::max(worst[k], testing::msm_excess(atoms, alpha, z, shadow, deltas[k]));
                    }
            }
            std::printf("%-8.1e %-6s %12.4f %12.4f %12.4f\n", alpha, to_string(q).c_str(), worst[0], worst[1],
                        worst[2]);
        }
    return 0;
}
