// Pismo's three float64 estimates on a receivers' grid from one set of maps
// (support/pismo_reference.h): the layered maps, the average of hard shadows
// from the same maps, and the maximum-depth variant. Shared by the
// convergence and self-shadowing tests and bench/pismo_acceptance.cpp, so
// the figures in docs/pismo.md come from the code the tests check.
#pragma once

#include "penumbra/image.h"
#include "penumbra/reference/pismo_maps.h"
#include "penumbra/reference/render.h"
#include "penumbra/reference/scene.h"
#include "support/pismo_reference.h"

namespace penumbra::testing {

struct PismoEstimates {
    Image pismo, averaged, maximum_depth;  // one channel each, 0 outside rx.mask
};

// Every valid receiver (rx.mask), rows in parallel, each over the kernel's ray
// pattern (support/pismo_reference.h): the result does not depend on the threads.
// With `normals`, each receiver's own surface (rx.normal) takes part in the test;
// with options.surface_ids, its surface id (rx.surface) too.
PismoEstimates pismo_estimates(const reference::PismoMaps& maps, const reference::Receivers& rx,
                               const PismoReferenceOptions& options, bool normals = false);

// The valid receivers (rx.mask) that lie on one of the scene's planes
// (on_planes), or the others: on a bounded caster, inside the casters' hull,
// where a caster may shadow itself.
Image receivers_on_planes(const reference::Scene& scene, const reference::Receivers& rx, bool on_planes);

// The memory of a set of maps, in bytes: the layered maps and their bled
// copies, as the layered method reads them.
std::size_t pismo_layered_bytes(const reference::PismoMaps& maps);

}  // namespace penumbra::testing
