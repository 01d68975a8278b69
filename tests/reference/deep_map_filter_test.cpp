// combine_functions (reference/src/deep_map_filter.cpp), the sweep that sums
// weighted sample functions, against brute force: every random sample
// function evaluated by a linear scan in long double, on both sides of every
// vertex depth and densely between.
#include <gtest/gtest.h>

#include <cmath>

#include "reference/src/deep_map_parts.h"
#include "support/deep_functions.h"

namespace penumbra::reference {
namespace {

using testing::brute_visibility;
using testing::Function;

TEST(DeepMapFilter, WeightedSumOfSampleFunctionsMatchesBruteForce)
{
    for (std::uint32_t seed = 1; seed <= 200; ++seed) {
        const int count = 1 + int(seed % 13);
        SampleSet set;
        std::vector<Function> functions;
        std::vector<WeightedSample> weights;
        double total = 0;
        for (int k = 0; k < count; ++k) {
            // Some samples see nothing (no vertices); the rest share a depth range.
            Function f = (seed + k) % 5 == 0 ? Function{} : testing::random_function(seed * 31 + k, 1 + k % 7, 1, 4);
            set.add(0, 0, RayFunction{f.z, std::vector<double>(f.t.begin(), f.t.end())});
            functions.push_back(f);
            const double w = 0.1 + (seed * 7 + k * 3) % 10;
            weights.push_back({std::uint32_t(k), w});
            total += w;
        }
        for (WeightedSample& w : weights) w.weight /= total;
        CombineScratch scratch;
        Function out;
        combine_functions(set, weights, scratch, out.z, out.t);
        ASSERT_NE(out.z.size(), 1u);
        auto brute = [&](double d, int side) {
            long double v = 0;
            for (std::size_t k = 0; k < functions.size(); ++k) v += weights[k].weight * brute_visibility(functions[k], d, side);
            return double(v);
        };
        std::vector<double> depths;
        for (const Function& f : functions) depths.insert(depths.end(), f.z.begin(), f.z.end());
        for (int i = 0; i <= 500; ++i) depths.push_back(0.5 + 5.0 * i / 500);
        for (double d : depths)
            for (int side : {-1, 1})
                ASSERT_NEAR(double(brute_visibility(out, d, side)), brute(d, side), 1e-6)
                    << "seed " << seed << " depth " << d << " side " << side;
    }
}

}  // namespace
}  // namespace penumbra::reference
