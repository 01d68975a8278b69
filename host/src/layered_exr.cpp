// Layered depth maps as OpenEXR deep images (penumbra/layered_exr.h). The
// reading and its checks are deep_exr_read.cpp's (read_deep_samples); this
// file maps layers to point samples and the camera to header attributes.
#include "penumbra/layered_exr.h"

#include <OpenEXR/ImfChannelList.h>
#include <OpenEXR/ImfDeepFrameBuffer.h>
#include <OpenEXR/ImfDeepImageStateAttribute.h>
#include <OpenEXR/ImfDeepScanLineOutputFile.h>
#include <OpenEXR/ImfDoubleAttribute.h>
#include <OpenEXR/ImfHeader.h>
#include <OpenEXR/ImfPartType.h>
#include <OpenEXR/ImfStandardAttributes.h>
#include <OpenEXR/ImfVecAttribute.h>

#include <algorithm>
#include <array>
#include <cstdint>
#include <limits>
#include <vector>

#include "deep_exr_samples.h"
#include "exr_streams.h"
#include "penumbra/error.h"

namespace penumbra {
namespace {

constexpr std::string_view kWrite = "write_layered_exr";
constexpr detail::DeepFileKind kLayeredFile{"read_layered_exr", "a layered depth map", "penumbra pismo-build", false};
constexpr detail::DeepFileKind kLayeredFileWithIds{"read_layered_exr", "a layered depth map", "penumbra pismo-build",
                                                   false, kLayeredSurfaceChannel};
using detail::kScanlineBand;

// The camera's attributes, in MapCamera's order.
constexpr const char* kAxes[4] = {"penumbra.cameraPosition", "penumbra.cameraRight", "penumbra.cameraDown",
                                  "penumbra.cameraForward"};
constexpr const char* kTanHalfFov = "penumbra.tanHalfFov";

std::array<std::array<double, 3>*, 4> axes(MapCamera& c) { return {&c.position, &c.right, &c.down, &c.forward}; }

Imf::Header layered_header(const LayeredDepthMap& map, bool ids)
{
    const Imath::Box2i window({0, 0}, {map.width() - 1, map.height() - 1});
    Imf::Header header(window, window, 1.0f, Imath::V2f(0, 0), 1.0f, Imf::INCREASING_Y, Imf::ZIPS_COMPRESSION);
    header.channels().insert("Z", Imf::Channel(Imf::FLOAT));
    if (ids) header.channels().insert(kLayeredSurfaceChannel, Imf::Channel(Imf::UINT));
    header.setType(Imf::DEEPSCANLINE);
    Imf::addDeepImageState(header, Imf::DIS_TIDY);  // point samples at increasing depths
    MapCamera camera = map.camera();
    const auto a = axes(camera);
    for (int k = 0; k < 4; ++k)
        header.insert(kAxes[k], Imf::V3dAttribute(Imath::V3d((*a[k])[0], (*a[k])[1], (*a[k])[2])));
    header.insert(kTanHalfFov, Imf::DoubleAttribute(camera.tan_half_fov));
    return header;
}

// A deep slice of one sample array: pixel p's samples start at base + offsets[p].
template <class T>
Imf::DeepSlice layer_slice(Imf::PixelType type, std::vector<T*>& pointers, T* base, const std::uint32_t* offsets,
                           std::size_t pixels, std::ptrdiff_t shift, int width)
{
    pointers.assign(pixels, nullptr);
    for (std::size_t p = 0; p < pixels; ++p) pointers[p] = base + offsets[p];
    return Imf::DeepSlice(type, reinterpret_cast<char*>(pointers.data() - shift), sizeof(T*),
                          sizeof(T*) * std::size_t(width), sizeof(T));
}

void write_layered_pixels(const std::string& temporary, const LayeredDepthMap& map,
                          std::span<const std::int32_t> surface_ids)
{
    detail::use_hardware_threads_for_exr();
    const Imf::Header header = layered_header(map, !surface_ids.empty());
    detail::CheckedOutputStream stream(temporary);
    {
        Imf::DeepScanLineOutputFile file(stream, header);
        const int width = map.width();
        std::vector<unsigned> counts;
        std::vector<float*> pointers;
        std::vector<std::uint32_t*> id_pointers;
        // OpenEXR only reads through these pointers when writing. Ids are >= 0: as UINT, the same values.
        float* depths = const_cast<float*>(map.depths().data());
        auto* ids = reinterpret_cast<std::uint32_t*>(const_cast<std::int32_t*>(surface_ids.data()));
        for (int y0 = 0; y0 < map.height(); y0 += kScanlineBand) {
            const int y1 = std::min(map.height(), y0 + kScanlineBand);
            const std::size_t pixels = std::size_t(y1 - y0) * std::size_t(width);
            const std::uint32_t* offsets = map.offsets().data() + std::size_t(y0) * std::size_t(width);
            counts.assign(pixels, 0);
            for (std::size_t p = 0; p < pixels; ++p) counts[p] = offsets[p + 1] - offsets[p];
            // Absolute pixel addressing: shift the bases so that row y0 lands at element 0.
            const std::ptrdiff_t shift = std::ptrdiff_t(y0) * width;
            Imf::DeepFrameBuffer frame;
            frame.insertSampleCountSlice(Imf::Slice(Imf::UINT, reinterpret_cast<char*>(counts.data() - shift),
                                                    sizeof(unsigned), sizeof(unsigned) * std::size_t(width)));
            frame.insert("Z", layer_slice(Imf::FLOAT, pointers, depths, offsets, pixels, shift, width));
            if (ids)
                frame.insert(kLayeredSurfaceChannel,
                             layer_slice(Imf::UINT, id_pointers, ids, offsets, pixels, shift, width));
            file.setFrameBuffer(frame);
            file.writePixels(y1 - y0);
        }
    }
    stream.close();  // after the file's destructor wrote the offset table
}

[[noreturn]] void refuse(const std::string& path, const std::string& what)
{
    throw Error(ErrorCategory::Io, kLayeredFile.operation, "'" + path + "' " + what);
}

MapCamera camera_from(const Imf::Header& header, const std::string& path)
{
    MapCamera camera;
    const auto a = axes(camera);
    for (int k = 0; k < 4; ++k) {
        const auto* v = header.findTypedAttribute<Imf::V3dAttribute>(kAxes[k]);
        if (!v) refuse(path, std::string("has no v3d attribute ") + kAxes[k] + "; penumbra pismo-build writes the "
                                 "map's camera into the header");
        *a[k] = {v->value().x, v->value().y, v->value().z};
    }
    const auto* fov = header.findTypedAttribute<Imf::DoubleAttribute>(kTanHalfFov);
    if (!fov) refuse(path, std::string("has no double attribute ") + kTanHalfFov + "; penumbra pismo-build writes "
                               "the map's camera into the header");
    camera.tan_half_fov = fov->value();
    return camera;
}

}  // namespace

void write_layered_exr(const std::string& path, const LayeredDepthMap& map, std::span<const std::int32_t> surface_ids)
{
    OutputFiles output{std::string(kWrite)};
    stage_layered_exr(output, path, map, surface_ids);
    output.publish();
}

void stage_layered_exr(OutputFiles& output, const std::string& path, const LayeredDepthMap& map,
                       std::span<const std::int32_t> surface_ids)
{
    require(map.width() >= 1 && map.height() >= 1, kWrite, "map",
            "the map for '" + path + "' is empty; a deep EXR file needs at least one pixel");
    require(surface_ids.empty() || surface_ids.size() == map.depths().size(), kWrite, "surface-ids",
            "the map for '" + path + "' has " + std::to_string(map.depths().size()) + " layers but " +
                std::to_string(surface_ids.size()) + " surface ids; give one id a layer, or none");
    require(std::all_of(surface_ids.begin(), surface_ids.end(), [](std::int32_t id) { return id >= 0; }), kWrite,
            "surface-ids", "the map for '" + path + "' has a negative surface id; ids are >= 0");
    require_safe_outputs({path}, {}, kWrite);
    output.stage(path, [&](const std::string& temporary) {
        detail::translating_exr_exceptions(kWrite, path, "; check free disk space and write permission",
                                           [&] { write_layered_pixels(temporary, map, surface_ids); });
    });
}

namespace {

// The ids as read, one a layer; above 2^31 - 1 is no id of a surface.
std::vector<std::int32_t> ids_from(const detail::DeepSamples& s, const std::vector<std::uint32_t>& offsets,
                                   const std::string& path)
{
    std::vector<std::int32_t> ids(s.ids.size());
    for (std::size_t l = 0; l < s.ids.size(); ++l) {
        if (s.ids[l] > std::uint32_t(std::numeric_limits<std::int32_t>::max())) {
            const std::size_t p = std::size_t(std::upper_bound(offsets.begin(), offsets.end(), std::uint32_t(l)) -
                                              offsets.begin()) - 1;
            throw Error(ErrorCategory::InvalidData, kLayeredFile.operation,
                        "'" + path + "' at pixel (" + std::to_string(p % std::size_t(s.width) + std::size_t(s.origin_x)) +
                            ", " + std::to_string(p / std::size_t(s.width) + std::size_t(s.origin_y)) + "), layer " +
                            std::to_string(l - offsets[p]) + ": surface id " + std::to_string(s.ids[l]) +
                            " is above 2^31 - 1; re-create the map with penumbra pismo-build");
        }
        ids[l] = std::int32_t(s.ids[l]);
    }
    return ids;
}

}  // namespace

LayeredDepthMap read_layered_exr(const std::string& path, const ExrReadLimits& limits,
                                 std::vector<std::int32_t>* surface_ids)
{
    MapCamera camera;
    const detail::DeepSamples s =
        detail::read_deep_samples(path, limits, surface_ids ? kLayeredFileWithIds : kLayeredFile,
                                  [&](const Imf::Header& header) { camera = camera_from(header, path); });
    if (s.z.size() > std::numeric_limits<std::uint32_t>::max())
        refuse(path, "holds more than 2^32 - 1 layers; a layered map's offsets are 32-bit");
    std::vector<std::uint32_t> offsets(s.counts.size() + 1, 0);
    for (std::size_t p = 0; p < s.counts.size(); ++p) offsets[p + 1] = offsets[p] + s.counts[p];
    if (surface_ids) *surface_ids = ids_from(s, offsets, path);
    try {
        return LayeredDepthMap(s.width, s.height, camera, std::move(offsets), s.z);
    } catch (const Error& e) {
        // Only the file's values can be wrong here: its sizes came from the file's own counts.
        std::string where = "'" + path + "' ";
        if (e.pixel())  // file coordinates, as the deep reader names them
            where += "at pixel (" + std::to_string(e.pixel()->x + s.origin_x) + ", " +
                     std::to_string(e.pixel()->y + s.origin_y) + "): ";
        throw Error(ErrorCategory::InvalidData, kLayeredFile.operation, where + e.message());
    }
}

}  // namespace penumbra
