// Up from a scan's structure, and the odometry that levels its start by it.

#include "slam/sgraph/structural_up.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "slam/sgraph/scan_odometry.hpp"
#include "slam/sgraph/tests/box_world.hpp"

namespace isg::slam {
namespace {

constexpr double kOneDegree = std::numbers::pi / 180.0;

std::vector<Eigen::Vector3f> cloudOfScan(const sensors::Scan& scan) {
  std::vector<Eigen::Vector3f> out;
  for (const auto& p : scan.points) out.emplace_back(p.x, p.y, p.z);
  return out;
}

// The box room scanned from 1 m above its floor, the sensor pitched 14° and rolled 5°.
Eigen::Isometry3d tiltedSensor() {
  Eigen::Isometry3d M_T_L = Eigen::Isometry3d::Identity();
  M_T_L.translation() = Eigen::Vector3d(1.0, 0.5, 0.0);
  M_T_L.linear() = (Eigen::AngleAxisd(0.3, Eigen::Vector3d::UnitZ()) *
                    Eigen::AngleAxisd(14 * kOneDegree, Eigen::Vector3d::UnitY()) *
                    Eigen::AngleAxisd(5 * kOneDegree, Eigen::Vector3d::UnitX()))
                       .toRotationMatrix();
  return M_T_L;
}

TEST(StructuralUp, AScanOfWallsAndFloorsTellsUpWhereGravityWasMisread) {
  const Eigen::Isometry3d M_T_L = tiltedSensor();
  const Eigen::Vector3d truth = M_T_L.linear().transpose() * Eigen::Vector3d::UnitZ();
  // The guess: the sensor taken for level (up along its own z), 14.8° off.
  const auto up = structuralUp(cloudOfScan(testing::boxScan(M_T_L, 0.0)), Eigen::Vector3d::UnitZ());
  ASSERT_TRUE(up.has_value());
  // Within a few tenths of a degree: the patches at the room's edges lean it a little.
  EXPECT_LT(std::acos(std::min(1.0, up->dot(truth))), 0.5 * kOneDegree);
}

TEST(StructuralUp, WallsOfOneDirectionAloneCannotTellIt) {
  // Two parallel walls (y = ±1.5), nothing level: up may turn about their normal.
  std::vector<Eigen::Vector3f> corridor;
  for (double x = -6; x <= 6; x += 0.2) {
    for (double z = -1; z <= 1.5; z += 0.2) {
      corridor.emplace_back(float(x), -1.5f, float(z));
      corridor.emplace_back(float(x), 1.5f, float(z));
    }
  }
  EXPECT_FALSE(structuralUp(corridor, Eigen::Vector3d::UnitZ()).has_value());
  EXPECT_FALSE(structuralUp({}, Eigen::Vector3d::UnitZ()).has_value());
}

TEST(ScanOdometry, AStartWhileAcceleratingIsLevelledByTheScansWallsAndFloor) {
  // The base level, the IMU's first sample reading 2.5 m/s² forward besides gravity: gravity
  // alone pitches the start 14.3°; the room's walls and floor level it.
  const auto startPitch = [](bool with_scan) {
    ScanOdometry odometry(Eigen::Isometry3d::Identity(), Eigen::Isometry3d::Identity());
    sensors::ImuSample sample;
    sample.accelerometer = Eigen::Vector3d(2.5, 0.0, 9.81);
    odometry.addImu(sample);
    sensors::Scan scan =
        with_scan ? testing::boxScan(Eigen::Isometry3d::Identity(), 0.0) : sensors::Scan();
    scan.stamp = 0.0;
    const Eigen::Isometry3d start = odometry.addScan(scan);
    return std::make_pair(std::asin(-start.linear()(2, 0)), odometry.startLevelled());
  };
  const auto [misread, none] = startPitch(false);
  EXPECT_NEAR(std::abs(misread), std::atan2(2.5, 9.81), 1e-6);
  EXPECT_FALSE(none.has_value());
  const auto [levelled, turned] = startPitch(true);
  EXPECT_LT(std::abs(levelled), 0.2 * kOneDegree);
  ASSERT_TRUE(turned.has_value());
  EXPECT_NEAR(*turned, std::atan2(2.5, 9.81), 0.2 * kOneDegree);
}

}  // namespace
}  // namespace isg::slam
