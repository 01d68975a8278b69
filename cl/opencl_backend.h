// The OpenCL backend: its device, its programs (one per kernel entry, built
// on first use: cl/opencl_programs.h) and the launches. One class: the
// generic lookup of every lookup-shaped entry in cl/opencl_lookup.cpp, and
// each schedule that differs (table builds, bilateral, SDF) in its family's
// file (cl/opencl_<family>.cpp), all through launch<K> (cl/opencl_launch.h).
//
// Schedule: per-pixel kernels run one work-item per pixel, per-task kernels one
// work-item per task (a band of rows), in work-groups of a fixed size
// (cl/opencl_work_groups.h).
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "host/backend/backend.h"
#include "cl/opencl_launch.h"
#include "cl/opencl_programs.h"
#include "cl/opencl_runtime.h"

namespace penumbra::cl_backend {

class OpenClBackend final : public detail::BackendImpl {
public:
    // Finds the device; builds no program (that happens on first use).
    explicit OpenClBackend(bool non_cpu_only);

    std::string description() const override;
    // The programs this context built so far (none before its first launch).
    double program_build_seconds() const override { return programs_.build_seconds(); }
    KernelPrograms& programs() { return programs_; }

    PN_BACKEND_OPERATIONS(, override);  // host/backend/backend.h

private:
    template <detail::KernelId K>
    void sdf(const float* data, std::size_t floats, const Image& positions, const Image& normals,
             const SdfParams& params, Image& out, int* bad_rows);
    // The table builds in the table's element type T, K the bands' scan.
    template <detail::KernelId K, class T>
    void build_table_as(const Image& depth, MomentTable& table, int* bad_rows);
    template <detail::KernelId K, class T>
    void build_encoded_table_as(const Image& depth, const EncodedSatParams& params, MomentTable& table,
                                int* bad_rows);
    // The join of the band totals shared by both table builds (kernels/moment_table.h).
    template <class T>
    void join_bands(const Output<T>& origin, const Output<T>& columns, const SatParams& params, Pixels pixels);

    const cl::Context& context() const { return runtime_.context(); }
    const cl::CommandQueue& queue() const { return runtime_.queue(); }
    template <detail::KernelId K, class Range, class... A>
    void launch(Range range, const A&... args)
    {
        cl_backend::launch<K>(programs_, runtime_.queue(), range, args...);
    }

    Runtime runtime_;
    KernelPrograms programs_{runtime_};
};

bool has_non_cpu_device();
// non_cpu_only: Auto's request (a GPU or accelerator); else any device, PoCL included.
std::unique_ptr<detail::BackendImpl> make_opencl_backend(bool non_cpu_only);

}  // namespace penumbra::cl_backend
