/* The C++ API's result on the same input as the C test (c_api_test.c): the
 * reference the C API must reproduce, callable from C. Images are planar and
 * packed. Returns 0 on success, 1 when the backend is unavailable here, 2 on
 * any other error (printed). */
#ifndef PENUMBRA_TESTS_CPP_RESULT_H
#define PENUMBRA_TESTS_CPP_RESULT_H

#include <stddef.h>

#ifdef __cplusplus
extern "C" {
#endif

/* backend: "scalar", "simd", "opencl". */
int cpp_shade(const char* backend, const char* method, const char* const* names, const char* const* values,
              size_t count, const float* map, int map_width, int map_height, const float* receivers,
              int receiver_channels, int width, int height, float* out);
/* The blur with the library's default options but `radius`. */
int cpp_blur(const char* backend, const float* mask, int channels, const float* guide, int width, int height,
             int radius, float* out);

#ifdef __cplusplus
}
#endif

#endif
