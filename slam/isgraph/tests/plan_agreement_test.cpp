// Whether the answer still holds (PlanAgreement), on the box room mapped by a walk along x: its
// scans agree with the plan under the right answer; a pose outside the building, walls that
// disagree and a plan that no longer explains the scan lose it, with their messages; too few walls
// held, none of them for disagreeing, leave it unconfirmed, not lost (docs/matching.md, "Lost").
#include "slam/isgraph/plan_agreement.hpp"

#include <gtest/gtest.h>

#include "slam/isgraph/match_input.hpp"
#include "slam/sgraph/tests/box_world.hpp"

namespace isg::slam {
namespace {

class BoxAgreement : public ::testing::Test {
 protected:
  BoxAgreement()
      : plan_(testing::boxPlan(), {}, 1.0),
        graph_(testing::boxSGraph()),
        input_(matchInputOf(graph_, 1.0)) {
    answer_.localized = true;
    answer_.P_T_M_x_y_yaw = plan_.inP(Eigen::Vector3d::Zero());  // B_T_M is the identity
    for (const MatchPlane& p : input_.planes) {
      const Eigen::Vector2d n = p.plane.normal.head<2>();
      answer_.plane_matches[p.id] = n.y() > 0.5 ? 0 : n.y() < -0.5 ? 4 : n.x() > 0.5 ? 6 : 2;
    }
  }
  CompiledPlan plan_;
  SGraph graph_;
  MatchInput input_;
  HeldAnswer answer_;
};

TEST_F(BoxAgreement, TheRightAnswerAgrees) {
  PlanAgreement agreement(plan_, Eigen::Isometry3d::Identity(), {});
  // Every point at wall height is on a wall of the plan.
  EXPECT_GT(agreement.planShare(graph_, answer_), 0.99);
  for (int k = 0; k < 5; ++k) EXPECT_EQ(agreement.update(input_, graph_, answer_), "") << k;
  EXPECT_EQ(answer_.plane_matches.size(), 4u);
}

TEST_F(BoxAgreement, APoseOutsideTheBuildingIsLost) {
  PlanAgreement agreement(plan_, Eigen::Isometry3d::Identity(), {});
  // The robot ends at x = 4 m in M; under an answer 9 m further east it stands at x = 13 in B,
  // beyond the east wall's outer face (8.2) and the 1 m margin. The scan's plan share is taken
  // first: without a history of shares, a scan that agrees with the map does not lose it.
  answer_.P_T_M_x_y_yaw.x() += 9.0;
  EXPECT_EQ(agreement.update(input_, graph_, answer_),
            "the pose (13.0, 0.0) is outside the building");
  // The scan registered on the recent map: the map is intact, only the answer is let go (the
  // localizer keeps the map and matches on it again once the pose is back within the plan).
  ASSERT_TRUE(graph_.keyframes().back().registration.attempted);
  EXPECT_TRUE(agreement.leftTheOutline());
}

// A wrong answer slid 0.6 m along x: the north and south walls stay in the gate (it slid along
// them), the east and west ones leave it (0.5 m) — two of four, not more than half, so not lost
// for that — and the two left are too few after walls disagreed: lost, not unconfirmed.
TEST_F(BoxAgreement, TooFewLeftAfterWallsDisagreedIsLost) {
  PlanAgreement agreement(plan_, Eigen::Isometry3d::Identity(),
                          {.plan_share_distance = 100.0});  // the scan check passes
  answer_.P_T_M_x_y_yaw.x() += 0.6;
  EXPECT_EQ(agreement.update(input_, graph_, answer_), "only 2 plan correspondences left");
  EXPECT_EQ(answer_.plane_matches.size(), 2u);
}

TEST_F(BoxAgreement, WallsThatLeaveTheHoldGateAreDroppedThenTheAnswerIsLost) {
  // Turned 30° (beyond the 20° gate), every held wall disagrees: dropped, and all four the
  // keyframe sees disagree.
  PlanAgreement agreement(plan_, Eigen::Isometry3d::Identity(),
                          {.plan_share_distance = 100.0});  // the scan check passes
  answer_.P_T_M_x_y_yaw.z() = 30.0 * std::numbers::pi / 180.0;
  EXPECT_EQ(agreement.update(input_, graph_, answer_),
            "4 of the 4 matched walls seen now disagree with the plan");
  EXPECT_FALSE(agreement.leftTheOutline());
  EXPECT_TRUE(answer_.plane_matches.empty());
}

TEST_F(BoxAgreement, TooFewCorrespondencesLeftIsUnconfirmedNotLost) {
  PlanAgreement agreement(plan_, Eigen::Isometry3d::Identity(), {});
  answer_.plane_matches.erase(answer_.plane_matches.begin());
  answer_.plane_matches.erase(answer_.plane_matches.begin());
  EXPECT_EQ(agreement.update(input_, graph_, answer_), "");
  EXPECT_EQ(agreement.unconfirmed(), "only 2 plan correspondences left");
  agreement.clear();
  EXPECT_EQ(agreement.unconfirmed(), "");
}

TEST_F(BoxAgreement, AScanThePlanNoLongerExplainsIsLostOnTheSecondKeyframe) {
  PlanAgreement agreement(plan_, Eigen::Isometry3d::Identity(), {});
  for (int k = 0; k < 3; ++k) ASSERT_EQ(agreement.update(input_, graph_, answer_), "");
  // Moved 0.4 m along x and y (within the 0.5 m hold gate), every wall's points are 0.4 m off
  // their face, beyond the 0.2 m that counts as on one, but near the corners: the share falls
  // below 0.3 × its median.
  answer_.P_T_M_x_y_yaw.head<2>() += Eigen::Vector2d(0.4, 0.4);
  const double share = agreement.planShare(graph_, answer_);
  EXPECT_LT(share, 0.3);
  EXPECT_EQ(agreement.update(input_, graph_, answer_), "");  // once: not yet
  char expected[200];
  std::snprintf(expected, sizeof expected,
                "the scans no longer agree with the plan (%.0f %% of the wall points on a plan "
                "wall, %.0f %% before)",
                100.0 * share, 100.0);
  EXPECT_EQ(agreement.update(input_, graph_, answer_), expected);
  // A new answer starts a new history.
  agreement.clear();
  EXPECT_EQ(agreement.update(input_, graph_, answer_), "");
}

}  // namespace
}  // namespace isg::slam
