// Deep samples to vertices (deep_exr_samples.h), the inverse of the mapping
// that deep_exr_write.cpp writes (penumbra/deep_exr.h).
#include "deep_exr_samples.h"

#include <cmath>
#include <cstdio>
#include <string>

#include "penumbra/error.h"

namespace penumbra::detail {
namespace {

// penumbra.T and the running product of (1 - A) may differ by the rounding of
// a float A (2^-25 relative) and no more; a larger gap means the channels were
// edited apart.
constexpr double kTransmittanceAgreement = 1e-5;

enum Channel { kZ = 0, kZBack = 1, kA = 2, kT = 3 };

// One pixel's samples, checked and turned into vertices.
class PixelReader {
public:
    PixelReader(const DeepSamples& s, const std::string& path) : s_(s), path_(path) {}

    // Fills z/t with the vertices of pixel (x, y) of the data window.
    void read(int x, int y, std::size_t pixel, std::vector<float>& z, std::vector<float>& t)
    {
        x_ = x, y_ = y;
        z.clear(), t.clear();
        const std::uint64_t first = s_.first[pixel];
        double transmittance = 1.0;
        float back_before = 0.0f;
        for (unsigned k = 0; k < s_.counts[pixel]; ++k) {
            sample_ = k;
            const std::uint64_t i = first + k;
            const float front = s_.z[i], back = s_.zback.empty() ? front : s_.zback[i], alpha = s_.a[i];
            check_depths(front, back, k == 0 ? front : back_before);
            if (!(alpha >= 0.0f && alpha <= 1.0f))
                bad(kA, alpha, "A is " + text(alpha) + ", outside [0, 1]; A is the opacity of the sample");
            if (k == 0) z.push_back(front), t.push_back(1.0f);
            if (front > back_before && k > 0) z.push_back(front), t.push_back(t.back());  // a gap: flat
            transmittance = next_transmittance(transmittance, alpha, i);
            z.push_back(back), t.push_back(float(transmittance));
            back_before = back;
        }
    }

private:
    void check_depths(float front, float back, float back_before) const
    {
        if (!std::isfinite(front)) bad(kZ, front, "Z is " + text(front) + "; depths must be finite");
        if (!std::isfinite(back)) bad(kZBack, back, "ZBack is " + text(back) + "; depths must be finite");
        if (back < front) bad(kZBack, back, "ZBack " + text(back) + " lies before Z " + text(front));
        if (front < back_before)
            bad(kZ, front, "Z " + text(front) + " lies before the previous sample's back " + text(back_before) +
                               ": samples are out of depth order or overlap; sort and tidy them "
                               "(OpenEXR's \"Interpreting Deep Pixels\", tidying)");
    }

    // The transmittance behind sample i: penumbra.T where the file has it (checked
    // against A), otherwise compositing's running product of (1 - A).
    double next_transmittance(double before, float alpha, std::uint64_t i) const
    {
        const double composited = before * (1.0 - double(alpha));
        if (s_.t.empty()) return composited;
        const float exact = s_.t[i];
        if (!(exact >= 0.0f && exact <= 1.0f))
            bad(kT, exact, std::string(kDeepTransmittanceChannel) + " is " + text(exact) + ", outside [0, 1]");
        if (double(exact) > before)
            bad(kT, exact, std::string(kDeepTransmittanceChannel) + " rises to " + text(exact) + " from " +
                               text(float(before)) + "; light is only ever absorbed along a beam");
        if (std::abs(double(exact) - composited) > kTransmittanceAgreement)
            bad(kT, exact, std::string(kDeepTransmittanceChannel) + " is " + text(exact) + " but A gives " +
                               text(float(composited)) + "; the channels disagree, re-create the file");
        return exact;
    }

    [[noreturn]] void bad(Channel channel, float value, const std::string& what) const
    {
        const int fx = s_.origin_x + x_, fy = s_.origin_y + y_;
        throw Error(ErrorCategory::InvalidData, "read_deep_exr", "path",
                    "'" + path_ + "', pixel (" + std::to_string(fx) + ", " + std::to_string(fy) + "), sample " +
                        std::to_string(sample_) + ": " + what,
                    BadPixel{int(channel), fx, fy, value});
    }

    static std::string text(float value)
    {
        if (std::isnan(value)) return "NaN";
        if (std::isinf(value)) return value > 0 ? "+inf" : "-inf";
        char buffer[32];
        std::snprintf(buffer, sizeof buffer, "%.9g", double(value));
        return buffer;
    }

    const DeepSamples& s_;
    const std::string& path_;
    int x_ = 0, y_ = 0;
    unsigned sample_ = 0;
};

}  // namespace

void DeepSamples::allocate(std::uint64_t total, bool has_zback, bool has_a, bool has_t)
{
    first.resize(counts.size());
    std::uint64_t at = 0;
    for (std::size_t p = 0; p < counts.size(); ++p) first[p] = at, at += counts[p];
    has[kZ] = true, has[kZBack] = has_zback, has[kA] = has_a, has[kT] = has_t;
    z.assign(total, 0.0f);
    if (has_a) a.assign(total, 0.0f);
    if (has_zback) zback.assign(total, 0.0f);
    if (has_t) t.assign(total, 0.0f);
}

std::vector<float>& DeepSamples::channel(int c)
{
    return const_cast<std::vector<float>&>(static_cast<const DeepSamples&>(*this).channel(c));
}

const std::vector<float>& DeepSamples::channel(int c) const
{
    switch (c) {
    case kZ: return z;
    case kZBack: return zback;
    case kA: return a;
    default: return t;
    }
}

DeepShadowMap deep_map_from_samples(const DeepSamples& samples, int width, int height, const std::string& path)
{
    DeepShadowMapBuilder builder(width, height);
    PixelReader reader(samples, path);
    std::vector<float> z, t;
    for (int y = 0; y < height; ++y)
        for (int x = 0; x < width; ++x) {
            reader.read(x, y, std::size_t(y) * std::size_t(width) + std::size_t(x), z, t);
            try {
                builder.add_pixel(z, t);  // refuses only more than 2^32 - 1 vertices
            } catch (const Error& e) {
                throw Error(ErrorCategory::Io, "read_deep_exr", "'" + path + "' " + e.message());
            }
        }
    return builder.build();  // the checks above cover every invariant it checks again
}

}  // namespace penumbra::detail
