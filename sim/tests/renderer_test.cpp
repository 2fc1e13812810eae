#include "sim/renderer.hpp"

#include <gtest/gtest.h>

#include "bim/plan_geometry.hpp"
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
  const Eigen::Isometry3d B_T_R = sim.baseMotion().pose(t);
  poseRobot(sim.world().model(), sim.world().data(), B_T_R, sim.baseMotion().gaitPhase(t), 1.0);
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

// The plan view: walls from above as their footprints (lit tops, near white), every door an
// opening onto the floor (the lintel is cut away), the route in red.
TEST(Renderer, PlanViewShowsDoorOpeningsAndTheRoute) {
  Simulation sim(worlds::loadScenarioOrBuiltin("builtin:d1", nullptr));
  const bim::Level& level = sim.scenario().plan.levels[0];
  const bim::LevelGeometry geometry = bim::computeLevelGeometry(level);
  Eigen::Vector2d lo = Eigen::Vector2d::Constant(1e18), hi = -lo;
  for (const auto& wall : geometry.walls) {
    for (const auto& p : wall.footprint()) {
      lo = lo.cwiseMin(p);
      hi = hi.cwiseMax(p);
    }
  }
  std::vector<Eigen::Vector3d> route;
  for (double t = 0.0; t <= sim.duration(); t += 0.25) {
    const Eigen::Vector3d p = sim.baseMotion().pose(t).translation();
    route.emplace_back(p.x(), p.y(), level.elevation + 0.05);
  }
  const int width = 800, height = 450;
  Renderer renderer(sim.world().model(), width, height);
  const Image plan = renderer.planView(sim.world().data(), lo, hi, route);
  // Where a point of B lands: the view is centred on the box, 6 % wider than it, fitted.
  const Eigen::Vector2d centre = 0.5 * (lo + hi), size = (hi - lo) * 1.06;
  const double half_height = 0.5 * std::max(size.y(), size.x() * height / width);
  auto pixel = [&](const Eigen::Vector2d& p) {
    const int u = int(std::lround(0.5 * width + (p.x() - centre.x()) / half_height * 0.5 * height));
    const int v =
        int(std::lround(0.5 * height - (p.y() - centre.y()) / half_height * 0.5 * height));
    const std::size_t i = 3 * (std::size_t(v) * width + std::size_t(u));
    return Eigen::Vector3i(plan.rgb[i], plan.rgb[i + 1], plan.rgb[i + 2]);
  };
  auto isWallTop = [](const Eigen::Vector3i& c) { return c.minCoeff() > 225; };
  ASSERT_FALSE(level.doors.empty());
  for (const auto& door : level.doors) {
    const bim::WallGeometry& wall = *geometry.findWall(door.wall);
    const Eigen::Vector2d opening = wall.pointAt(door.offset);
    // Beside the opening, 0.3 m past its edge, the wall; in it, no wall.
    const Eigen::Vector2d beside = wall.pointAt(door.offset + 0.5 * door.width + 0.3);
    EXPECT_FALSE(isWallTop(pixel(opening))) << door.id << " " << pixel(opening).transpose();
    if (door.offset + 0.5 * door.width + 0.3 < wall.length) {
      EXPECT_TRUE(isWallTop(pixel(beside))) << door.id << " " << pixel(beside).transpose();
    }
  }
  int red = 0;
  for (std::size_t i = 0; i < plan.rgb.size(); i += 3) {
    red += plan.rgb[i] > 150 && plan.rgb[i + 1] < 60 && plan.rgb[i + 2] < 60;
  }
  EXPECT_GT(red, 500);  // the route
}

}  // namespace
}  // namespace isg::sim
