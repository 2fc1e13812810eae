#include "slam/odometry_buffer.hpp"

#include <gtest/gtest.h>

#include <vector>

namespace isg::slam {
namespace {

sensors::Odometry at(double t, double x, double yaw) {
  sensors::Odometry o;
  o.stamp = t;
  o.M_T_R.translation() = Eigen::Vector3d(x, 0, 0);
  o.M_T_R.linear() = Eigen::AngleAxisd(yaw, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  return o;
}

TEST(OdometryBuffer, InterpolatesBetweenMessages) {
  OdometryBuffer buffer;
  buffer.push(at(0.0, 0.0, 0.0));
  buffer.push(at(1.0, 2.0, 1.0));
  const auto mid = buffer.at(0.25);
  ASSERT_TRUE(mid);
  EXPECT_NEAR(mid->translation().x(), 0.5, 1e-12);
  EXPECT_NEAR(std::atan2(mid->linear()(1, 0), mid->linear()(0, 0)), 0.25, 1e-12);
  EXPECT_FALSE(buffer.at(1.5));
  EXPECT_FALSE(buffer.at(-0.1));
}

// The base moves at 1 m/s along x and turns at 1 rad/s; a fixed world point is seen at instants
// `dt` about the scan's stamp. Deskewed, the observations coincide in the frame at the stamp.
void expectDeskewedToTheStamp(double stamp, const std::vector<double>& dts) {
  OdometryBuffer buffer;
  for (int i = 0; i <= 20; ++i) buffer.push(at(i * 0.01, i * 0.01, i * 0.01));
  Eigen::Isometry3d R_T_L = Eigen::Isometry3d::Identity();
  R_T_L.translation() = Eigen::Vector3d(0.1, 0, 0.25);
  const Eigen::Vector3d world(5, 2, 1);
  sensors::Scan scan;
  scan.stamp = stamp;
  for (double dt : dts) {
    const Eigen::Isometry3d M_T_L = *buffer.at(scan.stamp + dt) * R_T_L;
    const Eigen::Vector3d p = M_T_L.inverse() * world;
    scan.points.push_back({float(p.x()), float(p.y()), float(p.z()), 0, 0, float(dt)});
  }
  EXPECT_EQ(deskew(scan, buffer, R_T_L), 0);
  const Eigen::Vector3d expected = (*buffer.at(scan.stamp) * R_T_L).inverse() * world;
  for (const auto& p : scan.points) {
    EXPECT_NEAR((Eigen::Vector3d(p.x, p.y, p.z) - expected).norm(), 0.0, 1e-5) << p.time;
  }
}

TEST(Deskew, PointsOfAMovingSensorReturnToTheStampsFrame) {
  expectDeskewedToTheStamp(0.02, {0.0, 0.05, 0.09});
}

TEST(Deskew, PointsBeforeALastPacketStampReturnToItsFrameToo) {
  // The ROS 1 driver stamps a cloud at its last packet: most points come before the stamp
  // (time −0.0995 … +0.0013 s).
  expectDeskewedToTheStamp(0.1195, {-0.0995, -0.06, -0.0321, 0.0, 0.0013});
}

}  // namespace
}  // namespace isg::slam
