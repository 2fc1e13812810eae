#include "worlds/segment_distance.hpp"

#include <algorithm>

namespace isg::worlds {

double segmentDistance(const Eigen::Vector2d& a0, const Eigen::Vector2d& a1,
                       const Eigen::Vector2d& b0, const Eigen::Vector2d& b1) {
  const auto pointToSegment = [](const Eigen::Vector2d& p, const Eigen::Vector2d& s0,
                                 const Eigen::Vector2d& s1) {
    const Eigen::Vector2d d = s1 - s0;
    if (d.squaredNorm() < 1e-12) return (p - s0).norm();  // a point
    const double t = std::clamp((p - s0).dot(d) / d.squaredNorm(), 0.0, 1.0);
    return (s0 + t * d - p).norm();
  };
  return std::min({pointToSegment(a0, b0, b1), pointToSegment(a1, b0, b1),
                   pointToSegment(b0, a0, a1), pointToSegment(b1, a0, a1)});
}

bool crosses(const Eigen::Vector2d& a0, const Eigen::Vector2d& a1, const Eigen::Vector2d& b0,
             const Eigen::Vector2d& b1) {
  const auto cross = [](const Eigen::Vector2d& u, const Eigen::Vector2d& v) {
    return u.x() * v.y() - u.y() * v.x();
  };
  const double d1 = cross(a1 - a0, b0 - a0), d2 = cross(a1 - a0, b1 - a0);
  const double d3 = cross(b1 - b0, a0 - b0), d4 = cross(b1 - b0, a1 - b0);
  return d1 * d2 < 0 && d3 * d4 < 0;
}

}  // namespace isg::worlds
