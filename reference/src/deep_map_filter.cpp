// The pixel filter of a deep shadow map (Lokovic and Veach 2000, "The
// Visibility Function"): V(z) = sum_k w_k T_k(z) over the samples within the
// filter's radius, w_k the normalised filter weights. A weighted sum of
// piecewise-linear functions is piecewise linear with vertices at the union of
// theirs, so V at that union (on both sides of a depth where any of them
// steps) is V exactly; the paper notes V has about K times as many vertices as
// one T_k, which compression then removes.
#include <algorithm>
#include <cmath>
#include <limits>

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
    // 32-bit vertex indices: reached only by a single band row of ~16k pixels
    // with thousands of samples through dense fog.
    require(z.size() + f.z.size() <= std::numeric_limits<std::uint32_t>::max(), "render_deep_shadow_map", "samples",
            "one band of rows holds more than 2^32 - 1 sample vertices; use fewer samples or a smaller map");
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

// The value a sample reaches after its vertices at one depth, and the slope
// (of T, per unit z) it leaves with.
struct Leaving {
    double t, slope;
};
Leaving leave(const SampleSet& set, std::uint32_t last, std::uint32_t end)
{
    if (last + 1 == end) return {set.t[last], 0};
    const double dz = double(set.z[last + 1]) - double(set.z[last]);  // > 0: `last` is the last at its depth
    return {set.t[last], (set.t[last + 1] - set.t[last]) / dz};
}

}  // namespace

// A sweep over the samples' vertices in depth order, carrying the occlusion
// O = sum_k w_k (1 - T_k) and its slope: between two depths of the union O is
// linear (every T_k is), so O(d-) = O(previous d+) + slope * (d - previous);
// at d each sample with vertices there adds w (t_first - t_last), its own
// step (t_first is its value arriving, the functions being continuous between
// vertices), and swaps its slope for the next segment's. O(V log V) for V
// vertices, where evaluating every sample at every depth was O(V K).
void combine_functions(const SampleSet& set, std::span<const WeightedSample> samples, CombineScratch& scratch,
                       std::vector<float>& out_z, std::vector<float>& out_t)
{
    out_z.clear();
    out_t.clear();
    auto& entries = scratch.entries;
    entries.clear();
    for (std::uint32_t k = 0; k < samples.size(); ++k)
        for (std::uint32_t i = set.first[samples[k].index]; i < set.first[samples[k].index + 1]; ++i)
            entries.push_back({set.z[i], k, i});
    // By depth, then sample, then vertex: a sample's vertices at one depth are adjacent and in order.
    std::sort(entries.begin(), entries.end(), [](const CombineScratch::Entry& a, const CombineScratch::Entry& b) {
        return a.z != b.z ? a.z < b.z : a.sample != b.sample ? a.sample < b.sample : a.vertex < b.vertex;
    });
    scratch.slopes.assign(samples.size(), 0.0);
    double occlusion = 0, slope = 0;  // O just after the previous depth, and dO/dz beyond it
    float previous_z = entries.empty() ? 0 : entries.front().z, previous_v = 1;
    for (std::size_t e = 0; e < entries.size();) {
        const float d = entries[e].z;
        const double before = occlusion + slope * (double(d) - double(previous_z));
        double after = before;
        for (; e < entries.size() && entries[e].z == d;) {
            const std::uint32_t k = entries[e].sample, first = entries[e].vertex;
            while (e + 1 < entries.size() && entries[e + 1].z == d && entries[e + 1].sample == k) ++e;
            const double w = samples[k].weight;
            const Leaving next = leave(set, entries[e].vertex, set.first[samples[k].index + 1]);
            after += w * (set.t[first] - next.t);
            slope += -w * next.slope - scratch.slopes[k];
            scratch.slopes[k] = -w * next.slope;
            ++e;
        }
        // Rounding must not make V rise or leave [0, 1].
        const float v0 = std::min(previous_v, float(std::clamp(1 - before, 0.0, 1.0)));
        const float v1 = std::min(v0, float(std::clamp(1 - after, 0.0, 1.0)));
        out_z.push_back(d);
        out_t.push_back(v0);
        if (v1 < v0) {
            out_z.push_back(d);
            out_t.push_back(v1);
        }
        occlusion = after;
        previous_z = d;
        previous_v = v1;
    }
    if (out_z.size() == 1) {  // one vertex at V = 1: nothing absorbs
        out_z.clear();
        out_t.clear();
    }
}

}  // namespace penumbra::reference
