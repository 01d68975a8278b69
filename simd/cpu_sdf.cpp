// CPU launches of the SDF soft shadows (kernels/sdf.h): the per-pixel launch,
// one strip of lanes per call, rows spread over TBB's threads.
//
// Schedule notes (docs/sdf.md, "Lane utilisation"): a strip's march runs until
// its slowest lane is done. Strips along rows keep 91% of lane-steps active on
// the contact scene at 1920x1080 with 16 lanes (analytic; 86% through a grid).
// 4x4 tiles of receivers raise that to 95% (92%), but packing each band of
// rows into tile order cost more than the 4-6% of lane-steps it saved (a
// measured prototype: +25 ms of CPU per frame against about -8 ms), so strips
// stay along rows. Most of the idle lane-steps are a few long marches (rays
// leaving a curved surface almost tangentially) that no grouping removes.
#include "simd/cpu_backend.h"
#include "simd/cpu_schedule.h"

namespace penumbra::cpu {

void CpuBackend::sdf_grid(const float* data, std::size_t, const Image& positions, const Image& normals,
                          const SdfParams& p, Image& out, int* bad_rows)
{
    launch_pixels<KernelId::sdf_grid>(kernels_, out.width(), out.height(), data, positions.plane(0), normals.plane(0),
                                      out.plane(0), bad_rows, p);
}

void CpuBackend::sdf_analytic(const float* data, std::size_t, const Image& positions, const Image& normals,
                              const SdfParams& p, Image& out, int* bad_rows)
{
    launch_pixels<KernelId::sdf_analytic>(kernels_, out.width(), out.height(), data, positions.plane(0),
                                          normals.plane(0), out.plane(0), bad_rows, p);
}

}  // namespace penumbra::cpu
