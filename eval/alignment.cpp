#include "eval/alignment.hpp"

#include <Eigen/SVD>
#include <algorithm>
#include <stdexcept>

namespace isg::eval {

Eigen::Isometry3d Similarity::apply(const Eigen::Isometry3d& pose) const {
  Eigen::Isometry3d out = Eigen::Isometry3d::Identity();
  out.translation() = apply(pose.translation());
  out.linear() = rotation * pose.linear();
  return out;
}

Similarity umeyama(const std::vector<Eigen::Vector3d>& from, const std::vector<Eigen::Vector3d>& to,
                   bool with_scale) {
  if (from.size() != to.size()) throw std::invalid_argument("umeyama: point sets differ in size");
  const std::size_t n = from.size();
  if (n < 3) throw std::invalid_argument("umeyama: at least 3 point pairs are needed");
  Eigen::Vector3d mean_from = Eigen::Vector3d::Zero(), mean_to = Eigen::Vector3d::Zero();
  for (std::size_t i = 0; i < n; ++i) {
    mean_from += from[i];
    mean_to += to[i];
  }
  mean_from /= double(n);
  mean_to /= double(n);
  double variance_from = 0.0;
  Eigen::Matrix3d covariance = Eigen::Matrix3d::Zero();
  for (std::size_t i = 0; i < n; ++i) {
    const Eigen::Vector3d a = from[i] - mean_from;
    variance_from += a.squaredNorm();
    covariance += (to[i] - mean_to) * a.transpose();
  }
  variance_from /= double(n);
  covariance /= double(n);
  const Eigen::JacobiSVD<Eigen::Matrix3d> svd(covariance,
                                              Eigen::ComputeFullU | Eigen::ComputeFullV);
  const Eigen::Vector3d singular = svd.singularValues();
  if (!(singular(1) > 1e-12 * std::max(singular(0), 1e-300))) {
    throw std::invalid_argument("umeyama: degenerate point sets (collinear or equal)");
  }
  Eigen::Matrix3d s = Eigen::Matrix3d::Identity();
  if (svd.matrixU().determinant() * svd.matrixV().determinant() < 0.0)
    s(2, 2) = -1.0;  // no reflection
  Similarity out;
  out.rotation = svd.matrixU() * s * svd.matrixV().transpose();
  out.scale = with_scale ? (singular.asDiagonal() * s).trace() / variance_from : 1.0;
  out.translation = mean_to - out.scale * out.rotation * mean_from;
  return out;
}

}  // namespace isg::eval
