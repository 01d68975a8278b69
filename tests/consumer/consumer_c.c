/* The installed C API from a C program: a VSM lookup of a flat occluder,
 * the same check as consumer.cpp, and a bad call's status and message. */
#include <penumbra/penumbra.h>

#include <stdio.h>
#include <string.h>

int main(void)
{
    penumbra_context* context = NULL;
    if (penumbra_context_create(PENUMBRA_BACKEND_SCALAR, &context) != PENUMBRA_OK) {
        fprintf(stderr, "%s\n", penumbra_last_error());
        return 1;
    }
    const char* names[1] = {"radius"};
    const char* values[1] = {"1"};
    penumbra_method* vsm = NULL;
    if (penumbra_method_create("vsm", names, values, 1, &vsm) != PENUMBRA_OK) {
        fprintf(stderr, "%s\n", penumbra_last_error());
        return 1;
    }
    float map[16], receiver[3] = {0.5f, 0.5f, 0.75f}, visibility = -1.0f; /* behind the occluder */
    for (int i = 0; i < 16; ++i) map[i] = 0.25f;
    const penumbra_image_view map_view = {map, 4, 4, 1, 0, 0, PENUMBRA_PLANAR, PENUMBRA_FLOAT32};
    const penumbra_image_view receiver_view = {receiver, 1, 1, 3, 0, 0, PENUMBRA_INTERLEAVED, PENUMBRA_FLOAT32};
    const penumbra_output_view out = {&visibility, 1, 1, 1, 0, 0, PENUMBRA_PLANAR};
    const penumbra_status shaded = penumbra_shade(context, vsm, &map_view, &receiver_view, &out);
    const penumbra_status refused = penumbra_shade(context, vsm, NULL, &receiver_view, &out);
    printf("visibility %g; a NULL map: %s (%s)\n", visibility, penumbra_status_name(refused), penumbra_last_error());
    penumbra_method_destroy(vsm);
    penumbra_context_destroy(context);
    return shaded == PENUMBRA_OK && visibility < 0.01f && refused == PENUMBRA_INVALID_ARGUMENT &&
                   strcmp(penumbra_last_error_parameter(), "depth") == 0
               ? 0
               : 1;
}
