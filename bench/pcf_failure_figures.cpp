// The failure-mode figures of docs/pcf.md, "Failure modes": a measurement,
// not a check (it prints tables and asserts nothing), on the built-in scenes
// against the ray-traced ground truth (reference::ground_truth, 8 x 8 strata),
// every valid receiver counted (the receivers' mask).
//   1. acne on the `grazing` scene per bias mode: pcf r = 2, over-darkening;
//   2. peter-panning on `contact` as the constant bias grows: pcf r = 1, leak
//      over every receiver and in the band of 5 map texels around the
//      contacts, where a bias that lifts the shadow off its occluder shows first;
//   3. banding of the disc without rotation: pcf-disc N = 8, rotation none vs
//      tile, alone and after penumbra blur's cross-bilateral.
// usage: pcf_failure_figures [map size, default 512] [receivers width, default 320 (x 3/4)]
#include <cstdio>
#include <cstdlib>
#include <string>

#include "penumbra/bilateral.h"
#include "penumbra/pcf.h"
#include "penumbra/reference.h"
#include "contact_band.h"

using namespace penumbra;

namespace {

struct Frame {
    reference::Scene scene;
    Image map;
    reference::Receivers rx;
    Image truth;
};

Frame frame(const char* name, int map_size, int width)
{
    Frame f{reference::builtin_scene(name), {}, {}, {}};
    f.map = reference::render_shadow_map(f.scene, map_size, map_size);
    f.rx = reference::render_receivers(f.scene, width, width * 3 / 4);
    f.truth = reference::ground_truth(f.scene, f.rx, reference::GroundTruthOptions{8});
    return f;
}

void print_row(const std::string& label, const Image& estimate, const Frame& f)
{
    const Image* mask = &f.rx.mask;
    std::printf("%-34s %8.4f %8.4f %8.4f %8.4f\n", label.c_str(), reference::rmse(estimate, f.truth, mask),
                reference::p99_abs_error(estimate, f.truth, mask), reference::light_leaking(estimate, f.truth, mask),
                reference::over_darkening(estimate, f.truth, mask));
}

// Peter-panning's own measure: the light beyond the truth's in the contact band.
void print_band_row(const std::string& label, const Image& estimate, const Frame& f, const Image& band)
{
    std::printf("%-34s %8.4f %8.4f %8.4f %8.4f\n", label.c_str(), reference::light_leaking(estimate, f.truth, &f.rx.mask),
                reference::rmse(estimate, f.truth, &f.rx.mask), reference::light_leaking(estimate, f.truth, &band),
                reference::rmse(estimate, f.truth, &band));
}

void header(const char* title)
{
    std::printf("\n%s\n%-34s %8s %8s %8s %8s\n", title, "setting", "RMSE", "p99", "leak", "overdark");
}

}  // namespace

int main(int argc, char** argv)
{
    const int map_size = argc > 1 ? std::atoi(argv[1]) : 512, width = argc > 2 ? std::atoi(argv[2]) : 320;
    if (argc > 3 || map_size < 16 || width < 16) {
        std::fprintf(stderr, "usage: pcf_failure_figures [map size >= 16] [receivers width >= 16]\n");
        return 2;
    }
    Context ctx(ContextOptions{Backend::Auto, {}});

    const Frame grazing = frame("grazing", map_size, width);
    header("1. acne on `grazing`: pcf r=2 per bias mode");
    struct Mode {
        const char* label;
        DepthBias bias;
    };
    for (const Mode& m : {Mode{"constant 0", {BiasMode::Constant, 0.0f}},
                          Mode{"constant 1e-3", {BiasMode::Constant, 1e-3f}},
                          Mode{"constant 1e-2", {BiasMode::Constant, 1e-2f}},
                          Mode{"slope (1e-4 + 1 x step)", {BiasMode::Slope, 1e-4f, 1.0f, 0.0f, 0.02f}},
                          Mode{"receiver-plane (1e-4, [0, 0.02])", {BiasMode::ReceiverPlane, 1e-4f, 1.0f, 0.0f, 0.02f}}})
        print_row(m.label, pcf(ctx, grazing.map, grazing.rx.light_uvz, PcfOptions{2, m.bias}), grazing);

    const Frame contact = frame("contact", map_size, width);
    const Image band = bench::contact_band(contact.scene, contact.rx, map_size, 5.0);
    int in_band = 0;
    for (int y = 0; y < band.height(); ++y)
        for (int x = 0; x < band.width(); ++x) in_band += band.at(0, x, y) > 0.5f;
    std::printf("\n2. peter-panning on `contact`: pcf r=1, constant bias; 5tx: the %d receivers within 5 map "
                "texels of a contact\n%-34s %8s %8s %8s %8s\n", in_band, "setting",
                "leak", "RMSE", "leak 5tx", "RMSE 5tx");
    for (float b : {0.0f, 1e-3f, 3e-3f, 1e-2f, 3e-2f, 1e-1f})
        print_band_row("depth-bias " + std::to_string(b),
                       pcf(ctx, contact.map, contact.rx.light_uvz, PcfOptions{1, DepthBias{BiasMode::Constant, b}}),
                       contact, band);

    header("3. banding on `contact`: pcf-disc N=8, radius 3 texels, receiver-plane bias");
    BilateralOptions blur;
    blur.relative = true;
    blur.depth_sigma = 0.02f;
    blur.separable = true;
    for (const bool rotate : {false, true}) {
        const DepthBias bias{BiasMode::ReceiverPlane};
        const Image disc = pcf_disc(ctx, contact.map, contact.rx.light_uvz, PcfDiscOptions{8, 3.0f, rotate, bias});
        const std::string label = rotate ? "rotation tile" : "rotation none";
        print_row(label, disc, contact);
        print_row(label + " +blur", cross_bilateral(ctx, disc, contact.rx.view_depth, blur), contact);
    }
    return 0;
}
