// The S-Graph on data from the simulator, in memory: its keyframe trajectory, after SE(3)
// alignment (its map frame is arbitrary), must beat odometry alone by a wide margin.
#include <gtest/gtest.h>

#include "eval/ape.hpp"
#include "sim/simulation.hpp"
#include "slam/sgraph.hpp"
#include "worlds/reference_plans.hpp"

namespace isg::sim {
namespace {

TEST(SGraphOnSimulatedData, KeyframesBeatOdometryOnD1AsBuilt) {
  Simulation sim(worlds::loadScenarioOrBuiltin("builtin:d1.asbuilt", nullptr));
  const double duration = sim.duration();
  const eval::Trajectory odometry = sim.odometry(duration);
  slam::SGraph graph(sim.R_T_L());
  std::size_t next = 0;
  const auto lidar = sim.makeLidar();
  for (int k = 0; k < sim.scanCount(duration); ++k) {
    const LidarScan scan = sim.scan(k, *lidar);
    while (next < odometry.size() && odometry[next].t <= scan.stamp + sim.scanPeriod()) {
      graph.addOdometry({odometry[next].t, odometry[next].pose});
      ++next;
    }
    graph.addScan({scan.stamp, scan.points});
  }
  ASSERT_GT(graph.keyframes().size(), 15u);
  EXPECT_GT(graph.planes().size(), 8u);
  eval::Trajectory keyframes, odometry_at_keyframes;
  for (const auto& kf : graph.keyframes()) {
    keyframes.push_back({kf.stamp, kf.pose()});
    odometry_at_keyframes.push_back({kf.stamp, kf.odometry});
  }
  const eval::Trajectory truth = sim.groundTruth(duration, 100.0);
  eval::ErrorOptions se3;
  se3.align = eval::Alignment::kSE3;
  const double slam = eval::absolutePoseError(truth, keyframes, se3).translation_stats.rmse;
  const double odo =
      eval::absolutePoseError(truth, odometry_at_keyframes, se3).translation_stats.rmse;
  EXPECT_LT(slam, 0.03);
  EXPECT_GT(odo, 3.0 * slam);
}

}  // namespace
}  // namespace isg::sim

#include "slam/sgraph_localizer.hpp"

namespace isg::sim {
namespace {

TEST(SGraphOnSimulatedData, AsALocalizerItTracksTheBaseInItsMap) {
  Simulation sim(worlds::loadScenarioOrBuiltin("builtin:d2.asbuilt", nullptr));
  const double duration = 12.0;
  const eval::Trajectory odometry = sim.odometry(duration);
  slam::SGraphLocalizer localizer(sim.R_T_L());
  slam::Localizer& method = localizer;
  EXPECT_EQ(method.name(), "s-graph");
  EXPECT_FALSE(method.poseInMap());
  std::size_t next = 0;
  for (int k = 0; k < sim.scanCount(duration); ++k) {
    const LidarScan scan = sim.scan(k);
    while (next < odometry.size() && odometry[next].t <= scan.stamp + sim.scanPeriod()) {
      method.pushOdometry({odometry[next].t, odometry[next].pose});
      ++next;
    }
    method.pushScan({scan.stamp, scan.points});
  }
  ASSERT_TRUE(method.poseInMap());
  EXPECT_FALSE(method.mapInPlan());  // no plan: it knows only its own map frame
  // In M (the start pose), the base has moved as the ground truth says, within a few centimetres.
  const Eigen::Isometry3d truth =
      sim.trajectory().pose(0.0).inverse() * sim.trajectory().pose(method.poseInMap()->stamp);
  EXPECT_LT((method.poseInMap()->M_T_R.translation() - truth.translation()).head<2>().norm(), 0.05);
  EXPECT_GT(method.graph()["planes"].size(), 3u);
}

}  // namespace
}  // namespace isg::sim
