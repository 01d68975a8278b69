// Writes the seed corpus of deep_exr_reader_fuzz (run by make_corpus.sh): small
// deep files as penumbra writes them (scanline, tiled; steps, slopes, empty and
// opaque pixels) and as another renderer might (point samples without ZBack,
// HALF opacity, colour channels, RLE and no compression, gaps between samples),
// and a layered depth map of Pismo with its surface ids (a UINT channel).
//
//   deep_exr_seeds OUT_DIR
#include <cstdint>
#include <cstdio>
#include <string>
#include <vector>

#include "penumbra/deep_exr.h"
#include "penumbra/layered_exr.h"
#include "support/deep_files.h"

namespace {

penumbra::DeepShadowMap seed_map(int width, int height)
{
    penumbra::DeepShadowMapBuilder builder(width, height);
    for (int p = 0; p < width * height; ++p) {
        const float z = 1.0f + float(p % 5);
        if (p % 4 == 3) builder.add_pixel({}, {});
        else if (p % 4 == 2) builder.add_pixel(std::vector<float>{z, z, z + 3}, std::vector<float>{1, 0, 0});
        else builder.add_pixel(std::vector<float>{z, z, z + 1, z + 2}, std::vector<float>{1, 0.7f, 0.4f, 0.35f});
    }
    return builder.build();
}

void write_foreign(const std::string& path, Imf::Compression compression, bool zback)
{
    penumbra::testing::RawDeep raw(5, 4);
    raw.channels = zback ? std::vector<std::string>{"A", "B", "G", "R", "Z", "ZBack"}
                         : std::vector<std::string>{"A", "B", "G", "R", "Z"};
    raw.types["A"] = Imf::HALF;
    raw.compression = compression;
    for (int p = 0; p < 20; ++p) {
        auto& pixel = raw.pixels[std::size_t(p)];
        const int n = p % 3;
        for (const std::string& c : raw.channels) pixel[c].clear();
        for (int k = 0; k < n; ++k) {
            pixel["Z"].push_back(1.0f + 2.0f * float(k));
            if (zback) pixel["ZBack"].push_back(2.0f + 2.0f * float(k));
            pixel["A"].push_back(0.25f * float(k + 1));
            for (const char* c : {"R", "G", "B"}) pixel[c].push_back(0.5f);
        }
    }
    penumbra::testing::write_raw_deep(path, raw);
}

// Pixel p holds p % 4 layers, each with a surface id.
void write_layered_with_ids(const std::string& path, int width, int height)
{
    penumbra::LayeredDepthMapBuilder builder(width, height, penumbra::MapCamera{});
    std::vector<std::int32_t> ids;
    for (int p = 0; p < width * height; ++p) {
        std::vector<float> layers;
        for (int k = 0; k < p % 4; ++k) layers.push_back(1.0f + float(p) + 0.5f * float(k)), ids.push_back(k + p % 3);
        builder.add_pixel(layers);
    }
    penumbra::write_layered_exr(path, builder.build(), ids);
}

}  // namespace

int main(int argc, char** argv)
{
    if (argc != 2) {
        std::fprintf(stderr, "usage: deep_exr_seeds OUT_DIR\n");
        return 2;
    }
    const std::string out = argv[1];
    penumbra::write_deep_exr(out + "/deep_scanline.exr", seed_map(7, 5));
    penumbra::write_deep_exr(out + "/deep_tiled.exr", seed_map(7, 5), {penumbra::DeepExrLayout::Tiled, 4});
    write_foreign(out + "/foreign_points_rle.exr", Imf::RLE_COMPRESSION, false);
    write_foreign(out + "/foreign_volumes_none.exr", Imf::NO_COMPRESSION, true);
    write_layered_with_ids(out + "/layered_ids.exr", 7, 5);
    return 0;
}
