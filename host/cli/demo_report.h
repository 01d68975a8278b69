// out/demo/index.html: the demo's results as one static page (no script, no
// server, nothing fetched: every picture is a file beside it). The chart, the
// summary, the full results table, and per scene the truth and each method's
// picture and error picture, captioned with the method and its setting.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include "demo_results.h"
#include "demo_summary.h"

namespace penumbra::cli {

struct DemoPicture {
    std::string method, setting;  // the files are <scene>/<method>.png and <scene>/<method>_error.png
};

struct DemoReport {
    std::string machine;   // the context's description
    std::string protocol;  // what was scored and timed, and how
    const std::vector<DemoRow>* rows = nullptr;
    const std::vector<SceneSummary>* summaries = nullptr;
    std::vector<std::pair<std::string, std::vector<DemoPicture>>> pictures;  // per scene, in run order
    std::string frame;     // "1920x1080": the timed frame, for the budgets' heading
    bool chart = true;     // chart.png was drawn
};

// Writes `out`/index.html whole or not at all.
void write_report(const std::filesystem::path& out, const DemoReport& report);

}  // namespace penumbra::cli
