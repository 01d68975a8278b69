// The pieces of render_deep_shadow_map (deep_map.h) that have a file of their
// own: the sample functions of a band of rows, the pixel filter's weights and
// the weighted combination of functions. Private to reference/src.
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include "penumbra/reference/deep_map.h"

namespace penumbra::reference {

// The sample functions of a band of pixels, flat: sample s owns vertices
// [first[s], first[s+1]) and lies at (x[s], y[s]) in pixel units of the map
// (pixel (i, j) covers [i, i+1) x [j, j+1)).
struct SampleSet {
    std::vector<float> z;
    std::vector<double> t;
    std::vector<std::uint32_t> first{0};
    std::vector<double> x, y;

    void add(double sx, double sy, const RayFunction& f);
    void clear();
};

// One sample's share of a pixel's function; the weights of a pixel sum to 1.
struct WeightedSample {
    std::uint32_t index;
    double weight;
};

// The Gaussian's weight of a sample at offset (dx, dy) from a pixel's centre,
// in pixel units (deep_map.h: truncated at kDeepGaussianRadius, separable).
double gaussian_weight(double dx, double dy);

// What combine_functions reuses from one pixel to the next.
struct CombineScratch {
    struct Entry {
        float z;
        std::uint32_t sample, vertex;  // into the span of samples; into the set's vertices
    };
    std::vector<Entry> entries;
    std::vector<double> slopes;
};

// Sum_k w_k f_k(z), the paper's filtered visibility, at the union of the
// samples' vertex depths (both sides of each depth where one steps), written
// as a function (deep_shadow_map.h) to out_z, out_t (replacing their contents).
void combine_functions(const SampleSet& set, std::span<const WeightedSample> samples, CombineScratch& scratch,
                       std::vector<float>& out_z, std::vector<float>& out_t);

}  // namespace penumbra::reference
