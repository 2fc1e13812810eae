#include "sim/body_shadow.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace isg::sim {

BodyShadow::BodyShadow(const RobotBox& body, const Eigen::Isometry3d& R_T_L)
    : body_(body), R_T_L_(R_T_L) {}

double BodyShadow::distance(const Eigen::Vector3d& origin_L,
                            const Eigen::Vector3d& direction_L) const {
  // The slab test in the body's frame R, where the box is axis-aligned.
  const Eigen::Vector3d p = R_T_L_ * origin_L - body_.centre;
  const Eigen::Vector3d v = R_T_L_.linear() * direction_L;
  double enter = 0.0, leave = std::numeric_limits<double>::infinity();
  for (int i = 0; i < 3; ++i) {
    if (std::abs(v[i]) < 1e-12) {
      if (std::abs(p[i]) > body_.half[i]) return -1.0;
      continue;
    }
    const double a = (-body_.half[i] - p[i]) / v[i];
    const double b = (body_.half[i] - p[i]) / v[i];
    enter = std::max(enter, std::min(a, b));
    leave = std::min(leave, std::max(a, b));
  }
  return enter <= leave ? enter : -1.0;
}

}  // namespace isg::sim
