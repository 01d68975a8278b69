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
#include "host/backend/device_queue.h"
#include "cl/opencl_launch.h"
#include "cl/opencl_programs.h"
#include "cl/opencl_runtime.h"

namespace penumbra::cl_backend {

class OpenClDeviceQueue;  // cl/opencl_device_queue.h

// The buffers of one cross-bilateral run (backend.h's cross_bilateral).
struct BilateralBuffers {
    Input<float> mask, guide, normals;
    Input<int> taps;
    Input<float> weights;
    Output<float> out;
    Output<int> flags;
};

// Rows per band of the OpenCL table builds: the bands are built in parallel,
// each from zero column sums, and every band's column totals are then added
// to the bands below (kernels/moment_table.h; opencl_moments.cpp,
// opencl_moment_table.cpp).
inline constexpr int kTableBandHeight = 32;

class OpenClBackend final : public detail::BackendImpl {
public:
    // Finds the device; builds no program (that happens on first use).
    explicit OpenClBackend(bool non_cpu_only);
    // Over a caller's context and in-order queue (Context::from_opencl).
    OpenClBackend(cl_context context, cl_command_queue queue);
    ~OpenClBackend() override;

    std::string description() const override;
    // The programs this context built so far (none before its first launch).
    double program_build_seconds() const override { return programs_.build_seconds(); }
    KernelPrograms& programs() { return programs_; }

    PN_BACKEND_OPERATIONS(, override);  // host/backend/backend.h

    detail::DeviceQueue* device_queue() override;  // cl/opencl_device_queue.h
    const cl::Context& context() const { return runtime_.context(); }
    const cl::CommandQueue& queue() const { return runtime_.queue(); }

    // The launch sequences that the operations above and the device queue
    // both enqueue (they return without waiting).
    // The table build of `depth` into the table whose origin is `origin`
    // (`planes` planes, zeroed borders), in the table's precision.
    void enqueue_table_build(const Input<float>& depth, const cl::Buffer& origin, std::size_t origin_bytes,
                             Precision precision, const SatParams& params, int planes, const Output<int>& flags);
    void enqueue_bilateral(const BilateralBuffers& buffers, bool separable, const BilateralParams& params);
    // Zeros written on the device (no host transfer, unlike zeros()).
    template <class T>
    Output<T> device_zeros(std::size_t count) const
    {
        Output<T> buffer = scratch<T>(context(), count);
        queue().enqueueFillBuffer(buffer.buffer, T(0), 0, buffer.bytes);
        return buffer;
    }

private:
    template <detail::KernelId K>
    void sdf(const float* data, std::size_t floats, const Image& positions, const Image& normals,
             const SdfParams& params, Image& out, int* bad_rows);
    // The table builds in the table's element type T, K the bands' scan.
    template <detail::KernelId K, class T>
    void enqueue_table_build_as(const Input<float>& depth, const Output<T>& origin, const SatParams& params,
                                int planes, const Output<int>& flags);
    template <detail::KernelId K, class T>
    void build_encoded_table_as(const Image& depth, const EncodedSatParams& params, MomentTable& table,
                                int* bad_rows);
    // The join of the band totals shared by both table builds (kernels/moment_table.h).
    template <class T>
    void join_bands(const Output<T>& origin, const Output<T>& columns, const SatParams& params, Pixels pixels);

    template <detail::KernelId K, class Range, class... A>
    void launch(Range range, const A&... args)
    {
        cl_backend::launch<K>(programs_, runtime_.queue(), range, args...);
    }

    Runtime runtime_;
    KernelPrograms programs_{runtime_};
    std::unique_ptr<OpenClDeviceQueue> device_queue_;  // made on first use
};

bool has_non_cpu_device();
// non_cpu_only: Auto's request (a GPU or accelerator); else any device, PoCL included.
std::unique_ptr<detail::BackendImpl> make_opencl_backend(bool non_cpu_only);
std::unique_ptr<detail::BackendImpl> make_opencl_backend(cl_context context, cl_command_queue queue);

}  // namespace penumbra::cl_backend
