#include "slam/sgraph/scan_registration.hpp"
#include "common/angles.hpp"

#include <gtest/gtest.h>

#include <Eigen/Eigenvalues>

#include <cmath>
#include <numbers>
#include <random>

namespace isg::slam {
namespace {

// A 10 m × 6 m room with 2.5 m walls and a 1 m pillar box, as a LiDAR at `L_in_M` (x, y, yaw; the
// sensor at 0.7 m) would see it: the walls and the box sampled on a fine grid, kept within 30 m,
// expressed in L. The room spans [0, 10] × [0, 6].
std::vector<Eigen::Vector3f> roomCloud(const Eigen::Vector3d& L_in_M, std::mt19937_64& rng) {
  std::vector<Eigen::Vector3d> world;
  for (double z = 0.1; z < 2.5; z += 0.1) {
    for (double s = 0.0; s <= 10.0; s += 0.05)
      world.push_back({s, 0.0, z}), world.push_back({s, 6.0, z});
    for (double s = 0.0; s <= 6.0; s += 0.05)
      world.push_back({0.0, s, z}), world.push_back({10.0, s, z});
    if (z < 1.0) {
      for (double s = 0.0; s <= 1.0; s += 0.05) {
        world.push_back({7.0 + s, 4.0, z}), world.push_back({7.0 + s, 5.0, z});
        world.push_back({7.0, 4.0 + s, z}), world.push_back({8.0, 4.0 + s, z});
      }
    }
  }
  Eigen::Isometry3d M_T_L = Eigen::Isometry3d::Identity();
  M_T_L.linear() = Eigen::AngleAxisd(L_in_M.z(), Eigen::Vector3d::UnitZ()).toRotationMatrix();
  M_T_L.translation() = Eigen::Vector3d(L_in_M.x(), L_in_M.y(), 0.7);
  std::normal_distribution<double> noise(0.0, 0.01);
  std::vector<Eigen::Vector3f> out;
  for (const auto& p : world) {
    Eigen::Vector3d q = M_T_L.inverse() * p;
    q += noise(rng) * q.normalized();
    out.push_back(q.cast<float>());
  }
  return out;
}

sensors::Scan asScan(const std::vector<Eigen::Vector3f>& cloud) {
  sensors::Scan scan;
  for (const auto& p : cloud) scan.points.push_back({p.x(), p.y(), p.z(), 0.0f, 0, 0.0f});
  return scan;
}

Eigen::Isometry3d planarPose(double x, double y, double yaw) {
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  T.linear() = Eigen::AngleAxisd(yaw, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  T.translation() = Eigen::Vector3d(x, y, 0.0);
  return T;
}

TEST(ScanRegistration, DownsamplingKeepsOneCentroidPerVoxel) {
  sensors::Scan scan;
  // Two points in one 0.2 m voxel, one in another, one too close, one too far.
  scan.points = {{1.01f, 1.01f, 0.01f, 0, 0, 0},
                 {1.09f, 1.05f, 0.03f, 0, 0, 0},
                 {2.5f, 0.1f, 0.1f, 0, 0, 0},
                 {0.1f, 0.0f, 0.0f, 0, 0, 0},
                 {40.0f, 0.0f, 0.0f, 0, 0, 0}};
  ScanRegistrationOptions options;
  const auto cloud = downsampleScan(scan, options);
  ASSERT_EQ(cloud.size(), 2u);
  EXPECT_NEAR(cloud[0].x(), 1.05f, 1e-5);
  EXPECT_NEAR(cloud[0].y(), 1.03f, 1e-5);
  EXPECT_NEAR(cloud[1].x(), 2.5f, 1e-5);
}

// The robot stood at (3, 3, 0) for the map; now at (4, 3.2, 0.05 rad), but odometry predicts
// (4.1, 3.1, 0.10 rad): a 5.7° heading error, as a 3°/m bias gives over two metres.
TEST(ScanRegistration, RecoversThePoseFromAWrongPrediction) {
  std::mt19937_64 rng(7);
  ScanRegistrationOptions options;
  const Eigen::Isometry3d R_T_L = Eigen::Isometry3d(Eigen::Translation3d(0.0, 0.0, 0.7));
  const auto map_cloud = downsampleScan(asScan(roomCloud({3.0, 3.0, 0.0}, rng)), options);
  const LocalMap map({{&map_cloud, planarPose(3.0, 3.0, 0.0) * R_T_L}}, options);
  ASSERT_GT(map.size(), 500u);
  const auto scan = downsampleScan(asScan(roomCloud({4.0, 3.2, 0.05}, rng)), options);
  const Eigen::Isometry3d predicted = planarPose(4.1, 3.1, 0.10);
  // A weak prior: 0.3 m, 3°.
  const Eigen::Matrix3d prior =
      Eigen::Vector3d(1 / 0.09, 1 / 0.09, 1 / std::pow(3.0 * std::numbers::pi / 180, 2))
          .asDiagonal();
  const RegistrationResult r = registerScan(scan, predicted, R_T_L, map, prior, options);
  const Eigen::Isometry3d corrected = r.apply(predicted);
  EXPECT_NEAR(corrected.translation().x(), 4.0, 0.02);
  EXPECT_NEAR(corrected.translation().y(), 3.2, 0.02);
  EXPECT_NEAR(common::yawOf(corrected.linear()), 0.05, 0.3 * std::numbers::pi / 180);
  EXPECT_TRUE(r.agrees);
  EXPECT_GT(r.inlier_share, 0.9);
  EXPECT_LT(r.inlier_share_predicted, r.inlier_share);
  // Walls both ways: every direction is constrained, far more than by the prior.
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eigen(r.information);
  EXPECT_GT(eigen.eigenvalues()(0), prior.diagonal().minCoeff());
}

// The shares are taken from the ICP passes, not counted on their own: they must be what a count
// at the prediction and at the result gives, also when the pass budget ends before the steps
// become small (two passes, one).
TEST(ScanRegistration, SharesFromThePassesAreTheCountedShares) {
  std::mt19937_64 rng(11);
  const Eigen::Isometry3d R_T_L = Eigen::Isometry3d(Eigen::Translation3d(0.0, 0.0, 0.7));
  for (const int iterations : {12, 2, 1}) {
    ScanRegistrationOptions options;
    options.iterations = iterations;
    const auto map_cloud = downsampleScan(asScan(roomCloud({3.0, 3.0, 0.0}, rng)), options);
    const LocalMap map({{&map_cloud, planarPose(3.0, 3.0, 0.0) * R_T_L}}, options);
    const auto scan = downsampleScan(asScan(roomCloud({4.0, 3.2, 0.05}, rng)), options);
    const Eigen::Isometry3d predicted = planarPose(4.3, 3.0, 0.12);
    const Eigen::Matrix3d prior = Eigen::Matrix3d::Identity();
    const RegistrationResult r = registerScan(scan, predicted, R_T_L, map, prior, options);
    auto counted = [&](const Eigen::Isometry3d& M_T_R) {
      int near = 0;
      for (const auto& p : scan) {
        double d = 0.0;
        near +=
            map.nearest(M_T_R * R_T_L * p.cast<double>(), options.max_correspondence_end, &d) >= 0;
      }
      return double(near) / double(scan.size());
    };
    EXPECT_NEAR(r.inlier_share_predicted, counted(predicted), 1e-12) << iterations;
    // After a last step under a millimetre a point may cross the 0.25 m line: within a percent.
    EXPECT_NEAR(r.inlier_share, counted(r.apply(predicted)), 0.01) << iterations;
  }
}

// In a corridor (only the two long walls seen), the position along it is not observable: the
// registration leaves it to the prior (the odometry) instead of sliding.
TEST(ScanRegistration, ACorridorLeavesItsAxisToTheOdometry) {
  std::vector<Eigen::Vector3f> corridor;
  auto make = [](double x0) {
    std::vector<Eigen::Vector3f> out;
    for (double z = -0.6; z < 1.8; z += 0.1) {
      for (double s = -40.0; s <= 40.0; s += 0.05) {
        out.push_back(Eigen::Vector3f(float(s - x0), -1.0f, float(z)));
        out.push_back(Eigen::Vector3f(float(s - x0), 1.0f, float(z)));
      }
    }
    return out;
  };
  ScanRegistrationOptions options;
  sensors::Scan scan_map, scan_now;
  for (const auto& p : make(0.0)) scan_map.points.push_back({p.x(), p.y(), p.z(), 0, 0, 0});
  for (const auto& p : make(1.0)) scan_now.points.push_back({p.x(), p.y(), p.z(), 0, 0, 0});
  const auto map_cloud = downsampleScan(scan_map, options);
  const LocalMap map({{&map_cloud, Eigen::Isometry3d::Identity()}}, options);
  const auto scan = downsampleScan(scan_now, options);
  // Truth: 1.0 m along x. Predicted 1.3 m along x and 0.1 m off the axis.
  const Eigen::Isometry3d predicted = planarPose(1.3, 0.1, 0.0);
  const Eigen::Matrix3d prior = Eigen::Vector3d(100.0, 100.0, 1e4).asDiagonal();
  const RegistrationResult r =
      registerScan(scan, predicted, Eigen::Isometry3d::Identity(), map, prior, options);
  const Eigen::Isometry3d corrected = r.apply(predicted);
  EXPECT_NEAR(corrected.translation().y(), 0.0, 0.02);  // across: the walls say
  EXPECT_NEAR(corrected.translation().x(), 1.3, 0.05);  // along: the prior's
  EXPECT_LT(r.information(0, 0), 1e-3 * r.information(1, 1));
}

// A scan of another place does not agree with the local map.
TEST(ScanRegistration, AScanOfAnotherPlaceDisagrees) {
  std::mt19937_64 rng(3);
  ScanRegistrationOptions options;
  const auto map_cloud = downsampleScan(asScan(roomCloud({3.0, 3.0, 0.0}, rng)), options);
  const LocalMap map({{&map_cloud, planarPose(3.0, 3.0, 0.0)}}, options);
  // The same room seen from elsewhere but predicted at the map's pose, turned by 90°: as if the
  // robot had been carried off.
  const auto scan = downsampleScan(asScan(roomCloud({8.5, 1.5, 1.2}, rng)), options);
  const Eigen::Matrix3d prior = Eigen::Vector3d(100.0, 100.0, 1e4).asDiagonal();
  const RegistrationResult r = registerScan(scan, planarPose(3.0, 3.0, 0.0),
                                            Eigen::Isometry3d::Identity(), map, prior, options);
  EXPECT_FALSE(r.agrees);
  EXPECT_LT(r.inlier_share, options.min_inlier_share);
}

}  // namespace
}  // namespace isg::slam
