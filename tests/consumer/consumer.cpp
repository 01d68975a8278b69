// Filters a tiny map through the installed library and checks the answer.
#include <penumbra/chebyshev.h>

#include <cstdio>

int main()
{
    penumbra::Context ctx(penumbra::ContextOptions{penumbra::Backend::Scalar, {}});
    penumbra::Image map(4, 4, 1), rx(1, 1, 3);
    map.fill(0, 0.25f);
    rx.at(0, 0, 0) = rx.at(1, 0, 0) = 0.5f;
    rx.at(2, 0, 0) = 0.75f;  // behind the flat occluder: in shadow
    const auto table = penumbra::build_moment_table(ctx, map);
    const float lit = penumbra::vsm(ctx, table, rx, {1}).at(0, 0, 0);
    std::printf("visibility %g\n", lit);
    return lit < 0.01f ? 0 : 1;
}
