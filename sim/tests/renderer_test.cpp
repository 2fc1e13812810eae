#include "sim/renderer.hpp"

#include <gtest/gtest.h>

#include "sim/robot_model.hpp"
#include "sim/simulation.hpp"
#include "worlds/reference_plans.hpp"

namespace isg::sim {
namespace {

// Pixels of the robot's yellow (its body is rgba .95 .78 .1) and of the floor's greys.
int countYellow(const Image& image) {
  int n = 0;
  for (std::size_t i = 0; i < image.rgb.size(); i += 3) {
    const int r = image.rgb[i], g = image.rgb[i + 1], b = image.rgb[i + 2];
    n += r > 150 && g > 110 && b < 80 && r > b + 100;
  }
  return n;
}

int countGrey(const Image& image) {
  int n = 0;
  for (std::size_t i = 0; i < image.rgb.size(); i += 3) {
    const int r = image.rgb[i], g = image.rgb[i + 1], b = image.rgb[i + 2];
    n += r > 90 && std::abs(r - g) < 20 && std::abs(g - b) < 25;
  }
  return n;
}

TEST(Renderer, HeadlessPicturesShowTheBuildingAndTheRobot) {
  Simulation sim(worlds::loadScenarioOrBuiltin("builtin:d3.asbuilt", nullptr));
  const double t = 20.0;
  const Eigen::Isometry3d B_T_R = sim.trajectory().pose(t);
  poseRobot(sim.world().model(), sim.world().data(), B_T_R, sim.trajectory().gaitPhase(t), 1.0);
  Renderer renderer(sim.world().model(), 640, 360);
  const Image top = renderer.topDown(sim.world().data());
  const Image chase = renderer.chase(sim.world().data(), B_T_R);
  ASSERT_EQ(top.rgb.size(), 640u * 360u * 3u);
  // From above: the building fills much of the picture, the robot a few dozen pixels of it.
  EXPECT_GT(countGrey(top), 640 * 360 / 4);
  EXPECT_GT(countYellow(top), 20);
  // From behind, the robot is large.
  EXPECT_GT(countYellow(chase), 640 * 360 / 50);
  EXPECT_GT(countGrey(chase), 640 * 360 / 10);
}

}  // namespace
}  // namespace isg::sim
