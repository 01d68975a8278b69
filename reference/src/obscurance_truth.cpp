// Ambient-occlusion and volumetric-obscurance ground truth
// (obscurance_truth.h): one stratified estimate per receiver, rows in parallel.
#include <cmath>
#include <numbers>
#include <string>
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include "disk_mapping.h"
#include "penumbra/error.h"
#include "penumbra/reference/ground_truth.h"
#include "penumbra/reference/obscurance_truth.h"
#include "penumbra/reference/tracer.h"
#include "splitmix64.h"

namespace penumbra::reference {
namespace {

Vec3 load3(const Image& image, int x, int y) { return {image.at(0, x, y), image.at(1, x, y), image.at(2, x, y)}; }

// A frame whose n is the normal (any up that is not parallel to it).
Basis normal_frame(Vec3 n)
{
    return basis_looking_along(n, std::fabs(n.y) < 0.9 ? Vec3{0, 1, 0} : Vec3{1, 0, 0});
}

// The unoccluded fraction of n^2 cosine-weighted rays of length R.
double occlusion_at(const PreparedScene& scene, Vec3 p, Vec3 n, const ObscuranceTruthOptions& o, SplitMix64& rng)
{
    const Basis frame = normal_frame(n);
    const Vec3 origin = p + n * (kNormalOffset * (1 + std::max({std::fabs(p.x), std::fabs(p.y), std::fabs(p.z)})));
    int open = 0;
    for (int j = 0; j < o.strata; ++j)
        for (int i = 0; i < o.strata; ++i) {
            const Vec3 d = concentric_disk((i + rng.uniform()) / o.strata, (j + rng.uniform()) / o.strata);
            const double lift = std::sqrt(std::max(0.0, 1 - d.x * d.x - d.y * d.y));
            const Vec3 direction = frame.s * d.x + frame.t * d.y + frame.n * lift;
            open += !scene.occluded({origin, direction}, 0, o.radius);
        }
    return double(open) / (double(o.strata) * o.strata);
}

// The fraction of n^3 equal-volume points of the ball that lie inside a solid.
double obscurance_at(const PreparedScene& scene, Vec3 p, const ObscuranceTruthOptions& o, SplitMix64& rng)
{
    const int n = o.strata;
    long inside = 0;
    for (int k = 0; k < n; ++k)
        for (int j = 0; j < n; ++j)
            for (int i = 0; i < n; ++i) {
                const double r = o.radius * std::cbrt((k + rng.uniform()) / n);
                const double cos_theta = 1 - 2 * (j + rng.uniform()) / n;
                const double phi = 2 * std::numbers::pi * (i + rng.uniform()) / n;
                const double sin_theta = std::sqrt(std::max(0.0, 1 - cos_theta * cos_theta));
                const Vec3 q = p + Vec3{sin_theta * std::cos(phi), sin_theta * std::sin(phi), cos_theta} * r;
                inside += scene.signed_distance(q) < 0;
            }
    return double(inside) / (double(n) * n * n);
}

void check(const Receivers& rx, const ObscuranceTruthOptions& o, int max_strata, const std::string& op)
{
    require(o.radius > 0 && std::isfinite(o.radius), op, "radius",
            "radius must be > 0 and finite (got " + std::to_string(o.radius) + ")");
    require(o.strata >= 1 && o.strata <= max_strata, op, "strata",
            "strata must be in [1, " + std::to_string(max_strata) + "] (got " + std::to_string(o.strata) + ")");
    require(rx.width() > 0 && rx.world_position.width() == rx.width() && rx.normal.width() == rx.width() &&
                rx.hit.height() == rx.height(),
            op, "receivers", "the receivers must hold world_position, normal and hit images of one size");
}

// value(p, n, stream) at every hit pixel, `open` elsewhere.
template <class Value>
Image per_receiver(const Receivers& rx, std::uint64_t seed, float open, Value&& value)
{
    Image out(rx.width(), rx.height(), 1);
    tbb::parallel_for(tbb::blocked_range<int>(0, rx.height()), [&](const tbb::blocked_range<int>& rows) {
        for (int y = rows.begin(); y != rows.end(); ++y)
            for (int x = 0; x < rx.width(); ++x) {
                if (rx.hit.at(0, x, y) == 0) {
                    out.at(0, x, y) = open;
                    continue;
                }
                const std::uint64_t index = std::uint64_t(y) * std::uint64_t(rx.width()) + std::uint64_t(x);
                SplitMix64 rng(seed ^ (index * 0x9e3779b97f4a7c15ull));
                out.at(0, x, y) = float(value(load3(rx.world_position, x, y), load3(rx.normal, x, y), rng));
            }
    });
    return out;
}

}  // namespace

Image ambient_occlusion_truth(const Scene& scene, const Receivers& receivers, const ObscuranceTruthOptions& options)
{
    check(receivers, options, 1024, "ambient_occlusion_truth");
    validate_scene(scene, "ambient_occlusion_truth");
    const PreparedScene prepared(scene);
    return per_receiver(receivers, options.seed, 1.0f, [&](Vec3 p, Vec3 n, SplitMix64& rng) {
        return occlusion_at(prepared, p, n, options, rng);
    });
}

Image volumetric_obscurance_truth(const Scene& scene, const Receivers& receivers,
                                  const ObscuranceTruthOptions& options)
{
    check(receivers, options, 128, "volumetric_obscurance_truth");
    validate_scene(scene, "volumetric_obscurance_truth");
    const PreparedScene prepared(scene);
    return per_receiver(receivers, options.seed, 0.0f, [&](Vec3 p, Vec3, SplitMix64& rng) {
        return obscurance_at(prepared, p, options, rng);
    });
}

}  // namespace penumbra::reference
