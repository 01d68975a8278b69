// Host operations ambient_irradiance() and ambient_volume_factor()
// (penumbra/ambient.h): check the receivers, fill AmbientParams, run the
// lookup-shaped entries ambient_sh and ambient_volumes (kernels/ambient_sh.h,
// ambient_volumes.h) with the volume records as their source, and name the
// first bad pixel when a kernel flagged a row.
#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "ambient_weights.h"
#include "host/backend/backend.h"
#include "penumbra/ambient.h"
#include "penumbra/error.h"

namespace penumbra {
namespace {

const std::string kAmbientOp = "ambient";

int terms_of(int order) { return (order + 1) * (order + 1); }

// The records as a one-row float image (a buffer of at least one element, so
// that OpenCL gets a non-empty one with no volumes).
Image records_image(const AmbientVolumes& volumes)
{
    const std::vector<float>& r = volumes.records();
    Image image(std::max<int>(int(r.size()), 1), 1, 1);
    std::copy(r.begin(), r.end(), image.plane(0));
    return image;
}

AmbientParams params_for(const AmbientLighting& l, const Image& receivers, const Image& out)
{
    AmbientParams p{};
    p.receivers = detail::dims_of(receivers);
    p.out = detail::dims_of(out);
    p.light_terms = terms_of(l.light.order);
    detail::polynomial_weights(l.light, p.light);
    if (!l.dark) return p;
    p.blend = l.volumes.count() > 0 ? PN_AMBIENT_BLEND_VOLUMES : PN_AMBIENT_BLEND_PLANE;
    p.dark_terms = l.cheap_dark ? 4 : terms_of(l.dark->order);
    detail::polynomial_weights(*l.dark, p.dark);
    p.factor_plane = 3;
    p.position_plane = 3;
    p.volume_count = l.volumes.count();
    return p;
}

Error bad_pixel(int c, int x, int y, float v, const std::string& what)
{
    return Error(ErrorCategory::InvalidData, kAmbientOp, "receivers",
                 "pixel (" + std::to_string(x) + ", " + std::to_string(y) + ") of the receivers: " + what,
                 BadPixel{c, x, y, v});
}

// The first value the kernel could not take, in the flagged rows.
void report(const std::vector<int>& bad_rows, const Image& rx, const AmbientParams& p, ZeroNormals zero)
{
    for (int y = 0; y < rx.height(); ++y) {
        if (!bad_rows[std::size_t(y)]) continue;
        for (int x = 0; x < rx.width(); ++x) {
            for (int c = 0; c < rx.channels(); ++c)
                if (!std::isfinite(rx.at(c, x, y)))
                    throw bad_pixel(c, x, y, rx.at(c, x, y), "channel " + std::to_string(c) + " is not finite");
            const bool zero_normal = rx.at(0, x, y) == 0.0f && rx.at(1, x, y) == 0.0f && rx.at(2, x, y) == 0.0f;
            if (zero_normal && zero == ZeroNormals::Error)
                throw bad_pixel(0, x, y, 0.0f,
                                "the normal is zero; give every pixel a normal of non-zero length, or leave pixels "
                                "that see no surface black (zero_normals = Black)");
            const float f = p.blend == PN_AMBIENT_BLEND_PLANE ? rx.at(p.factor_plane, x, y) : 0.0f;
            if (f < 0.0f || f > 1.0f)
                throw bad_pixel(p.factor_plane, x, y, f, "the blend factor " + std::to_string(f) + " is outside [0, 1]");
        }
    }
}

template <detail::KernelId K>
std::vector<int> run(Context& context, const Image& records, const Image& rx, const AmbientParams& p, Image& out)
{
    std::vector<int> bad_rows(std::size_t(rx.height()), 0);
    detail::receiver_lookup<K>(context.impl(), records, rx, p, out, bad_rows.data());
    return bad_rows;
}

void check_size(const Image& rx, const Image& out, int channels, const std::string& what)
{
    require(out.width() == rx.width() && out.height() == rx.height() && out.channels() == channels, kAmbientOp, "out",
            "the output must have " + std::to_string(channels) + " channel(s) (" + what + ") and the receivers' size (" +
                std::to_string(rx.width()) + "x" + std::to_string(rx.height()) + ")");
}

}  // namespace

int ambient_receiver_channels(const AmbientLighting& lighting)
{
    if (!lighting.dark) return 3;
    return lighting.volumes.count() > 0 ? 6 : 4;
}

void ambient_irradiance(Context& context, const Image& receivers, const AmbientLighting& lighting, Image& out)
{
    require(lighting.light.order == 1 || lighting.light.order == 2, kAmbientOp, "light", "the light rig's order must be 1 or 2");
    require(!lighting.dark || lighting.dark->order == 1 || lighting.dark->order == 2, kAmbientOp, "dark",
            "the dark rig's order must be 1 or 2");
    require(!receivers.empty(), kAmbientOp, "receivers", "the receivers image is empty (0 pixels)");
    const int channels = ambient_receiver_channels(lighting);
    require(receivers.channels() == channels, kAmbientOp, "receivers",
            "the receivers must have " + std::to_string(channels) +
                " channels (normal x, y, z; then the blend factor with a dark rig and no volumes, or the world "
                "position with volumes), got " + std::to_string(receivers.channels()));
    check_size(receivers, out, 3, "R, G, B");
    const AmbientParams p = params_for(lighting, receivers, out);
    const std::vector<int> bad_rows = run<detail::KernelId::ambient_sh>(context, records_image(lighting.volumes),
                                                                       receivers, p, out);
    report(bad_rows, receivers, p, lighting.zero_normals);
}

Image ambient_irradiance(Context& context, const Image& receivers, const AmbientLighting& lighting)
{
    Image out(receivers.width(), receivers.height(), 3);
    ambient_irradiance(context, receivers, lighting, out);
    return out;
}

Image ambient_volume_factor(Context& context, const Image& positions, const AmbientVolumes& volumes)
{
    require(!positions.empty() && positions.channels() == 3, kAmbientOp, "positions",
            "the positions must have 3 channels (world x, y, z) and at least one pixel");
    Image out(positions.width(), positions.height(), 1);
    AmbientParams p{};
    p.receivers = detail::dims_of(positions);
    p.out = detail::dims_of(out);
    p.volume_count = volumes.count();
    const std::vector<int> bad_rows = run<detail::KernelId::ambient_volumes>(context, records_image(volumes),
                                                                            positions, p, out);
    if (std::find(bad_rows.begin(), bad_rows.end(), 1) != bad_rows.end())
        require_finite(positions, kAmbientOp, "the positions", "positions");
    return out;
}

}  // namespace penumbra
