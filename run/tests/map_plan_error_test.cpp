// The map against the plan's walls, by hand on the two-room plan: the East room's faces are
// x = 5.9 (W2), y = 3.9 (W3) and x = 3.05 (W5); walls 3 m high (W5 2.8 m), so with the 0.2 m
// margin a point counts between z = 0.2 and 2.8.
#include "run/map_plan_error.hpp"

#include <gtest/gtest.h>

#include <cmath>

#include "bim/agraph.hpp"
#include "bim/tests/test_plans.hpp"
#include "run/keyframe_placements.hpp"

namespace isg::run {
namespace {

Eigen::Isometry3d shifted(double x, double y) {
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  T.translation() = Eigen::Vector3d(x, y, 0.0);
  return T;
}

class MapPlanErrorTest : public ::testing::Test {
 protected:
  MapPlanErrorTest()
      : plan_(bim::testing::parsePlanJson(bim::testing::twoRoomPlanJson())),
        agraph_(bim::buildAGraph(plan_)) {
    run_.setup.agraph = &agraph_;
    run_.streams.odometry = {{0.0, Eigen::Isometry3d::Identity()},
                             {1.0, Eigen::Isometry3d::Identity()}};
    run_.estimate_map = run_.streams.odometry.toTrajectory();
    run_.final_B_T_M = Eigen::Isometry3d::Identity();
    MapScanSample scan;
    scan.stamp = 0.5;
    scan.points = {{5.85f, 2.0f, 1.0f, 0.0f},   // 0.05 from W2
                   {4.5f, 3.8f, 1.0f, 0.0f},    // 0.1 from W3
                   {4.5f, 2.0f, 1.0f, 0.0f},    // 1.4 from the nearest face: counted, not near
                   {4.5f, 2.0f, 0.05f, 0.0f},   // the floor: not counted
                   {4.5f, 2.0f, 2.9f, 0.05f}};  // the ceiling: not counted
    run_.map_samples = {scan};
  }

  bim::Plan plan_;
  bim::AGraph agraph_;
  RunRecord run_;
};

TEST_F(MapPlanErrorTest, DistancesToTheWallsInTheirBand) {
  const auto error = mapPlanError(run_);
  ASSERT_TRUE(error);
  EXPECT_EQ(error->points, 3u);
  EXPECT_NEAR(error->near_share, 2.0 / 3.0, 1e-12);
  EXPECT_EQ(error->distance.count, 2);
  EXPECT_NEAR(error->distance.rmse, std::sqrt((0.05 * 0.05 + 0.1 * 0.1) / 2), 1e-6);
  int in_band = 0;
  forEachWallBandMapPoint(run_, {}, [&](const Eigen::Vector3d&) { ++in_band; });
  EXPECT_EQ(in_band, 3);
}

TEST_F(MapPlanErrorTest, PlacedByTheMapsPlaceInThePlan) {
  run_.final_B_T_M = shifted(0.02, 0.0);
  const auto error = mapPlanError(run_);
  ASSERT_TRUE(error);
  EXPECT_NEAR(error->distance.rmse, std::sqrt((0.03 * 0.03 + 0.1 * 0.1) / 2), 1e-6);
}

TEST_F(MapPlanErrorTest, PlacedByTheOptimisedKeyframesCarriedByOdometry) {
  // The keyframe at 0.2 s was optimised 5 cm to -y of its odometry: every later point follows it,
  // whatever the online estimate said.
  slam::MapDiagnostics map;
  map.keyframes.push_back({0.2, shifted(0.0, -0.05), Eigen::Isometry3d::Identity(), {}});
  run_.map = map;
  const auto error = mapPlanError(run_);
  ASSERT_TRUE(error);
  EXPECT_NEAR(error->distance.rmse, std::sqrt((0.05 * 0.05 + 0.15 * 0.15) / 2), 1e-6);
}

TEST_F(MapPlanErrorTest, ASegmentThatEndedIsPlacedWhereTheLocalizerHadItsMapThen) {
  // The map was restarted at 0.9 s. The ended segment's keyframes at 0.2 s (not localized then)
  // and 0.3 s (localized, the map 5 cm to -y of where the final B_T_M, identity, has it): its
  // scan at 0.25 s lies where the localizer had that segment, as the keyframe nearest in time of
  // it says; the final B_T_M places only the current segment.
  slam::MapDiagnostics map;
  map.keyframes.push_back({0.2, Eigen::Isometry3d::Identity(), Eigen::Isometry3d::Identity(), {}});
  map.keyframes.push_back({0.3, Eigen::Isometry3d::Identity(), Eigen::Isometry3d::Identity(), {}});
  map.keyframes.push_back(
      {0.9, Eigen::Isometry3d::Identity(), Eigen::Isometry3d::Identity(), {}, 1});
  map.current_segment = 2;
  run_.map = map;
  run_.estimate = {{0.3, shifted(0.0, -0.05)}, {0.9, Eigen::Isometry3d::Identity()}};
  run_.map_samples[0].stamp = 0.25;
  const auto placements = keyframePlacements(run_);
  ASSERT_EQ(placements.size(), 3u);
  ASSERT_TRUE(placements[0]);  // from the keyframe at 0.3 s, of the same segment
  EXPECT_NEAR(placements[0]->translation().y(), -0.05, 1e-12);
  const auto error = mapPlanError(run_);
  ASSERT_TRUE(error);
  EXPECT_NEAR(error->distance.rmse, std::sqrt((0.05 * 0.05 + 0.15 * 0.15) / 2), 1e-6);
  // The same scan in the current segment: the final B_T_M places it.
  run_.map_samples[0].stamp = 0.95;
  const auto current = mapPlanError(run_);
  ASSERT_TRUE(current);
  EXPECT_NEAR(current->distance.rmse, std::sqrt((0.05 * 0.05 + 0.1 * 0.1) / 2), 1e-6);
  // A segment never localized is not placed at all.
  run_.estimate = {{0.9, Eigen::Isometry3d::Identity()}};
  run_.map_samples[0].stamp = 0.25;
  int placed = 0;
  forEachPlacedMapPoint(run_, [&](const Eigen::Vector3d&) { ++placed; });
  EXPECT_EQ(placed, 0);
}

TEST_F(MapPlanErrorTest, NothingWithoutAPlaceInThePlanOrAPlan) {
  run_.final_B_T_M.reset();
  EXPECT_FALSE(mapPlanError(run_));
  int placed = 0;
  forEachPlacedMapPoint(run_, [&](const Eigen::Vector3d&) { ++placed; });
  EXPECT_EQ(placed, 0);
  run_.final_B_T_M = Eigen::Isometry3d::Identity();
  run_.setup.agraph = nullptr;
  EXPECT_FALSE(mapPlanError(run_));
}

}  // namespace
}  // namespace isg::run
