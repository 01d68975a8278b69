/* penumbra's C API: the library for C and for other languages' FFI.
 *
 * Opaque handles (a context owns a backend; a method is a shading method of
 * the method table with its options parsed), views of the caller's memory
 * (read and written in place where the layout allows, docs/integration.md),
 * and status codes: every function that can fail returns one, and
 * penumbra_last_error() gives the message of the calling thread's last
 * failure. No C++ exception crosses this boundary.
 *
 * The same operations as the C++ API (penumbra/context.h, methods.h,
 * bilateral.h, image_view.h), which this wraps: a context on a backend, a
 * method by name with its options ("radius" = "3", as `penumbra shade
 * --radius 3`), shading a shadow map's receivers into a caller's buffer, and
 * the cross-bilateral blur. A context is used by one thread at a time;
 * methods are immutable and may be shared. */
#ifndef PENUMBRA_C_API_H
#define PENUMBRA_C_API_H

#include <stddef.h>

#ifdef __cplusplus
extern "C" {
#endif

/* Every enum ends in a _MAX_ENUM of 0x7FFFFFFF, as Vulkan's do: C has no
 * fixed underlying type before C23, and without it a value the caller casts
 * (say (penumbra_backend)42) lies outside the type's range, so reading it in
 * the library would be undefined (UBSan reports it) before it could be
 * refused. With it, every int from 0 up is a value of the type, and the
 * library refuses the ones it does not know with PENUMBRA_INVALID_ARGUMENT.
 * The _MAX_ENUM values themselves are never valid arguments. */

/* The categories of penumbra::Error (penumbra/error.h), then failures the C++
 * API reports by other exceptions. */
typedef enum {
    PENUMBRA_OK = 0,
    PENUMBRA_INVALID_ARGUMENT = 1, /* a parameter, size or value the caller passed */
    PENUMBRA_INVALID_DATA = 2,     /* NaN, infinite or out-of-range values in an image */
    PENUMBRA_IO = 3,
    PENUMBRA_UNAVAILABLE = 4,      /* the backend, ISA or device does not exist here */
    PENUMBRA_BACKEND = 5,          /* an OpenCL call or program build failed */
    PENUMBRA_OUT_OF_MEMORY = 6,
    PENUMBRA_INTERNAL = 7,         /* a defect: please report it with the message */
    PENUMBRA_STATUS_MAX_ENUM = 0x7FFFFFFF
} penumbra_status;

typedef enum {
    PENUMBRA_BACKEND_AUTO = 0, /* PENUMBRA_BACKEND, else a GPU if any, else SIMD (penumbra/context.h) */
    PENUMBRA_BACKEND_SIMD = 1,
    PENUMBRA_BACKEND_OPENCL = 2,
    PENUMBRA_BACKEND_SCALAR = 3,
    PENUMBRA_BACKEND_MAX_ENUM = 0x7FFFFFFF
} penumbra_backend;

typedef enum {
    PENUMBRA_FLOAT32 = 0,
    PENUMBRA_UINT16 = 1, /* value / 65535; inputs only */
    PENUMBRA_PIXEL_TYPE_MAX_ENUM = 0x7FFFFFFF
} penumbra_pixel_type;
typedef enum { PENUMBRA_PLANAR = 0, PENUMBRA_INTERLEAVED = 1, PENUMBRA_LAYOUT_MAX_ENUM = 0x7FFFFFFF } penumbra_layout;

/* The caller's memory (penumbra/image_view.h): pitches in bytes, 0 for
 * packed rows (and planes of height x row_pitch). */
typedef struct {
    const void* data;
    int width, height, channels;
    size_t row_pitch, plane_pitch;
    penumbra_layout layout;
    penumbra_pixel_type type;
} penumbra_image_view;

typedef struct {
    void* data; /* float32 */
    int width, height, channels;
    size_t row_pitch, plane_pitch;
    penumbra_layout layout;
} penumbra_output_view;

typedef struct penumbra_context penumbra_context;
typedef struct penumbra_method penumbra_method;

/* The message of this thread's last failed call ("vsm: ..."), or "" if none
 * failed; valid until this thread's next failing call. */
const char* penumbra_last_error(void);
/* The parameter that last failure names ("radius", "receivers", "out"), or "". */
const char* penumbra_last_error_parameter(void);
/* "ok", "invalid argument", ...: for logs. */
const char* penumbra_status_name(penumbra_status status);

/* *context is set on success, NULL otherwise. An explicit backend that this
 * machine lacks is PENUMBRA_UNAVAILABLE. */
penumbra_status penumbra_context_create(penumbra_backend backend, penumbra_context** context);
void penumbra_context_destroy(penumbra_context* context); /* NULL: nothing */
/* What runs: "simd (avx512, 16 lanes)", "opencl (...)"; owned by the context. */
const char* penumbra_context_description(const penumbra_context* context);

/* A shading method of the method table ("vsm", "pcf", ...; `penumbra shade
 * --help` lists them) with `count` options as names and texts. */
penumbra_status penumbra_method_create(const char* name, const char* const* option_names,
                                       const char* const* option_values, size_t count, penumbra_method** method);
void penumbra_method_destroy(penumbra_method* method);

/* Visibility in [0, 1] of each receiver into `out` (one channel, the
 * receivers' size): the method's build step on `map` (one channel, depth in
 * [0, 1]), then its shade step on `receivers` (u, v, z, ...). */
penumbra_status penumbra_shade(penumbra_context* context, const penumbra_method* method,
                               const penumbra_image_view* map, const penumbra_image_view* receivers,
                               const penumbra_output_view* out);

/* The cross-bilateral blur's options (penumbra/bilateral.h, BilateralOptions). */
typedef enum {
    PENUMBRA_RANGE_GAUSSIAN = 0,
    PENUMBRA_RANGE_THRESHOLD = 1,
    PENUMBRA_BLUR_RANGE_MAX_ENUM = 0x7FFFFFFF
} penumbra_blur_range;
typedef enum {
    PENUMBRA_WINDOW_SQUARE = 0,
    PENUMBRA_WINDOW_DISK = 1,
    PENUMBRA_BLUR_WINDOW_MAX_ENUM = 0x7FFFFFFF
} penumbra_blur_window;
typedef struct {
    int radius;
    float spatial_sigma;
    penumbra_blur_range range;
    int relative; /* 1: depth differences as a fraction of the centre depth */
    float depth_sigma, depth_threshold;
    penumbra_blur_window window;
    int separable;
    float normal_sigma;
} penumbra_blur_options;

/* The library's defaults: start from these and change what you need. */
penumbra_blur_options penumbra_blur_defaults(void);

/* The mask (1 to 4 channels) blurred into `out` (its size and channels),
 * guided by `guide_depth` (one channel) and optionally `guide_normals` (3
 * channels, or NULL). `options` NULL: the defaults. */
penumbra_status penumbra_blur(penumbra_context* context, const penumbra_image_view* mask,
                              const penumbra_image_view* guide_depth, const penumbra_image_view* guide_normals,
                              const penumbra_blur_options* options, const penumbra_output_view* out);

/* Device-resident images and tables (penumbra/device_image.h,
 * docs/integration.md "Device residency"): on OpenCL their storage is a
 * buffer on the context's device and the penumbra_enqueue_* calls return
 * without waiting; penumbra_finish() waits and returns the status of bad data
 * the kernels found (PENUMBRA_INVALID_DATA). On the CPU backends they are
 * host memory and every call runs at once. A handle is used with the context
 * that made it and destroyed before it. */
typedef struct penumbra_device_image penumbra_device_image;
typedef struct penumbra_device_table penumbra_device_table;

/* One upload of a float32 view (a copy first where the view's layout is not
 * planar float32, as penumbra_shade's inputs). */
penumbra_status penumbra_device_image_upload(penumbra_context* context, const penumbra_image_view* image,
                                             penumbra_device_image** device);
/* Uninitialised, for an operation to write. */
penumbra_status penumbra_device_image_create(penumbra_context* context, int width, int height, int channels,
                                             penumbra_device_image** device);
/* The caller's cl_mem (as void*), planes of `height` rows `row_pitch` bytes
 * apart (0: packed); retained until the handle is destroyed. */
penumbra_status penumbra_device_image_wrap(penumbra_context* context, void* cl_mem, int width, int height,
                                           int channels, size_t row_pitch, penumbra_device_image** device);
void penumbra_device_image_destroy(penumbra_device_image* device); /* NULL: nothing */
/* Waits (penumbra_finish), then downloads into `out` (the image's size and channels). */
penumbra_status penumbra_device_image_download(penumbra_context* context, const penumbra_device_image* device,
                                               const penumbra_output_view* out);

/* How a shadow map's depths are stored (penumbra/depth_convention.h,
 * docs/integration.md "Depth conventions"), for a device table. For a
 * distance d from the light along its axis: normalised l = (d - near) /
 * (far - near) in [0, 1] (the default); linear d itself, in [near, far];
 * perspective the D3D / Vulkan depth far (d - near) / (d (far - near));
 * reversed 1 - the perspective depth.
 *
 * A typed struct, not the method options' strings ("depth-convention" =
 * "linear", "near" = "0.5", as penumbra_method_create takes them): a renderer
 * holds near and far as floats, and printing them for the library to parse
 * back would depend on the C locale's decimal separator (LC_NUMERIC) and on
 * the caller's precision; the struct passes the exact floats, as
 * penumbra_blur_options passes the blur's. The fields are near_plane and
 * far_plane, not near and far: <windows.h> defines those two words as empty
 * macros. A zeroed struct is normalised depth. */
typedef enum {
    PENUMBRA_DEPTH_NORMALIZED = 0,
    PENUMBRA_DEPTH_LINEAR = 1,
    PENUMBRA_DEPTH_PERSPECTIVE = 2,
    PENUMBRA_DEPTH_REVERSED = 3,
    PENUMBRA_DEPTH_KIND_MAX_ENUM = 0x7FFFFFFF
} penumbra_depth_kind;
typedef struct {
    penumbra_depth_kind kind;
    /* Read by linear, perspective and reversed: both finite, far_plane >
     * near_plane, and near_plane > 0 for perspective and reversed (the
     * projection divides by d). Normalised takes both 0: a plane given there
     * would be ignored, so it is refused as a likely mistake. */
    float near_plane, far_plane;
} penumbra_depth_convention;

/* An exact moment table (VSM's: 2 moments) of a width x height map stored in
 * `depth` (NULL: normalised). penumbra_enqueue_moment_table converts the map
 * in the kernels' load, and penumbra_enqueue_shade reads the receivers' z in
 * the same convention: its method must name it in its options
 * ("depth-convention", "near", "far"), or the call is refused naming
 * "depth-convention". A bad convention is PENUMBRA_INVALID_ARGUMENT naming
 * "depth-convention", "near" or "far"; a map value outside the convention's
 * range is PENUMBRA_INVALID_DATA from penumbra_finish. */
penumbra_status penumbra_device_table_create(penumbra_context* context, int width, int height,
                                             const penumbra_depth_convention* depth, penumbra_device_table** table);
void penumbra_device_table_destroy(penumbra_device_table* table); /* NULL: nothing */

penumbra_status penumbra_enqueue_moment_table(penumbra_context* context, const penumbra_device_image* depth,
                                              penumbra_device_table* table);
/* The lookup step of `method` on a device table: "vsm" or "vssm", with the
 * method's options; another method is PENUMBRA_INVALID_ARGUMENT. */
penumbra_status penumbra_enqueue_shade(penumbra_context* context, const penumbra_method* method,
                                       const penumbra_device_table* table, const penumbra_device_image* receivers,
                                       penumbra_device_image* out);
penumbra_status penumbra_enqueue_blur(penumbra_context* context, const penumbra_device_image* mask,
                                      const penumbra_device_image* guide_depth,
                                      const penumbra_device_image* guide_normals,
                                      const penumbra_blur_options* options, penumbra_device_image* out);
penumbra_status penumbra_finish(penumbra_context* context);

#ifdef __cplusplus
}
#endif

#endif
