#include "slam/baselines/unscented_kalman_filter.hpp"

#include <gtest/gtest.h>

#include <Eigen/Dense>

#include "slam/baselines/pose2.hpp"

namespace isg::slam {
namespace {

// On a linear system the unscented transform is exact: the UKF must give the linear Kalman
// filter's mean and covariance, step for step.
TEST(UnscentedKalmanFilter, EqualsTheLinearKalmanFilterOnALinearSystem) {
  // Constant velocity in 2D: x = (px, py, vx, vy), dt = 0.1; position measured.
  const double dt = 0.1;
  Eigen::Matrix4d F = Eigen::Matrix4d::Identity();
  F(0, 2) = F(1, 3) = dt;
  Eigen::Matrix<double, 2, 4> H = Eigen::Matrix<double, 2, 4>::Zero();
  H(0, 0) = H(1, 1) = 1.0;
  const Eigen::Matrix4d Q = Eigen::Vector4d(0.01, 0.02, 0.1, 0.05).asDiagonal();
  const Eigen::Matrix2d R = Eigen::Vector2d(0.04, 0.09).asDiagonal();
  Eigen::Vector4d x(1.0, -2.0, 0.5, 0.3);
  Eigen::Matrix4d P = Eigen::Vector4d(0.5, 0.4, 0.3, 0.2).asDiagonal();
  P(0, 2) = P(2, 0) = 0.1;
  UnscentedKalmanFilter ukf(x, P);
  const auto f = [&](const Eigen::VectorXd& s) { return Eigen::VectorXd(F * s); };
  const auto h = [&](const Eigen::VectorXd& s) { return Eigen::VectorXd(H * s); };
  for (int k = 0; k < 20; ++k) {
    x = F * x;
    P = F * P * F.transpose() + Q;
    ukf.predict(f, Q);
    ASSERT_TRUE(ukf.mean().isApprox(x, 1e-9)) << k;
    ASSERT_TRUE(ukf.covariance().isApprox(P, 1e-9)) << k;
    const Eigen::Vector2d z(1.0 + 0.05 * k + 0.1 * std::sin(k), -2.0 + 0.03 * k);
    const Eigen::Matrix2d S = H * P * H.transpose() + R;
    const Eigen::Matrix<double, 4, 2> K = P * H.transpose() * S.inverse();
    x += K * (z - H * x);
    P = (Eigen::Matrix4d::Identity() - K * H) * P;
    ukf.update(z, h, R);
    ASSERT_TRUE(ukf.mean().isApprox(x, 1e-9)) << k;
    ASSERT_TRUE(ukf.covariance().isApprox(P, 1e-9)) << k;
  }
}

// Angles are averaged on the circle: a heading near ±π does not average to 0.
TEST(UnscentedKalmanFilter, HeadingsAcrossPiStayThere) {
  Eigen::VectorXd x(1);
  x << M_PI - 0.01;
  UnscentedKalmanFilter ukf(x, Eigen::MatrixXd::Identity(1, 1) * 0.01, {0});
  ukf.predict([](const Eigen::VectorXd& s) { return Eigen::VectorXd(s.array() + 0.02); },
              Eigen::MatrixXd::Identity(1, 1) * 1e-4);
  EXPECT_NEAR(common::angleDifference(ukf.mean()[0], -M_PI + 0.01), 0.0, 1e-9);
  EXPECT_NEAR(ukf.covariance()(0, 0), 0.01 + 1e-4, 1e-9);
  Eigen::VectorXd z(1);
  z << -M_PI + 0.03;  // 0.02 past the prediction, across the seam
  const Eigen::VectorXd innovation = ukf.update(z, [](const Eigen::VectorXd& s) { return s; },
                                                Eigen::MatrixXd::Identity(1, 1) * 0.0101, {0});
  EXPECT_NEAR(innovation[0], 0.02, 1e-9);
  EXPECT_NEAR(common::angleDifference(ukf.mean()[0], -M_PI + 0.02), 0.0,
              1e-9);  // halfway: equal noise
}

}  // namespace
}  // namespace isg::slam
