#pragma once

#include <Eigen/Core>

namespace isg::worlds {

// Whether two segments cross at a point inside both (touching or collinear is not crossing).
bool crosses(const Eigen::Vector2d& a0, const Eigen::Vector2d& a1, const Eigen::Vector2d& b0,
             const Eigen::Vector2d& b1);

// The least distance between the end points of each segment and the other segment: the distance
// between two segments that do not cross (0 where they touch). A segment of zero length is a
// point.
double segmentDistance(const Eigen::Vector2d& a0, const Eigen::Vector2d& a1,
                       const Eigen::Vector2d& b0, const Eigen::Vector2d& b1);

}  // namespace isg::worlds
