/* The C API (penumbra/penumbra.h) from a C program, on every backend the
 * machine has: shading through several methods with options, a 16-bit map,
 * interleaved receivers at a padded pitch and the blur give bit for bit what
 * the C++ API gives on the same input (cpp_result.cpp), and the device-resident
 * chain gives what those calls give, in each depth convention too; bad input returns
 * its status code, names its parameter and leaves a message. Exit 0 when
 * every check passes. */
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "cpp_result.h"
#include "penumbra/penumbra.h"

static int failures = 0;

#define CHECK(condition, ...)                                      \
    do {                                                           \
        if (!(condition)) {                                        \
            ++failures;                                            \
            fprintf(stderr, "%s:%d: check failed: ", __FILE__, __LINE__); \
            fprintf(stderr, __VA_ARGS__);                          \
            fprintf(stderr, "\n");                                 \
        }                                                          \
    } while (0)

enum { MAP_W = 13, MAP_H = 7, W = 9, H = 5, PAD = 3 /* floats past each interleaved row */ };

static uint32_t lcg_state = 12345u;
static float next_unit(void)
{
    lcg_state = lcg_state * 1664525u + 1013904223u;
    return (float)(lcg_state >> 8) / 16777216.0f;
}

/* The inputs, once in the C++ reference's packed planar form and once as a C
 * caller holds them: receivers interleaved (u, v, z) with padding per row. */
static float map[MAP_W * MAP_H];
static uint16_t map16[MAP_W * MAP_H];
static float map16_values[MAP_W * MAP_H];
static float receivers_planar[3 * W * H];
static float receivers_interleaved[H * (3 * W + PAD)];

static void make_inputs(void)
{
    for (int i = 0; i < MAP_W * MAP_H; ++i) {
        map[i] = next_unit();
        map16[i] = (uint16_t)(next_unit() * 65535.0f);
        map16_values[i] = (float)map16[i] / 65535.0f;
    }
    for (int y = 0; y < H; ++y)
        for (int x = 0; x < W; ++x)
            for (int c = 0; c < 3; ++c) {
                const float v = next_unit();
                receivers_planar[(c * H + y) * W + x] = v;
                receivers_interleaved[y * (3 * W + PAD) + 3 * x + c] = v;
            }
}

static penumbra_image_view map_view(void)
{
    penumbra_image_view v = {map, MAP_W, MAP_H, 1, 0, 0, PENUMBRA_PLANAR, PENUMBRA_FLOAT32};
    return v;
}

static penumbra_image_view receivers_view(void)
{
    penumbra_image_view v = {receivers_interleaved, W, H, 3, (3 * W + PAD) * sizeof(float), 0,
                             PENUMBRA_INTERLEAVED, PENUMBRA_FLOAT32};
    return v;
}

static penumbra_output_view output_view(float* out, int channels)
{
    penumbra_output_view v = {out, W, H, channels, 0, 0, PENUMBRA_PLANAR};
    return v;
}

static int same_floats(const float* a, const float* b, int n)
{
    for (int i = 0; i < n; ++i)
        if (memcmp(&a[i], &b[i], sizeof(float)) != 0) return 0;
    return 1;
}

struct MethodCase {
    const char* name;
    const char* options[3][2]; /* name, value */
    size_t count;
};

static const struct MethodCase kMethods[] = {
    {"vsm", {{"radius", "3"}}, 1},
    {"msm", {{"radius", "2"}}, 1},
    {"pcf", {{"radius", "1"}, {"depth-bias", "0.002"}}, 2},
    {"pcss", {{"light-size", "0.05"}}, 1},
    {"evsm4", {{"radius", "2"}}, 1},
    /* The depth convention reaches the method table too (the map's values in [0, 1] are perspective depths). */
    {"pcf", {{"depth-convention", "perspective"}, {"near", "0.5"}, {"far", "50"}}, 3},
    {"vsm", {{"depth-convention", "reversed"}, {"near", "1"}, {"far", "20"}}, 3},
};

static void shade_matches_cpp(const char* backend_name, penumbra_context* context, const struct MethodCase* m,
                              const float* map_values, penumbra_image_view map_in)
{
    const char* names[3] = {m->options[0][0], m->options[1][0], m->options[2][0]};
    const char* values[3] = {m->options[0][1], m->options[1][1], m->options[2][1]};
    penumbra_method* method = NULL;
    penumbra_status s = penumbra_method_create(m->name, names, values, m->count, &method);
    CHECK(s == PENUMBRA_OK, "%s: method_create: %s", m->name, penumbra_last_error());
    if (s != PENUMBRA_OK) return;

    float got[W * H], expected[W * H];
    const penumbra_output_view out = output_view(got, 1);
    const penumbra_image_view receivers = receivers_view();
    s = penumbra_shade(context, method, &map_in, &receivers, &out);
    CHECK(s == PENUMBRA_OK, "%s on %s: shade: %s", m->name, backend_name, penumbra_last_error());
    const int r = cpp_shade(backend_name, m->name, names, values, m->count, map_values, MAP_W, MAP_H,
                            receivers_planar, 3, W, H, expected);
    CHECK(r == 0, "%s on %s: the C++ reference failed", m->name, backend_name);
    if (s == PENUMBRA_OK && r == 0)
        CHECK(same_floats(got, expected, W * H), "%s on %s: the C API's result differs from the C++ API's", m->name,
              backend_name);
    penumbra_method_destroy(method);
}

static void blur_matches_cpp(const char* backend_name, penumbra_context* context)
{
    enum { C = 2 };
    float mask[C * W * H], guide[W * H], got[C * W * H], expected[C * W * H];
    for (int i = 0; i < C * W * H; ++i) mask[i] = next_unit();
    for (int i = 0; i < W * H; ++i) guide[i] = 0.5f + next_unit();
    const penumbra_image_view mask_view = {mask, W, H, C, 0, 0, PENUMBRA_PLANAR, PENUMBRA_FLOAT32};
    const penumbra_image_view guide_view = {guide, W, H, 1, 0, 0, PENUMBRA_PLANAR, PENUMBRA_FLOAT32};
    const penumbra_output_view out = output_view(got, C);
    penumbra_blur_options options = penumbra_blur_defaults();
    options.radius = 1;
    const penumbra_status s = penumbra_blur(context, &mask_view, &guide_view, NULL, &options, &out);
    CHECK(s == PENUMBRA_OK, "blur on %s: %s", backend_name, penumbra_last_error());
    const int r = cpp_blur(backend_name, mask, C, guide, W, H, 1, expected);
    CHECK(r == 0, "blur on %s: the C++ reference failed", backend_name);
    if (s == PENUMBRA_OK && r == 0)
        CHECK(same_floats(got, expected, C * W * H), "blur on %s: the C API's result differs", backend_name);
}

/* A call that must fail with `status`, naming `parameter`, with a message holding `says`. */
static void expect_failure(penumbra_status got, penumbra_status status, const char* parameter, const char* says,
                           const char* what);

/* build -> vsm -> blur on device images, one finish, equals the same chain
 * through penumbra_shade and penumbra_blur on views (itself checked against
 * the C++ API above), bit for bit. */
static void device_chain_matches_views(const char* backend_name, penumbra_context* context)
{
    const char* names[] = {"radius"};
    const char* values[] = {"2"};
    penumbra_method* vsm = NULL;
    CHECK(penumbra_method_create("vsm", names, values, 1, &vsm) == PENUMBRA_OK, "vsm: %s", penumbra_last_error());
    static float guide[W * H], visibility[W * H], expected[W * H], got[W * H];
    for (int i = 0; i < W * H; ++i) guide[i] = receivers_planar[2 * W * H + i];
    const penumbra_image_view m = map_view();
    const penumbra_image_view r = {receivers_planar, W, H, 3, 0, 0, PENUMBRA_PLANAR, PENUMBRA_FLOAT32};
    const penumbra_image_view g = {guide, W, H, 1, 0, 0, PENUMBRA_PLANAR, PENUMBRA_FLOAT32};
    const penumbra_image_view v = {visibility, W, H, 1, 0, 0, PENUMBRA_PLANAR, PENUMBRA_FLOAT32};
    const penumbra_output_view vis_out = output_view(visibility, 1), want = output_view(expected, 1),
                               out = output_view(got, 1);
    CHECK(penumbra_shade(context, vsm, &m, &r, &vis_out) == PENUMBRA_OK, "%s", penumbra_last_error());
    CHECK(penumbra_blur(context, &v, &g, NULL, NULL, &want) == PENUMBRA_OK, "%s", penumbra_last_error());

    penumbra_device_image *depth = NULL, *rx = NULL, *gd = NULL, *vis = NULL, *soft = NULL;
    penumbra_device_table* table = NULL;
    CHECK(penumbra_device_image_upload(context, &m, &depth) == PENUMBRA_OK, "%s", penumbra_last_error());
    CHECK(penumbra_device_image_upload(context, &r, &rx) == PENUMBRA_OK, "%s", penumbra_last_error());
    CHECK(penumbra_device_image_upload(context, &g, &gd) == PENUMBRA_OK, "%s", penumbra_last_error());
    CHECK(penumbra_device_image_create(context, W, H, 1, &vis) == PENUMBRA_OK, "%s", penumbra_last_error());
    CHECK(penumbra_device_image_create(context, W, H, 1, &soft) == PENUMBRA_OK, "%s", penumbra_last_error());
    CHECK(penumbra_device_table_create(context, MAP_W, MAP_H, NULL, &table) == PENUMBRA_OK, "%s", penumbra_last_error());
    CHECK(penumbra_enqueue_moment_table(context, depth, table) == PENUMBRA_OK, "%s", penumbra_last_error());
    CHECK(penumbra_enqueue_shade(context, vsm, table, rx, vis) == PENUMBRA_OK, "%s", penumbra_last_error());
    CHECK(penumbra_enqueue_blur(context, vis, gd, NULL, NULL, soft) == PENUMBRA_OK, "%s", penumbra_last_error());
    CHECK(penumbra_finish(context) == PENUMBRA_OK, "%s", penumbra_last_error());
    CHECK(penumbra_device_image_download(context, soft, &out) == PENUMBRA_OK, "%s", penumbra_last_error());
    CHECK(same_floats(got, expected, W * H), "device chain on %s: differs from the views' chain", backend_name);

    /* Bad input: another method, a wrong output size, a foreign cl_mem on a CPU context, NULL handles. */
    penumbra_method* pcf = NULL;
    CHECK(penumbra_method_create("pcf", NULL, NULL, 0, &pcf) == PENUMBRA_OK, "%s", penumbra_last_error());
    expect_failure(penumbra_enqueue_shade(context, pcf, table, rx, vis), PENUMBRA_INVALID_ARGUMENT, "method", "vssm",
                   "a method that is not device-resident");
    expect_failure(penumbra_enqueue_shade(context, vsm, table, rx, rx), PENUMBRA_INVALID_ARGUMENT,
                   "out", "1-channel", "a 3-channel output");
    expect_failure(penumbra_enqueue_blur(context, NULL, gd, NULL, NULL, soft), PENUMBRA_INVALID_ARGUMENT, "mask",
                   "NULL", "a NULL mask");
    if (strncmp(backend_name, "opencl", 6) != 0) {
        int not_a_buffer = 0;
        penumbra_device_image* none = NULL;
        expect_failure(penumbra_device_image_wrap(context, &not_a_buffer, W, H, 1, 0, &none),
                       PENUMBRA_INVALID_ARGUMENT, "buffer", "cl_mem", "a cl_mem on a CPU context");
    }
    penumbra_method_destroy(pcf);
    penumbra_device_image_destroy(depth);
    penumbra_device_image_destroy(rx);
    penumbra_device_image_destroy(gd);
    penumbra_device_image_destroy(vis);
    penumbra_device_image_destroy(soft);
    penumbra_device_table_destroy(table);
    penumbra_method_destroy(vsm);
}

/* The depth conventions' float64 reference, from their definitions (as
 * tests/support/depth_conventions.h): normalised l is the distance d = near +
 * l (far - near); linear stores d, perspective z = far (d - near) / (d (far -
 * near)), reversed 1 - z. Back: d = near far / (far - z (far - near)), then l. */
static double stored_from_normalized(double l, penumbra_depth_convention c)
{
    const double n = c.near_plane, f = c.far_plane, d = n + l * (f - n);
    const double projected = f * (d - n) / (d * (f - n));
    switch (c.kind) {
    case PENUMBRA_DEPTH_LINEAR: return d;
    case PENUMBRA_DEPTH_PERSPECTIVE: return projected;
    case PENUMBRA_DEPTH_REVERSED: return 1.0 - projected;
    default: return l;
    }
}

static double normalized_from_projected(double z, penumbra_depth_convention c)
{
    const double n = c.near_plane, f = c.far_plane;
    return (n * f / (f - z * (f - n)) - n) / (f - n);
}

static double normalized_from_stored(double s, penumbra_depth_convention c)
{
    switch (c.kind) {
    case PENUMBRA_DEPTH_LINEAR: return (s - c.near_plane) / ((double)c.far_plane - c.near_plane);
    case PENUMBRA_DEPTH_PERSPECTIVE: return normalized_from_projected(s, c);
    case PENUMBRA_DEPTH_REVERSED: return normalized_from_projected(1.0 - s, c);
    default: return s;
    }
}

/* `n` values written in convention c (in double, stored float32) into
 * `stored`, and what that float32 storage holds, back in normalised depth,
 * into `held`. */
static void in_convention(const float* values, int n, penumbra_depth_convention c, float* stored, float* held)
{
    for (int i = 0; i < n; ++i) {
        stored[i] = (float)stored_from_normalized(values[i], c);
        held[i] = (float)normalized_from_stored(stored[i], c);
    }
}

static penumbra_method* method_in(const char* name, const char* convention_name)
{
    const char* names[] = {"radius", "depth-convention", "near", "far"};
    const char* values[] = {"2", convention_name, "0.5", "50"};
    const int vsm = strcmp(name, "vsm") == 0; /* vssm reads no radius */
    const size_t count = convention_name ? 4 : 1;
    penumbra_method* method = NULL;
    CHECK(penumbra_method_create(name, names + !vsm, values + !vsm, count - !vsm, &method) == PENUMBRA_OK,
          "%s in %s: %s", name, convention_name ? convention_name : "normalized", penumbra_last_error());
    return method;
}

static double max_difference(const float* a, const float* b, int n)
{
    double largest = 0.0;
    for (int i = 0; i < n; ++i) {
        const double d = fabs((double)a[i] - b[i]);
        if (d > largest || isnan(d)) largest = d; /* a NaN is the largest */
    }
    return largest;
}

/* Device chain (upload, table in c, lookup, finish, download) of `method` on
 * a map and receivers stored in c, into `got`. */
static void device_chain_in(penumbra_context* context, const penumbra_depth_convention* c,
                            const penumbra_method* method, const float* stored_map, const float* stored_rx, float* got)
{
    const penumbra_image_view m = {stored_map, MAP_W, MAP_H, 1, 0, 0, PENUMBRA_PLANAR, PENUMBRA_FLOAT32};
    const penumbra_image_view r = {stored_rx, W, H, 3, 0, 0, PENUMBRA_PLANAR, PENUMBRA_FLOAT32};
    const penumbra_output_view out = output_view(got, 1);
    penumbra_device_image *depth = NULL, *rx = NULL, *vis = NULL;
    penumbra_device_table* table = NULL;
    CHECK(penumbra_device_image_upload(context, &m, &depth) == PENUMBRA_OK, "%s", penumbra_last_error());
    CHECK(penumbra_device_image_upload(context, &r, &rx) == PENUMBRA_OK, "%s", penumbra_last_error());
    CHECK(penumbra_device_image_create(context, W, H, 1, &vis) == PENUMBRA_OK, "%s", penumbra_last_error());
    CHECK(penumbra_device_table_create(context, MAP_W, MAP_H, c, &table) == PENUMBRA_OK, "%s", penumbra_last_error());
    CHECK(penumbra_enqueue_moment_table(context, depth, table) == PENUMBRA_OK, "%s", penumbra_last_error());
    CHECK(penumbra_enqueue_shade(context, method, table, rx, vis) == PENUMBRA_OK, "%s", penumbra_last_error());
    CHECK(penumbra_device_image_download(context, vis, &out) == PENUMBRA_OK, "%s", penumbra_last_error());
    penumbra_device_image_destroy(depth);
    penumbra_device_image_destroy(rx);
    penumbra_device_image_destroy(vis);
    penumbra_device_table_destroy(table);
}

/* penumbra_shade of `method` on planar packed map and receivers, into `out`. */
static void shade_planar(penumbra_context* context, const penumbra_method* method, const float* map_values,
                         const float* rx_values, float* out)
{
    const penumbra_image_view m = {map_values, MAP_W, MAP_H, 1, 0, 0, PENUMBRA_PLANAR, PENUMBRA_FLOAT32};
    const penumbra_image_view r = {rx_values, W, H, 3, 0, 0, PENUMBRA_PLANAR, PENUMBRA_FLOAT32};
    const penumbra_output_view o = output_view(out, 1);
    CHECK(penumbra_shade(context, method, &m, &r, &o) == PENUMBRA_OK, "%s", penumbra_last_error());
}

/* A map and receivers written in each convention (near 0.5, far 50, as the
 * C++ tests') through the device chain, its table made in the convention and
 * its method naming it: vsm (radius 2, a table lookup) and vssm equal, within
 * 1e-4 (the C++ DepthConventions.EachMethodShadesItsStoredMapAsTheNormalisedOne
 * tolerance: the kernels' float conversion against the float64 one, times a
 * Chebyshev bound's slope), penumbra_shade in normalised depth on the
 * normalised map the convention's float32 storage holds; and bit for bit
 * penumbra_shade on the stored inputs in the convention (one conversion, the
 * same kernels). Normalised runs once with a zeroed struct: the NULL table's. */
static void device_chain_in_each_convention(const char* backend_name, penumbra_context* context)
{
    static const struct {
        penumbra_depth_kind kind;
        const char* name;
    } kConventions[] = {{PENUMBRA_DEPTH_NORMALIZED, NULL},
                        {PENUMBRA_DEPTH_LINEAR, "linear"},
                        {PENUMBRA_DEPTH_PERSPECTIVE, "perspective"},
                        {PENUMBRA_DEPTH_REVERSED, "reversed"}};
    static const char* const kMethodNames[] = {"vsm", "vssm"};
    static float stored_map[MAP_W * MAP_H], held_map[MAP_W * MAP_H], stored_rx[3 * W * H], held_rx[3 * W * H];
    for (size_t k = 0; k < sizeof kConventions / sizeof kConventions[0]; ++k) {
        const int normalized = kConventions[k].kind == PENUMBRA_DEPTH_NORMALIZED;
        const penumbra_depth_convention c = {kConventions[k].kind, normalized ? 0.0f : 0.5f,
                                             normalized ? 0.0f : 50.0f};
        const char* label = normalized ? "normalized" : kConventions[k].name;
        in_convention(map, MAP_W * MAP_H, c, stored_map, held_map);
        memcpy(stored_rx, receivers_planar, sizeof stored_rx);
        memcpy(held_rx, receivers_planar, sizeof held_rx);
        in_convention(receivers_planar + 2 * W * H, W * H, c, stored_rx + 2 * W * H, held_rx + 2 * W * H);
        for (size_t i = 0; i < 2; ++i) {
            penumbra_method* in_c = method_in(kMethodNames[i], kConventions[k].name);
            penumbra_method* plain = method_in(kMethodNames[i], NULL);
            float got[W * H], held[W * H], host[W * H];
            device_chain_in(context, &c, in_c, stored_map, stored_rx, got);
            shade_planar(context, plain, held_map, held_rx, held);
            shade_planar(context, in_c, stored_map, stored_rx, host);
            const double d = max_difference(got, held, W * H);
            CHECK(d <= 1e-4, "%s device chain in %s on %s: %.3g from the normalised map's shade", kMethodNames[i],
                  label, backend_name, d);
            CHECK(same_floats(got, host, W * H), "%s device chain in %s on %s: differs from penumbra_shade in it",
                  kMethodNames[i], label, backend_name);
            penumbra_method_destroy(in_c);
            penumbra_method_destroy(plain);
        }
    }
}

/* Bad conventions for a device table: each is PENUMBRA_INVALID_ARGUMENT
 * naming its field, the handle left NULL; a lookup whose method names another
 * convention than the table's is refused; a map value outside the table's
 * convention is bad data (at the build on the CPU backends, at finish on
 * OpenCL). */
static void device_table_refuses_bad_conventions(penumbra_context* context)
{
    static const struct {
        penumbra_depth_convention c;
        const char* parameter;
        const char* says;
        const char* what;
    } kBad[] = {
        {{(penumbra_depth_kind)42, 0.5f, 50.0f}, "depth-convention", "42", "an unknown convention"},
        {{PENUMBRA_DEPTH_KIND_MAX_ENUM, 0.5f, 50.0f}, "depth-convention", "2147483647", "the range marker"},
        {{PENUMBRA_DEPTH_LINEAR, 5.0f, 5.0f}, "far", "far > near", "near = far"},
        {{PENUMBRA_DEPTH_PERSPECTIVE, 2.0f, 1.0f}, "far", "far > near", "near > far"},
        {{PENUMBRA_DEPTH_PERSPECTIVE, 0.0f, 10.0f}, "near", "near > 0", "a perspective near of 0"},
        {{PENUMBRA_DEPTH_REVERSED, -1.0f, 10.0f}, "near", "near > 0", "a reversed near below 0"},
        {{PENUMBRA_DEPTH_LINEAR, NAN, 1.0f}, "near", "finite near", "a NaN near"},
        {{PENUMBRA_DEPTH_REVERSED, 0.1f, INFINITY}, "far", "infinite far plane", "an infinite far"},
        {{PENUMBRA_DEPTH_LINEAR, 0.0f, 0.0f}, "near", "both 0", "linear depth without its planes"},
        {{PENUMBRA_DEPTH_NORMALIZED, 0.5f, 0.0f}, "near", "reads no near", "a near on normalised depth"},
        {{PENUMBRA_DEPTH_NORMALIZED, 0.0f, NAN}, "far", "reads no far", "a NaN far on normalised depth"},
    };
    for (size_t i = 0; i < sizeof kBad / sizeof kBad[0]; ++i) {
        penumbra_device_table* table = NULL;
        expect_failure(penumbra_device_table_create(context, MAP_W, MAP_H, &kBad[i].c, &table),
                       PENUMBRA_INVALID_ARGUMENT, kBad[i].parameter, kBad[i].says, kBad[i].what);
        CHECK(table == NULL, "%s: a failed table_create leaves the handle NULL", kBad[i].what);
        penumbra_device_table_destroy(table);
    }

    const penumbra_depth_convention linear = {PENUMBRA_DEPTH_LINEAR, 0.5f, 50.0f};
    penumbra_device_table* table = NULL;
    penumbra_device_image *depth = NULL, *rx = NULL, *vis = NULL;
    const penumbra_image_view m = map_view(); /* values in [0, 1]: below linear's near, 0.5, for most */
    const penumbra_image_view r = {receivers_planar, W, H, 3, 0, 0, PENUMBRA_PLANAR, PENUMBRA_FLOAT32};
    CHECK(penumbra_device_table_create(context, MAP_W, MAP_H, &linear, &table) == PENUMBRA_OK, "%s",
          penumbra_last_error());
    CHECK(penumbra_device_image_upload(context, &m, &depth) == PENUMBRA_OK, "%s", penumbra_last_error());
    CHECK(penumbra_device_image_upload(context, &r, &rx) == PENUMBRA_OK, "%s", penumbra_last_error());
    CHECK(penumbra_device_image_create(context, W, H, 1, &vis) == PENUMBRA_OK, "%s", penumbra_last_error());
    penumbra_method* normalized_vsm = method_in("vsm", NULL);
    penumbra_method* perspective_vsm = method_in("vsm", "perspective");
    expect_failure(penumbra_enqueue_shade(context, normalized_vsm, table, rx, vis), PENUMBRA_INVALID_ARGUMENT,
                   "depth-convention", "the table holds a map of linear depth", "a normalised lookup on a linear table");
    expect_failure(penumbra_enqueue_shade(context, perspective_vsm, table, rx, vis), PENUMBRA_INVALID_ARGUMENT,
                   "depth-convention", "given as perspective", "a perspective lookup on a linear table");
    penumbra_status s = penumbra_enqueue_moment_table(context, depth, table);
    if (s == PENUMBRA_OK) s = penumbra_finish(context);
    expect_failure(s, PENUMBRA_INVALID_DATA, "depth", "outside [0.5, 50]", "a normalised map in a linear table");
    CHECK(penumbra_finish(context) == PENUMBRA_OK, "the failure was reported once: %s", penumbra_last_error());
    penumbra_method_destroy(normalized_vsm);
    penumbra_method_destroy(perspective_vsm);
    penumbra_device_image_destroy(depth);
    penumbra_device_image_destroy(rx);
    penumbra_device_image_destroy(vis);
    penumbra_device_table_destroy(table);
}

static void expect_failure(penumbra_status got, penumbra_status status, const char* parameter, const char* says,
                           const char* what)
{
    CHECK(got == status, "%s: status %s, expected %s (%s)", what, penumbra_status_name(got),
          penumbra_status_name(status), penumbra_last_error());
    CHECK(strcmp(penumbra_last_error_parameter(), parameter) == 0, "%s: parameter '%s', expected '%s'", what,
          penumbra_last_error_parameter(), parameter);
    CHECK(strstr(penumbra_last_error(), says) != NULL, "%s: message '%s' lacks '%s'", what, penumbra_last_error(),
          says);
}

static void bad_input(penumbra_context* context)
{
    penumbra_method* method = NULL;
    const char* radius[1] = {"radius"};
    const char* minus_one[1] = {"-1"};
    expect_failure(penumbra_method_create("nope", NULL, NULL, 0, &method), PENUMBRA_INVALID_ARGUMENT, "method",
                   "vsm", "an unknown method");
    CHECK(method == NULL, "a failed method_create leaves the handle NULL");
    expect_failure(penumbra_method_create("vsm", radius, minus_one, 1, &method), PENUMBRA_INVALID_ARGUMENT, "radius",
                   "radius", "a radius of -1");
    const char* convention[3] = {"depth-convention", "near", "far"};
    const char* zero_near[3] = {"perspective", "0", "10"};
    expect_failure(penumbra_method_create("pcf", convention, zero_near, 3, &method), PENUMBRA_INVALID_ARGUMENT, "near",
                   "near > 0", "a perspective depth with near 0");
    penumbra_context* none = NULL;
    expect_failure(penumbra_context_create((penumbra_backend)42, &none), PENUMBRA_INVALID_ARGUMENT, "backend", "42",
                   "an unknown backend");
    expect_failure(penumbra_context_create(PENUMBRA_BACKEND_MAX_ENUM, &none), PENUMBRA_INVALID_ARGUMENT, "backend",
                   "2147483647", "the range marker, not a backend");
    CHECK(none == NULL, "a failed context_create leaves the handle NULL");

    CHECK(penumbra_method_create("vsm", NULL, NULL, 0, &method) == PENUMBRA_OK, "vsm: %s", penumbra_last_error());
    float out_values[W * H];
    const penumbra_output_view out = output_view(out_values, 1);
    const penumbra_image_view m = map_view();
    penumbra_image_view r = receivers_view();
    expect_failure(penumbra_shade(NULL, method, &m, &r, &out), PENUMBRA_INVALID_ARGUMENT, "context", "NULL",
                   "a NULL context");
    expect_failure(penumbra_shade(context, method, &m, NULL, &out), PENUMBRA_INVALID_ARGUMENT, "receivers", "NULL",
                   "NULL receivers");
    r.row_pitch = 3 * W * sizeof(float) - 4;
    expect_failure(penumbra_shade(context, method, &m, &r, &out), PENUMBRA_INVALID_ARGUMENT, "receivers",
                   "shorter than a row", "a row pitch too small");
    r = receivers_view();
    r.data = NULL;
    expect_failure(penumbra_shade(context, method, &m, &r, &out), PENUMBRA_INVALID_ARGUMENT, "receivers",
                   "null data pointer", "a NULL pointer in a view");
    r = receivers_view();
    r.height = 0;
    expect_failure(penumbra_shade(context, method, &m, &r, &out), PENUMBRA_INVALID_ARGUMENT, "receivers",
                   "at least one pixel", "an empty view");
    penumbra_output_view small = out;
    small.width = W - 1;
    r = receivers_view();
    expect_failure(penumbra_shade(context, method, &m, &r, &small), PENUMBRA_INVALID_ARGUMENT, "", "receivers",
                   "an output of another size");

    /* A NaN receiver is bad data, named with its pixel. */
    float saved = receivers_interleaved[3 * 4 + 2];
    receivers_interleaved[3 * 4 + 2] = NAN;
    expect_failure(penumbra_shade(context, method, &m, &r, &out), PENUMBRA_INVALID_DATA, "receivers", "(4, 0)",
                   "a NaN receiver");
    receivers_interleaved[3 * 4 + 2] = saved;
    penumbra_method_destroy(method);

    penumbra_blur_options options = penumbra_blur_defaults();
    options.radius = 99;
    const penumbra_image_view guide = {map, W, H, 1, MAP_W * sizeof(float), 0, PENUMBRA_PLANAR, PENUMBRA_FLOAT32};
    const penumbra_output_view blurred = output_view(out_values, 1);
    expect_failure(penumbra_blur(context, &guide, &guide, NULL, &options, &blurred), PENUMBRA_INVALID_ARGUMENT, "",
                   "radius", "a blur radius of 99");
}

int main(void)
{
    make_inputs();
    static const struct {
        const char* name;
        penumbra_backend backend;
    } kBackends[] = {{"scalar", PENUMBRA_BACKEND_SCALAR}, {"simd", PENUMBRA_BACKEND_SIMD},
                     {"opencl", PENUMBRA_BACKEND_OPENCL}};
    int ran = 0;
    for (size_t b = 0; b < sizeof kBackends / sizeof kBackends[0]; ++b) {
        penumbra_context* context = NULL;
        const penumbra_status s = penumbra_context_create(kBackends[b].backend, &context);
        if (s == PENUMBRA_UNAVAILABLE) {
            printf("%s: unavailable here (%s); skipped\n", kBackends[b].name, penumbra_last_error());
            continue;
        }
        CHECK(s == PENUMBRA_OK, "context %s: %s", kBackends[b].name, penumbra_last_error());
        if (s != PENUMBRA_OK) continue;
        printf("%s: %s\n", kBackends[b].name, penumbra_context_description(context));
        ++ran;
        for (size_t i = 0; i < sizeof kMethods / sizeof kMethods[0]; ++i)
            shade_matches_cpp(kBackends[b].name, context, &kMethods[i], map, map_view());
        const penumbra_image_view depth16 = {map16, MAP_W, MAP_H, 1, 0, 0, PENUMBRA_PLANAR, PENUMBRA_UINT16};
        shade_matches_cpp(kBackends[b].name, context, &kMethods[0], map16_values, depth16);
        blur_matches_cpp(kBackends[b].name, context);
        device_chain_matches_views(kBackends[b].name, context);
        device_chain_in_each_convention(kBackends[b].name, context);
        device_table_refuses_bad_conventions(context);
        bad_input(context);
        penumbra_context_destroy(context);
    }
    CHECK(ran >= 2, "only %d backends ran (scalar and simd are always built)", ran);
    printf("%d failures\n", failures);
    return failures == 0 ? 0 : 1;
}
