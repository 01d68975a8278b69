// The deviation table of issue 9: every moment method, in every mode the
// tool accepts, against the float64 reference of tests/support/
// fidelity_reference.h (direct loops over the window of the float32 input
// depths), on the smooth and the two-layer map at 33x17, 257^2 and 1024^2,
// box radii 0, 1, 2, 4, 8 (vssm and msm-soft: light size 0.02), receivers on,
// in front of and behind the surface (tests/support/fidelity_cases.h).
//
// Per method, mode and radius: the worst |library - reference|, its 99th
// percentile, the share beyond the method's tolerance (2e-4; msm, msm-soft
// 1e-3), the share beyond 1e-2, and the share that fails the ill-conditioned
// rule (docs/fidelity.md). Backend: the context's default (PENUMBRA_BACKEND
// overrides it).
// The opt-in 16-bit MSM mode has two rows: against the reference on its
// dequantized moments (the arithmetic after the quantization) and against the
// input depths (what its quantization costs).
// usage: moment_fidelity [receivers per case, default 2000]
#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <map>
#include <string>
#include <utility>

#include "support/fidelity_cases.h"

using namespace penumbra;
using namespace penumbra::testing::fidelity;

namespace {

struct Row {
    Tally total;
};

void merge(Tally& into, const Tally& t)
{
    into.receivers += t.receivers;
    into.beyond += t.beyond;
    into.beyond_1e2 += t.beyond_1e2;
    into.failed += t.failed;
    into.ill += t.ill;
    into.worst = std::max(into.worst, t.worst);
    into.deviations.insert(into.deviations.end(), t.deviations.begin(), t.deviations.end());
}

double p99(std::vector<double> d)
{
    if (d.empty()) return 0;
    const std::size_t k = std::min(d.size() - 1, std::size_t(0.99 * double(d.size())));
    std::nth_element(d.begin(), d.begin() + std::ptrdiff_t(k), d.end());
    return d[k];
}

double percent(int part, int whole) { return whole ? 100.0 * part / whole : 0.0; }

}  // namespace

int main(int argc, char** argv)
{
    const int count = argc > 1 ? std::atoi(argv[1]) : 2000;
    Context ctx;
    const std::pair<int, int> sizes[] = {{33, 17}, {257, 257}, {1024, 1024}};
    const Method methods[] = {Method::Vsm, Method::Vssm, Method::Msm, Method::MsmSoft, Method::Evsm2, Method::Evsm4};
    std::map<std::tuple<int, std::string, int>, Tally> rows;
    std::uint32_t seed = 9;
    for (auto [w, h] : sizes)
        for (int layered = 0; layered < 2; ++layered) {
            const Image map = layered ? two_layer_map(w, h) : smooth_map(w, h);
            const Image rx = receivers_for(map, count, seed++);
            for (Method m : methods)
                for (Mode mode : modes_of(m)) {
                    std::vector<Setting> settings;
                    if (is_soft(m)) settings.push_back({0, 0.02f});
                    else
                        for (int r : {0, 1, 2, 4, 8}) settings.push_back({r, 0.02f});
                    StoredMoments stored;
                    std::vector<LibraryRun> runs = run_library(ctx, m, mode, map, rx, settings, &stored);
                    for (std::size_t i = 0; i < runs.size(); ++i) {
                        Params& p = runs[i].params;
                        const int radius = is_soft(m) ? -1 : settings[i].radius;
                        if (p.stored) {  // the 16-bit opt-in: its arithmetic, then its quantization error
                            merge(rows[{int(m), mode_name(m, mode) + ", vs its dequantized moments", radius}],
                                  judge_all(m, map, rx, runs[i].out, p, 0));
                            p.stored = nullptr;
                        }
                        merge(rows[{int(m), mode_name(m, mode), radius}], judge_all(m, map, rx, runs[i].out, p, 0));
                    }
                }
        }
    std::printf("| method | mode | radius | receivers | worst | p99 | share > tol | share > 1e-2 | ill-conditioned | fail the rule |\n");
    std::printf("|---|---|---|---|---|---|---|---|---|---|\n");
    for (const auto& [key, t] : rows) {
        const auto& [m, mode, radius] = key;
        const std::string r = radius < 0 ? "L 0.02" : std::to_string(radius);
        std::printf("| %s | %s | %s | %d | %.3g | %.3g | %.2f%% | %.2f%% | %.2f%% | %.2f%% |\n",
                    method_name(Method(m)).c_str(), mode.c_str(), r.c_str(), t.receivers, t.worst, p99(t.deviations),
                    percent(t.beyond, t.receivers), percent(t.beyond_1e2, t.receivers), percent(t.ill, t.receivers),
                    percent(t.failed, t.receivers));
    }
    return 0;
}
