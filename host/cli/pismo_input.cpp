// Pismo's maps for the tool (pismo_input.h).
#include "pismo_input.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <sstream>

#include "input_limits.h"
#include "penumbra/error.h"
#include "penumbra/exr_io.h"
#include "penumbra/pismo.h"

namespace penumbra::cli {

std::string pismo_map_options_help()
{
    return "  --light-level L   the light mesh's subdivision level in [0, " + std::to_string(reference::kMaxLightLevel) +
           "] (default " + std::to_string(kDefaultPismoLevel) +
           "): a rectangle has (2^L + 1)^2 maps (4, 9, 25, 81, 289, 1089)\n"
           "  --map-size N      each map is N x N pixels, N in [1, 8192] (default 512)\n"
           "  --layers K        at most K depths per pixel, in [1, 64] (default 8)\n";
}

PismoBuild pismo_build_from(const Args& args)
{
    PismoBuild b;
    b.level = args.integer("--light-level", b.level);
    b.maps.size = args.integer("--map-size", b.maps.size);
    b.maps.max_layers = args.integer("--layers", b.maps.max_layers);
    return b;
}

PismoMapSet render_pismo_set(const reference::Scene& scene, const PismoBuild& build,
                             std::span<const reference::Vec3> region)
{
    try {
        // The maps' pixels are bounded as a reader bounds them (read_pismo_maps
        // under --max-pixels): a set the tool writes, it reads back.
        const std::uint64_t maps = reference::light_mesh(scene.light, build.level).vertices.size();
        const std::uint64_t pixels = maps * std::uint64_t(build.maps.size) * std::uint64_t(build.maps.size);
        if (build.maps.size >= 1 && pixels > exr_limits().max_pixels)
            throw UsageError{"option --map-size: " + std::to_string(maps) + " maps of " +
                             std::to_string(build.maps.size) + "^2 are " + std::to_string(pixels) +
                             " pixels, over the limit of " + std::to_string(exr_limits().max_pixels) +
                             "; give a smaller --map-size or --light-level, or raise --max-pixels"};
        return reference::render_pismo_map_set(scene, build.level, build.maps, region);
    } catch (const Error& e) {
        // The library names its parameter; the tool names its flag or the scene.
        if (e.parameter() == "light") throw UsageError{"scene '" + scene.name + "': " + e.message()};
        for (const char* name : {"light-level", "map-size", "layers"})
            if (e.parameter() == name) throw UsageError{"option --" + std::string(name) + ": " + e.message()};
        throw;
    }
}

std::vector<reference::Vec3> receiver_region_from(const std::string& path, const std::string& command)
{
    try {
        const std::vector<std::string> names = exr_channel_names(path, exr_limits());
        std::vector<std::string> channels = kWorldPositionChannels;
        const bool masked = std::find(names.begin(), names.end(), "mask") != names.end();
        if (masked) channels.push_back("mask");
        const Image rx = read_exr(path, channels, exr_limits());
        std::vector<reference::Vec3> region;
        for (int y = 0; y < rx.height(); ++y)
            for (int x = 0; x < rx.width(); ++x)
                if (!masked || rx.at(3, x, y) > 0.5f) {
                    const reference::Vec3 p{rx.at(0, x, y), rx.at(1, x, y), rx.at(2, x, y)};
                    if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z))
                        throw Error(ErrorCategory::InvalidData, command,
                                    path + ": P at pixel (" + std::to_string(x) + ", " + std::to_string(y) +
                                        ") is not finite");
                    region.push_back(p);
                }
        if (region.empty()) throw Error(ErrorCategory::InvalidData, command, path + ": no receiver is valid (mask)");
        return region;
    } catch (const Error& e) {
        if (e.operation() == command) throw;
        throw Error(e.category(), command, e.message());
    }
}

std::vector<std::string> pismo_receiver_channels(const std::string& path, const std::string& command)
{
    const std::vector<std::string> present = exr_channel_names(path, exr_limits());
    const auto has = [&](const char* name) { return std::find(present.begin(), present.end(), name) != present.end(); };
    std::vector<std::string> channels = kWorldPositionChannels;
    const bool normals = has("N.x") && has("N.y") && has("N.z");
    if (normals) channels.insert(channels.end(), {"N.x", "N.y", "N.z"});
    if (has(kSurfaceChannel)) {
        if (!normals)
            throw Error(ErrorCategory::InvalidData, command,
                        path + ": has channel surface but not the normals N.x, N.y, N.z, which Pismo reads with "
                               "the surface ids; add them (render-scene writes both) or drop channel surface");
        channels.push_back(kSurfaceChannel);
    }
    return channels;
}

void check_receiver_surfaces(const Image& receivers, const PismoMapSet& set, const std::string& path,
                             const std::string& command)
{
    if (receivers.channels() != 7) return;
    const bool maps_know = !set.surface_ids.empty();
    const double limit = maps_know ? double(set.surface_count) : double(kPismoMaxSurfaceId) + 1;
    for (int y = 0; y < receivers.height(); ++y)
        for (int x = 0; x < receivers.width(); ++x) {
            const float id = receivers.at(6, x, y);
            if (id == -1.0f || (id >= 0.0f && double(id) < limit && id == std::floor(id))) continue;
            const std::string range = maps_know ? "the maps' scene has " + std::to_string(set.surface_count) +
                                                      " surfaces (ids 0 to " + std::to_string(set.surface_count - 1) +
                                                      "): render the receivers from the maps' scene"
                                                : "ids are integers in [0, " + std::to_string(kPismoMaxSurfaceId) + "]";
            std::ostringstream value;
            value << id;
            throw Error(ErrorCategory::InvalidData, command,
                        path + ": channel surface at pixel (" + std::to_string(x) + ", " + std::to_string(y) + ") is " +
                            value.str() + "; a surface id is -1 (unknown) or " + range);
        }
}

}  // namespace penumbra::cli
