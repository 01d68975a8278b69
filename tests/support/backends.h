// Every backend this machine has (support/backend_list.h), for parameterised
// tests: scalar, each SIMD ISA the CPU runs, and OpenCL. A backend that cannot
// start here (OpenCL with no device) makes its tests GTEST_SKIP with the
// reason: never a silent pass.
#pragma once

#include <gtest/gtest.h>

#include <stdexcept>
#include <string>
#include <vector>

#include "penumbra/context.h"
#include "support/backend_list.h"

namespace penumbra::testing {

// One context per backend per test process (the OpenCL program is built once).
// Returns nullptr and sets `why` when the backend cannot start here.
Context* shared_context(const std::string& name, std::string* why);

// For gtest's name generator: "avx512", "sse4_2", ...
std::string backend_test_name(const ::testing::TestParamInfo<std::string>& info);

}  // namespace penumbra::testing

// In a test body: Context& ctx = PN_CONTEXT_OR_SKIP(GetParam());
#define PN_CONTEXT_OR_SKIP(name)                                                  \
    ([&]() -> penumbra::Context& {                                                \
        std::string why_;                                                         \
        penumbra::Context* c_ = penumbra::testing::shared_context((name), &why_); \
        if (!c_) throw penumbra::testing::SkipBackend{why_};                      \
        return *c_;                                                               \
    }())

namespace penumbra::testing {
struct SkipBackend {
    std::string why;
};

// The scalar oracle's context, for a test that compares `backend` with it.
// Throws, failing the test, when `backend` is "scalar" itself: the test would
// compare the oracle with itself and pass whatever the kernels do. Such
// suites are instantiated over non_scalar_backends().
inline Context& scalar_oracle(const std::string& backend)
{
    if (backend == "scalar")
        throw std::logic_error("an agreement test run for \"scalar\" compares the oracle with itself: "
                               "instantiate its suite over non_scalar_backends()");
    return PN_CONTEXT_OR_SKIP("scalar");
}
}  // namespace penumbra::testing

// Wraps a test body so that an unavailable backend skips the test with its reason.
#define PN_BACKEND_TEST(suite, name)                                       \
    static void suite##_##name##_body(const std::string& backend);          \
    TEST_P(suite, name)                                                     \
    {                                                                       \
        try {                                                               \
            suite##_##name##_body(GetParam());                              \
        } catch (const penumbra::testing::SkipBackend& skip) {              \
            GTEST_SKIP() << "backend " << GetParam() << " unavailable here: " << skip.why; \
        }                                                                   \
    }                                                                       \
    static void suite##_##name##_body(const std::string& backend)
