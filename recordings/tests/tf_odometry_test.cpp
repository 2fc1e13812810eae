// Odometry from /tf: the tree of moving frames, the chain from the odometry's frame down to the
// base, and its poses against hand calculations.
#include <gtest/gtest.h>

#include <numbers>

#include "recordings/tf_odometry.hpp"
#include "sensors/mount_transform.hpp"

namespace isg::recordings {
namespace {

Eigen::Isometry3d along(double x, double yaw = 0.0) {
  return sensors::mountTransform({x, 0, 0, 0, 0, yaw});
}

double difference(const Eigen::Isometry3d& a, const Eigen::Isometry3d& b) {
  return (a.matrix() - b.matrix()).cwiseAbs().maxCoeff();
}

// map → odom (moving, slow) → base_footprint (moving) → base_link (fixed) → velodyne (repeated
// unchanged on /tf), and an arm joint beside the chain.
struct Navigation : ::testing::Test {
  void SetUp() override {
    fixed.add("base_footprint", "base_link", sensors::mountTransform({0, 0, 0.35, 0, 0, 0}));
    // Links that change on /tf move; one that repeats its transform (ROS 1's
    // static_transform_publisher on /tf) is fixed.
    for (double x : {0.0, 1.0}) {
      EXPECT_FALSE(tree.add("map", "odom", along(x)));
      EXPECT_FALSE(tree.add("odom", "base_footprint", along(x)));
      EXPECT_FALSE(tree.add("base_link", "arm_link", along(0.0, x)));
      EXPECT_FALSE(
          tree.add("base_link", "velodyne", sensors::mountTransform({0.1, 0, 0.5, 0, 0, 0})));
    }
  }
  StaticFrames fixed;
  MovingFrameTree tree;
};

TEST_F(Navigation, FramesAboveTheLidarNearestFirst) {
  const auto above = tree.above("velodyne", fixed);
  ASSERT_EQ(above.size(), 4u);
  const char* frames[] = {"base_link", "base_footprint", "odom", "map"};
  const bool moving[] = {false, false, true, true};
  for (int i = 0; i < 4; ++i) {
    EXPECT_EQ(above[i].frame, frames[i]);
    EXPECT_EQ(above[i].moving, moving[i]);
  }
  EXPECT_LT(
      difference(above[1].fixed_parent_T_child, sensors::mountTransform({0, 0, 0.35, 0, 0, 0})),
      1e-15);
  EXPECT_LT(
      difference(above[0].fixed_parent_T_child, sensors::mountTransform({0.1, 0, 0.5, 0, 0, 0})),
      1e-15);
  ASSERT_EQ(tree.unchanging().size(), 1u);
  EXPECT_EQ(tree.unchanging()[0].child, "velodyne");
  // A second parent is refused, naming the first.
  EXPECT_EQ(tree.add("world", "odom", along(0.0)), std::optional<std::string>("map"));
}

TEST_F(Navigation, PosesComposeTheChainAtTheStampsOfTheLinkNearestTheBase) {
  TfOdometry odometry("map", "base_link", tree.above("base_link", fixed));
  EXPECT_EQ(odometry.describe(),
            "map → odom (moving) → base_footprint (moving) → base_link (fixed)");
  // map → odom at 0 s and 2 s: 1 m apart, a quarter turn apart.
  odometry.offer("map", "odom", {100, 0}, along(0.0));
  odometry.offer("map", "odom", {102, 0}, along(1.0, std::numbers::pi / 2));
  // odom → base_footprint every 0.5 s from 99.5 s (before map → odom starts: left out).
  for (const formats::RosTime t :
       {formats::RosTime{99, 500000000}, formats::RosTime{100, 0}, formats::RosTime{100, 500000000},
        formats::RosTime{101, 0}, formats::RosTime{101, 500000000}, formats::RosTime{102, 0}}) {
    odometry.offer("odom", "base_footprint", t, along(0.0));
  }
  odometry.offer("base_link", "arm_link", {100, 0}, along(5.0));  // not of the chain
  // Links off the chain are ignored; a repeated stamp is dropped, an earlier one refused.
  odometry.offer("odom", "base_footprint", {102, 0}, along(9.0));
  EXPECT_EQ(odometry.repeated(), 1u);
  EXPECT_THROW(odometry.offer("odom", "base_footprint", {101, 0}, along(0.0)),
               std::invalid_argument);

  const auto poses = odometry.poses();
  // 99.5 s is before map → odom: out. 100 … 102 s remain.
  ASSERT_EQ(poses.size(), 5u);
  EXPECT_EQ(poses[0].stamp.sec, 100u);
  EXPECT_EQ(poses[1].stamp.nsec, 500000000u);
  // At 101 s map → odom is halfway: 0.5 m along x, turned by π/4; base_link 0.35 m above.
  const Eigen::Isometry3d expected =
      along(0.5, std::numbers::pi / 4) * sensors::mountTransform({0, 0, 0.35, 0, 0, 0});
  EXPECT_LT(difference(poses[2].top_T_base, expected), 1e-12);
  // At 100.5 s a quarter of the way.
  EXPECT_LT(difference(poses[1].top_T_base, along(0.25, std::numbers::pi / 8) *
                                                sensors::mountTransform({0, 0, 0.35, 0, 0, 0})),
            1e-12);
}

TEST_F(Navigation, AChainMustReachItsTopAndMove) {
  EXPECT_THROW(TfOdometry("world", "base_link", tree.above("base_link", fixed)),
               std::invalid_argument);
  try {
    TfOdometry("base_footprint", "velodyne", tree.above("velodyne", fixed));
    ADD_FAILURE();
  } catch (const std::invalid_argument& e) {
    EXPECT_STREQ(e.what(),
                 "nothing on /tf moves \"velodyne\" in \"base_footprint\": the frames join by "
                 "/tf_static alone");
  }
}

TEST(TfOdometryNames, OdometryFramesByName) {
  EXPECT_TRUE(namedLikeOdometry("odom"));
  EXPECT_TRUE(namedLikeOdometry("robot1/odom"));
  EXPECT_TRUE(namedLikeOdometry("odom_combined"));
  EXPECT_TRUE(namedLikeOdometry("Odometry"));
  EXPECT_FALSE(namedLikeOdometry("map"));
  EXPECT_FALSE(namedLikeOdometry("odom/base_link"));
  EXPECT_FALSE(namedLikeOdometry("vision_odom"));
}

}  // namespace
}  // namespace isg::recordings
