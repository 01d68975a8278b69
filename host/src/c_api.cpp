// The C API (penumbra/penumbra.h) over the C++ one: handles own C++ objects,
// views become ImageViews, and every entry point runs inside guarded(), which
// turns any exception into a status and this thread's last error, so that no
// exception crosses into C.
#include "penumbra/penumbra.h"

#include <algorithm>
#include <initializer_list>
#include <new>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include "penumbra/bilateral.h"
#include "penumbra/context.h"
#include "penumbra/depth_convention.h"
#include "penumbra/device_image.h"
#include "penumbra/error.h"
#include "penumbra/image_view.h"
#include "penumbra/methods.h"

struct penumbra_context {
    penumbra::Context context;
    std::string description;
};

struct penumbra_method {
    const penumbra::Method* method;
    penumbra::MethodSettings settings;
};

struct penumbra_device_image {
    penumbra::DeviceImage image;
};

struct penumbra_device_table {
    penumbra::DeviceMomentTable table;
};

namespace {

using penumbra::Error;
using penumbra::ErrorCategory;

thread_local std::string last_message, last_parameter;

penumbra_status status_of(ErrorCategory category)
{
    switch (category) {
    case ErrorCategory::InvalidArgument: return PENUMBRA_INVALID_ARGUMENT;
    case ErrorCategory::InvalidData: return PENUMBRA_INVALID_DATA;
    case ErrorCategory::Io: return PENUMBRA_IO;
    case ErrorCategory::Unavailable: return PENUMBRA_UNAVAILABLE;
    case ErrorCategory::Backend: return PENUMBRA_BACKEND;
    }
    return PENUMBRA_INTERNAL;
}

penumbra_status fail(penumbra_status status, std::string message, std::string parameter = {})
{
    last_message = std::move(message);
    last_parameter = std::move(parameter);
    return status;
}

// Runs `body`; its exceptions become a status and the thread's last error.
template <class Body>
penumbra_status guarded(Body&& body) noexcept
{
    try {
        body();
        return PENUMBRA_OK;
    } catch (const Error& e) {
        return fail(status_of(e.category()), e.what(), e.parameter());
    } catch (const std::bad_alloc&) {
        return fail(PENUMBRA_OUT_OF_MEMORY, "out of memory");
    } catch (const std::exception& e) {
        return fail(PENUMBRA_INTERNAL, std::string("internal error: ") + e.what());
    } catch (...) {
        return fail(PENUMBRA_INTERNAL, "internal error: an unknown exception");
    }
}

// A NULL argument is the caller's mistake, named like any other parameter.
void require_pointer(const void* p, const char* function, const char* parameter)
{
    if (!p)
        throw Error(ErrorCategory::InvalidArgument, function, parameter,
                    std::string("'") + parameter + "' is NULL");
}

void require_pointers(const char* function, std::initializer_list<std::pair<const void*, const char*>> arguments)
{
    for (const auto& [p, parameter] : arguments) require_pointer(p, function, parameter);
}

// A device handle's creation: *handle cleared first, the context checked, then made.
template <class Handle, class Make>
penumbra_status create_handle(Handle** handle, const char* function, const char* parameter, penumbra_context* context,
                              Make&& make) noexcept
{
    return guarded([&] {
        require_pointer(handle, function, parameter);
        *handle = nullptr;
        require_pointer(context, function, "context");
        *handle = new Handle{make(context->context)};
    });
}

penumbra::ChannelLayout layout_of(penumbra_layout layout, const char* function, const char* parameter)
{
    if (layout == PENUMBRA_PLANAR) return penumbra::ChannelLayout::Planar;
    if (layout == PENUMBRA_INTERLEAVED) return penumbra::ChannelLayout::Interleaved;
    throw Error(ErrorCategory::InvalidArgument, function, parameter,
                "the layout " + std::to_string(int(layout)) + " is neither PENUMBRA_PLANAR nor PENUMBRA_INTERLEAVED");
}

// The fields both view types share, copied from the C struct of either.
template <class View, class CView>
View geometry_of(const CView* v, const char* function, const char* parameter)
{
    require_pointer(v, function, parameter);
    View view;
    view.data = v->data;
    view.width = v->width;
    view.height = v->height;
    view.channels = v->channels;
    view.row_pitch = v->row_pitch;
    view.plane_pitch = v->plane_pitch;
    view.layout = layout_of(v->layout, function, parameter);
    return view;
}

penumbra::ImageView view_of(const penumbra_image_view* v, const char* function, const char* parameter)
{
    auto view = geometry_of<penumbra::ImageView>(v, function, parameter);
    if (v->type != PENUMBRA_FLOAT32 && v->type != PENUMBRA_UINT16)
        throw Error(ErrorCategory::InvalidArgument, function, parameter,
                    "the pixel type " + std::to_string(int(v->type)) + " is neither PENUMBRA_FLOAT32 nor PENUMBRA_UINT16");
    view.type = v->type == PENUMBRA_UINT16 ? penumbra::PixelType::UInt16 : penumbra::PixelType::Float32;
    return view;
}

penumbra::MutableImageView view_of(const penumbra_output_view* v, const char* function, const char* parameter)
{
    return geometry_of<penumbra::MutableImageView>(v, function, parameter);
}

penumbra::Backend backend_of(penumbra_backend backend)
{
    switch (backend) {
    case PENUMBRA_BACKEND_AUTO: return penumbra::Backend::Auto;
    case PENUMBRA_BACKEND_SIMD: return penumbra::Backend::Simd;
    case PENUMBRA_BACKEND_OPENCL: return penumbra::Backend::OpenCL;
    case PENUMBRA_BACKEND_SCALAR: return penumbra::Backend::Scalar;
    case PENUMBRA_BACKEND_MAX_ENUM: break;  // the range marker (penumbra.h), not a backend
    }
    throw Error(ErrorCategory::InvalidArgument, "penumbra_context_create", "backend",
                "the backend " + std::to_string(int(backend)) + " is none of PENUMBRA_BACKEND_AUTO, _SIMD, _OPENCL, _SCALAR");
}

penumbra::BilateralOptions blur_options(const penumbra_blur_options& o)
{
    constexpr const char* kFunction = "penumbra_blur";
    if (o.range != PENUMBRA_RANGE_GAUSSIAN && o.range != PENUMBRA_RANGE_THRESHOLD)
        throw Error(ErrorCategory::InvalidArgument, kFunction, "range",
                    "the range " + std::to_string(int(o.range)) + " is neither PENUMBRA_RANGE_GAUSSIAN nor _THRESHOLD");
    if (o.window != PENUMBRA_WINDOW_SQUARE && o.window != PENUMBRA_WINDOW_DISK)
        throw Error(ErrorCategory::InvalidArgument, kFunction, "window",
                    "the window " + std::to_string(int(o.window)) + " is neither PENUMBRA_WINDOW_SQUARE nor _DISK");
    penumbra::BilateralOptions b;
    b.radius = o.radius;
    b.spatial_sigma = o.spatial_sigma;
    b.range = o.range == PENUMBRA_RANGE_THRESHOLD ? penumbra::BilateralRange::Threshold
                                                   : penumbra::BilateralRange::Gaussian;
    b.relative = o.relative != 0;
    b.depth_sigma = o.depth_sigma;
    b.depth_threshold = o.depth_threshold;
    b.window = o.window == PENUMBRA_WINDOW_DISK ? penumbra::BilateralWindow::Disk : penumbra::BilateralWindow::Square;
    b.separable = o.separable != 0;
    b.normal_sigma = o.normal_sigma;
    return b;
}

// Normalised depth reads no planes; the other conventions read both.
bool reads_planes(penumbra::DepthConventionKind kind) { return kind != penumbra::DepthConventionKind::Normalized; }

// A plane given to normalised depth, which reads none.
void require_unset_plane(float value, const char* function, const char* plane)
{
    if (value == 0.0f) return;
    std::ostringstream text;
    text << "normalized depth reads no " << plane << " plane (" << plane << "_plane is " << value
         << "): leave it 0, or name the convention that reads it (PENUMBRA_DEPTH_LINEAR, _PERSPECTIVE, _REVERSED)";
    throw Error(ErrorCategory::InvalidArgument, function, plane, text.str());
}

penumbra::DepthConventionKind depth_kind_of(penumbra_depth_kind kind, const char* function)
{
    using penumbra::DepthConventionKind;
    switch (kind) {
    case PENUMBRA_DEPTH_NORMALIZED: return DepthConventionKind::Normalized;
    case PENUMBRA_DEPTH_LINEAR: return DepthConventionKind::Linear;
    case PENUMBRA_DEPTH_PERSPECTIVE: return DepthConventionKind::Perspective;
    case PENUMBRA_DEPTH_REVERSED: return DepthConventionKind::Reversed;
    case PENUMBRA_DEPTH_KIND_MAX_ENUM: break;  // the range marker (penumbra.h), not a convention
    }
    throw Error(ErrorCategory::InvalidArgument, function, "depth-convention",
                "the depth convention " + std::to_string(int(kind)) +
                    " is none of PENUMBRA_DEPTH_NORMALIZED, _LINEAR, _PERSPECTIVE, _REVERSED");
}

// The C struct (NULL: normalised) as the C++ one. What only a C struct can
// get wrong is refused here: planes on normalised depth (ignored there, so a
// likely mistake, as the method options refuse them) and a convention that
// reads planes left zeroed; check_depth_convention does the rest.
penumbra::DepthConvention depth_convention_of(const penumbra_depth_convention* c, const char* function)
{
    if (!c) return {};
    penumbra::DepthConvention d;
    d.kind = depth_kind_of(c->kind, function);
    const std::string kind = penumbra::to_string(d.kind);
    if (!reads_planes(d.kind)) {
        require_unset_plane(c->near_plane, function, "near");
        require_unset_plane(c->far_plane, function, "far");
        return d;
    }
    penumbra::require(c->near_plane != 0.0f || c->far_plane != 0.0f, function, "near",
                      kind + " depth needs the light's near and far planes (near_plane and far_plane are both 0)");
    d.near = c->near_plane;
    d.far = c->far_plane;
    penumbra::check_depth_convention(d, function);
    return d;
}

}  // namespace

extern "C" {

const char* penumbra_last_error(void) { return last_message.c_str(); }
const char* penumbra_last_error_parameter(void) { return last_parameter.c_str(); }

const char* penumbra_status_name(penumbra_status status)
{
    switch (status) {
    case PENUMBRA_OK: return "ok";
    case PENUMBRA_INVALID_ARGUMENT: return "invalid argument";
    case PENUMBRA_INVALID_DATA: return "invalid data";
    case PENUMBRA_IO: return "i/o error";
    case PENUMBRA_UNAVAILABLE: return "unavailable";
    case PENUMBRA_BACKEND: return "backend failure";
    case PENUMBRA_OUT_OF_MEMORY: return "out of memory";
    case PENUMBRA_INTERNAL: return "internal error";
    case PENUMBRA_STATUS_MAX_ENUM: break;
    }
    return "unknown status";
}

penumbra_status penumbra_context_create(penumbra_backend backend, penumbra_context** context)
{
    return guarded([&] {
        require_pointer(context, "penumbra_context_create", "context");
        *context = nullptr;
        penumbra::Context made(penumbra::ContextOptions{backend_of(backend), {}});
        std::string description = made.description();
        *context = new penumbra_context{std::move(made), std::move(description)};
    });
}

void penumbra_context_destroy(penumbra_context* context) { delete context; }

const char* penumbra_context_description(const penumbra_context* context)
{
    return context ? context->description.c_str() : "";
}

penumbra_status penumbra_method_create(const char* name, const char* const* option_names,
                                       const char* const* option_values, size_t count, penumbra_method** method)
{
    constexpr const char* kFunction = "penumbra_method_create";
    return guarded([&] {
        require_pointer(method, kFunction, "method");
        *method = nullptr;
        require_pointer(name, kFunction, "name");
        if (count > 0) {
            require_pointer(option_names, kFunction, "option_names");
            require_pointer(option_values, kFunction, "option_values");
        }
        std::vector<std::pair<std::string, std::string>> given;
        for (size_t i = 0; i < count; ++i) {
            require_pointer(option_names[i], kFunction, "option_names");
            require_pointer(option_values[i], kFunction, "option_values");
            given.emplace_back(option_names[i], option_values[i]);
        }
        const penumbra::Method& m = penumbra::find_method(name);
        *method = new penumbra_method{&m, penumbra::parse_method_settings(m, given)};
    });
}

void penumbra_method_destroy(penumbra_method* method) { delete method; }

penumbra_status penumbra_shade(penumbra_context* context, const penumbra_method* method,
                               const penumbra_image_view* map, const penumbra_image_view* receivers,
                               const penumbra_output_view* out)
{
    constexpr const char* kFunction = "penumbra_shade";
    return guarded([&] {
        require_pointer(context, kFunction, "context");
        require_pointer(method, kFunction, "method");
        method->method->run(context->context, view_of(map, kFunction, "depth"),
                            view_of(receivers, kFunction, "receivers"), method->settings,
                            view_of(out, kFunction, "out"));
    });
}

penumbra_blur_options penumbra_blur_defaults(void)
{
    const penumbra::BilateralOptions d;
    return {d.radius,
            d.spatial_sigma,
            d.range == penumbra::BilateralRange::Threshold ? PENUMBRA_RANGE_THRESHOLD : PENUMBRA_RANGE_GAUSSIAN,
            d.relative ? 1 : 0,
            d.depth_sigma,
            d.depth_threshold,
            d.window == penumbra::BilateralWindow::Disk ? PENUMBRA_WINDOW_DISK : PENUMBRA_WINDOW_SQUARE,
            d.separable ? 1 : 0,
            d.normal_sigma};
}

penumbra_status penumbra_blur(penumbra_context* context, const penumbra_image_view* mask,
                              const penumbra_image_view* guide_depth, const penumbra_image_view* guide_normals,
                              const penumbra_blur_options* options, const penumbra_output_view* out)
{
    constexpr const char* kFunction = "penumbra_blur";
    return guarded([&] {
        require_pointer(context, kFunction, "context");
        const penumbra::ImageView normals =
            guide_normals ? view_of(guide_normals, kFunction, "guide-normals") : penumbra::ImageView{};
        penumbra::cross_bilateral(context->context, view_of(mask, kFunction, "mask"),
                                  view_of(guide_depth, kFunction, "guide-depth"),
                                  options ? blur_options(*options) : penumbra::BilateralOptions{},
                                  view_of(out, kFunction, "out"), guide_normals ? &normals : nullptr);
    });
}

penumbra_status penumbra_device_image_upload(penumbra_context* context, const penumbra_image_view* image,
                                             penumbra_device_image** device)
{
    constexpr const char* kFunction = "penumbra_device_image_upload";
    return create_handle(device, kFunction, "device", context, [&](penumbra::Context& ctx) {
        const penumbra::InputImage input(view_of(image, kFunction, "image"), kFunction, "image");
        return penumbra::upload(ctx, input.image());
    });
}

penumbra_status penumbra_device_image_create(penumbra_context* context, int width, int height, int channels,
                                             penumbra_device_image** device)
{
    return create_handle(device, "penumbra_device_image_create", "device", context, [&](penumbra::Context& ctx) {
        return penumbra::device_image(ctx, width, height, channels);
    });
}

penumbra_status penumbra_device_image_wrap(penumbra_context* context, void* cl_mem, int width, int height,
                                           int channels, size_t row_pitch, penumbra_device_image** device)
{
    return create_handle(device, "penumbra_device_image_wrap", "device", context, [&](penumbra::Context& ctx) {
        return penumbra::wrap_opencl_buffer(ctx, static_cast<_cl_mem*>(cl_mem), width, height, channels, row_pitch);
    });
}

void penumbra_device_image_destroy(penumbra_device_image* device) { delete device; }

penumbra_status penumbra_device_image_download(penumbra_context* context, const penumbra_device_image* device,
                                               const penumbra_output_view* out)
{
    constexpr const char* kFunction = "penumbra_device_image_download";
    return guarded([&] {
        require_pointers(kFunction, {{context, "context"}, {device, "device"}});
        penumbra::OutputImage target(view_of(out, kFunction, "out"), kFunction, "out");
        const penumbra::Image got = penumbra::download(context->context, device->image);
        penumbra::require(got.width() == target.image().width() && got.height() == target.image().height() &&
                              got.channels() == target.image().channels(),
                          kFunction, "out", "the output view must have the device image's size and channels");
        for (int c = 0; c < got.channels(); ++c)
            for (int y = 0; y < got.height(); ++y)
                std::copy(got.row(c, y), got.row(c, y) + got.width(), target.image().row(c, y));
        target.commit();
    });
}

penumbra_status penumbra_device_table_create(penumbra_context* context, int width, int height,
                                             const penumbra_depth_convention* depth, penumbra_device_table** table)
{
    constexpr const char* kFunction = "penumbra_device_table_create";
    return create_handle(table, kFunction, "table", context, [&](penumbra::Context& ctx) {
        return penumbra::device_moment_table(ctx, width, height, penumbra::Precision::Exact,
                                             depth_convention_of(depth, kFunction));
    });
}

void penumbra_device_table_destroy(penumbra_device_table* table) { delete table; }

penumbra_status penumbra_enqueue_moment_table(penumbra_context* context, const penumbra_device_image* depth,
                                              penumbra_device_table* table)
{
    return guarded([&] {
        require_pointers("penumbra_enqueue_moment_table", {{context, "context"}, {depth, "depth"}, {table, "table"}});
        penumbra::build_moment_table(context->context, depth->image, table->table);
    });
}

penumbra_status penumbra_enqueue_shade(penumbra_context* context, const penumbra_method* method,
                                       const penumbra_device_table* table, const penumbra_device_image* receivers,
                                       penumbra_device_image* out)
{
    constexpr const char* kFunction = "penumbra_enqueue_shade";
    return guarded([&] {
        require_pointers(kFunction, {{context, "context"},
                                     {method, "method"},
                                     {table, "table"},
                                     {receivers, "receivers"},
                                     {out, "out"}});
        const std::string name = method->method->name;
        penumbra::require(name == "vsm" || name == "vssm", kFunction, "method",
                          "'" + name + "' does not run on device images yet; vsm and vssm do");
        const penumbra::MethodSettings& m = method->settings;
        // The method's convention is the receivers'; the C++ call refuses one that is not the table's.
        if (name == "vssm")
            penumbra::vssm(context->context, table->table, receivers->image,
                           {m.light_size, m.min_variance, m.bleed, m.depth_convention}, out->image);
        else
            penumbra::vsm(context->context, table->table, receivers->image,
                          {m.radius, m.min_variance, m.bleed, m.depth_convention}, out->image);
    });
}

penumbra_status penumbra_enqueue_blur(penumbra_context* context, const penumbra_device_image* mask,
                                      const penumbra_device_image* guide_depth,
                                      const penumbra_device_image* guide_normals,
                                      const penumbra_blur_options* options, penumbra_device_image* out)
{
    return guarded([&] {
        require_pointers("penumbra_enqueue_blur",
                         {{context, "context"}, {mask, "mask"}, {guide_depth, "guide-depth"}, {out, "out"}});
        penumbra::cross_bilateral(context->context, mask->image, guide_depth->image,
                                  options ? blur_options(*options) : penumbra::BilateralOptions{}, out->image,
                                  guide_normals ? &guide_normals->image : nullptr);
    });
}

penumbra_status penumbra_finish(penumbra_context* context)
{
    return guarded([&] {
        require_pointer(context, "penumbra_finish", "context");
        penumbra::finish(context->context);
    });
}

}  // extern "C"
