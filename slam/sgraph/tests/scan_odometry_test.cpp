// Odometry without odometry: the attitude filter against hand-made IMU readings, and the whole of
// ScanOdometry on scans of a box room whose motion is known (walking, climbing).

#include "slam/sgraph/scan_odometry.hpp"
#include "common/angles.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>
#include <utility>

#include "slam/sgraph/tests/box_world.hpp"

namespace isg::slam {
namespace {

constexpr double kDeg = std::numbers::pi / 180.0;

Eigen::Matrix3d rollPitchYaw(double roll, double pitch, double yaw) {
  return (Eigen::AngleAxisd(yaw, Eigen::Vector3d::UnitZ()) *
          Eigen::AngleAxisd(pitch, Eigen::Vector3d::UnitY()) *
          Eigen::AngleAxisd(roll, Eigen::Vector3d::UnitX()))
      .toRotationMatrix();
}

double rollOf(const Eigen::Matrix3d& R) { return std::atan2(R(2, 1), R(2, 2)); }
double pitchOf(const Eigen::Matrix3d& R) { return std::asin(-R(2, 0)); }

// A unit at rest, tilted by `M_R_I`: it reads +g along M's up, in I.
sensors::ImuSample atRest(double t, const Eigen::Matrix3d& M_R_I) {
  sensors::ImuSample s;
  s.t = t;
  s.accelerometer = M_R_I.transpose() * Eigen::Vector3d(0, 0, 9.81);
  return s;
}

sensors::Scan emptyScan(double t) {
  sensors::Scan scan;
  scan.stamp = t;
  return scan;
}

TEST(ScanOdometry, GravityLevelsTheStartAndTheGyroscopeTurnsIt) {
  // The IMU mounted turned 90° about z on the base; the base tilted 4° in roll, -3° in pitch.
  Eigen::Isometry3d R_T_I = Eigen::Isometry3d::Identity();
  R_T_I.linear() = rollPitchYaw(0, 0, std::numbers::pi / 2);
  const Eigen::Matrix3d M_R_R = rollPitchYaw(4 * kDeg, -3 * kDeg, 0.7);
  ScanOdometry odometry(Eigen::Isometry3d::Identity(), R_T_I);
  for (int i = 0; i <= 100; ++i) odometry.addImu(atRest(0.01 * i, M_R_R * R_T_I.linear()));
  const Eigen::Isometry3d start = odometry.addScan(emptyScan(1.0));
  // M is the start pose: heading along x, tilt as gravity says, at the origin.
  EXPECT_NEAR(rollOf(start.linear()), 4 * kDeg, 1e-6);
  EXPECT_NEAR(pitchOf(start.linear()), -3 * kDeg, 1e-6);
  EXPECT_NEAR(common::yawOf(start.linear()), 0.0, 1e-9);
  EXPECT_LT(start.translation().norm(), 1e-12);
  // Turning at 0.5 rad/s about the base's up for one second, still level to gravity.
  const Eigen::Vector3d up_in_I = (M_R_R * R_T_I.linear()).transpose() * Eigen::Vector3d::UnitZ();
  for (int i = 1; i <= 100; ++i) {
    sensors::ImuSample s = atRest(1.0 + 0.01 * i, M_R_R * R_T_I.linear());
    s.gyroscope = 0.5 * up_in_I;
    odometry.addImu(s);
  }
  const Eigen::Isometry3d turned = odometry.addScan(emptyScan(2.0));
  EXPECT_NEAR(common::yawOf(turned.linear()), 0.5, 0.01);
  EXPECT_TRUE(odometry.hasImu());
}

// A unit at rest and level whose gyroscope reads `bias` about x, fed to `filter` for `seconds`:
// the roll it ends at.
double rollAfterBiasedRest(AttitudeFilter& filter, double bias, double seconds) {
  for (int i = 0; i <= int(seconds * 100); ++i) {
    sensors::ImuSample s = atRest(0.01 * i, Eigen::Matrix3d::Identity());
    s.gyroscope = Eigen::Vector3d(bias, 0, 0);
    filter.add(s);
  }
  return rollOf(filter.M_R_I_at(seconds));
}

TEST(AttitudeFilter, TheAccelerometerPullsADriftingGyroscopeBackToLevel) {
  // A gyroscope that believes the unit rolls at 1°/s while the accelerometer says level: the
  // filter settles where the pull (tilt / τ) balances the rate: 1°/s × 2 s = 2°, not a drift of
  // 30° over the 30 s.
  AttitudeFilter filter(2.0);
  EXPECT_NEAR(rollAfterBiasedRest(filter, 1 * kDeg, 30.0), 2 * kDeg, 0.05 * kDeg);
}

TEST(AttitudeFilter, EstimatingTheGyroscopesBiasLevelsALongTimeConstant) {
  // The odometry's 30 s time constant with a bias of 0.1°/s: held 3° off without the bias's
  // estimate (0.1°/s × 30 s); with it, level within 0.01° after 15 minutes (the critically damped
  // loop's time constant is 2τ = 60 s), the bias found.
  AttitudeFilter plain(30.0);
  EXPECT_NEAR(rollAfterBiasedRest(plain, 0.1 * kDeg, 900.0), 3 * kDeg, 0.05 * kDeg);
  AttitudeFilter estimating(30.0, 9.81, /*estimate_bias=*/true);
  EXPECT_NEAR(rollAfterBiasedRest(estimating, 0.1 * kDeg, 900.0), 0.0, 0.01 * kDeg);
  EXPECT_NEAR(estimating.gyroscopeBias().x(), 0.1 * kDeg, 1e-3 * kDeg);
}

TEST(ScanOdometry, FollowsAWalkAcrossARoomFromTheScansAlone) {
  // No IMU: the base walks 3 m along x at 0.5 m/s while turning 0.3 rad, level; the scans alone
  // must follow it.
  ScanOdometry odometry(Eigen::Isometry3d::Identity(), Eigen::Isometry3d::Identity());
  Eigen::Isometry3d truth = Eigen::Isometry3d::Identity();
  Eigen::Isometry3d estimate = Eigen::Isometry3d::Identity();
  for (int k = 0; k <= 60; ++k) {
    const double t = 0.1 * k;
    truth = Eigen::Isometry3d::Identity();
    truth.translation() = Eigen::Vector3d(0.05 * k, 0.01 * k, 0.0);
    truth.linear() = rollPitchYaw(0, 0, 0.005 * k);
    estimate = odometry.addScan(testing::boxScan(truth, t, 360));  // 1° apart
  }
  EXPECT_NEAR(estimate.translation().x(), truth.translation().x(), 0.03);
  EXPECT_NEAR(estimate.translation().y(), truth.translation().y(), 0.03);
  EXPECT_NEAR(common::yawOf(estimate.linear()), 0.3, 0.01);
  EXPECT_GT(odometry.agreed(), 55);
}

// A box room's scan in a spinning LiDAR's order: firing by firing, each firing's 16 lasers.
sensors::Scan firingOrder(const sensors::Scan& scan, int azimuths) {
  sensors::Scan out = scan;
  out.points.clear();
  for (int a = 0; a < azimuths; ++a) {
    for (int ring = 0; ring < 16; ++ring) out.points.push_back(scan.points[ring * azimuths + a]);
  }
  return out;
}

TEST(ScanOdometry, ReadsEverySecondReturnOfEachLaser) {
  // The same walk twice: whole scans read at the default stride of 2, and scans that hold only
  // each laser's first, third, ... returns read whole (stride 1). The odometry must not tell them
  // apart, pose for pose, to the bit. In firing order, a stride over the scan's points instead of
  // each laser's would drop every second laser.
  ScanOdometryOptions every_return;
  every_return.return_stride = 1;
  ScanOdometry halved(Eigen::Isometry3d::Identity(), Eigen::Isometry3d::Identity());
  ScanOdometry thinned(Eigen::Isometry3d::Identity(), Eigen::Isometry3d::Identity(), every_return);
  constexpr int kAzimuths = 720;
  for (int k = 0; k <= 30; ++k) {
    Eigen::Isometry3d truth = Eigen::Isometry3d::Identity();
    truth.translation() = Eigen::Vector3d(0.05 * k, 0.01 * k, 0.0);
    truth.linear() = rollPitchYaw(0, 0, 0.005 * k);
    const sensors::Scan scan = firingOrder(testing::boxScan(truth, 0.1 * k, kAzimuths), kAzimuths);
    sensors::Scan odd_dropped = scan;
    odd_dropped.points.clear();
    for (std::size_t i = 0; i < scan.points.size(); ++i) {
      if ((i / 16) % 2 == 0) odd_dropped.points.push_back(scan.points[i]);
    }
    const Eigen::Isometry3d a = halved.addScan(scan), b = thinned.addScan(odd_dropped);
    ASSERT_TRUE(a.matrix() == b.matrix()) << "scan " << k;
  }
  EXPECT_GT(halved.agreed(), 25);
  EXPECT_THROW(
      {
        ScanOdometryOptions none;
        none.return_stride = 0;
        ScanOdometry odometry(Eigen::Isometry3d::Identity(), Eigen::Isometry3d::Identity(), none);
      },
      std::invalid_argument);
}

// The box room's scans from a base that walks along x at 0.5 m/s and turns, level for 3 s (the
// odometry's map fills: one keyframe's rings are lines, not planes) then rising `climb` metres a
// scan for 3 s: the odometry's pose at the end and the truth's. `level_seen`: false drops the
// points on the floor and the ceiling.
std::pair<Eigen::Isometry3d, Eigen::Isometry3d> climb(double climb, bool level_seen) {
  ScanOdometry odometry(Eigen::Isometry3d::Identity(), Eigen::Isometry3d::Identity());
  Eigen::Isometry3d truth = Eigen::Isometry3d::Identity(), estimate = truth;
  for (int k = 0; k <= 60; ++k) {
    truth.translation() = Eigen::Vector3d(0.05 * k, 0.01 * k, climb * std::max(0, k - 30));
    truth.linear() = rollPitchYaw(0, 0, 0.005 * k);
    sensors::Scan scan = testing::boxScan(truth, 0.1 * k);
    if (!level_seen) {
      std::erase_if(scan.points, [&](const sensors::ScanPoint& p) {
        const double z = (truth * Eigen::Vector3d(p.x, p.y, p.z)).z();
        return z < -0.99 || z > 1.99;  // the floor at −1, the ceiling at 2
      });
    }
    estimate = odometry.addScan(scan);
  }
  return {estimate, truth};
}

TEST(ScanOdometry, FollowsAClimbByTheFloorAndTheCeiling) {
  // 0.3 m up over 3 s, as on a flight of stairs: the floor and the ceiling tell the height, within
  // 10 % (it ends 6 % short here: each keyframe enters the map a little behind the climb).
  const auto [estimate, truth] = climb(0.01, true);
  EXPECT_NEAR(estimate.translation().z(), 0.3, 0.03);
  EXPECT_NEAR(estimate.translation().x(), truth.translation().x(), 0.03);
  EXPECT_NEAR(estimate.translation().y(), truth.translation().y(), 0.03);
}

TEST(ScanOdometry, HoldsItsHeightWhereNothingLevelIsSeen) {
  // The same climb with the walls alone: nothing tells the height, and it is held where it was.
  const auto [estimate, truth] = climb(0.01, false);
  EXPECT_EQ(estimate.translation().z(), 0.0);
  EXPECT_NEAR(estimate.translation().x(), truth.translation().x(), 0.03);
}

}  // namespace
}  // namespace isg::slam
