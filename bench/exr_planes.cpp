#include "exr_planes.h"

#include <OpenEXR/ImfChannelList.h>
#include <OpenEXR/ImfFrameBuffer.h>
#include <OpenEXR/ImfHeader.h>
#include <OpenEXR/ImfInputFile.h>
#include <OpenEXR/ImfOutputFile.h>

#include <cstddef>

namespace penumbra::bench {

FloatPlanes read_exr_planes(const std::string& path, const std::vector<std::string>& channels)
{
    Imf::InputFile file(path.c_str());
    const Imath::Box2i window = file.header().dataWindow();
    FloatPlanes image{window.max.x - window.min.x + 1, window.max.y - window.min.y + 1, {}};
    const std::size_t plane = std::size_t(image.width) * std::size_t(image.height);
    image.pixels.resize(plane * channels.size());
    Imf::FrameBuffer frame;
    for (std::size_t c = 0; c < channels.size(); ++c)
        frame.insert(channels[c], Imf::Slice::Make(Imf::FLOAT, image.pixels.data() + c * plane, window, sizeof(float),
                                                   std::size_t(image.width) * sizeof(float)));
    file.setFrameBuffer(frame);
    file.readPixels(window.min.y, window.max.y);
    return image;
}

void write_exr_plane(const std::string& path, const FloatPlanes& image, const std::string& channel)
{
    const Imath::Box2i window({0, 0}, {image.width - 1, image.height - 1});
    Imf::Header header(window, window, 1.0f, Imath::V2f(0, 0), 1.0f, Imf::INCREASING_Y, Imf::ZIP_COMPRESSION);
    header.channels().insert(channel, Imf::Channel(Imf::FLOAT));
    Imf::OutputFile file(path.c_str(), header);
    Imf::FrameBuffer frame;
    frame.insert(channel, Imf::Slice(Imf::FLOAT, reinterpret_cast<char*>(const_cast<float*>(image.pixels.data())),
                                     sizeof(float), std::size_t(image.width) * sizeof(float)));
    file.setFrameBuffer(frame);
    file.writePixels(image.height);
}

}  // namespace penumbra::bench
