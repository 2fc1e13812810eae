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
