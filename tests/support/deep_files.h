// Deep EXR files written with OpenEXR directly, as another renderer (or a
// damaged file) would have them: any channels, any samples, scanline or tiled,
// any compression. For the deep reader's tests; independent of deep_exr_write.
#pragma once

#include <OpenEXR/ImfChannelList.h>
#include <OpenEXR/ImfDeepFrameBuffer.h>
#include <OpenEXR/ImfDeepScanLineInputFile.h>
#include <OpenEXR/ImfDeepScanLineOutputFile.h>
#include <OpenEXR/ImfDeepTiledOutputFile.h>
#include <OpenEXR/ImfHeader.h>
#include <OpenEXR/ImfPartType.h>
#include <OpenEXR/ImfTileDescription.h>

#include <functional>
#include <map>
#include <string>
#include <vector>

namespace penumbra::testing {

// Per pixel (row-major), per channel name, the samples' values; every channel
// of a pixel holds the same number of samples.
struct RawDeep {
    int width = 1, height = 1;
    std::vector<std::string> channels{"A", "Z", "ZBack"};
    std::map<std::string, Imf::PixelType> types;  // FLOAT unless named here
    std::vector<std::map<std::string, std::vector<float>>> pixels;
    Imf::Compression compression = Imf::ZIPS_COMPRESSION;
    int tile = 0;  // 0: scanline; else square tiles of this size
    std::function<void(Imf::Header&)> edit_header;  // attributes to add, when set

    RawDeep(int w, int h) : width(w), height(h), pixels(std::size_t(w) * std::size_t(h)) {}
    std::map<std::string, std::vector<float>>& at(int x, int y) { return pixels[std::size_t(y) * width + x]; }
};

inline void write_raw_deep(const std::string& path, RawDeep raw)
{
    const Imath::Box2i window({0, 0}, {raw.width - 1, raw.height - 1});
    Imf::Header header(window, window, 1.0f, Imath::V2f(0, 0), 1.0f, Imf::INCREASING_Y, raw.compression);
    for (const std::string& name : raw.channels) {
        const auto type = raw.types.find(name);
        header.channels().insert(name, Imf::Channel(type == raw.types.end() ? Imf::FLOAT : type->second));
    }
    header.setType(raw.tile ? Imf::DEEPTILE : Imf::DEEPSCANLINE);
    if (raw.tile) header.setTileDescription(Imf::TileDescription(raw.tile, raw.tile, Imf::ONE_LEVEL));
    if (raw.edit_header) raw.edit_header(header);

    const std::size_t pixels = raw.pixels.size();
    std::vector<unsigned> counts(pixels, 0);
    std::map<std::string, std::vector<char*>> pointers;
    // Converted per type: HALF channels from half buffers, UINT from unsigned ones.
    std::map<std::string, std::vector<std::vector<half>>> halves;
    std::map<std::string, std::vector<std::vector<unsigned>>> uints;
    for (const std::string& name : raw.channels) {
        pointers[name].resize(pixels, nullptr);
        halves[name].resize(pixels);
        uints[name].resize(pixels);
    }
    for (std::size_t p = 0; p < pixels; ++p)
        for (const std::string& name : raw.channels) {
            std::vector<float>& values = raw.pixels[p][name];
            counts[p] = unsigned(values.size());
            const auto type = raw.types.find(name);
            if (type != raw.types.end() && type->second == Imf::HALF) {
                halves[name][p].assign(values.begin(), values.end());
                pointers[name][p] = reinterpret_cast<char*>(halves[name][p].data());
            } else if (type != raw.types.end() && type->second == Imf::UINT) {
                for (float v : values) uints[name][p].push_back(unsigned(v));
                pointers[name][p] = reinterpret_cast<char*>(uints[name][p].data());
            } else {
                pointers[name][p] = reinterpret_cast<char*>(values.data());
            }
        }
    Imf::DeepFrameBuffer frame;
    frame.insertSampleCountSlice(Imf::Slice(Imf::UINT, reinterpret_cast<char*>(counts.data()), sizeof(unsigned),
                                            sizeof(unsigned) * std::size_t(raw.width)));
    for (const std::string& name : raw.channels) {
        const auto type = raw.types.find(name);
        const Imf::PixelType stored = type == raw.types.end() ? Imf::FLOAT : type->second;
        frame.insert(name, Imf::DeepSlice(stored, reinterpret_cast<char*>(pointers[name].data()), sizeof(char*),
                                          sizeof(char*) * std::size_t(raw.width),
                                          stored == Imf::HALF ? sizeof(half) : sizeof(float)));
    }
    if (raw.tile) {
        Imf::DeepTiledOutputFile file(path.c_str(), header);
        file.setFrameBuffer(frame);
        file.writeTiles(0, file.numXTiles() - 1, 0, file.numYTiles() - 1);
    } else {
        Imf::DeepScanLineOutputFile file(path.c_str(), header);
        file.setFrameBuffer(frame);
        file.writePixels(raw.height);
    }
}

}  // namespace penumbra::testing
