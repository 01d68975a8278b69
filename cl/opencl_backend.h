// The OpenCL backend: the embedded program, its kernels, and the launches.
// One class; each kernel family implements its methods in its own file
// (cl/opencl_<family>.cpp), next to its launches.
//
// Schedule: per-pixel kernels run one work-item per pixel (the driver picks the
// work-group size). Host images are wrapped with CL_MEM_USE_HOST_PTR so that a
// CPU driver such as PoCL works in place; results are read back through a map,
// which is free in that case.
#pragma once

#include <map>
#include <memory>
#include <string>
#include <vector>

#include "host/backend/backend.h"
#include "cl/opencl_runtime.h"

namespace penumbra::cl_backend {

extern const char* const kEmbeddedProgramSource;  // generated: kernels/params.h + cl/dialect_cl.h + kernels/*.h

// Options every build of the program uses. Division and sqrt correctly
// rounded, as on the CPU, so that the backends agree to the last bit where
// the operations are the same.
inline constexpr const char* kProgramOptions = "-cl-std=CL1.2 -cl-fp32-correctly-rounded-divide-sqrt";

// The entry points of kernels/registry.h, by name.
std::vector<std::string> registry_kernel_names();

class OpenClBackend final : public detail::BackendImpl {
public:
    explicit OpenClBackend(bool non_cpu_only);

    std::string description() const override;
    double program_build_seconds() const override { return build_seconds_; }

    // cl/opencl_moment_table.cpp
    void build_moment_table(const Image& depth, MomentTable& table, int* bad_rows) override;
    // cl/opencl_chebyshev.cpp
    void chebyshev(detail::ChebyshevMethod method, const MomentTable& table, const Image& receivers,
                   const ChebyshevParams& params, Image& out, int* bad_rows) override;
    // cl/opencl_bilateral.cpp
    void cross_bilateral(const Image& mask, const Image& guide, const Image* normals, const std::vector<int>& taps,
                         const std::vector<float>& weights, bool separable, const BilateralParams& params, Image& out,
                         int* bad_rows) override;
    // cl/opencl_sdf.cpp
    void sdf_grid(const float* data, std::size_t floats, const Image& positions, const Image& normals,
                  const SdfParams& params, Image& out, int* bad_rows) override;
    void sdf_analytic(const float* data, std::size_t floats, const Image& positions, const Image& normals,
                      const SdfParams& params, Image& out, int* bad_rows) override;
    // cl/opencl_moments.cpp
    void build_encoded_table(const Image& depth, const EncodedSatParams& params, MomentTable& table,
                             int* bad_rows) override;
    void moment_lookup(MomentMethod method, const MomentTable& table, const Image& receivers,
                       const MomentParams& params, Image& out, int* bad_rows) override;

private:
    cl::Kernel& kernel(const char* name) { return kernels_.at(name); }
    // A per-pixel lookup over a moment table (VSM, VSSM, MSM, EVSM entries share
    // the argument list: table origin, receivers, output, row flags, params).
    // cl/opencl_chebyshev.cpp
    void table_lookup(const char* name, const MomentTable& table, const Image& receivers, const void* params,
                      std::size_t params_bytes, Image& out, int* bad_rows);

    Runtime runtime_;
    cl::Program program_;
    double build_seconds_ = 0.0;
    std::map<std::string, cl::Kernel> kernels_;
};

// Buffers over host memory, shared by the launches.
std::size_t image_bytes(const Image& image);
cl::Buffer wrap(const cl::Context& context, const void* data, std::size_t bytes, cl_mem_flags access);
cl::Buffer zeros(const cl::Context& context, std::size_t bytes);
// The table's origin (its zero row) as a sub-buffer of its storage.
cl::Buffer table_origin(cl::Buffer& storage, const MomentTable& table, cl_mem_flags access);
// Makes the host copy of a USE_HOST_PTR buffer current.
void sync_to_host(const cl::CommandQueue& queue, const cl::Buffer& buffer, std::size_t bytes);
// A 2D launch over width x height pixels (PN_PIXEL_ARGS: row offset 0).
void launch_pixels(const cl::CommandQueue& queue, cl::Kernel& kernel, int width, int height);

bool has_non_cpu_device();
// non_cpu_only: Auto's request (a GPU or accelerator); else any device, PoCL included.
std::unique_ptr<detail::BackendImpl> make_opencl_backend(bool non_cpu_only);

}  // namespace penumbra::cl_backend
