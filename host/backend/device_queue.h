// The device-resident side of a backend (penumbra/device_image.h): storage
// that lives on the backend's device and operations that enqueue on its
// queue without waiting. Only OpenCL has one (cl/opencl_device_queue.h);
// BackendImpl::device_queue() is null on the CPU backends, whose device
// images are host Images and whose operations run at once
// (host/src/device_image.cpp). Inputs are validated before these are called.
#pragma once

#include <cstddef>
#include <functional>
#include <memory>
#include <vector>

#include "host/backend/kernel_id.h"
#include "kernels/params.h"
#include "penumbra/device_image.h"
#include "penumbra/error.h"
#include "penumbra/image.h"
#include "penumbra/moment_table.h"

namespace penumbra::detail {

class BackendImpl;

// What every device image and table knows of itself: the backend that made
// it (an image of one context is refused by another) and its geometry in
// elements, as the kernels' pn_dims read it.
struct DeviceData {
    virtual ~DeviceData() = default;
    const BackendImpl* owner = nullptr;
    int channels = 0;
    pn_dims dims{};
    // Every value is known to be finite and at most 1 in magnitude (a
    // visibility written by penumbra, an upload scanned on the host): the blur
    // skips its overflow guard's scan (host/src/bilateral.cpp) for such a mask.
    bool unit_bounded = false;
    virtual _cl_mem* opencl_mem() const { return nullptr; }  // the OpenCL buffer, if any
};

// An Event's backend side (the CPU backends make none: their Events are complete).
struct EventData {
    virtual ~EventData() = default;
    virtual void wait() = 0;
    virtual bool complete() = 0;
    virtual _cl_event* opencl_event() = 0;
};

// A device table: the moment table's shape and layout, its storage on the device.
struct DeviceTableData {
    virtual ~DeviceTableData() = default;
    const BackendImpl* owner = nullptr;
    int width = 0, height = 0, moments = 2, limbs = 1;
    Precision precision = Precision::Exact;
    DepthConvention depth{};      // the maps' convention (the lookups' check)
    DepthConversion conversion{}; // the same as the build kernels read it (kernels/params.h)
    MomentTableLayout layout{};
    pn_dims dims() const { return {width, height, layout.pitch, int(layout.plane_pitch)}; }
};

// The first row a kernel flagged as bad, turned into the operation's Error
// when the queue finishes (the kernels ran asynchronously).
using RowError = std::function<Error(int row)>;

class DeviceQueue {
public:
    virtual ~DeviceQueue() = default;

    virtual std::shared_ptr<DeviceData> upload(const Image& image) = 0;
    virtual std::shared_ptr<DeviceData> allocate(int width, int height, int channels) = 0;
    // The caller's buffer, retained; checked for its context and size (Error(InvalidArgument, "buffer")).
    virtual std::shared_ptr<DeviceData> wrap(void* opencl_buffer, int width, int height, int channels,
                                             std::size_t row_pitch_bytes) = 0;
    // Waits for what was enqueued, then reads `data` into `out` (its size and channels).
    virtual void download(const DeviceData& data, Image& out) = 0;
    virtual std::shared_ptr<DeviceTableData> allocate_table(int width, int height, Precision precision) = 0;

    // Enqueue, and return. `bad` is how a flagged row becomes an Error at finish().
    virtual void build_moment_table(const DeviceData& depth, DeviceTableData& table, RowError bad) = 0;
    // A lookup-shaped entry reading a table (backend.h's receiver_lookup).
    virtual void table_lookup(KernelId kernel, const DeviceTableData& table, const DeviceData& receivers,
                              const void* params, DeviceData& out, RowError bad) = 0;
    virtual void cross_bilateral(const DeviceData& mask, const DeviceData& guide, const DeviceData* normals,
                                 const std::vector<int>& taps, const std::vector<float>& weights, bool separable,
                                 const BilateralParams& params, DeviceData& out, RowError bad) = 0;

    // A marker after everything enqueued so far.
    virtual Event marker() = 0;
    // Waits for the queue, then throws the first flagged row's Error (once).
    virtual void finish() = 0;
};

}  // namespace penumbra::detail
