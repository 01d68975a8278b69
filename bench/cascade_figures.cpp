// docs/cascades.md, "The kernel": how the bias clamp shapes the cascaded
// mask. For each scene and setting, over the pixels a cascade holds at
// 321 x 181 (the tests' inputs, tests/support/cascade_cases.h): pixels partly
// shadowed (visibility in (0.05, 0.95): acne on lit ground, elsewhere the
// PCF's own edge), over-darkened (below 0.5 where the truth is lit) and
// leaking (above 0.5 where it is in shadow), and the RMSE. Prints a table,
// asserts nothing.
//   cascade_figures [bias_min static_bias bias_max]...   (texels; default: the defaults)
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

#include "penumbra/cascades.h"
#include "penumbra/reference/metrics.h"
#include "support/cascade_cases.h"

using namespace penumbra;

int main(int argc, char** argv)
{
    std::vector<CascadeOptions> settings;
    for (int i = 1; i + 2 < argc; i += 3) {
        CascadeOptions o;
        o.bias_min = std::strtof(argv[i], nullptr);
        o.static_bias = std::strtof(argv[i + 1], nullptr);
        o.bias_max = std::strtof(argv[i + 2], nullptr);
        settings.push_back(o);
    }
    if (settings.empty()) settings.push_back({});
    Context context;
    std::printf("scene,light,bias_min,static_bias,bias_max,held,partial,overdark,leak,rmse\n");
    for (const auto& [scene, light] : {std::pair{"contact", 0}, {"contact", 1}, {"large", 0}, {"courtyard", 0}})
        for (const CascadeOptions& o : settings) {
            const auto& c = testing::cascade_case(scene, light, 321, 181);
            const Image out = cascade_mask(context, c.shadows, c.rx, o);
            Image visibility(out.width(), out.height(), 1), held(out.width(), out.height(), 1);
            int n = 0, partial = 0, overdark = 0, leak = 0;
            for (int y = 0; y < out.height(); ++y)
                for (int x = 0; x < out.width(); ++x) {
                    const float v = out.at(0, x, y), t = c.truth.at(0, x, y);
                    visibility.at(0, x, y) = v;
                    held.at(0, x, y) = out.at(1, x, y) >= 0 ? 1.0f : 0.0f;
                    if (out.at(1, x, y) < 0) continue;
                    ++n;
                    partial += v > 0.05f && v < 0.95f;
                    overdark += t > 0.5f && v < 0.5f;
                    leak += t < 0.5f && v > 0.5f;
                }
            std::printf("%s,%d,%g,%g,%g,%d,%d,%d,%d,%.4f\n", scene, light, o.bias_min, o.static_bias, o.bias_max, n,
                        partial, overdark, leak, reference::rmse(visibility, c.truth, &held));
        }
}
