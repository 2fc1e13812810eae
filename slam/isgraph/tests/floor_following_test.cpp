// Following floors (FloorFollower): the answer's height from the floor seen, the level at an
// elevation, and a pose on stairs where the plan has none, by hand on the box room and the two
// storeys of worlds/plans/storeys.json (ground floor at 0 m, first floor at 3.2 m, flight S1 from
// (9, 0.85) to (13.5, 0.85), 1 m wide).
#include "slam/isgraph/floor_following.hpp"

#include <gtest/gtest.h>

#include "bim/plan_parser.hpp"
#include "slam/sgraph/tests/box_world.hpp"

namespace isg::slam {
namespace {

TEST(FloorFollower, TheAnswersHeightIsTheLevelsElevationAboveTheFloorSeen) {
  const CompiledPlan plan(testing::boxPlan(), {}, 1.0);
  const SGraph graph = testing::boxSGraph();
  // The robot's floor lies 1 m below M's origin (the LiDAR rides 1 m above it).
  ASSERT_TRUE(graph.floorHeight().has_value());
  EXPECT_NEAR(*graph.floorHeight(), -1.0, 0.01);
  FloorFollower floors(plan, {});
  HeldAnswer answer;
  floors.start(-1, graph, answer);  // a level not known: the first
  EXPECT_EQ(floors.level(), 0);
  EXPECT_NEAR(answer.P_T_M_z, 1.0, 0.01);  // level L0 at 0 m, the floor 1 m below M
  EXPECT_TRUE(answer.z_from_floor);
  EXPECT_EQ(floors.floorLevels(), (std::map<int, int>{{graph.currentFloor(), 0}}));
  answer.P_T_M_z = 5.0;
  EXPECT_EQ(floors.follow(1.0, graph, answer), "");
  EXPECT_NEAR(answer.P_T_M_z, 1.0, 0.01);  // followed from the floor again
  EXPECT_TRUE(floors.changes().empty());
  floors.clear();
  EXPECT_TRUE(floors.floorLevels().empty());
}

class StoreysFloorFollower : public ::testing::Test {
 protected:
  StoreysFloorFollower()
      : plan_(bim::buildAGraph(
                  bim::loadPlan(std::string(ISG_SOURCE_DIR) + "/worlds/plans/storeys.json")),
              {}, 1.0) {}
  // A point of B in P.
  Eigen::Vector2d inP(double x, double y) const { return Eigen::Vector2d(x, y) - plan_.B_t_P(); }
  CompiledPlan plan_;
};

TEST_F(StoreysFloorFollower, ALevelIsTheNearestWithinTheTolerance) {
  const FloorFollower floors(plan_, {.level_tolerance = 1.0, .flight_margin = 1.0});
  EXPECT_EQ(floors.levelAt(0.3), 0);
  EXPECT_EQ(floors.levelAt(2.5), 1);   // 0.7 from 3.2
  EXPECT_EQ(floors.levelAt(1.6), -1);  // 1.6 from both
  EXPECT_EQ(floors.levelAt(-1.2), -1);
  EXPECT_EQ(FloorFollower(plan_, {.level_tolerance = 2.0}).levelAt(1.5), 0);
}

TEST_F(StoreysFloorFollower, OnStairsOnlyWhereAFlightOfTheLevelIs) {
  const FloorFollower floors(plan_, {.level_tolerance = 1.0, .flight_margin = 1.0});
  ASSERT_EQ(floors.level(), -1);
  FloorFollower on_ground(plan_, {});
  HeldAnswer answer;
  // Adopted on the ground floor with no S-Graph floor seen yet.
  on_ground.start(0, SGraph(Eigen::Isometry3d::Identity()), answer);
  EXPECT_EQ(on_ground.level(), 0);
  EXPECT_EQ(on_ground.offFlightAt(inP(11.0, 0.85)), "");  // on S1
  EXPECT_EQ(on_ground.offFlightAt(inP(11.0, 2.2)), "");   // 0.85 m beside it: within the margin
  EXPECT_EQ(on_ground.offFlightAt(inP(4.0, 0.85)),
            "the robot is on stairs at (4.0, 0.8), 5.0 m from every flight that joins level L0");
}

}  // namespace
}  // namespace isg::slam
