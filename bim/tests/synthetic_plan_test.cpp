#include "bim/synthetic_plan.hpp"

#include <gtest/gtest.h>

#include "bim/plan_geometry.hpp"
#include "bim/tests/test_plans.hpp"

namespace isg::bim {
namespace {

TEST(SyntheticPlan, GridOfTwoHundredRoomsIsValidAndFullyBounded) {
  const GridPlanSpec spec;  // 10 x 20
  const Plan plan = testing::parsePlanJson(makeGridPlan(spec));
  const Level& level = plan.levels[0];
  EXPECT_EQ(level.rooms.size(), 200u);
  EXPECT_EQ(level.walls.size(), std::size_t(spec.rows + 1 + spec.cols + 1));
  // One door per neighbour pair plus the entrance.
  EXPECT_EQ(level.doors.size(),
            std::size_t((spec.rows - 1) * spec.cols + spec.rows * (spec.cols - 1) + 1));
  const LevelGeometry g = computeLevelGeometry(level);
  for (const auto& room : level.rooms) {
    EXPECT_EQ(g.boundariesOf(room.id).size(), 4u) << room.id;
  }
}

TEST(SyntheticPlan, InferredDoorRoomsMatchTheGivenOnes) {
  GridPlanSpec spec;
  spec.rows = 4;
  spec.cols = 5;
  const Plan inferred = testing::parsePlanJson(makeGridPlan(spec));
  spec.give_door_rooms = true;
  const Plan given = testing::parsePlanJson(makeGridPlan(spec));
  const auto& a = inferred.levels[0].doors;
  const auto& b = given.levels[0].doors;
  ASSERT_EQ(a.size(), b.size());
  for (std::size_t i = 0; i < a.size(); ++i) {
    EXPECT_TRUE(a[i].rooms_inferred);
    EXPECT_EQ(a[i].rooms, b[i].rooms) << a[i].id;
  }
}

}  // namespace
}  // namespace isg::bim
