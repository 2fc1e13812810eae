// The sensor contract's own arithmetic: mounts as [x, y, z, roll, pitch, yaw], where the odometry
// frame lies at the start, the streams quantised as their TUM files keep them, stage times.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "sensors/mount_transform.hpp"
#include "sensors/sensor_streams.hpp"
#include "sensors/stage_times.hpp"
#include "sensors/vlp16_layout.hpp"

namespace isg::sensors {
namespace {

constexpr double kPi = std::numbers::pi;

TEST(MountTransform, RotatesYawAfterPitchAfterRoll) {
  // A mount turned 90° in yaw only: the sensor's x axis is the base's y axis.
  const Eigen::Isometry3d yawed = mountTransform({0.1, 0.2, 0.5, 0.0, 0.0, kPi / 2});
  EXPECT_NEAR((yawed.linear() * Eigen::Vector3d::UnitX() - Eigen::Vector3d::UnitY()).norm(), 0.0,
              1e-12);
  EXPECT_NEAR((yawed.translation() - Eigen::Vector3d(0.1, 0.2, 0.5)).norm(), 0.0, 1e-15);
  // Roll 90° then yaw 90°: the sensor's y axis goes to z by the roll and stays there, its z axis
  // goes to −y by the roll, then to +x by the yaw.
  const Eigen::Isometry3d rolled = mountTransform({0, 0, 0, kPi / 2, 0.0, kPi / 2});
  EXPECT_NEAR((rolled.linear() * Eigen::Vector3d::UnitY() - Eigen::Vector3d::UnitZ()).norm(), 0.0,
              1e-12);
  EXPECT_NEAR((rolled.linear() * Eigen::Vector3d::UnitZ() - Eigen::Vector3d::UnitX()).norm(), 0.0,
              1e-12);
}

TEST(MountTransform, XyzRpyIsItsInverse) {
  const std::array<double, 6> mount{0.3, -0.1, 0.45, 0.05, -0.2, 2.9};
  const std::array<double, 6> again = mountXyzRpy(mountTransform(mount));
  for (int k = 0; k < 6; ++k) EXPECT_NEAR(again[k], mount[k], 1e-12) << k;
}

TEST(SensorStreams, TheOdometryFrameLiesWhereTheFirstPosesSayAndLevelWithoutOdometry) {
  SensorStreams streams;
  Eigen::Isometry3d B_T_R = Eigen::Isometry3d::Identity();
  B_T_R.translation() = Eigen::Vector3d(4.0, 2.0, 0.5);
  B_T_R.linear() = (Eigen::AngleAxisd(0.5, Eigen::Vector3d::UnitZ()) *
                    Eigen::AngleAxisd(0.1, Eigen::Vector3d::UnitX()))
                       .toRotationMatrix();
  streams.ground_truth = {{0.0, B_T_R}};
  EXPECT_TRUE(trueStartB_T_M(SensorStreams{}).isApprox(Eigen::Isometry3d::Identity()));
  // No odometry: M is the first pose levelled, its heading kept (the base's x axis heads 0.5 rad
  // in the plane; the roll of 0.1 rad does not turn it).
  const Eigen::Isometry3d levelled = trueStartB_T_M(streams);
  EXPECT_NEAR(std::atan2(levelled.linear()(1, 0), levelled.linear()(0, 0)), 0.5, 1e-12);
  EXPECT_NEAR((levelled.linear() * Eigen::Vector3d::UnitZ() - Eigen::Vector3d::UnitZ()).norm(),
              0.0, 1e-12);
  EXPECT_NEAR((levelled.translation() - B_T_R.translation()).norm(), 0.0, 1e-15);
  // With odometry starting at M_T_R: B_T_M = B_T_R · M_T_R⁻¹.
  Eigen::Isometry3d M_T_R = Eigen::Isometry3d::Identity();
  M_T_R.translation() = Eigen::Vector3d(1.0, 0.0, 0.0);
  streams.odometry = {{0.0, M_T_R}};
  const Eigen::Isometry3d B_T_M = trueStartB_T_M(streams);
  EXPECT_TRUE((B_T_M * M_T_R).isApprox(B_T_R, 1e-12));
}

TEST(SensorStreams, QuantisedToWhatTheirFilesKeep) {
  SensorStreams streams;
  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
  pose.translation() = Eigen::Vector3d(1.23456789, 0.0, 0.0);
  streams.ground_truth = {{0.1234567891234, pose}};
  streams.scan_stamps = {0.1234567891234};
  quantiseStreams(streams);
  // Nanoseconds of time and micrometres of position, as a TUM row holds them.
  EXPECT_DOUBLE_EQ(streams.scan_stamps[0], 0.123456789);
  EXPECT_DOUBLE_EQ(streams.ground_truth[0].t, 0.123456789);
  EXPECT_DOUBLE_EQ(streams.ground_truth[0].pose.translation().x(), 1.234568);
}

TEST(StageTimes, AddsByNameInTheOrderFirstReported) {
  StageTimes times;
  times.add("casting", 1.5);
  times.add("noise", 0.25);
  times.add("casting", 0.5);
  StageTimes more;
  more.add("noise", 0.25);
  more.add("poses", 1.0);
  times.add(more);
  ASSERT_EQ(times.stages().size(), 3u);
  EXPECT_EQ(times.stages()[0].first, "casting");
  EXPECT_EQ(times.stages()[2].first, "poses");
  EXPECT_DOUBLE_EQ(times.seconds("casting"), 2.0);
  EXPECT_DOUBLE_EQ(times.seconds("noise"), 0.5);
  EXPECT_DOUBLE_EQ(times.seconds("absent"), 0.0);
  EXPECT_DOUBLE_EQ(times.total(), 3.5);
}

TEST(Vlp16Layout, RingsNumberTheLasersByElevation) {
  for (int laser = 0; laser < Vlp16Layout::kLasers; ++laser) {
    EXPECT_EQ(Vlp16Layout::laser(Vlp16Layout::ring(laser)), laser);
    // Ring r is at −15° + 2° r.
    EXPECT_EQ(Vlp16Layout::kElevationDeg[laser], -15.0 + 2.0 * Vlp16Layout::ring(laser));
  }
}

}  // namespace
}  // namespace isg::sensors
