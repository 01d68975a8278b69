// Device-resident images and tables and the enqueued chain (penumbra/device_image.h):
// the checks and parameters of the Image forms, then the backend's device
// queue (OpenCL), or the Image forms themselves at once (the CPU backends,
// whose device images are host memory).
#include "penumbra/device_image.h"

#include <sstream>
#include <string>
#include <utility>

#include "bilateral_setup.h"
#include "chebyshev_params.h"
#include "depth_conversion.h"
#include "host/backend/backend.h"
#include "host/backend/device_queue.h"
#include "penumbra/config.h"
#include "penumbra/error.h"
#if PENUMBRA_OPENCL
#include "cl/transfer_counts.h"
#endif

namespace penumbra {
namespace {

// The CPU backends' storage: host memory, operated on at once.
struct HostImageData final : detail::DeviceData {
    Image image;
};
struct HostTableData final : detail::DeviceTableData {
    MomentTable table;
};

std::shared_ptr<detail::DeviceData> host_image_data(Context& context, Image image)
{
    auto data = std::make_shared<HostImageData>();
    data->owner = &context.impl();
    data->channels = image.channels();
    data->dims = detail::dims_of(image);
    data->image = std::move(image);
    return data;
}

// The CPU backends' storage of a checked image (the Image forms read and write it).
Image& host_image(const DeviceImage& image)
{
    return static_cast<HostImageData&>(const_cast<DeviceImage&>(image).data()).image;
}
MomentTable& host_table(const DeviceMomentTable& table)
{
    return static_cast<HostTableData&>(const_cast<DeviceMomentTable&>(table).data()).table;
}

std::string size_text(int width, int height) { return std::to_string(width) + "x" + std::to_string(height); }

void check_size(const std::string& op, int width, int height, int channels)
{
    require(width > 0 && height > 0, op, "size", "the image is empty (" + size_text(width, height) + ")");
    require(channels >= 1 && channels <= 16, op, "channels",
            "channel count must be in [1, 16] (got " + std::to_string(channels) + ")");
}

// An image or table given to `op` as `parameter`: present, and this context's.
template <class Device>
void check_owned(const Context& context, const Device& device, const std::string& op, const std::string& parameter)
{
    require(!device.empty(), op, parameter, "the " + parameter + " device image is empty (default-constructed)");
    require(device.data().owner == &const_cast<Context&>(context).impl(), op, parameter,
            "the " + parameter + " belongs to another Context; a device image or table is used with the context "
            "that made it (download and upload it to move it)");
}

void check_shape(const std::string& op, const DeviceImage& image, const std::string& parameter, int width, int height,
                 int channels)
{
    require(image.width() == width && image.height() == height && image.channels() == channels, op, parameter,
            "the " + parameter + " must be a " + std::to_string(channels) + "-channel device image of " +
                size_text(width, height) + " (got " + std::to_string(image.channels()) + " channels of " +
                size_text(image.width(), image.height()) + ")");
}

detail::DeviceQueue* queue_of(Context& context) { return context.impl().device_queue(); }

// "[0, 1]", or "[0.5, 50], the range of linear (near 0.5, far 50)", for the build's row errors.
std::string stored_range_text(const DepthConvention& convention)
{
    if (convention.kind == DepthConventionKind::Normalized) return "[0, 1]";
    const StoredDepthRange range = stored_depth_range(convention);
    std::ostringstream text;
    text << "[" << range.low << ", " << range.high << "], the range of " << describe(convention);
    return text.str();
}

Event enqueued(detail::DeviceQueue* queue) { return queue ? queue->marker() : Event(); }

// The Error of a row a kernel flagged, reported at finish().
detail::RowError row_error(std::string op, std::string parameter, std::string what)
{
    return [op = std::move(op), parameter = std::move(parameter), what = std::move(what)](int row) {
        return Error(ErrorCategory::InvalidData, op, parameter,
                     "row " + std::to_string(row) + " of " + what +
                         " (found when the enqueued kernels ran, reported by finish(); the output is unspecified)");
    };
}

}  // namespace

void Event::wait() const
{
    if (data_) data_->wait();
}
bool Event::complete() const { return !data_ || data_->complete(); }
_cl_event* Event::opencl_event() const { return data_ ? data_->opencl_event() : nullptr; }

int DeviceImage::width() const noexcept { return data_ ? data_->dims.width : 0; }
int DeviceImage::height() const noexcept { return data_ ? data_->dims.height : 0; }
int DeviceImage::channels() const noexcept { return data_ ? data_->channels : 0; }
const detail::DeviceData& DeviceImage::data() const { return *data_; }
detail::DeviceData& DeviceImage::data() { return *data_; }

int DeviceMomentTable::width() const noexcept { return data_ ? data_->width : 0; }
int DeviceMomentTable::height() const noexcept { return data_ ? data_->height : 0; }
Precision DeviceMomentTable::precision() const noexcept { return data_ ? data_->precision : Precision::Exact; }
const DepthConvention& DeviceMomentTable::depth_convention() const
{
    static const DepthConvention normalized{};
    return data_ ? data_->depth : normalized;
}
const detail::DeviceTableData& DeviceMomentTable::data() const { return *data_; }
detail::DeviceTableData& DeviceMomentTable::data() { return *data_; }

DeviceImage upload(Context& context, const Image& image)
{
    check_size("upload", image.width(), image.height(), image.channels());
    if (detail::DeviceQueue* queue = queue_of(context)) return DeviceImage(queue->upload(image));
    return DeviceImage(host_image_data(context, image));
}

DeviceImage device_image(Context& context, int width, int height, int channels)
{
    check_size("device_image", width, height, channels);
    if (detail::DeviceQueue* queue = queue_of(context)) return DeviceImage(queue->allocate(width, height, channels));
    return DeviceImage(host_image_data(context, Image(width, height, channels, Image::Uninitialized{})));
}

DeviceImage wrap_opencl_buffer(Context& context, _cl_mem* buffer, int width, int height, int channels,
                               std::size_t row_pitch_bytes)
{
    const std::string op = "wrap_opencl_buffer";
    check_size(op, width, height, channels);
    require(buffer != nullptr, op, "buffer", "the cl_mem is null");
    detail::DeviceQueue* queue = queue_of(context);
    require(queue != nullptr, op, "buffer",
            "the context runs on the " + to_string(context.backend()) +
                " backend, which cannot use a cl_mem; make an OpenCL context over the buffer's cl_context "
                "(Context::from_opencl)");
    return DeviceImage(queue->wrap(buffer, width, height, channels, row_pitch_bytes));
}

_cl_mem* DeviceImage::opencl_buffer() const
{
    return data_ ? data_->opencl_mem() : nullptr;
}

Image download(Context& context, const DeviceImage& image)
{
    check_owned(context, image, "download", "image");
    if (detail::DeviceQueue* queue = queue_of(context)) {
        Image out(image.width(), image.height(), image.channels(), Image::Uninitialized{});
        queue->download(image.data(), out);
        return out;
    }
    return host_image(image);
}

DeviceMomentTable device_moment_table(Context& context, int width, int height, Precision precision,
                                      const DepthConvention& depth)
{
    check_size("device_moment_table", width, height, 1);
    check_depth_convention(depth, "device_moment_table");
    if (detail::DeviceQueue* queue = queue_of(context)) {
        std::shared_ptr<detail::DeviceTableData> data = queue->allocate_table(width, height, precision);
        data->depth = depth;
        data->conversion = detail::kernel_conversion(depth);
        return DeviceMomentTable(std::move(data));
    }
    auto data = std::make_shared<HostTableData>();
    data->owner = &context.impl();
    data->width = width;
    data->height = height;
    data->precision = precision;
    data->depth = depth;
    data->conversion = detail::kernel_conversion(depth);
    data->table = MomentTable(width, height, 2, precision, kVsmLimbs, TableValues{0, 0.0f, 0.0f, depth});
    data->limbs = data->table.limbs();
    data->layout = moment_table_layout(width, height, data->table.planes());
    return DeviceMomentTable(std::move(data));
}

Event build_moment_table(Context& context, const DeviceImage& depth, DeviceMomentTable& table)
{
    const std::string op = "build_moment_table";
    check_owned(context, depth, op, "depth");
    check_owned(context, table, op, "table");
    check_shape(op, depth, "depth", table.width(), table.height(), 1);
    detail::DeviceQueue* queue = queue_of(context);
    if (!queue) {
        build_moment_table(context, host_image(depth), host_table(table));
        return {};
    }
    const std::string range = stored_range_text(table.depth_convention());
    queue->build_moment_table(depth.data(), table.data(),
                              row_error(op, "depth", "the depth map holds a NaN, an infinite value or a depth outside " +
                                                         range));
    return enqueued(queue);
}

namespace {

// VSM and VSSM on a device table: the same checks, then the method's Params
// (`params`, which checks its options) and its Float / Exact twin, or the
// Image form at once (`run_host`) on the CPU backends.
template <detail::KernelId Float, detail::KernelId Exact, class Params, class RunHost>
Event chebyshev_lookup(Context& context, const std::string& op, const DeviceMomentTable& table,
                       const DeviceImage& receivers, DeviceImage& out, Params&& params, RunHost&& run_host)
{
    check_owned(context, table, op, "table");
    check_owned(context, receivers, op, "receivers");
    check_owned(context, out, op, "out");
    require(receivers.channels() == 3, op, "receivers",
            "receivers must have 3 channels (u, v, z), got " + std::to_string(receivers.channels()));
    check_shape(op, out, "out", receivers.width(), receivers.height(), 1);
    detail::DeviceQueue* queue = queue_of(context);
    if (!queue) {
        run_host(host_table(table), host_image(receivers), host_image(out));
        out.data().unit_bounded = true;  // a visibility
        return {};
    }
    const detail::DeviceTableData& t = table.data();
    const ChebyshevParams p = params(t, receivers.data().dims, out.data().dims);
    queue->table_lookup(t.precision == Precision::Float ? Float : Exact, t, receivers.data(), &p, out.data(),
                        row_error(op, "receivers", "the receivers holds a NaN or infinite value"));
    out.data().unit_bounded = true;
    return enqueued(queue);
}

}  // namespace

Event vsm(Context& context, const DeviceMomentTable& table, const DeviceImage& receivers, const VsmOptions& options,
          DeviceImage& out)
{
    return chebyshev_lookup<detail::KernelId::vsm_float, detail::KernelId::vsm_exact>(
        context, "vsm", table, receivers, out,
        [&](const detail::DeviceTableData& t, pn_dims rx, pn_dims o) {
            ChebyshevParams p = detail::vsm_table_params("vsm", t.dims(), t.precision, t.limbs, rx, o, options);
            p.convention = detail::receivers_conversion("vsm", t.depth, options.depth_convention);
            return p;
        },
        [&](const MomentTable& t, const Image& rx, Image& o) { vsm(context, t, rx, options, o); });
}

Event vssm(Context& context, const DeviceMomentTable& table, const DeviceImage& receivers, const VssmOptions& options,
           DeviceImage& out)
{
    return chebyshev_lookup<detail::KernelId::vssm_float, detail::KernelId::vssm_exact>(
        context, "vssm", table, receivers, out,
        [&](const detail::DeviceTableData& t, pn_dims rx, pn_dims o) {
            ChebyshevParams p = detail::vssm_table_params("vssm", t.dims(), t.precision, t.limbs, rx, o, options);
            p.convention = detail::receivers_conversion("vssm", t.depth, options.depth_convention);
            return p;
        },
        [&](const MomentTable& t, const Image& rx, Image& o) { vssm(context, t, rx, options, o); });
}

Event cross_bilateral(Context& context, const DeviceImage& mask, const DeviceImage& guide_depth,
                      const BilateralOptions& options, DeviceImage& out, const DeviceImage* guide_normals)
{
    const std::string op = "cross_bilateral";
    check_owned(context, mask, op, "mask");
    check_owned(context, guide_depth, op, "guide-depth");
    check_owned(context, out, op, "out");
    if (guide_normals) check_owned(context, *guide_normals, op, "guide-normals");
    require(mask.channels() <= kBilateralMaxChannels, op, "mask",
            "the mask has " + std::to_string(mask.channels()) + " channels; the filter takes 1 to 4");
    check_shape(op, guide_depth, "guide-depth", mask.width(), mask.height(), 1);
    if (guide_normals) check_shape(op, *guide_normals, "guide-normals", mask.width(), mask.height(), 3);
    check_shape(op, out, "out", mask.width(), mask.height(), mask.channels());
    const bool aliased = &out.data() == &mask.data() || &out.data() == &guide_depth.data() ||
                         (guide_normals && &out.data() == &guide_normals->data());
    require(!aliased, op, "out", "the output must not be the mask or a guide image (the filter reads its neighbours)");
    detail::DeviceQueue* queue = queue_of(context);
    const bool bounded = mask.data().unit_bounded;
    if (!queue) {
        cross_bilateral(context, host_image(mask), host_image(guide_depth), options, host_image(out),
                        guide_normals ? &host_image(*guide_normals) : nullptr);
        out.data().unit_bounded = bounded;
        return {};
    }
    // The overflow guard scales a mask beyond 2^100 on the host
    // (bilateral.cpp); a mask not known to be a visibility is read back once
    // to see whether it needs that, which the device path cannot do.
    const pn_dims* normals = guide_normals ? &guide_normals->data().dims : nullptr;
    const detail::BilateralSetup setup = detail::bilateral_setup(options, mask.data().dims, mask.channels(),
                                                                 guide_depth.data().dims, normals, out.data().dims);
    if (!bounded)
        require(!detail::needs_overflow_guard(download(context, mask)), op, "mask",
                "the mask holds magnitudes beyond 2^100, which the float sums of the device path cannot take; "
                "blur it through cross_bilateral on Images, which scales it");
    queue->cross_bilateral(mask.data(), guide_depth.data(), guide_normals ? &guide_normals->data() : nullptr,
                           setup.taps, setup.weights, options.separable, setup.params, out.data(),
                           row_error(op, "mask", "the mask, the guide depth or the guide normals holds a NaN or "
                                                 "infinite value"));
    out.data().unit_bounded = bounded;  // a weighted mean of the mask
    return enqueued(queue);
}

void finish(Context& context)
{
    if (detail::DeviceQueue* queue = queue_of(context)) queue->finish();
}

HostTransfers host_transfers()
{
#if PENUMBRA_OPENCL
    return cl_backend::transfer_counts();
#else
    return {};
#endif
}

}  // namespace penumbra
