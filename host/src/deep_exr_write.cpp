// Deep shadow maps as OpenEXR deep images (penumbra/deep_exr.h: the mapping
// of a function's segments to samples, and why penumbra.T exists).
#include "penumbra/deep_exr.h"

#include <OpenEXR/ImfChannelList.h>
#include <OpenEXR/ImfDeepFrameBuffer.h>
#include <OpenEXR/ImfDeepImageStateAttribute.h>
#include <OpenEXR/ImfDeepScanLineOutputFile.h>
#include <OpenEXR/ImfDeepTiledOutputFile.h>
#include <OpenEXR/ImfHeader.h>
#include <OpenEXR/ImfPartType.h>
#include <OpenEXR/ImfStandardAttributes.h>
#include <OpenEXR/ImfTileDescription.h>

#include <algorithm>
#include <cstdint>
#include <vector>

#include "exr_streams.h"
#include "penumbra/error.h"

namespace penumbra {
namespace {

constexpr std::string_view kWriteDeepOp = "write_deep_exr";
using detail::kScanlineBand;

// Per-sample opacity A_k = 1 - t_{k+1}/t_k, at the index of the sample's first
// vertex (so one array serves every pixel with the offsets of the map).
std::vector<float> sample_opacities(const DeepShadowMap& map)
{
    const std::vector<float>& t = map.transmittances();
    std::vector<float> alpha(t.size(), 0.0f);
    for (std::size_t i = 0; i + 1 < t.size(); ++i)
        if (t[i] > 0.0f) alpha[i] = float(std::clamp(1.0 - double(t[i + 1]) / double(t[i]), 0.0, 1.0));
    return alpha;  // entries at a pixel's last vertex are never read
}

// Tidy (OpenEXR's DeepImageState) unless some pixel has two point samples at
// one depth, i.e. three vertices at one depth.
bool is_tidy(const DeepShadowMap& map)
{
    const std::vector<float>& z = map.depths();
    const std::vector<std::uint32_t>& offsets = map.offsets();
    for (std::size_t p = 0; p + 1 < offsets.size(); ++p)
        for (std::uint32_t i = offsets[p]; i + 2 < offsets[p + 1]; ++i)
            if (z[i] == z[i + 2]) return false;
    return true;
}

Imf::Header deep_header(const DeepShadowMap& map, const DeepExrWriteOptions& options)
{
    const Imath::Box2i window({0, 0}, {map.width() - 1, map.height() - 1});
    Imf::Header header(window, window, 1.0f, Imath::V2f(0, 0), 1.0f, Imf::INCREASING_Y, Imf::ZIPS_COMPRESSION);
    for (const char* name : {"A", "Z", "ZBack", kDeepTransmittanceChannel})
        header.channels().insert(name, Imf::Channel(Imf::FLOAT));
    const bool tiled = options.layout == DeepExrLayout::Tiled;
    header.setType(tiled ? Imf::DEEPTILE : Imf::DEEPSCANLINE);
    if (tiled) header.setTileDescription(Imf::TileDescription(options.tile_size, options.tile_size, Imf::ONE_LEVEL));
    // Absent means "messy": claim tidy only when it is true.
    if (is_tidy(map)) Imf::addDeepImageState(header, Imf::DIS_TIDY);
    return header;
}

// The frame buffer for rows [y0, y1): per pixel a sample count and, per
// channel, a pointer to its first sample. The samples point straight into the
// map's arrays: sample k of a pixel at vertex offset o has Z = depths[o+k],
// ZBack = depths[o+k+1], T = transmittances[o+k+1], A = alpha[o+k].
class Band {
public:
    Band(const DeepShadowMap& map, const std::vector<float>& alpha) : map_(map), alpha_(alpha) {}

    const Imf::DeepFrameBuffer& rows(int y0, int y1)
    {
        const int width = map_.width();
        const std::size_t pixels = std::size_t(y1 - y0) * std::size_t(width);
        counts_.assign(pixels, 0);
        for (auto& column : pointers_) column.assign(pixels, nullptr);
        const std::uint32_t* offsets = map_.offsets().data() + std::size_t(y0) * std::size_t(width);
        // OpenEXR only reads through these pointers when writing.
        float* z = const_cast<float*>(map_.depths().data());
        float* t = const_cast<float*>(map_.transmittances().data());
        float* a = const_cast<float*>(alpha_.data());
        for (std::size_t p = 0; p < pixels; ++p) {
            const std::uint32_t begin = offsets[p], end = offsets[p + 1];
            if (end == begin) continue;  // an empty pixel: no samples
            counts_[p] = end - begin - 1;
            pointers_[0][p] = a + begin;
            pointers_[1][p] = z + begin;
            pointers_[2][p] = z + begin + 1;
            pointers_[3][p] = t + begin + 1;
        }
        frame_ = Imf::DeepFrameBuffer();
        // OpenEXR addresses pixels by absolute coordinates: shift the bases so
        // that row y0 lands at element 0.
        const std::ptrdiff_t shift = std::ptrdiff_t(y0) * width;
        frame_.insertSampleCountSlice(Imf::Slice(Imf::UINT, reinterpret_cast<char*>(counts_.data() - shift),
                                                 sizeof(unsigned), sizeof(unsigned) * std::size_t(width)));
        const char* names[] = {"A", "Z", "ZBack", kDeepTransmittanceChannel};
        for (int c = 0; c < 4; ++c)
            frame_.insert(names[c], Imf::DeepSlice(Imf::FLOAT, reinterpret_cast<char*>(pointers_[c].data() - shift),
                                                   sizeof(float*), sizeof(float*) * std::size_t(width),
                                                   sizeof(float)));
        return frame_;
    }

private:
    const DeepShadowMap& map_;
    const std::vector<float>& alpha_;
    std::vector<unsigned> counts_;
    std::vector<float*> pointers_[4];
    Imf::DeepFrameBuffer frame_;
};

void write_scanlines(detail::CheckedOutputStream& stream, const Imf::Header& header, Band& band, int height)
{
    Imf::DeepScanLineOutputFile file(stream, header);
    for (int y0 = 0; y0 < height; y0 += kScanlineBand) {
        const int y1 = std::min(height, y0 + kScanlineBand);
        file.setFrameBuffer(band.rows(y0, y1));
        file.writePixels(y1 - y0);
    }
}

void write_tiles(detail::CheckedOutputStream& stream, const Imf::Header& header, Band& band, int height)
{
    Imf::DeepTiledOutputFile file(stream, header);
    const int tile = file.tileYSize();
    for (int ty = 0; ty < file.numYTiles(); ++ty) {
        file.setFrameBuffer(band.rows(ty * tile, std::min(height, (ty + 1) * tile)));
        file.writeTiles(0, file.numXTiles() - 1, ty, ty);
    }
}

void write_deep_pixels(const std::string& temporary, const DeepShadowMap& map, const DeepExrWriteOptions& options)
{
    detail::use_hardware_threads_for_exr();
    const Imf::Header header = deep_header(map, options);
    const std::vector<float> alpha = sample_opacities(map);
    Band band(map, alpha);
    detail::CheckedOutputStream stream(temporary);
    if (options.layout == DeepExrLayout::Tiled)
        write_tiles(stream, header, band, map.height());
    else
        write_scanlines(stream, header, band, map.height());
    stream.close();  // after the file's destructor wrote the offset table
}

}  // namespace

void write_deep_exr(const std::string& path, const DeepShadowMap& map, const DeepExrWriteOptions& options)
{
    OutputFiles output{std::string(kWriteDeepOp)};
    stage_deep_exr(output, path, map, options);
    output.publish();
}

void stage_deep_exr(OutputFiles& output, const std::string& path, const DeepShadowMap& map,
                    const DeepExrWriteOptions& options)
{
    require(map.width() >= 1 && map.height() >= 1, kWriteDeepOp, "map",
            "the map for '" + path + "' is empty; a deep EXR file needs at least one pixel");
    // 2048^2 = 2^22 pixels: the largest tile the reader takes for any image
    // (check_declared_sizes allows the image's pixels plus 2^22).
    require(options.tile_size >= 1 && options.tile_size <= 2048, kWriteDeepOp, "tile_size",
            "must be in [1, 2048], not " + std::to_string(options.tile_size));
    require_safe_outputs({path}, {}, kWriteDeepOp);
    output.stage(path, [&](const std::string& temporary) {
        detail::translating_exr_exceptions(kWriteDeepOp, path, "; check free disk space and write permission",
                                           [&] { write_deep_pixels(temporary, map, options); });
    });
}

}  // namespace penumbra
