#include "run/level_metrics.hpp"

#include <gtest/gtest.h>

namespace isg::run {
namespace {

bim::FloorNode floor(const std::string& id, double elevation) {
  bim::FloorNode node;
  node.id = id;
  node.elevation = elevation;
  return node;
}

bim::AGraph twoStoreys() {
  bim::AGraph graph;
  graph.floors = {floor("L0", 0.0), floor("L1", 3.2)};
  return graph;
}

// 10 s on L0, 10 s on L1 (rows every 0.5 s); the APE rows of the second half are on L1.
// The estimate reaches L1 later than the truth (as after a kidnap up a storey).
TEST(LevelMetrics, TimeAndErrorsPerLevelInTheOrderReached) {
  Trajectory truth;
  for (int i = 0; i <= 40; ++i) {
    StampedPose p;
    p.t = 100.0 + 0.5 * i;
    p.pose.translation() = Eigen::Vector3d(0.1 * i, 0.0, i < 20 ? 0.45 : 3.65);
    truth.push_back(p);
  }
  const std::vector<std::pair<double, double>> ape = {
      {104.0, 0.1}, {106.0, 0.3}, {112.0, 0.2}, {115.0, 0.2}, {119.9, 0.2}};
  Trajectory estimate;  // on the level of the truth, but right after it reached L1
  for (const auto& [t, error] : ape) {
    StampedPose p;
    p.t = t;
    p.pose.translation() = Eigen::Vector3d(0.0, 0.0, t < 112.5 ? 0.45 : 3.65);
    estimate.push_back(p);
  }
  const auto levels = levelMetrics(twoStoreys(), truth, estimate, ape);
  ASSERT_EQ(levels.size(), 2u);
  EXPECT_EQ(levels[0].level, "L0");
  EXPECT_DOUBLE_EQ(levels[0].seconds, 10.0);
  EXPECT_DOUBLE_EQ(levels[0].arrived_at, 0.0);
  ASSERT_TRUE(levels[0].first_estimate_at.has_value());
  EXPECT_DOUBLE_EQ(*levels[0].first_estimate_at, 4.0);
  ASSERT_TRUE(levels[0].ape_B.has_value());
  EXPECT_EQ(levels[0].ape_B->count, 2);
  EXPECT_DOUBLE_EQ(levels[0].ape_B->max, 0.3);
  EXPECT_EQ(levels[1].level, "L1");
  EXPECT_DOUBLE_EQ(levels[1].seconds, 10.0);
  EXPECT_DOUBLE_EQ(levels[1].arrived_at, 10.0);
  // The row at 112 s still put the robot on L0: L1's first pose is the one at 115 s.
  EXPECT_DOUBLE_EQ(*levels[1].first_estimate_at, 15.0);
  EXPECT_EQ(levels[1].ape_B->count, 3);
  EXPECT_NEAR(levels[1].ape_B->rmse, 0.2, 1e-12);
}

TEST(LevelMetrics, NoneForAPlanOfOneLevel) {
  bim::AGraph graph;
  graph.floors = {floor("L0", 0.0)};
  Trajectory truth(3);
  EXPECT_TRUE(levelMetrics(graph, truth, {}, {}).empty());
}

}  // namespace
}  // namespace isg::run
