// The S-Graph on data from the simulator, in memory, through the run driver as `isg run` feeds
// it: its keyframe trajectory, after SE(3) alignment (its map frame is arbitrary), must beat
// odometry alone by a wide margin; as a localizer it tracks the base in its own frame M.
#include <gtest/gtest.h>

#include "run/builtin_methods.hpp"
#include "run/driver.hpp"
#include "run/map_diagnosis.hpp"
#include "sim/scan_pipeline.hpp"
#include "sim/simulation.hpp"
#include "worlds/reference_plans.hpp"

namespace isg::sim {
namespace {

run::RunRecord runSGraph(const Simulation& sim, double duration) {
  run::LocalizerContext context;
  context.R_T_L = sim.R_T_L();
  const auto localizer = run::builtinMethods().make("s-graph", context);
  EXPECT_EQ(localizer->name(), "s-graph");
  EXPECT_FALSE(localizer->poseInMap());
  sensors::SensorStreams streams = sensorStreams(sim, duration);
  LookaheadScans scans(sim, int(streams.scan_stamps.size()), 1);
  return run::runLocalizer({}, *localizer, std::move(streams), scans);
}

TEST(SGraphOnSimulatedData, KeyframesBeatOdometryOnD1AsBuilt) {
  const Simulation sim(worlds::loadScenarioOrBuiltin("builtin:d1.asbuilt", nullptr));
  const run::RunRecord record = runSGraph(sim, -1.0);
  ASSERT_TRUE(record.map.has_value());
  ASSERT_GT(record.map->keyframes.size(), 15u);
  EXPECT_GT(record.map->planes, 8u);
  const run::MapDiagnosis diagnosis =
      run::diagnoseMap(*record.map, record.streams.ground_truth, nullptr, "");
  ASSERT_TRUE(diagnosis.keyframe_ape_rmse && diagnosis.odometry_ape_rmse);
  EXPECT_LT(*diagnosis.keyframe_ape_rmse, 0.03);
  EXPECT_GT(*diagnosis.odometry_ape_rmse, 3.0 * *diagnosis.keyframe_ape_rmse);
}

TEST(SGraphOnSimulatedData, AsALocalizerItTracksTheBaseInItsMap) {
  const Simulation sim(worlds::loadScenarioOrBuiltin("builtin:d2.asbuilt", nullptr));
  const run::RunRecord record = runSGraph(sim, 12.0);
  ASSERT_FALSE(record.estimate_map.empty());
  EXPECT_TRUE(record.estimate.empty());  // no plan: it knows only its own map frame
  EXPECT_FALSE(record.search_status.has_value());
  // In M (the start pose), the base has moved as the ground truth says, within a few centimetres.
  const auto& last = record.estimate_map.back();
  const Eigen::Isometry3d truth =
      sim.baseMotion().pose(0.0).inverse() * sim.baseMotion().pose(last.t);
  EXPECT_LT((last.pose.translation() - truth.translation()).head<2>().norm(), 0.05);
  EXPECT_GT(record.graph["planes"].size(), 3u);
}

}  // namespace
}  // namespace isg::sim
