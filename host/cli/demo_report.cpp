#include "demo_report.h"

#include <algorithm>
#include <cstdio>
#include <fstream>
#include <utility>

#include "demo_images.h"
#include "penumbra/error.h"
#include "penumbra/exr_io.h"

namespace penumbra::cli {
namespace {

std::string escaped(const std::string& text)
{
    std::string out;
    for (char c : text) {
        switch (c) {
        case '&': out += "&amp;"; break;
        case '<': out += "&lt;"; break;
        case '>': out += "&gt;"; break;
        case '"': out += "&quot;"; break;
        default: out += c;
        }
    }
    return out;
}

std::string number(const char* format, double value)
{
    char text[32];
    std::snprintf(text, sizeof text, format, value);
    return text;
}

constexpr const char* kStyle = R"(body{font:14px/1.4 sans-serif;margin:1.5em;max-width:1400px;color:#222}
table{border-collapse:collapse;margin:.5em 0}td,th{border:1px solid #ccc;padding:2px 6px;text-align:right}
td:first-child,td:nth-child(2),td:nth-child(3),th{text-align:left}tr:nth-child(even){background:#f6f6f6}
.pictures{display:flex;flex-wrap:wrap;gap:10px}figure{margin:0;text-align:center;font-size:12px}
figure img{display:block;width:192px;image-rendering:pixelated}.pair{display:flex;gap:2px}
.key{display:flex;align-items:center;gap:8px;font-size:12px}.swatch{width:14px;height:14px;display:inline-block}
.chart{max-width:100%}.tie{color:#666;font-size:12px})";

void write_summary(std::ostream& html, const DemoReport& report)
{
    html << "<h2 id=\"summary\">Summary</h2>\n<p>Per scene, the most accurate method within each time budget per "
         << escaped(report.frame)
         << " frame (map and receivers), and overall, among the rows of the scene's light. Methods whose RMSE is within the truth's noise of the pick are "
            "named with it: the truth cannot tell them apart.</p>\n<table><tr><th>scene</th><th>truth noise</th>";
    const std::vector<DemoPick> none;
    for (const DemoPick& pick : report.summaries->empty() ? none : report.summaries->front().picks)
        if (pick.budget_ms > 0) html << "<th>&le; " << number("%g", pick.budget_ms) << " ms</th>";
    html << "<th>most accurate</th></tr>\n";
    for (const SceneSummary& s : *report.summaries) {
        html << "<tr><td>" << escaped(s.scene) << "</td><td>" << number("%.4f", s.truth_noise) << "</td>";
        for (const DemoPick& pick : s.picks) html << "<td style=\"text-align:left\">" << escaped(describe_pick(pick)) << "</td>";
        html << "</tr>\n";
    }
    html << "</table>\n";
}

// What each kind of row is scored against, for its table's heading.
constexpr std::pair<DemoTruth, const char*> kResultTables[] = {
    {DemoTruth::Shadow, "All results: visibility of the scene's light"},
    {DemoTruth::Obscurance,
     "ssao-vo: volumetric obscurance o against its truth (another quantity: 1/2 on a plane, no light)"},
    {DemoTruth::Sun, "The sun: cascades against one map of the same texels, against the directional light's hard "
                     "shadow"},
};

void write_results(std::ostream& html, const DemoReport& report, DemoTruth truth, const char* heading)
{
    if (std::none_of(report.rows->begin(), report.rows->end(), [truth](const DemoRow& r) { return r.truth == truth; }))
        return;
    html << "<h2 id=\"results-" << truth_name(truth) << "\">" << escaped(heading)
         << "</h2>\n<table><tr><th>scene</th><th>method</th><th>setting</th>"
            "<th>map ms</th><th>receiver ms</th><th>frame ms</th><th>min-max ms</th><th>RMSE</th><th>p99</th>"
            "<th>leak</th><th>overdark</th><th>flicker</th></tr>\n";
    for (const DemoRow& r : *report.rows) {
        if (r.truth != truth) continue;
        html << "<tr><td>" << escaped(r.scene) << "</td><td>" << escaped(r.method) << "</td><td>" << escaped(r.setting)
             << "</td><td>" << number("%.3g", r.time.map_ms) << "</td><td>" << number("%.3g", r.time.receiver_ms)
             << "</td><td>" << number("%.3g", r.time.frame_ms) << "</td><td>" << number("%.3g", r.time.frame_min_ms)
             << "&ndash;" << number("%.3g", r.time.frame_max_ms) << "</td>";
        for (double v : {r.rmse, r.p99, r.leak, r.overdark, r.flicker}) html << "<td>" << number("%.4f", v) << "</td>";
        html << "</tr>\n";
    }
    html << "</table>\n";
}

void write_key(std::ostream& html)
{
    html << "<div class=\"key\">error: <span>&minus;" << number("%g", kDemoErrorScale)
         << " too dark</span><img src=\"error_scale.png\" alt=\"error colour scale\" width=\"256\" height=\"12\">"
            "<span>+"
         << number("%g", kDemoErrorScale) << " too bright</span>&nbsp;&nbsp;<span class=\"swatch\" style=\"background:"
         << kDemoBackFaceColour << "\"></span> faces away from the light (not scored)</div>\n";
}

void write_pictures(std::ostream& html, const DemoReport& report)
{
    html << "<h2 id=\"pictures\">Pictures</h2>\n<p>Each method at the setting named under it: its visibility, then "
            "its error against the truth.</p>\n";
    for (const auto& [scene, pictures] : report.pictures) {
        const std::string dir = escaped(scene) + "/";
        html << "<h3 id=\"scene-" << escaped(scene) << "\">" << escaped(scene) << "</h3>\n";
        write_key(html);
        html << "<div class=\"pictures\">\n<figure><img src=\"" << dir << "truth.png\" alt=\"" << escaped(scene)
             << " ground truth\"><figcaption>ground truth</figcaption></figure>\n";
        for (const DemoPicture& p : pictures) {
            const std::string caption = escaped(p.method + ", " + p.setting);
            html << "<figure><div class=\"pair\"><img src=\"" << dir << escaped(p.method) << ".png\" alt=\"" << caption
                 << "\"><img src=\"" << dir << escaped(p.method) << "_error.png\" alt=\"" << caption
                 << " error\"></div><figcaption>" << caption << "</figcaption></figure>\n";
        }
        html << "</div>\n";
    }
}

void write_page(std::ostream& html, const DemoReport& report)
{
    html << "<!doctype html>\n<html lang=\"en\"><head><meta charset=\"utf-8\"><title>penumbra demo</title><style>"
         << kStyle << "</style></head><body>\n<h1>penumbra demo</h1>\n<p>" << escaped(report.machine) << "</p>\n<p>"
         << escaped(report.protocol) << "</p>\n";
    if (report.chart)
        html << "<h2 id=\"chart\">Time against error</h2>\n<img class=\"chart\" src=\"chart.png\" alt=\"time against "
                "error, one panel per scene\">\n";
    write_summary(html, report);
    for (const auto& [truth, heading] : kResultTables) write_results(html, report, truth, heading);
    write_pictures(html, report);
    html << "</body></html>\n";
}

}  // namespace

void write_report(const std::filesystem::path& out, const DemoReport& report)
{
    const std::filesystem::path page = out / "index.html";
    detail::write_file_atomically(page.string(), "demo", [&](const std::string& temporary) {
        std::ofstream file(temporary, std::ios::binary | std::ios::trunc);
        write_page(file, report);
        if (!(file << std::flush)) throw Error(ErrorCategory::Io, "demo", "could not write " + page.string());
    });
}

}  // namespace penumbra::cli
