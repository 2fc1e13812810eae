// sgraph.json's "matching" of the iS-Graph (matchingJson): the answer in B, correspondences and
// released walls by the plan's ids, the level.
#include "slam/isgraph/isgraph_json.hpp"

#include <gtest/gtest.h>

#include "slam/sgraph/tests/box_world.hpp"

namespace isg::slam {
namespace {

TEST(ISGraphJson, TheAnswerInBAndItsCorrespondencesByPlanIds) {
  const CompiledPlan plan(testing::boxPlan(), {}, 1.0);
  HeldAnswer answer;
  MatchLog log;
  ReleasedWalls released(WallReleaseOptions{});
  FloorFollower floors(plan, {});
  const nlohmann::json before = matchingJson({plan, answer, log, released, floors, 0});
  EXPECT_EQ(before["localized"], false);
  EXPECT_FALSE(before.contains("B_T_M"));
  EXPECT_EQ(before["status"], "not yet");

  answer.localized = true;
  answer.P_T_M_x_y_yaw = Eigen::Vector3d(-2.5, 0.25, 0.1);  // in P: B is 3 m further along x
  answer.P_T_M_z = 1.0;
  answer.plane_matches = {{0, 0}, {3, 2}};
  answer.room_matches = {{0, 0}};
  floors.start(0, SGraph(Eigen::Isometry3d::Identity()), answer);
  answer.P_T_M_z = 1.0;
  const nlohmann::json after = matchingJson({plan, answer, log, released, floors, 2});
  EXPECT_EQ(after["B_T_M"], nlohmann::json({{"x", 0.5}, {"y", 0.25}, {"z", 1.0}, {"yaw", 0.1}}));
  EXPECT_EQ(after["level"], "L0");
  EXPECT_EQ(after["plane_matches"], nlohmann::json::parse(R"([[0, "S:left"], [3, "E:left"]])"));
  EXPECT_EQ(after["room_matches"], nlohmann::json::parse(R"([[0, "R"]])"));
  EXPECT_EQ(after["windows_with_B_T_M_held"], 2);
  EXPECT_EQ(after["released_walls"], nlohmann::json::array());
}

}  // namespace
}  // namespace isg::slam
