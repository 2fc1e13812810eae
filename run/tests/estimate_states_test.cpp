#include "run/estimate_states.hpp"

#include <gtest/gtest.h>

#include <optional>

#include "run/driver.hpp"

namespace isg::run {
namespace {

Eigen::Isometry3d at(double x, double y) {
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  T.translation() = Eigen::Vector3d(x, y, 0.0);
  return T;
}

// Sigma by the stated model: 3 cm where the plan confirms; from there 1 cm a metre while the map
// carries the pose, 3 cm a metre while the last answer does (lost); back to 3 cm when confirmed.
TEST(EstimateStateTrack, SigmaGrowsWithTheMetresWalkedUnconfirmed) {
  EstimateStateTrack track;
  EXPECT_DOUBLE_EQ(track.next(PoseState::kLocalized, {0, 0, 0}).sigma_xy, 0.03);
  EXPECT_DOUBLE_EQ(track.next(PoseState::kLocalized, {4, 0, 0}).sigma_xy, 0.03);
  // 10 m tracked (3-4-5 triangles: 5 m, 5 m; height is not walked).
  EXPECT_DOUBLE_EQ(track.next(PoseState::kTracking, {7, 4, 1}).sigma_xy, 0.03 + 0.05);
  EXPECT_DOUBLE_EQ(track.next(PoseState::kTracking, {10, 8, 0}).sigma_xy, 0.03 + 0.10);
  // Then 10 m lost.
  EXPECT_DOUBLE_EQ(track.next(PoseState::kLost, {20, 8, 0}).sigma_xy, 0.13 + 0.30);
  const EstimateState found = track.next(PoseState::kLocalized, {21, 8, 0});
  EXPECT_EQ(found.state, PoseState::kLocalized);
  EXPECT_DOUBLE_EQ(found.sigma_xy, 0.03);
}

TEST(EstimateStates, SpelledAsTheFilesSpellThem) {
  for (PoseState s : {PoseState::kLocalized, PoseState::kTracking, PoseState::kLost}) {
    EXPECT_EQ(poseStateFromString(toString(s)), s);
  }
  EXPECT_STREQ(toString(PoseState::kTracking), "tracking");
  EXPECT_FALSE(poseStateFromString("Lost"));
  EXPECT_FALSE(poseStateFromString(""));
}

TEST(EstimateStates, TheSideFileHasARowPerPoseAtItsStamp) {
  const common::Trajectory estimate = {{12.5, at(0, 0)}, {12.6, at(1, 0)}, {1e20, at(2, 0)}};
  const std::vector<EstimateState> states = {
      {PoseState::kLocalized, 0.03}, {PoseState::kTracking, 0.0412}, {PoseState::kLost, 1.5}};
  EXPECT_EQ(estimateStatesText(estimate, states),
            "# stamp state sigma_xy_m (docs/formats.md, \"estimate_states.txt\")\n"
            "12.500000000 localized 0.0300\n"
            "12.600000000 tracking 0.0412\n"
            "100000000000000000000.000000000 lost 1.5000\n");
  EXPECT_THROW(estimateStatesText(estimate, std::vector<EstimateState>(2)), std::logic_error);
  const common::Trajectory lost = posesIn(estimate, states, {PoseState::kLost});
  ASSERT_EQ(lost.size(), 1u);
  EXPECT_EQ(lost[0].t, 1e20);
  EXPECT_EQ(posesIn(estimate, states, {PoseState::kLocalized, PoseState::kTracking}).size(), 2u);
  // Poses recorded without states were placed and confirmed.
  EXPECT_EQ(posesIn(estimate, {}, {PoseState::kLocalized}).size(), 3u);
}

// A localizer told what to say: its pose in M, whether it places its map in B, whether the plan
// confirms.
class ScriptedLocalizer : public slam::Localizer {
 public:
  std::string name() const override { return "scripted"; }
  void pushOdometry(const sensors::Odometry&) override {}
  void pushScan(const sensors::Scan&) override {}
  std::optional<sensors::Odometry> poseInMap() const override { return pose; }
  std::optional<Eigen::Isometry3d> mapInPlan() const override { return B_T_M; }
  bool planConfirms() const override { return confirms; }
  nlohmann::json graph() const override { return {}; }

  std::optional<sensors::Odometry> pose;
  std::optional<Eigen::Isometry3d> B_T_M;
  bool confirms = true;
};

// Nothing in B before the first localization; from then on a pose at every scan: placed while
// localized or tracking, by the last B_T_M while lost, each with its state.
TEST(LocalizerDriver, OncePlacedTheEstimateNeverGoesSilent) {
  ScriptedLocalizer localizer;
  const common::Trajectory no_odometry;
  LocalizerDriver driver(localizer, no_odometry, 0.1);
  const auto scanAt = [&](double t, double x) {
    localizer.pose = sensors::Odometry{t, at(x, 0)};
    driver.skip(t);
  };
  scanAt(0.0, 0.0);  // not yet localized
  localizer.B_T_M = at(100, 50);
  scanAt(0.1, 1.0);
  localizer.confirms = false;
  scanAt(0.2, 2.0);
  localizer.B_T_M.reset();  // lost: the map goes on, the answer is gone
  scanAt(0.3, 3.0);
  scanAt(0.4, 5.0);
  localizer.B_T_M = at(100, 51);  // found again, somewhat elsewhere
  localizer.confirms = true;
  scanAt(0.5, 6.0);
  ASSERT_EQ(driver.estimateMap().size(), 6u);
  ASSERT_EQ(driver.estimate().size(), 5u);
  ASSERT_EQ(driver.estimateStates().size(), 5u);
  EXPECT_EQ(driver.estimate()[0].t, 0.1);
  EXPECT_EQ(driver.estimateStates()[0].state, PoseState::kLocalized);
  EXPECT_EQ(driver.estimateStates()[1].state, PoseState::kTracking);
  EXPECT_DOUBLE_EQ(driver.estimateStates()[1].sigma_xy, 0.03 + 0.01);
  EXPECT_EQ(driver.estimateStates()[2].state, PoseState::kLost);
  EXPECT_EQ(driver.estimateStates()[3].state, PoseState::kLost);
  EXPECT_DOUBLE_EQ(driver.estimateStates()[3].sigma_xy, 0.04 + 0.03 + 0.06);
  EXPECT_EQ(driver.estimate()[3].pose.translation(), Eigen::Vector3d(105, 50, 0));
  EXPECT_EQ(driver.estimateStates()[4].state, PoseState::kLocalized);
  EXPECT_EQ(driver.estimate()[4].pose.translation(), Eigen::Vector3d(106, 51, 0));
  EXPECT_EQ(driver.localizedAt(), 0.1);
  ASSERT_TRUE(driver.mapInPlan());
  EXPECT_EQ(driver.mapInPlan()->translation(), Eigen::Vector3d(100, 51, 0));
}

// What the report judges the map by at the end: the last word while localized; the word at the
// last localized pose while only tracking since; nothing once lost, until localized again.
TEST(LocalizerDriver, TheMapIsJudgedWhereThePlanLastConfirmedIt) {
  ScriptedLocalizer localizer;
  const common::Trajectory no_odometry;
  LocalizerDriver driver(localizer, no_odometry, 0.1);
  const auto scanAt = [&](double t) {
    localizer.pose = sensors::Odometry{t, at(t, 0)};
    driver.skip(t);
  };
  scanAt(0.0);
  EXPECT_FALSE(driver.confirmedMapInPlan());  // never localized
  localizer.B_T_M = at(100, 50);
  scanAt(0.1);
  EXPECT_EQ(driver.confirmedMapInPlan()->translation(), Eigen::Vector3d(100, 50, 0));
  localizer.B_T_M = at(100.4, 50);  // the answer slides where the plan does not confirm it
  localizer.confirms = false;
  scanAt(0.2);
  EXPECT_EQ(driver.mapInPlan()->translation(), Eigen::Vector3d(100.4, 50, 0));
  EXPECT_EQ(driver.confirmedMapInPlan()->translation(), Eigen::Vector3d(100, 50, 0));
  localizer.B_T_M.reset();  // lost
  scanAt(0.3);
  EXPECT_TRUE(driver.mapInPlan());
  EXPECT_FALSE(driver.confirmedMapInPlan());
  localizer.B_T_M = at(100, 52);  // found again, not yet confirmed
  scanAt(0.4);
  EXPECT_FALSE(driver.confirmedMapInPlan());
  localizer.confirms = true;
  scanAt(0.5);
  EXPECT_EQ(driver.confirmedMapInPlan()->translation(), Eigen::Vector3d(100, 52, 0));
}

}  // namespace
}  // namespace isg::run
