// Light leaking on the `overlap` reference scene (tests/support/overlap_scene.h:
// two slabs overlapping as seen from the light): VSM against EVSM2, EVSM4 and
// MSM, scored against ray-traced ground truth, at a small size. The table of
// docs/moments.md is bench/overlap_leak_table (a tool: it measures, this checks).
#include <gtest/gtest.h>

#include <string>

#include "support/overlap_scene.h"

namespace penumbra {
namespace {

using testing::LeakScore;
using testing::LeakTable;

LeakScore find(const LeakTable& rows, const std::string& name)
{
    for (const auto& [n, s] : rows)
        if (n == name) return s;
    ADD_FAILURE() << "no row " << name;
    return {};
}

// The overlap case at a small size: MSM must leak less than VSM, with EVSM4
// in between (Peters & Klein 2015, fig. 1; Lauritzen & McCool 2008).
TEST(MomentsOverlap, MsmLeaksLessThanVsm)
{
    const testing::OverlapFrame f = testing::render_overlap_frame(256, 80, 60, 12);
    const LeakTable rows = testing::overlap_leak_table(f, 2);
    testing::print_leak_table(rows);
    // Under both slabs (the two-layer mask): the overlap case itself.
    const double vsm_leak = find(rows, "vsm exact").leak_two_layers;
    EXPECT_GT(vsm_leak, 0.005) << "the overlap scene should make VSM leak";
    EXPECT_LT(find(rows, "msm 16 exact").leak_two_layers, 0.5 * vsm_leak);
    EXPECT_LT(find(rows, "evsm4 16 exact").leak_two_layers, vsm_leak);
}

}  // namespace
}  // namespace penumbra
