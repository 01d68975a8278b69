// Every backend this machine has, by name: scalar, each SIMD ISA the CPU runs,
// and OpenCL. The one list the tests (tests/support/backends.h) and the
// benchmarks (bench/) iterate; it needs no GoogleTest, so both link it
// (penumbra_test_support, tests/support/CMakeLists.txt).
#pragma once

#include <string>
#include <vector>

#include "penumbra/context.h"

namespace penumbra::testing {

// "scalar", "sse4.2", "avx2", "avx512" (those this CPU runs), "opencl".
std::vector<std::string> backend_names();
// backend_names() without "opencl": the CPU kernel tables, scalar first.
std::vector<std::string> cpu_backend_names();
// backend_names() without "scalar": for tests that compare a backend with the
// scalar oracle, which must not be instantiated (and pass) for scalar itself.
std::vector<std::string> non_scalar_backends();
// Lanes of a backend's strips (1 for scalar and OpenCL).
int backend_lanes(const std::string& name);
// The options that start the backend `name` (one of backend_names()).
ContextOptions backend_options(const std::string& name);

// Widths that exercise every strip/tail shape of every lane count here:
// 1, N-1, N, N+1, 3N+1 for each ISA's N.
std::vector<int> lane_edge_widths();

}  // namespace penumbra::testing
