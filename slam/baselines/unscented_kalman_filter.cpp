#include "slam/baselines/unscented_kalman_filter.hpp"

#include <Eigen/Cholesky>
#include <cmath>
#include <stdexcept>

#include "slam/baselines/pose2.hpp"

namespace isg::slam {

namespace {

// a − b with the listed components wrapped.
Eigen::VectorXd difference(const Eigen::VectorXd& a, const Eigen::VectorXd& b,
                           const std::vector<int>& angles) {
  Eigen::VectorXd d = a - b;
  for (int i : angles) d[i] = common::angleDifference(a[i], b[i]);
  return d;
}

}  // namespace

UnscentedKalmanFilter::UnscentedKalmanFilter(Vector mean, Matrix covariance,
                                             std::vector<int> angles, double lambda)
    : mean_(std::move(mean)),
      covariance_(std::move(covariance)),
      angles_(std::move(angles)),
      lambda_(lambda) {
  const int n = int(mean_.size());
  if (covariance_.rows() != n || covariance_.cols() != n) {
    throw std::invalid_argument("the covariance does not match the state's size");
  }
  weights_.assign(2 * n + 1, 1.0 / (2.0 * (n + lambda_)));
  weights_[0] = lambda_ / (n + lambda_);
}

std::vector<UnscentedKalmanFilter::Vector> UnscentedKalmanFilter::sigmaPoints() const {
  const int n = int(mean_.size());
  const Matrix scaled = (n + lambda_) * covariance_;
  const Eigen::LLT<Matrix> llt(0.5 * (scaled + scaled.transpose()));
  if (llt.info() != Eigen::Success) {
    throw std::runtime_error("the filter's covariance is no longer positive definite");
  }
  const Matrix L = llt.matrixL();
  std::vector<Vector> points{mean_};
  for (int i = 0; i < n; ++i) points.push_back(mean_ + L.col(i));
  for (int i = 0; i < n; ++i) points.push_back(mean_ - L.col(i));
  return points;
}

UnscentedKalmanFilter::Vector UnscentedKalmanFilter::weightedMean(
    const std::vector<Vector>& points, const std::vector<int>& angles) const {
  Vector mean = Vector::Zero(points.front().size());
  for (std::size_t k = 0; k < points.size(); ++k) mean += weights_[k] * points[k];
  for (int i : angles) {
    double c = 0.0, s = 0.0;
    for (std::size_t k = 0; k < points.size(); ++k) {
      c += weights_[k] * std::cos(points[k][i]);
      s += weights_[k] * std::sin(points[k][i]);
    }
    mean[i] = std::atan2(s, c);
  }
  return mean;
}

void UnscentedKalmanFilter::predict(const Function& f, const Matrix& Q) {
  std::vector<Vector> points = sigmaPoints();
  for (auto& p : points) p = f(p);
  mean_ = weightedMean(points, angles_);
  covariance_ = Q;
  for (std::size_t k = 0; k < points.size(); ++k) {
    const Vector d = difference(points[k], mean_, angles_);
    covariance_ += weights_[k] * d * d.transpose();
  }
}

UnscentedKalmanFilter::Vector UnscentedKalmanFilter::update(const Vector& z, const Function& h,
                                                            const Matrix& R,
                                                            const std::vector<int>& angles) {
  const std::vector<Vector> points = sigmaPoints();
  std::vector<Vector> predicted;
  for (const auto& p : points) predicted.push_back(h(p));
  const Vector z_mean = weightedMean(predicted, angles);
  Matrix S = R;
  Matrix cross = Matrix::Zero(mean_.size(), z.size());
  for (std::size_t k = 0; k < points.size(); ++k) {
    const Vector dz = difference(predicted[k], z_mean, angles);
    S += weights_[k] * dz * dz.transpose();
    cross += weights_[k] * difference(points[k], mean_, angles_) * dz.transpose();
  }
  const Matrix K = cross * S.inverse();
  const Vector innovation = difference(z, z_mean, angles);
  mean_ += K * innovation;
  for (int i : angles_) mean_[i] = common::angleDifference(mean_[i], 0.0);
  covariance_ -= K * S * K.transpose();
  return innovation;
}

}  // namespace isg::slam
