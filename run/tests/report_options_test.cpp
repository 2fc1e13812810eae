// Options of two layers that a run puts together: the map's (slam/sgraph) and the deviation
// report's (slam/deviations), which may not see each other.
#include <gtest/gtest.h>

#include "slam/deviations/plan_deviations.hpp"
#include "slam/sgraph/sgraph.hpp"

namespace isg::run {
namespace {

// Where a part of a wall seen by few abuts one seen by many, the map leaves up to near_m of it
// unconfirmed (slam::ConfirmationOptions); the progress report must bridge that as not seen, not
// report a gap not built, so near_m stays below the shortest gap the report believes.
TEST(ReportOptions, TheMapsUnconfirmedEdgeIsShorterThanAGapTheReportBelieves) {
  EXPECT_LT(slam::SGraphOptions{}.confirmation.near_m, slam::DeviationOptions{}.progress_gap_m);
}

}  // namespace
}  // namespace isg::run
