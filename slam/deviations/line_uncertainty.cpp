#include "slam/deviations/line_uncertainty.hpp"

#include <algorithm>
#include <cmath>

namespace isg::slam {

Eigen::Matrix2d lineCovariance(const std::vector<std::pair<Eigen::Vector2d, double>>& ends,
                               double offset, double slope, double end_sigma) {
  Eigen::Matrix2d H = Eigen::Matrix2d::Zero(), S = Eigen::Matrix2d::Zero();
  double weight = 0.0, squares = 0.0;
  for (const auto& [q, w] : ends) {
    const Eigen::Vector2d J(1.0, q.x());
    H += w * J * J.transpose();
    S += w * w * J * J.transpose();
    const double r = q.y() - (offset + slope * q.x());
    weight += w;
    squares += w * r * r;
  }
  if (ends.size() < 2 || std::abs(H.determinant()) < 1e-12) {
    return Eigen::Vector2d(end_sigma * end_sigma, 1e6).asDiagonal();
  }
  double variance = end_sigma * end_sigma;
  if (ends.size() > 4) {
    const double n = double(ends.size());
    variance = std::max(variance, squares / weight * n / (n - 2.0));
  }
  const Eigen::Matrix2d H_inverse = H.inverse();
  return variance * H_inverse * S * H_inverse;
}

}  // namespace isg::slam
