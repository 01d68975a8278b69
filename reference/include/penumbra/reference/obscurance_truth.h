// The two ground truths of screen-space ambient obscurance (issue 16), on the
// receivers' grid (render.h), by stratified sampling against the analytic
// scene:
//  - ambient occlusion: the unoccluded fraction of cosine-weighted rays from
//    P over the hemisphere of N, up to the distance R (the quantity an AO
//    term approximates; 1 = open);
//  - volumetric obscurance (Loos & Sloan 2010): the fraction of the ball of
//    radius R around P that lies inside solid geometry (the scene's
//    primitives are solids: PreparedScene::signed_distance < 0), 1/2 on a
//    plane, the quantity ssao-vo estimates before its remap.
// Samples: n x n strata of the unit square (AO: mapped to the disk by
// Shirley and Chiu's concentric map, lifted to the hemisphere, Malley's
// method), or n x n x n strata of the unit cube (VO: radius R u^(1/3),
// direction from (v, w) uniform on the sphere, so equal strata are equal
// volumes), one jittered sample in each, from a SplitMix64 stream seeded by
// (seed, pixel): a pixel's value depends on nothing else. Pixels that see no
// surface get 1 (AO) and 0 (VO). docs/ssao.md has the convergence figures.
#pragma once

#include <cstdint>

#include "penumbra/image.h"
#include "penumbra/reference/render.h"
#include "penumbra/reference/scene.h"

namespace penumbra::reference {

struct ObscuranceTruthOptions {
    double radius = 0.5;  // R, world units, > 0
    int strata = 16;      // n: n^2 rays (AO) or n^3 points (VO) per pixel, in [1, 1024] (VO: [1, 128])
    std::uint64_t seed = 0x2545f4914f6cdd1dull;
};

// Error(InvalidArgument, "ambient_occlusion_truth") for a radius <= 0 or
// strata outside their range.
Image ambient_occlusion_truth(const Scene& scene, const Receivers& receivers,
                              const ObscuranceTruthOptions& options = {});
Image volumetric_obscurance_truth(const Scene& scene, const Receivers& receivers,
                                  const ObscuranceTruthOptions& options = {});

}  // namespace penumbra::reference
