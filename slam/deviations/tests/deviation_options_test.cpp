// The deviation report's options validate themselves, naming the field as deviations.json does.
#include "slam/deviations/deviation_options.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "slam/deviations/plan_deviations.hpp"

namespace isg::slam {
namespace {

TEST(DeviationOptions, TheDefaultsAreValid) {
  EXPECT_TRUE(DeviationOptions{}.isValid());
  EXPECT_EQ(DeviationOptions{}.invalidField(), std::nullopt);
}

TEST(DeviationOptions, AFieldOutOfRangeIsNamedAsDeviationsJsonNamesIt) {
  DeviationOptions o;
  o.shift_m = 0.0;
  EXPECT_EQ(o.invalidField(), "shift_m: must be above 0");
  o = {};
  o.search_distance = std::numeric_limits<double>::quiet_NaN();
  EXPECT_EQ(o.invalidField(), "search_distance_m: must be above 0");
  o = {};
  o.min_noise_walls = 3;
  EXPECT_EQ(o.invalidField(),
            "min_noise_walls: must be at least 4 (the local placement fits 3 numbers on them)");
  o = {};
  o.missing_seen_share = 0.3;  // above judged_share (0.2): a wall would be missing and judged
  EXPECT_EQ(o.invalidField(), "missing_seen_share: must lie in [0, judged_share]");
  o = {};
  o.progress_gap_m = 0.01;  // under a step
  EXPECT_EQ(o.invalidField(), "progress_gap_m: must be at least progress_step_m");
  o = {};
  o.max_incidence_deg = 95.0;
  EXPECT_FALSE(o.isValid());
}

TEST(DeviationOptions, TheReportRefusesOptionsThatAreNotValid) {
  DeviationOptions o;
  o.view_range = -1.0;
  const bim::AGraph plan;
  const MapDiagnostics map;
  try {
    measureDeviations(plan, map, Eigen::Isometry3d::Identity(), o);
    FAIL() << "invalid options were taken";
  } catch (const std::invalid_argument& e) {
    EXPECT_STREQ(e.what(), "deviation options: view_range_m: must be above 0");
  }
}

}  // namespace
}  // namespace isg::slam
