// The OpenCL programs per kernel entry (cl/opencl_programs.h) against the
// kernel table (kernels/kernel_table.h): every KernelId gets a kernel object
// of a program that holds it and no other kernel (its family's other entries
// and a helper file's kernels stay out), a context builds nothing until a
// launch, and a VSM run builds only the entries it launches. Skips, saying
// so, without an OpenCL device.
#include <gtest/gtest.h>

#include <algorithm>
#include <set>
#include <sstream>
#include <string>

#include "penumbra/config.h"
#include "support/backends.h"
#if PENUMBRA_OPENCL
#include "cl/opencl_backend.h"
#include "penumbra/chebyshev.h"
#include "penumbra/moment_table.h"
#endif

namespace penumbra {
namespace {

#if PENUMBRA_OPENCL
using detail::KernelId;

bool opencl_here(std::string* why)
{
    return testing::shared_context("opencl", why) != nullptr;
}

std::set<std::string> kernels_of_program(const cl::Program& program)
{
    std::string listed = program.getInfo<CL_PROGRAM_KERNEL_NAMES>();
    listed.erase(std::remove(listed.begin(), listed.end(), '\0'), listed.end());  // a driver's trailing NUL
    std::set<std::string> names;
    std::stringstream stream(listed);
    for (std::string name; std::getline(stream, name, ';');)
        if (!name.empty()) names.insert(name);
    return names;
}

TEST(OpenClPrograms, EveryKernelIdGetsAProgramHoldingItAlone)
{
    std::string why;
    if (!opencl_here(&why)) GTEST_SKIP() << "OpenCL unavailable here: " << why;
    cl_backend::OpenClBackend backend(false);
    for (int k = 0; k < detail::kKernelCount; ++k) {
        const KernelId id = KernelId(k);
        cl::Kernel& kernel = backend.programs().kernel(id);
        EXPECT_EQ(kernel.getInfo<CL_KERNEL_FUNCTION_NAME>(), std::string(detail::kernel_name(id)));
        // PoCL compiles every kernel of a program for its binary: one kernel a program.
        const cl::Program program = kernel.getInfo<CL_KERNEL_PROGRAM>();
        EXPECT_EQ(kernels_of_program(program), std::set<std::string>{std::string(detail::kernel_name(id))});
    }
    EXPECT_EQ(backend.programs().programs_built(), detail::kKernelCount);
}

TEST(OpenClPrograms, AContextBuildsNoProgramBeforeItsFirstLaunch)
{
    std::string why;
    if (!opencl_here(&why)) GTEST_SKIP() << "OpenCL unavailable here: " << why;
    Context context(ContextOptions{Backend::OpenCL, {}});
    auto& backend = dynamic_cast<cl_backend::OpenClBackend&>(context.impl());
    EXPECT_EQ(backend.programs().programs_built(), 0);
    EXPECT_EQ(context.program_build_seconds(), 0.0);
}

TEST(OpenClPrograms, AVsmRunBuildsOnlyTheKernelsItLaunches)
{
    std::string why;
    if (!opencl_here(&why)) GTEST_SKIP() << "OpenCL unavailable here: " << why;
    Context context(ContextOptions{Backend::OpenCL, {}});
    auto& backend = dynamic_cast<cl_backend::OpenClBackend&>(context.impl());
    Image depth(7, 3, 1);
    for (int y = 0; y < 3; ++y)
        for (int x = 0; x < 7; ++x) depth.at(0, x, y) = 0.1f * float(x + y);
    Image receivers(7, 3, 3);  // u, v, z: one receiver over each texel, at depth 0.5
    for (int y = 0; y < 3; ++y)
        for (int x = 0; x < 7; ++x) {
            receivers.at(0, x, y) = (float(x) + 0.5f) / 7.0f;
            receivers.at(1, x, y) = (float(y) + 0.5f) / 3.0f;
            receivers.at(2, x, y) = 0.5f;
        }
    const MomentTable table = build_moment_table(context, depth);
    const Image out = vsm(context, table, receivers, VsmOptions{});
    EXPECT_EQ(out.width(), 7);

    cl_backend::KernelPrograms& programs = backend.programs();
    // The default precision is exact: the limb table's two passes, then its lookup.
    for (KernelId id : {KernelId::sat_bands_exact, KernelId::sat_join_bands_exact, KernelId::vsm_exact})
        EXPECT_TRUE(programs.built(id)) << detail::kernel_name(id);
    EXPECT_EQ(programs.programs_built(), 3) << "a VSM run built a kernel it does not launch";
    EXPECT_GT(context.program_build_seconds(), 0.0);
}
#else
TEST(OpenClPrograms, SkippedWithoutOpenCl) { GTEST_SKIP() << "this build has no OpenCL backend (PENUMBRA_OPENCL=OFF)"; }
#endif

}  // namespace
}  // namespace penumbra
