// The merge's factors (PlanMerger) for a window of the box room's map: one plane-to-plane factor
// per matched plane, each surface's prior once, the room's factors, the weak prior on P_T_M; P_T_M
// held constant where the window's surfaces do not fix it; nothing before the answer is held.
#include "slam/isgraph/plan_merging.hpp"

#include <gtest/gtest.h>

#include "slam/isgraph/match_input.hpp"
#include "slam/sgraph/tests/box_world.hpp"

namespace isg::slam {
namespace {

// As the S-Graph's window makes it: the merger keeps its loss and manifold.
ceres::Problem::Options windowOptions() {
  ceres::Problem::Options options;
  options.manifold_ownership = ceres::DO_NOT_TAKE_OWNERSHIP;
  options.loss_function_ownership = ceres::DO_NOT_TAKE_OWNERSHIP;
  return options;
}

class BoxMerge : public ::testing::Test {
 protected:
  BoxMerge()
      : plan_(testing::boxPlan(), {}, 1.0),
        graph_(testing::boxSGraph()),
        input_(matchInputOf(graph_, 1.0)),
        released_(WallReleaseOptions{}) {
    answer_.localized = true;
    answer_.P_T_M_x_y_yaw = plan_.inP(Eigen::Vector3d::Zero());
    for (const MatchPlane& p : input_.planes) {
      const Eigen::Vector2d n = p.plane.normal.head<2>();
      answer_.plane_matches[p.id] = n.y() > 0.5 ? 0 : n.y() < -0.5 ? 4 : n.x() > 0.5 ? 6 : 2;
      (n.y() > 0.5 || n.y() < -0.5 ? long_walls_ : short_walls_).insert(p.id);
    }
  }
  CompiledPlan plan_;
  SGraph graph_;
  MatchInput input_;
  HeldAnswer answer_;
  ReleasedWalls released_;
  std::set<int> long_walls_, short_walls_;
};

TEST_F(BoxMerge, NothingBeforeTheAnswerIsHeld) {
  PlanMerger merger(plan_, {});
  ceres::Problem problem(windowOptions());
  answer_.localized = false;
  std::set<int> all = long_walls_;
  all.insert(short_walls_.begin(), short_walls_.end());
  merger.addFactors(problem, all, {}, graph_, answer_, released_);
  EXPECT_EQ(problem.NumResidualBlocks(), 0);
}

TEST_F(BoxMerge, FourWallsInTwoDirectionsFixTheAnswer) {
  PlanMerger merger(plan_, {});
  ceres::Problem problem(windowOptions());
  std::set<int> all = long_walls_;
  all.insert(short_walls_.begin(), short_walls_.end());
  merger.addFactors(problem, all, {}, graph_, answer_, released_);
  // 4 plane-to-plane factors, 4 surface priors, the prior on P_T_M; the walls' factors need both
  // faces of a wall, and only the inner faces are matched.
  EXPECT_EQ(problem.NumResidualBlocks(), 9);
  EXPECT_FALSE(problem.IsParameterBlockConstant(answer_.P_T_M_x_y_yaw.data()));
  EXPECT_EQ(merger.windowsWithAnswerHeld(), 0);
}

TEST_F(BoxMerge, WallsOneWayOnlyHoldTheAnswerConstant) {
  PlanMerger merger(plan_, {});
  ceres::Problem problem(windowOptions());
  merger.addFactors(problem, long_walls_, {}, graph_, answer_, released_);
  EXPECT_EQ(problem.NumResidualBlocks(), 5);  // 2 + 2 + the prior
  EXPECT_TRUE(problem.IsParameterBlockConstant(answer_.P_T_M_x_y_yaw.data()));
  EXPECT_EQ(merger.windowsWithAnswerHeld(), 1);
}

TEST_F(BoxMerge, AMatchedFourWallRoomAddsItsFactorsAndFixesTheAnswer) {
  ASSERT_EQ(input_.rooms.size(), 1u);
  ASSERT_EQ(plan_.agraph().rooms.size(), 1u);
  ASSERT_EQ(plan_.agraph().rooms[0].kind, bim::RoomKind::kFourWall);
  answer_.room_matches[input_.rooms[0].id] = 0;
  PlanMerger merger(plan_, {});
  ceres::Problem problem(windowOptions());
  // The long walls alone would leave P_T_M free along x: the room fixes it.
  merger.addFactors(problem, long_walls_, {input_.rooms[0].id}, graph_, answer_, released_);
  // 2 plane-to-plane, 4 surface priors (the room's four faces), the A-Graph's four-wall room
  // factor, the room-to-room factor, the prior on P_T_M.
  EXPECT_EQ(problem.NumResidualBlocks(), 9);
  EXPECT_FALSE(problem.IsParameterBlockConstant(answer_.P_T_M_x_y_yaw.data()));
}

}  // namespace
}  // namespace isg::slam
