// Writes the EXR seed corpus for exr_reader_fuzz (run by make_corpus.sh): small
// valid files in every compression OpenEXR 3.1 writes (NONE .. DWAB), as
// scanline and as tiled files, with FLOAT, HALF and UINT channels and a data
// window away from the origin -- the layouts whose decoders and bounds the
// reader must survive when a mutation breaks them. Seeds stay a few KB so that
// libFuzzer's mutations, not the copying of large inputs, take the time.
//
//   exr_seeds OUT_DIR
#include <cstdio>
#include <iterator>
#include <string>
#include <vector>

#include <Imath/half.h>
#include <OpenEXR/ImfChannelList.h>
#include <OpenEXR/ImfCompression.h>
#include <OpenEXR/ImfFrameBuffer.h>
#include <OpenEXR/ImfHeader.h>
#include <OpenEXR/ImfOutputFile.h>
#include <OpenEXR/ImfTiledOutputFile.h>

namespace {

// File names, in the order of Imf::Compression (ImfCompression.h); OpenEXR 3.1
// has no id-to-name function.
constexpr const char* kCompressionNames[] = {"none", "rle",  "zips", "zip",  "piz",
                                             "pxr24", "b44", "b44a", "dwaa", "dwab"};
static_assert(std::size(kCompressionNames) == Imf::NUM_COMPRESSION_METHODS);

// One plane per pixel type; values are a depth ramp with a step, so that the
// predictors and Huffman tables of the lossy and lossless codecs are non-trivial.
struct Planes {
    std::vector<float> f;
    std::vector<half> h;
    std::vector<unsigned> u;
};

Planes make_planes(int w, int h)
{
    Planes p;
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            float depth = 0.1f + 0.8f * float(x) / float(w) + (y >= h / 2 ? 0.05f : 0.0f);
            p.f.push_back(depth);
            p.h.push_back(half(depth));
            p.u.push_back(unsigned(x * 7 + y * 131));
        }
    return p;
}

// The three channels the reader converts (FLOAT as is, HALF and UINT to float),
// bound to `planes` for a data window whose corner is (x0, y0).
Imf::FrameBuffer frame_buffer(Planes& planes, const Imath::Box2i& window)
{
    Imf::FrameBuffer fb;
    fb.insert("Z", Imf::Slice::Make(Imf::FLOAT, planes.f.data(), window));
    fb.insert("u", Imf::Slice::Make(Imf::HALF, planes.h.data(), window));
    fb.insert("v", Imf::Slice::Make(Imf::UINT, planes.u.data(), window));
    return fb;
}

void write_one(const std::string& path, Imf::Compression compression, bool tiled, const Imath::Box2i& window)
{
    int w = window.max.x - window.min.x + 1, h = window.max.y - window.min.y + 1;
    Planes planes = make_planes(w, h);
    Imf::Header header(window, window);
    header.compression() = compression;
    header.channels().insert("Z", Imf::Channel(Imf::FLOAT));
    header.channels().insert("u", Imf::Channel(Imf::HALF));
    header.channels().insert("v", Imf::Channel(Imf::UINT));
    if (tiled) {
        header.setTileDescription(Imf::TileDescription(8, 4, Imf::ONE_LEVEL));
        Imf::TiledOutputFile file(path.c_str(), header);
        file.setFrameBuffer(frame_buffer(planes, window));
        file.writeTiles(0, file.numXTiles() - 1, 0, file.numYTiles() - 1);
    } else {
        Imf::OutputFile file(path.c_str(), header);
        file.setFrameBuffer(frame_buffer(planes, window));
        file.writePixels(h);
    }
}

}  // namespace

int main(int argc, char** argv)
{
    if (argc != 2) {
        std::fprintf(stderr, "usage: exr_seeds OUT_DIR\n");
        return 2;
    }
    const std::string dir = argv[1];
    const Imath::Box2i at_origin({0, 0}, {15, 11});  // 16x12
    const Imath::Box2i shifted({3, -2}, {9, 0});      // 7x3, corner off the origin
    int written = 0;
    for (int c = 0; c < Imf::NUM_COMPRESSION_METHODS; ++c) {
        auto compression = Imf::Compression(c);
        std::string name = kCompressionNames[c];
        for (bool tiled : {false, true}) {
            const Imath::Box2i& window = (c % 2 == 0) == tiled ? at_origin : shifted;
            write_one(dir + "/" + name + (tiled ? "-tiled" : "-scanline") + ".exr", compression, tiled, window);
            ++written;
        }
    }
    std::printf("%d EXR seeds in %s\n", written, dir.c_str());
    return 0;
}
