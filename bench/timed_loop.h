// The timing loop every per-backend benchmark of penumbra_bench shares: the
// call once untimed (PoCL's first launch, page faults), then timed, inside a
// tbb::task_arena of `threads` (0: the backend's own threads, OpenCL), and
// an error (a backend that cannot start) reported as the case's skip.
#pragma once

#include <benchmark/benchmark.h>
#include <tbb/task_arena.h>

#include <exception>
#include <string>

#include "bench_inputs.h"

namespace penumbra::bench {

// False when the case was skipped with an error.
template <class Fn>
bool timed_loop(benchmark::State& state, const std::string& backend, int threads, Fn&& call)
{
    try {
        Context& ctx = context(backend);
        state.SetLabel(ctx.description());
        auto loop = [&] {
            call(ctx);
            for (auto _ : state) {
                call(ctx);
                benchmark::ClobberMemory();
            }
        };
        if (threads > 0) tbb::task_arena(threads).execute(loop);
        else loop();
    } catch (const std::exception& e) {
        state.SkipWithError(e.what());
        return false;
    }
    return true;
}

}  // namespace penumbra::bench
