#include "cl/opencl_device_queue.h"

#include <algorithm>
#include <array>
#include <string>
#include <utility>

#include "penumbra/error.h"

namespace penumbra::cl_backend {

using detail::KernelId;

namespace {

struct ClEvent final : detail::EventData {
    cl::Event event;
    void wait() override { translate_cl_errors([&] { event.wait(); }); }
    bool complete() override
    {
        return translate_cl_errors([&] { return event.getInfo<CL_EVENT_COMMAND_EXECUTION_STATUS>() == CL_COMPLETE; });
    }
    _cl_event* opencl_event() override { return event(); }
};

template <class T>
Input<T> input_of(const ClImageData& data)
{
    return {data.buffer, extent_of(data.dims, data.channels) * sizeof(T)};
}
Output<float> output_of(const ClImageData& data)
{
    return {data.buffer, extent_of(data.dims, data.channels) * sizeof(float)};
}

std::shared_ptr<ClImageData> image_data(const detail::BackendImpl& owner, int width, int height, int channels,
                                        int pitch)
{
    auto data = std::make_shared<ClImageData>();
    data->owner = &owner;
    data->channels = channels;
    data->dims = {width, height, pitch, pitch * height};
    return data;
}

// 3D rectangle of an image's planes, for the rect reads and writes (bytes).
struct Rect {
    std::array<cl::size_type, 3> origin{0, 0, 0}, region{0, 0, 0};
    cl::size_type row_pitch = 0, slice_pitch = 0;
};
Rect rect_of(const pn_dims& dims, int channels)
{
    return {{0, 0, 0},
            {std::size_t(dims.width) * 4, std::size_t(dims.height), std::size_t(channels)},
            std::size_t(dims.pitch) * 4,
            std::size_t(dims.plane_pitch) * 4};
}

}  // namespace

std::shared_ptr<detail::DeviceData> OpenClDeviceQueue::upload(const Image& image)
{
    return translate_cl_errors([&] {
        auto data = image_data(backend_, image.width(), image.height(), image.channels(), image.pitch());
        data->dims.plane_pitch = int(image.plane_pitch());
        const std::size_t bytes = image.extent() * sizeof(float);
        data->buffer = cl::Buffer(backend_.context(), CL_MEM_READ_WRITE, bytes);
        count_upload(bytes);
        backend_.queue().enqueueWriteBuffer(data->buffer, CL_TRUE, 0, bytes, image.plane(0));
        return std::shared_ptr<detail::DeviceData>(std::move(data));
    });
}

std::shared_ptr<detail::DeviceData> OpenClDeviceQueue::allocate(int width, int height, int channels)
{
    return translate_cl_errors([&] {
        auto data = image_data(backend_, width, height, channels, padded_pitch(width));
        data->buffer = cl::Buffer(backend_.context(), CL_MEM_READ_WRITE,
                                  extent_of(data->dims, channels) * sizeof(float));
        return std::shared_ptr<detail::DeviceData>(std::move(data));
    });
}

std::shared_ptr<detail::DeviceData> OpenClDeviceQueue::wrap(void* opencl_buffer, int width, int height, int channels,
                                                            std::size_t row_pitch_bytes)
{
    const std::string op = "wrap_opencl_buffer";
    const std::size_t pitch_bytes = row_pitch_bytes == 0 ? std::size_t(width) * 4 : row_pitch_bytes;
    require(pitch_bytes % 4 == 0 && pitch_bytes >= std::size_t(width) * 4, op, "row_pitch_bytes",
            "the row pitch (" + std::to_string(pitch_bytes) + " bytes) must be a multiple of 4 and at least a row (" +
                std::to_string(std::size_t(width) * 4) + " bytes)");
    require(pitch_bytes / 4 * std::size_t(height) < (std::size_t(1) << 31), op, "row_pitch_bytes",
            "a plane of more than 2^31 floats is not supported");
    auto data = image_data(backend_, width, height, channels, int(pitch_bytes / 4));
    cl_context owner = nullptr;
    std::size_t size = 0;
    const cl_mem mem = static_cast<cl_mem>(opencl_buffer);
    if (clGetMemObjectInfo(mem, CL_MEM_CONTEXT, sizeof owner, &owner, nullptr) != CL_SUCCESS ||
        clGetMemObjectInfo(mem, CL_MEM_SIZE, sizeof size, &size, nullptr) != CL_SUCCESS)
        throw Error(ErrorCategory::InvalidArgument, op, "buffer", "the buffer is not a valid cl_mem");
    require(owner == backend_.context()(), op, "buffer",
            "the buffer belongs to another cl_context than this context's; create the Context with "
            "Context::from_opencl(your context, your queue)");
    const std::size_t needed = extent_of(data->dims, channels) * sizeof(float);
    require(size >= needed, op, "buffer",
            "the buffer holds " + std::to_string(size) + " bytes but " + std::to_string(width) + "x" +
                std::to_string(height) + "x" + std::to_string(channels) + " floats at a row pitch of " +
                std::to_string(pitch_bytes) + " bytes need " + std::to_string(needed));
    data->buffer = cl::Buffer(mem, true);  // retained; released with the last copy of the image
    return data;
}

void OpenClDeviceQueue::download(const detail::DeviceData& data, Image& out)
{
    finish();
    translate_cl_errors([&] {
        const auto& image = static_cast<const ClImageData&>(data);
        const Rect device = rect_of(image.dims, image.channels);
        const Rect host = rect_of(detail::dims_of(out), out.channels());
        count_download(out.extent() * sizeof(float));
        backend_.queue().enqueueReadBufferRect(image.buffer, CL_TRUE, device.origin, host.origin, device.region,
                                               device.row_pitch, device.slice_pitch, host.row_pitch,
                                               host.slice_pitch, out.plane(0));
    });
}

std::shared_ptr<detail::DeviceTableData> OpenClDeviceQueue::allocate_table(int width, int height,
                                                                           Precision precision)
{
    return translate_cl_errors([&] {
        auto table = std::make_shared<ClTableData>();
        table->owner = &backend_;
        table->width = width;
        table->height = height;
        table->moments = 2;
        table->precision = precision;
        table->limbs = precision == Precision::Exact ? kVsmLimbs : 1;
        table->layout = moment_table_layout(width, height, table->moments * table->limbs);
        const std::size_t bytes = table->layout.storage_elements * 4;
        // The kernels write every entry of the rows; the borders the corner
        // queries read must be zero (moment_table.cpp): zeroed on the device.
        table->storage = backend_.device_zeros<float>(table->layout.storage_elements).buffer;
        cl_buffer_region region{table->layout.origin_offset_bytes, bytes - table->layout.origin_offset_bytes};
        table->origin = table->storage.createSubBuffer(CL_MEM_READ_WRITE, CL_BUFFER_CREATE_TYPE_REGION, &region);
        return std::shared_ptr<detail::DeviceTableData>(std::move(table));
    });
}

void OpenClDeviceQueue::checked(const Output<int>& flags, int rows, detail::RowError bad)
{
    const std::size_t needed = summary_used_ + std::size_t(rows);
    if (needed > summary_capacity_) {
        const std::size_t capacity = std::max<std::size_t>({needed, 2 * summary_capacity_, 4096});
        cl::Buffer grown(backend_.context(), CL_MEM_READ_WRITE, capacity * sizeof(int));
        if (summary_used_ > 0) backend_.queue().enqueueCopyBuffer(summary_, grown, 0, 0, summary_used_ * sizeof(int));
        summary_ = grown;
        summary_capacity_ = capacity;
    }
    backend_.queue().enqueueCopyBuffer(flags.buffer, summary_, 0, summary_used_ * sizeof(int),
                                       std::size_t(rows) * sizeof(int));
    pending_.push_back({summary_used_, rows, std::move(bad)});
    summary_used_ = needed;
}

void OpenClDeviceQueue::build_moment_table(const detail::DeviceData& depth, detail::DeviceTableData& table,
                                           detail::RowError bad)
{
    translate_cl_errors([&] {
        auto& t = static_cast<ClTableData&>(table);
        SatParams p = device_table_params(depth.dims, t.dims(), t.limbs);
        p.convention = t.conversion;
        const Output<int> flags = flags_for(depth.dims.height);
        const std::size_t origin_bytes = t.layout.storage_elements * 4 - t.layout.origin_offset_bytes;
        backend_.enqueue_table_build(input_of<float>(static_cast<const ClImageData&>(depth)), t.origin, origin_bytes,
                                     t.precision, p, t.moments * t.limbs, flags);
        checked(flags, depth.dims.height, std::move(bad));
    });
}

void OpenClDeviceQueue::table_lookup(KernelId kernel, const detail::DeviceTableData& table,
                                     const detail::DeviceData& receivers, const void* params, detail::DeviceData& out,
                                     detail::RowError bad)
{
    detail::visit_lookup(kernel, params, [&](auto k, const auto& p) {
        constexpr KernelId K = decltype(k)::value;
        using Sources = detail::LookupSourcesOf<K>;
        if constexpr (std::tuple_size_v<Sources> != 1) {
            detail::throw_wrong_arrays(K, std::tuple_size_v<Sources>, 1);
        } else {
            using T = std::tuple_element_t<0, Sources>;
            const auto& t = static_cast<const ClTableData&>(table);
            require((t.precision == Precision::Exact) == !std::is_same_v<T, float>, kernel_name(K), "source",
                    "the table's precision is not the one this lookup reads");
            translate_cl_errors([&] {
                const std::size_t origin_bytes = t.layout.storage_elements * 4 - t.layout.origin_offset_bytes;
                const Output<int> flags = flags_for(receivers.dims.height);
                launch<K>(backend_.programs(), backend_.queue(), Pixels{out.dims.width, out.dims.height},
                          Input<T>{t.origin, origin_bytes}, input_of<float>(static_cast<const ClImageData&>(receivers)),
                          output_of(static_cast<ClImageData&>(out)), flags, p);
                checked(flags, receivers.dims.height, std::move(bad));
            });
        }
    });
}

void OpenClDeviceQueue::window_buffers(const std::vector<int>& taps, const std::vector<float>& weights)
{
    if (taps == taps_ && weights == weights_ && taps_buffer_.bytes > 0) return;
    taps_buffer_ = copy_of(backend_.context(), taps);
    weights_buffer_ = copy_of(backend_.context(), weights);
    taps_ = taps;
    weights_ = weights;
}

void OpenClDeviceQueue::cross_bilateral(const detail::DeviceData& mask, const detail::DeviceData& guide,
                                        const detail::DeviceData* normals, const std::vector<int>& taps,
                                        const std::vector<float>& weights, bool separable,
                                        const BilateralParams& params, detail::DeviceData& out,
                                        detail::RowError bad)
{
    translate_cl_errors([&] {
        window_buffers(taps, weights);
        const Input<float> guide_buf = input_of<float>(static_cast<const ClImageData&>(guide));
        const BilateralBuffers buffers{input_of<float>(static_cast<const ClImageData&>(mask)),
                                       guide_buf,
                                       normals ? input_of<float>(static_cast<const ClImageData&>(*normals)) : guide_buf,
                                       taps_buffer_,
                                       weights_buffer_,
                                       output_of(static_cast<ClImageData&>(out)),
                                       flags_for(mask.dims.height)};
        backend_.enqueue_bilateral(buffers, separable, params);
        checked(buffers.flags, mask.dims.height, std::move(bad));
    });
}

Event OpenClDeviceQueue::marker()
{
    auto event = std::make_shared<ClEvent>();
    translate_cl_errors([&] { backend_.queue().enqueueMarkerWithWaitList(nullptr, &event->event); });
    return Event(std::move(event));
}

void OpenClDeviceQueue::finish()
{
    translate_cl_errors([&] { backend_.queue().finish(); });
    if (pending_.empty()) return;
    std::vector<int> flags(summary_used_);
    std::vector<PendingCheck> pending = std::move(pending_);
    pending_.clear();
    summary_used_ = 0;
    translate_cl_errors([&] {
        count_download(flags.size() * sizeof(int));
        backend_.queue().enqueueReadBuffer(summary_, CL_TRUE, 0, flags.size() * sizeof(int), flags.data());
    });
    for (const PendingCheck& check : pending) {
        const auto first = flags.begin() + std::ptrdiff_t(check.offset);
        const auto bad = std::find(first, first + check.rows, 1);
        if (bad != first + check.rows) throw check.bad(int(bad - first));
    }
}

}  // namespace penumbra::cl_backend
