// The pixel filter of a deep shadow map (Lokovic and Veach 2000, "The
// Visibility Function"): V(z) = sum_k w_k T_k(z) over the samples within the
// filter's radius, w_k the normalised filter weights. A weighted sum of
// piecewise-linear functions is piecewise linear with vertices at the union of
// theirs, so evaluating every T_k at that union (on both sides of a depth where
// any of them steps) gives V exactly; the paper notes V has about K times as
// many vertices as one T_k, which compression then removes.
#include <algorithm>
#include <cmath>

#include "deep_map_parts.h"
#include "penumbra/error.h"

namespace penumbra::reference {

DeepMapFilter deep_map_filter_from_name(const std::string& name, const std::string& parameter)
{
    if (name == "box") return DeepMapFilter::Box;
    if (name == "gaussian") return DeepMapFilter::Gaussian;
    throw Error(ErrorCategory::InvalidArgument, "render_deep_shadow_map", parameter,
                "'" + name + "' is not a deep-map filter (box or gaussian)");
}

const char* deep_map_filter_name(DeepMapFilter filter) { return filter == DeepMapFilter::Box ? "box" : "gaussian"; }

void SampleSet::add(double sx, double sy, const RayFunction& f)
{
    z.insert(z.end(), f.z.begin(), f.z.end());
    t.insert(t.end(), f.t.begin(), f.t.end());
    first.push_back(std::uint32_t(z.size()));
    x.push_back(sx);
    y.push_back(sy);
}

void SampleSet::clear()
{
    z.clear();
    t.clear();
    first.assign(1, 0);
    x.clear();
    y.clear();
}

double gaussian_weight(double dx, double dy)
{
    // pbrt's truncated Gaussian: subtracting its value at the radius makes it
    // reach 0 there instead of jumping.
    auto g = [](double d) {
        constexpr double two_s2 = 2 * kDeepGaussianSigma * kDeepGaussianSigma;
        const double edge = std::exp(-kDeepGaussianRadius * kDeepGaussianRadius / two_s2);
        return std::max(0.0, std::exp(-d * d / two_s2) - edge);
    };
    return g(dx) * g(dy);
}

namespace {

// A cursor through one sample's vertices [begin, end) that evaluates its
// function at increasing depths, from either side of a step.
struct Cursor {
    const SampleSet& set;
    std::uint32_t begin, end;
    std::uint32_t below, upto;  // first vertex with z >= d, first with z > d

    // The value through the segment ending at vertex c (1 before the first
    // vertex, the last t after the last).
    double at(std::uint32_t c, double d) const
    {
        if (c == begin) return 1;
        if (c == end) return set.t[end - 1];
        const double z0 = set.z[c - 1], z1 = set.z[c];
        return set.t[c - 1] + (set.t[c] - set.t[c - 1]) * (d - z0) / (z1 - z0);
    }
    // The value just before depth d (a step's own depth takes the value
    // before it, as deep_visibility) and just after it.
    void advance(float d)
    {
        while (below < end && set.z[below] < d) ++below;
        upto = std::max(upto, below);
        while (upto < end && set.z[upto] <= d) ++upto;
    }
};

}  // namespace

void combine_functions(const SampleSet& set, std::span<const WeightedSample> samples, std::vector<float>& out_z,
                       std::vector<float>& out_t)
{
    out_z.clear();
    out_t.clear();
    std::vector<float> depths;
    std::vector<Cursor> cursors;
    for (const WeightedSample& s : samples) {
        const std::uint32_t b = set.first[s.index], e = set.first[s.index + 1];
        depths.insert(depths.end(), set.z.begin() + b, set.z.begin() + e);
        cursors.push_back({set, b, e, b, b});
    }
    std::sort(depths.begin(), depths.end());
    depths.erase(std::unique(depths.begin(), depths.end()), depths.end());
    // Summing the occlusion 1 - T keeps V exactly 1 where every sample is 1.
    float previous = 1;
    for (float d : depths) {
        double before = 0, after = 0;
        for (std::size_t k = 0; k < cursors.size(); ++k) {
            cursors[k].advance(d);
            before += samples[k].weight * (1 - cursors[k].at(cursors[k].below, d));
            after += samples[k].weight * (1 - cursors[k].at(cursors[k].upto, d));
        }
        // Rounding must not make V rise or leave [0, 1].
        const float v0 = std::min(previous, float(std::clamp(1 - before, 0.0, 1.0)));
        const float v1 = std::min(v0, float(std::clamp(1 - after, 0.0, 1.0)));
        out_z.push_back(d);
        out_t.push_back(v0);
        if (v1 < v0) {
            out_z.push_back(d);
            out_t.push_back(v1);
        }
        previous = v1;
    }
    if (out_z.size() == 1) {  // one vertex at V = 1: nothing absorbs
        out_z.clear();
        out_t.clear();
    }
}

}  // namespace penumbra::reference
