// Traces the ground truth of a built-in scene through the installed
// penumbra::reference, shades the same receivers with VSM through
// penumbra::penumbra, and checks the answers against each other.
#include <penumbra/chebyshev.h>
#include <penumbra/reference.h>

#include <cstdio>

int main()
{
    namespace ref = penumbra::reference;
    const ref::Scene scene = ref::builtin_scene("contact");
    const ref::Receivers rx = ref::render_receivers(scene, 40, 30);
    const penumbra::Image truth = ref::ground_truth(scene, rx, {4});
    // The contact scene's receivers see both lit ground and a shadow.
    int lit = 0, dark = 0;
    for (int y = 0; y < rx.height(); ++y)
        for (int x = 0; x < rx.width(); ++x) {
            if (rx.mask.at(0, x, y) < 0.5f) continue;
            const float v = truth.at(0, x, y);
            if (!(v >= 0.0f && v <= 1.0f)) return 1;
            lit += v == 1.0f;
            dark += v < 0.5f;
        }
    penumbra::Context ctx(penumbra::ContextOptions{penumbra::Backend::Scalar, {}});
    const penumbra::Image map = ref::render_shadow_map(scene, 128, 128);
    const auto table = penumbra::build_moment_table(ctx, map);
    const penumbra::Image vsm = penumbra::vsm(ctx, table, rx.light_uvz, {2});
    const double rmse = ref::rmse(vsm, truth, &rx.mask);
    std::printf("lit %d, in shadow %d, VSM rmse %g\n", lit, dark, rmse);
    return lit > 0 && dark > 0 && rmse < 0.3 ? 0 : 1;
}
