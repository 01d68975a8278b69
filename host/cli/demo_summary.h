// The demo's summary: per scene, the most accurate method within each time
// budget per frame and overall, among the rows scored against the scene's
// light (DemoTruth::Shadow: the obscurance and sun rows measure other
// things), and the truth's own noise, below which two methods' RMSEs cannot
// be told apart (such near-ties are named with the pick).
#pragma once

#include <string>
#include <utility>
#include <vector>

#include "demo_results.h"

namespace penumbra::cli {

// The default budgets, milliseconds per timed frame (1920x1080 by default):
// 60, 30 and 10 frames per second. GPU budgets (1, 4 ms) fit no row on a
// 2-core CPU, whose fastest 1080p row takes about 10 ms (docs/demo.md);
// --budgets sets others.
inline const std::vector<double> kDemoBudgetsMs = {16.0, 33.0, 100.0};

struct DemoPick {
    double budget_ms = 0;                 // 0: no budget (the most accurate overall)
    const DemoRow* best = nullptr;        // null: nothing fits the budget
    std::vector<const DemoRow*> ties;     // other methods' best rows within the truth's noise of it
};

struct SceneSummary {
    std::string scene;
    double truth_noise = 0;  // RMSE of the truth against a truth with 4x the rays
    std::vector<DemoPick> picks;  // one per budget, then the overall one
};

// `rows` must outlive the result (the picks point into it).
std::vector<SceneSummary> summarize_scenes(const std::vector<DemoRow>& rows,
                                           const std::vector<std::pair<std::string, double>>& truth_noise,
                                           const std::vector<double>& budgets_ms);

// "best" and its ties as one line's text: "vssm L=0.05 (RMSE 0.0213, 3.1 ms; ties: msm-soft L=0.05)".
std::string describe_pick(const DemoPick& pick);

}  // namespace penumbra::cli
