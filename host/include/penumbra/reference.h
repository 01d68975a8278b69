// The reference side in one include: scenes, renders, ground truth, light
// space and ray casting (docs/reference.md). Metrics are in metrics.h.
#pragma once

#include "penumbra/reference_geometry.h"
#include "penumbra/reference_ground_truth.h"
#include "penumbra/reference_light_space.h"
#include "penumbra/reference_render.h"
#include "penumbra/reference_scene.h"
#include "penumbra/reference_tracer.h"
