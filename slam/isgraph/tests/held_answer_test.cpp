// The answer held (HeldAnswer) and its walls as the release judges them (heldWalls), on the box
// room mapped by a walk: its four walls against the plan's inner faces, by hand.
#include "slam/isgraph/held_answer.hpp"

#include <gtest/gtest.h>

#include <numbers>

#include "slam/isgraph/compiled_plan.hpp"
#include "slam/isgraph/match_input.hpp"
#include "slam/sgraph/tests/box_world.hpp"

namespace isg::slam {
namespace {

TEST(HeldAnswer, TakesAVerificationWholeAndForgetsIt) {
  HeldAnswer answer;
  answer.plane_matches = {{9, 9}};
  answer.room_matches = {{8, 8}};
  Verification v;
  v.x_y_yaw = Eigen::Vector3d(1.0, 2.0, std::numbers::pi / 2);
  v.planes = {{0, 4}, {1, 5}};
  v.rooms = {{0, 1}};
  answer.take(v);
  EXPECT_EQ(answer.plane_matches, (std::map<int, int>{{0, 4}, {1, 5}}));
  EXPECT_EQ(answer.room_matches, (std::map<int, int>{{0, 1}}));
  // (1, 0) in M, turned a quarter and moved by (1, 2): (1, 3) in P.
  EXPECT_NEAR((answer.inP({1.0, 0.0}) - Eigen::Vector2d(1.0, 3.0)).norm(), 0.0, 1e-12);
  answer.localized = true;
  answer.clear();
  EXPECT_FALSE(answer.localized);
  EXPECT_TRUE(answer.plane_matches.empty());
  EXPECT_TRUE(answer.room_matches.empty());
}

TEST(HeldAnswer, HeldWallsAreTheMapsWallsAgainstTheirSurfacesInP) {
  const CompiledPlan plan(testing::boxPlan(), {}, 1.0);
  const SGraph graph = testing::boxSGraph();
  const MatchInput input = matchInputOf(graph, 1.0);
  ASSERT_EQ(input.planes.size(), 4u);
  HeldAnswer answer;
  answer.localized = true;
  answer.P_T_M_x_y_yaw = plan.inP(Eigen::Vector3d::Zero());  // B_T_M is the identity
  // Each S-plane to the inner face its normal faces: S, N, W and E (surfaces 0, 4, 6, 2).
  for (const MatchPlane& p : input.planes) {
    const Eigen::Vector2d n = p.plane.normal.head<2>();
    answer.plane_matches[p.id] = n.y() > 0.5 ? 0 : n.y() < -0.5 ? 4 : n.x() > 0.5 ? 6 : 2;
  }
  std::vector<std::pair<int, int>> held;
  const std::vector<HeldWall> walls = heldWalls(answer, input, graph, plan.agraph(), &held);
  ASSERT_EQ(walls.size(), 4u);
  ASSERT_EQ(held.size(), 4u);
  for (std::size_t k = 0; k < walls.size(); ++k) {
    EXPECT_EQ(answer.plane_matches.at(held[k].first), held[k].second);
    // Each seen wall stands on its face: within the scans' 1.2 cm and 0.2° (docs/slam.md).
    EXPECT_NEAR(walls[k].offset, 0.0, 0.015) << k;
    EXPECT_NEAR(walls[k].angle, 0.0, 0.005) << k;
    // Each plan wall its own; the long walls seen over their 10 m, the short over 6 m.
    const bool long_wall = held[k].second == 0 || held[k].second == 4;
    EXPECT_NEAR(walls[k].length, long_wall ? 10.0 : 6.0, 0.01) << k;
  }
  // Moved 0.3 m along x in P, the west and east walls stand 0.3 m off their faces: the west
  // face's normal points +x, so its offset is +0.3; the east face's points −x: −0.3.
  answer.P_T_M_x_y_yaw.x() += 0.3;
  const std::vector<HeldWall> moved = heldWalls(answer, input, graph, plan.agraph(), nullptr);
  for (std::size_t k = 0; k < moved.size(); ++k) {
    const int surface = held[k].second;
    const double expected = surface == 6 ? 0.3 : surface == 2 ? -0.3 : 0.0;
    EXPECT_NEAR(moved[k].offset, expected, 0.015) << surface;
  }
  // A correspondence of a plane the matcher does not see (no wall) is not held.
  answer.plane_matches[99] = 0;
  EXPECT_EQ(heldWalls(answer, input, graph, plan.agraph(), nullptr).size(), 4u);
}

}  // namespace
}  // namespace isg::slam
