// The map against the plan placed, by hand on the two-room plan: W2's inner face is x = 5.9
// from y = 0.1 to 3.9 (looking to −x, into the East room), cut in four stretches of 0.95 m;
// W3's inner face is y = 3.9. Walls 3 m high, so with the 0.2 m margin a point counts between
// z = 0.2 and 2.8.
#include "run/map_to_plan_levels.hpp"

#include <gtest/gtest.h>

#include "bim/agraph.hpp"
#include "bim/tests/test_plans.hpp"

namespace isg::run {
namespace {

class MapAgainstPlanTest : public ::testing::Test {
 protected:
  MapAgainstPlanTest()
      : plan_(bim::testing::parsePlanJson(bim::testing::twoRoomPlanJson())),
        agraph_(bim::buildAGraph(plan_)) {
    run_.setup.agraph = &agraph_;
    run_.streams.odometry = {{0.0, Eigen::Isometry3d::Identity()},
                             {1.0, Eigen::Isometry3d::Identity()}};
    run_.estimate_map = run_.streams.odometry.toTrajectory();
    run_.final_B_T_M = Eigen::Isometry3d::Identity();
    MapScanSample scan;
    scan.stamp = 0.5;
    for (int i = 0; i < 40; ++i) {
      const float y = 0.2f + 0.02f * float(i);
      scan.points.push_back({5.85f, y, 1.0f, 0.0f});         // 5 cm in front of W2's face
      scan.points.push_back({5.93f, y + 1.9f, 1.5f, 0.0f});  // 3 cm behind it, farther on
    }
    for (int i = 0; i < 10; ++i) {
      scan.points.push_back({4.0f + 0.1f * float(i), 3.8f, 1.0f, 0.0f});  // 10 cm before W3's
    }
    for (int i = 0; i < 5; ++i) scan.points.push_back({4.5f, 2.0f, 1.0f, 0.0f});  // near none
    scan.points.push_back({4.5f, 2.0f, 0.05f, 0.0f});                             // the floor
    run_.map_samples = {scan};
  }

  const slam::FaceStretch* stretchHolding(const slam::LevelAgainstPlan& level, double y) const {
    for (const auto& s : level.stretches) {
      if (std::min(s.start.y(), s.end.y()) <= y && y <= std::max(s.start.y(), s.end.y())) {
        return &s;
      }
    }
    return nullptr;
  }

  bim::Plan plan_;
  bim::AGraph agraph_;
  RunRecord run_;
};

TEST_F(MapAgainstPlanTest, EachFaceStretchHoldsTheSignedMeanOfItsPoints) {
  const auto levels = mapAgainstPlan(run_, {"L0"});
  ASSERT_EQ(levels.size(), 1u);
  const slam::LevelAgainstPlan& level = levels[0];
  EXPECT_EQ(level.level, "L0");
  EXPECT_EQ(level.points, 95u);  // the floor's point is out of every band
  EXPECT_NEAR(level.near_share, 90.0 / 95.0, 1e-12);
  EXPECT_NEAR(level.cutoff_m, 0.3, 1e-12);
  // Sorted: forty at 0.03 m, forty at 0.05 m, ten at 0.1 m.
  EXPECT_NEAR(level.median_m, 0.05, 1e-3);
  EXPECT_NEAR(level.p95_m, 0.10, 1e-3);
  // W3's ten points are too few for a stretch of their own.
  ASSERT_EQ(level.stretches.size(), 2u);
  const slam::FaceStretch* front = stretchHolding(level, 0.6);
  const slam::FaceStretch* behind = stretchHolding(level, 2.6);
  ASSERT_TRUE(front && behind);
  EXPECT_EQ(front->surface, "W2:left");
  EXPECT_EQ(front->points, 40u);
  EXPECT_NEAR(front->mean_m, 0.05, 1e-5);
  EXPECT_NEAR(front->rms_m, 0.05, 1e-5);
  EXPECT_NEAR(std::abs(front->end.y() - front->start.y()), 0.95, 1e-9);
  EXPECT_NEAR(front->start.x(), 5.9, 1e-9);
  EXPECT_EQ(behind->points, 40u);
  EXPECT_NEAR(behind->mean_m, -0.03, 1e-5);
  EXPECT_EQ(slam::offClass(front->mean_m), 2);
  EXPECT_EQ(slam::offClass(behind->mean_m), 1);
  EXPECT_EQ(slam::offClass(0.005), 0);
  EXPECT_EQ(slam::offClass(-0.2), 3);
}

// metrics.json's line of the level: W2's front stretch (+5 cm) lies off by 4 cm or more, the one
// behind (-3 cm) does not; each is 3.8 m / 4 = 0.95 m long.
TEST_F(MapAgainstPlanTest, ALevelsSummaryCountsTheStretchesLyingOffAndNamesTheFarthest) {
  const RunMetrics::MapToPlan::Level level = levelSummary(mapAgainstPlan(run_, {"L0"})[0]);
  EXPECT_EQ(level.level, "L0");
  EXPECT_EQ(level.points, 95);
  EXPECT_NEAR(level.median_m, 0.05, 1e-3);
  EXPECT_EQ(level.stretches, 2);
  EXPECT_EQ(level.off_stretches, 1);
  EXPECT_NEAR(level.off_length_m, 0.95, 1e-9);
  ASSERT_TRUE(level.farthest);
  EXPECT_EQ(level.farthest->surface, "W2:left");
  EXPECT_NEAR(level.farthest->mean_m, 0.05, 1e-5);
  // With a threshold of 2 cm both lie off; with none measured, none is the farthest.
  EXPECT_EQ(levelSummary(mapAgainstPlan(run_, {"L0"})[0], 0.02).off_stretches, 2);
  slam::MapAgainstPlanOptions options;
  options.min_points = 41;
  const RunMetrics::MapToPlan::Level bare = levelSummary(mapAgainstPlan(run_, {"L0"}, options)[0]);
  EXPECT_EQ(bare.stretches, 0);
  EXPECT_FALSE(bare.farthest);
}

TEST_F(MapAgainstPlanTest, AStretchNeedsItsPointsAndALevelWalked) {
  slam::MapAgainstPlanOptions options;
  options.min_points = 41;
  EXPECT_TRUE(mapAgainstPlan(run_, {"L0"}, options)[0].stretches.empty());
  // A level not walked is not reported, and its points are nobody's.
  EXPECT_TRUE(mapAgainstPlan(run_, {}).empty());
  const auto other = mapAgainstPlan(run_, {"L9"});
  ASSERT_EQ(other.size(), 1u);
  EXPECT_EQ(other[0].points, 0u);
  run_.final_B_T_M.reset();
  EXPECT_TRUE(mapAgainstPlan(run_, {"L0"}).empty());
}

}  // namespace
}  // namespace isg::run
