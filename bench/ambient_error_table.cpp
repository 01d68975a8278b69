// The error table of docs/ambient.md: SH irradiance of each rig of
// tests/support/ambient_cases.h against its exact irradiance (sum of colour x
// intensity x max(0, n . l)) over 100,000 normals evenly spread on the sphere,
// evaluated by the library's kernel on the default backend (or
// PENUMBRA_BACKEND). Errors are in units of the rig's strongest light's peak
// irradiance (its intensity: every rig's strongest light has intensity 1):
// mean and max of |SH - exact| over normals and channels, and the lowest
// SH value (negative: ringing below zero). Prints a Markdown table; asserts
// nothing.
//   build/bench/ambient_error_table
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>

#include "penumbra/ambient.h"
#include "support/ambient_cases.h"

using namespace penumbra;

namespace {

struct Row {
    const char* name;
    ShOptions options;
};

void measure(Context& ctx, const testing::NamedRig& rig, const Row& row, const Image& normals)
{
    AmbientLighting l;
    l.light = project_rig(rig.rig, row.options);
    const Image e = ambient_irradiance(ctx, normals, l);
    double sum = 0, worst = 0, lowest = 1e30;
    long n = 0;
    for (int y = 0; y < normals.height(); ++y)
        for (int x = 0; x < normals.width(); ++x) {
            const std::array<double, 3> exact = exact_irradiance(rig.rig, testing::normal_at(normals, x, y));
            for (int c = 0; c < 3; ++c) {
                const double d = std::abs(e.at(c, x, y) - exact[c]);
                sum += d;
                worst = std::max(worst, d);
                lowest = std::min(lowest, double(e.at(c, x, y)));
                ++n;
            }
        }
    std::printf("| %-14s | %-24s | %7.4f | %7.4f | %8.4f |\n", rig.name.c_str(), row.name, sum / n, worst, lowest);
}

}  // namespace

int main()
{
    Context ctx;
    std::printf("backend: %s\n\n", ctx.description().c_str());
    const Image normals = testing::sphere_of_normals(100000, 400);
    const Row rows[] = {{"order 2", {2, ShWindow::None}},
                        {"order 2, Hanning w=4", {2, ShWindow::Hanning, 4.0}},
                        {"order 2, Lanczos w=4", {2, ShWindow::Lanczos, 4.0}},
                        {"order 1", {1, ShWindow::None}}};
    std::printf("| rig            | projection               |  mean   |   max   |  lowest  |\n");
    std::printf("|----------------|--------------------------|---------|---------|----------|\n");
    for (const testing::NamedRig& rig : testing::error_table_rigs())
        for (const Row& row : rows) measure(ctx, rig, row, normals);
    return 0;
}
