// Screen-space ambient obscurance: volumetric obscurance with line integrals
// and paired samples (Loos & Sloan 2010, as the Toy Story 3 notes use it:
// Hall, Siggraph 2010 course; kernels/ssao_vo.h has the formulas,
// docs/ssao.md the measured accuracy and speed), followed, for the pipeline's
// output, by the cross-bilateral blur of penumbra/bilateral.h.
//
// Input: one channel of view depth (the distance along the view axis, world
// units, > 0 where a surface is seen, 0 where none is), and the camera's
// vertical field of view; the pixels are square. Output: one channel, the
// obscurance o in [0, 1] (1/2 on a flat surface, the method's "open") or the
// ambient-occlusion term 1 - saturate(2 o - 1) (1 open, 0 fully occluded).
// Bad input throws penumbra::Error naming the parameter.
#pragma once

#include <vector>

#include "penumbra/bilateral.h"
#include "penumbra/context.h"
#include "penumbra/image.h"
#include "penumbra/parameter_range.h"

namespace penumbra {

// What an unusable sample (off screen, or an occluder beyond the falloff)
// contributes. Paired is the notes' shader; the others are the alternatives
// it was chosen over (docs/ssao.md shows the halo each one leaves).
enum class SsaoUnusable {
    Paired,       // its partner's inverse 1 - f (a flat surface's), else 1/2
    Zero,         // 0: a halo of missing occlusion around silhouettes
    Half,         // 1/2: right on planes facing the camera only
    Renormalise,  // dropped, the usable samples' weights renormalised
};

enum class SsaoOutput {
    Accessibility,  // 1 - saturate(2 o - 1): the notes' remap, as an AO term
    Obscurance,     // o itself
};

// The pattern's largest size: 16 pairs (33 lines with the centre's), already
// five times the notes' 3 pairs; the kernel's cost grows linearly with it.
inline constexpr int kSsaoMaxPairs = 16;

inline constexpr ParameterRange kSsaoRadiusRange{"radius", "radius", 0, kNoUpperBound, true, true};
inline constexpr ParameterRange kSsaoPairsRange{
    "pairs", "pairs", 1, kSsaoMaxPairs, false, false,
    ", the stated limit of the pattern (33 lines a pixel); the 4x4 rotations already give 16 times as many"};
inline constexpr ParameterRange kSsaoMaxScreenRadiusRange{"max-screen-radius", "max-screen-radius", 0, 1, true,
                                                          false};
inline constexpr ParameterRange kSsaoFalloffRange{"falloff", "falloff", 1, 1000, true, false};
inline constexpr ParameterRange kSsaoFovRange{"fov", "field of view (degrees)", 0, 180, true, true};

struct SsaoOptions {
    double radius = 0.5;              // R, the sphere's radius in world units, > 0
    int pairs = 3;                    // sample pairs, in [1, 16]; the notes use 3 (6 samples)
    double max_screen_radius = 0.07;  // the cap of the screen radius, a fraction of the height (the notes' 0.07)
    double falloff = 2.0;             // occluders nearer than the centre by falloff R or more are unusable; > 1
    SsaoUnusable unusable = SsaoUnusable::Paired;
    bool rotate = true;               // the 4x4 tile of rotations; false: one pattern for every pixel
    SsaoOutput output = SsaoOutput::Accessibility;
};

// The sample pattern: `pairs` points of the unit disc and their mirrors, and
// the share of the unit sphere's volume each one's line stands for.
struct SsaoSample {
    double x = 0, y = 0;  // in the unit disc; its pair is (-x, -y)
    double weight = 0;    // the volume share of this point (its mirror has the same)
};
struct SsaoPattern {
    std::vector<SsaoSample> pairs;
    double centre_weight = 0;  // the centre line's share; centre + 2 sum(pairs) = 1
};

// Radii of equal volume rings, angles by the golden angle, and the volumes
// of the Voronoi cells of the 2 pairs + 1 points measured by the notes' brute
// force (a raster of the disc, each pixel adding its line's length to its
// nearest point); docs/ssao.md states how equal they come out.
SsaoPattern ssao_pattern(int pairs);

// The 4x4 rotation tile's angle at (x mod 4, y mod 4), radians: sequential
// angles k pi / 16 (a half turn maps the paired pattern onto itself) placed
// by the notes' 4x4 table of offsets.
double ssao_tile_angle(int x, int y);

// o (or the AO term) per pixel; view_depth: 1 channel, finite, >= 0
// (Error(InvalidData, "ssao", "view_depth") names the first bad pixel).
Image ssao_obscurance(Context& context, const Image& view_depth, double fov_degrees, const SsaoOptions& options = {});
void ssao_obscurance(Context& context, const Image& view_depth, double fov_degrees, const SsaoOptions& options,
                     Image& out);

// The blur of the notes' mask (5x5, threshold on the relative depth
// difference): the pipeline's default second step.
BilateralOptions ssao_blur_options();

// The pipeline: ssao_obscurance, then cross_bilateral guided by view_depth.
Image ssao_blurred(Context& context, const Image& view_depth, double fov_degrees, const SsaoOptions& options = {},
                   const BilateralOptions& blur = ssao_blur_options());

}  // namespace penumbra
