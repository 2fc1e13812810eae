// The wrapper that gives a localizer odometry made from the scans (docs/slam.md, "Without
// odometry") answers every question about the estimate as the localizer inside it does: a query
// it did not pass on would answer with the base class's default for every hand-held run (it once
// did for planConfirms, and no hand-held pose was ever reported "tracking").
#include "slam/sgraph/scan_odometry_localizer.hpp"

#include <gtest/gtest.h>

namespace isg::slam {
namespace {

class FixedAnswers : public Localizer {
 public:
  std::string name() const override { return "fixed"; }
  void pushOdometry(const sensors::Odometry&) override {}
  void pushScan(const sensors::Scan&) override {}
  std::optional<sensors::Odometry> poseInMap() const override {
    return sensors::Odometry{2.5, Eigen::Isometry3d::Identity()};
  }
  std::optional<Eigen::Isometry3d> mapInPlan() const override {
    Eigen::Isometry3d B_T_M = Eigen::Isometry3d::Identity();
    B_T_M.translation().x() = 7.0;
    return B_T_M;
  }
  bool planConfirms() const override { return false; }
  nlohmann::json graph() const override { return {{"fixed", true}}; }
  std::optional<std::string> searchStatus() const override { return "searching"; }
};

TEST(ScanOdometryLocalizer, PassesEveryQueryToTheLocalizerInside) {
  const ScanOdometryLocalizer wrapped(std::make_unique<FixedAnswers>(),
                                      Eigen::Isometry3d::Identity(), Eigen::Isometry3d::Identity());
  EXPECT_EQ(wrapped.name(), "fixed");
  ASSERT_TRUE(wrapped.poseInMap());
  EXPECT_EQ(wrapped.poseInMap()->stamp, 2.5);
  ASSERT_TRUE(wrapped.mapInPlan());
  EXPECT_EQ(wrapped.mapInPlan()->translation().x(), 7.0);
  EXPECT_FALSE(wrapped.planConfirms());
  EXPECT_EQ(wrapped.searchStatus(), "searching");
}

}  // namespace
}  // namespace isg::slam
