// The leak table of docs/moments.md, "Leak on overlapping occluders": every
// moment method on the `overlap` reference scene (tests/support/overlap_scene.h),
// scored against ray-traced ground truth (32^2 rays per receiver), 160 x 120
// receivers, per shadow-map size and box radius. A measurement, not a check:
// tests/kernels/moments_overlap_test.cpp checks the ordering at a small size.
// usage: overlap_leak_table [map sizes...]   (default 512 1024)
#include <cstdio>
#include <cstdlib>
#include <vector>

#include "support/overlap_scene.h"

int main(int argc, char** argv)
{
    std::vector<int> map_sizes;
    for (int i = 1; i < argc; ++i) map_sizes.push_back(std::atoi(argv[i]));
    if (map_sizes.empty()) map_sizes = {512, 1024};
    for (int size : map_sizes)
        if (size < 1 || size > 16384) {
            std::fprintf(stderr, "usage: overlap_leak_table [map sizes in 1..16384...]\n");
            return 2;
        }
    for (int map_size : map_sizes) {
        const penumbra::testing::OverlapFrame f = penumbra::testing::render_overlap_frame(map_size, 160, 120, 32);
        for (int radius : {1, 2, 4}) {
            std::printf("\noverlap, %dx%d map, 160x120 receivers, truth 32x32 samples, box radius %d\n", map_size,
                        map_size, radius);
            penumbra::testing::print_leak_table(penumbra::testing::overlap_leak_table(f, radius));
        }
    }
    return 0;
}
