// The reference side in one include (the penumbra::reference target):
// scenes, renders, ground truth, deep shadow maps, light space, ray casting
// (docs/reference.md), error metrics, and the SDF view of a scene
// (docs/sdf.md).
#pragma once

#include "penumbra/reference/deep_map.h"
#include "penumbra/reference/geometry.h"
#include "penumbra/reference/ground_truth.h"
#include "penumbra/reference/light_space.h"
#include "penumbra/reference/metrics.h"
#include "penumbra/reference/obscurance_truth.h"
#include "penumbra/reference/render.h"
#include "penumbra/reference/scene.h"
#include "penumbra/reference/sdf_scene.h"
#include "penumbra/reference/tracer.h"
