#include "demo_summary.h"

#include <cstdio>
#include <map>

namespace penumbra::cli {
namespace {

bool fits(const DemoRow& row, double budget_ms)
{
    return budget_ms <= 0 || row.time.frame_ms <= budget_ms;
}

// Each method's most accurate row among those that fit the budget.
std::map<std::string, const DemoRow*> best_per_method(const std::vector<const DemoRow*>& rows, double budget_ms)
{
    std::map<std::string, const DemoRow*> best;
    for (const DemoRow* row : rows) {
        if (!fits(*row, budget_ms)) continue;
        const DemoRow*& slot = best[row->method];
        if (!slot || row->rmse < slot->rmse) slot = row;
    }
    return best;
}

DemoPick pick(const std::vector<const DemoRow*>& rows, double budget_ms, double noise)
{
    DemoPick result{budget_ms, nullptr, {}};
    const std::map<std::string, const DemoRow*> best = best_per_method(rows, budget_ms);
    for (const auto& [method, row] : best)
        if (!result.best || row->rmse < result.best->rmse) result.best = row;
    if (!result.best) return result;
    for (const auto& [method, row] : best)
        if (row != result.best && row->rmse - result.best->rmse < noise) result.ties.push_back(row);
    return result;
}

std::string row_label(const DemoRow& row)
{
    std::string label = row.method;
    return label.append(1, ' ').append(row.setting);
}

}  // namespace

std::vector<SceneSummary> summarize_scenes(const std::vector<DemoRow>& rows,
                                           const std::vector<std::pair<std::string, double>>& truth_noise,
                                           const std::vector<double>& budgets_ms)
{
    std::vector<SceneSummary> summaries;
    for (const auto& [scene, noise] : truth_noise) {
        std::vector<const DemoRow*> scene_rows;
        for (const DemoRow& row : rows)
            if (row.scene == scene && row.truth == DemoTruth::Shadow) scene_rows.push_back(&row);
        if (scene_rows.empty()) continue;  // only obscurance or sun rows asked for
        SceneSummary summary{scene, noise, {}};
        for (double budget : budgets_ms) summary.picks.push_back(pick(scene_rows, budget, noise));
        summary.picks.push_back(pick(scene_rows, 0.0, noise));
        summaries.push_back(std::move(summary));
    }
    return summaries;
}

std::string describe_pick(const DemoPick& pick)
{
    if (!pick.best) return "none fits";
    char figures[96];
    std::snprintf(figures, sizeof figures, " (RMSE %.4f, %.3g ms)", pick.best->rmse, pick.best->time.frame_ms);
    std::string text = row_label(*pick.best);
    text.append(figures);
    const char* separator = "; within the truth's noise: ";
    for (const DemoRow* tie : pick.ties) {
        text.append(separator).append(row_label(*tie));
        separator = ", ";
    }
    return text;
}

}  // namespace penumbra::cli
