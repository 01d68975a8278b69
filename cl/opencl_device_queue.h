// The OpenCL device queue (host/backend/device_queue.h): images and tables as
// buffers on the context's device, operations enqueued on its in-order queue
// through the backend's launch sequences (cl/opencl_backend.h), and the row
// flags of every enqueued operation copied, on the device, into one summary
// buffer that finish() reads back once (docs/integration.md, "Device residency").
#pragma once

#include <CL/opencl.hpp>

#include <vector>

#include "cl/opencl_backend.h"
#include "host/backend/device_queue.h"

namespace penumbra::cl_backend {

struct ClImageData final : detail::DeviceData {
    cl::Buffer buffer;
    _cl_mem* opencl_mem() const override { return buffer(); }
};

struct ClTableData final : detail::DeviceTableData {
    cl::Buffer storage, origin;
};

// The moment table build's parameters in this backend's schedule (opencl_moment_table.cpp).
SatParams device_table_params(pn_dims depth, pn_dims table, int limbs);

class OpenClDeviceQueue final : public detail::DeviceQueue {
public:
    explicit OpenClDeviceQueue(OpenClBackend& backend) : backend_(backend) {}

    std::shared_ptr<detail::DeviceData> upload(const Image& image) override;
    std::shared_ptr<detail::DeviceData> allocate(int width, int height, int channels) override;
    std::shared_ptr<detail::DeviceData> wrap(void* opencl_buffer, int width, int height, int channels,
                                             std::size_t row_pitch_bytes) override;
    void download(const detail::DeviceData& data, Image& out) override;
    std::shared_ptr<detail::DeviceTableData> allocate_table(int width, int height, Precision precision) override;

    void build_moment_table(const detail::DeviceData& depth, detail::DeviceTableData& table,
                            detail::RowError bad) override;
    void table_lookup(detail::KernelId kernel, const detail::DeviceTableData& table,
                      const detail::DeviceData& receivers, const void* params, detail::DeviceData& out,
                      detail::RowError bad) override;
    void cross_bilateral(const detail::DeviceData& mask, const detail::DeviceData& guide,
                         const detail::DeviceData* normals, const std::vector<int>& taps,
                         const std::vector<float>& weights, bool separable, const BilateralParams& params,
                         detail::DeviceData& out, detail::RowError bad) override;

    Event marker() override;
    void finish() override;

private:
    // Zeroed row flags for an operation checking `rows` rows; checked() files them.
    Output<int> flags_for(int rows) const { return backend_.device_zeros<int>(std::size_t(rows)); }
    // Copies `flags` into the summary (on the device) and remembers how to report them.
    void checked(const Output<int>& flags, int rows, detail::RowError bad);
    // The window's taps and weights on the device: kept from the last blur
    // while they are the same (a renderer blurs with one setting per frame),
    // so that a frame's chain uploads nothing.
    void window_buffers(const std::vector<int>& taps, const std::vector<float>& weights);

    struct PendingCheck {
        std::size_t offset;
        int rows;
        detail::RowError bad;
    };

    OpenClBackend& backend_;
    cl::Buffer summary_;
    std::size_t summary_capacity_ = 0, summary_used_ = 0;  // ints
    std::vector<PendingCheck> pending_;
    std::vector<int> taps_;
    std::vector<float> weights_;
    Input<int> taps_buffer_;
    Input<float> weights_buffer_;
};

}  // namespace penumbra::cl_backend
