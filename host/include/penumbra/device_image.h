// Device-resident images and moment tables, and operations that enqueue
// without waiting (issue 18, item 2; docs/integration.md, "Device residency").
//
// On OpenCL a DeviceImage's storage is a buffer on the context's device: made
// from host data (one upload), empty (for an operation to write), or the
// caller's own cl_mem in the caller's cl_context (Context::from_opencl). The
// operations below enqueue their kernels on the context's in-order queue and
// return; a chain such as build_moment_table -> vsm -> cross_bilateral moves
// nothing between host and device between its steps. finish() (or
// download(), which calls it) waits, and is where bad input the kernels
// flagged (a NaN receiver, a depth outside [0, 1]) is reported as the
// operation's Error: the kernels ran after the call returned.
//
// On the CPU backends (Simd, Scalar) the same code runs synchronously: a
// DeviceImage is host memory, each operation runs at once and throws at
// once, and every Event is already complete. So user code is backend-neutral.
//
// A DeviceImage or table belongs to the context that made it; another context
// refuses it (Error(InvalidArgument)). Copies share the storage.
#pragma once

#include <cstddef>
#include <memory>

#include "penumbra/bilateral.h"
#include "penumbra/chebyshev.h"
#include "penumbra/context.h"
#include "penumbra/depth_convention.h"
#include "penumbra/image.h"
#include "penumbra/moment_table.h"

struct _cl_mem;    // cl_mem, as CL/cl.h declares it
struct _cl_event;  // cl_event

namespace penumbra {

namespace detail {
struct DeviceData;
struct DeviceTableData;
struct EventData;
}  // namespace detail

// Completion of what was enqueued before it. Default-constructed, and on the
// CPU backends, it is complete.
class Event {
public:
    Event() = default;
    explicit Event(std::shared_ptr<detail::EventData> data) : data_(std::move(data)) {}
    void wait() const;
    bool complete() const;
    // The OpenCL event (owned by this Event: retain it to keep it longer); null on the CPU backends.
    _cl_event* opencl_event() const;

private:
    std::shared_ptr<detail::EventData> data_;
};

class DeviceImage {
public:
    DeviceImage() = default;
    explicit DeviceImage(std::shared_ptr<detail::DeviceData> data) : data_(std::move(data)) {}
    int width() const noexcept;
    int height() const noexcept;
    int channels() const noexcept;
    bool empty() const noexcept { return !data_; }
    // OpenCL: the buffer (owned by the image: retain it to keep it longer); null on the CPU backends.
    _cl_mem* opencl_buffer() const;
    const detail::DeviceData& data() const;
    detail::DeviceData& data();

private:
    std::shared_ptr<detail::DeviceData> data_;
};

// A moment table of VSM's shape (2 moments: VSM and VSSM read it) on the device.
// It records the convention of the maps it is built from (device_moment_table).
class DeviceMomentTable {
public:
    DeviceMomentTable() = default;
    explicit DeviceMomentTable(std::shared_ptr<detail::DeviceTableData> data) : data_(std::move(data)) {}
    int width() const noexcept;
    int height() const noexcept;
    Precision precision() const noexcept;
    // The convention of the depth maps it is built from.
    const DepthConvention& depth_convention() const;
    bool empty() const noexcept { return !data_; }
    const detail::DeviceTableData& data() const;
    detail::DeviceTableData& data();

private:
    std::shared_ptr<detail::DeviceTableData> data_;
};

// (a) One upload of `image` (the call waits for it: `image` may be freed after).
DeviceImage upload(Context& context, const Image& image);
// (b) Uninitialised storage of this shape, for an operation to write.
DeviceImage device_image(Context& context, int width, int height, int channels);
// (c) The caller's buffer: planes of `height` rows `row_pitch_bytes` apart
// (0: width floats), one after another. Retained until the last copy of the
// image goes. Error(InvalidArgument, "buffer") for a buffer of another
// context, one too small for the size, or a context that is not OpenCL.
DeviceImage wrap_opencl_buffer(Context& context, _cl_mem* buffer, int width, int height, int channels,
                               std::size_t row_pitch_bytes = 0);
// Waits (finish()), then one download into a new Image.
Image download(Context& context, const DeviceImage& image);

// A table for maps stored in `depth` (penumbra/depth_convention.h):
// build_moment_table converts them in the kernels' load, as the Image form
// does, and vsm / vssm read their receivers' z in it (their options must name
// the same convention). Error(InvalidArgument) naming near or far for a bad
// convention.
DeviceMomentTable device_moment_table(Context& context, int width, int height,
                                      Precision precision = Precision::Exact, const DepthConvention& depth = {});

// The operations, enqueued. Their checks of sizes and options throw at once,
// as the Image forms'; the kernels' findings in the data come from finish().
Event build_moment_table(Context& context, const DeviceImage& depth, DeviceMomentTable& table);
Event vsm(Context& context, const DeviceMomentTable& table, const DeviceImage& receivers, const VsmOptions& options,
          DeviceImage& out);
Event vssm(Context& context, const DeviceMomentTable& table, const DeviceImage& receivers, const VssmOptions& options,
           DeviceImage& out);
Event cross_bilateral(Context& context, const DeviceImage& mask, const DeviceImage& guide_depth,
                      const BilateralOptions& options, DeviceImage& out, const DeviceImage* guide_normals = nullptr);

// Waits for everything enqueued on the context, then throws the first bad
// input a kernel flagged since the last finish() (Error(InvalidData)).
void finish(Context& context);

// Host <-> device transfers made by the OpenCL backend in this process: each
// upload or write of host data (a CL_MEM_USE_HOST_PTR or COPY_HOST_PTR
// buffer counts as one), each read or map back. For tests and benchmarks
// that show what a chain moves. Zero without OpenCL.
struct HostTransfers {
    long uploads = 0, downloads = 0;
    std::size_t upload_bytes = 0, download_bytes = 0;
};
HostTransfers host_transfers();

}  // namespace penumbra
