#pragma once

#include <Eigen/Geometry>
#include <string>
#include <vector>

namespace isg::eval {

// A trajectory in the TUM format: one pose per line, "t tx ty tz qx qy qz qw".
struct StampedPose {
  double t = 0.0;
  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
};
using Trajectory = std::vector<StampedPose>;

// The text of a TUM file: time with nanoseconds, positions with micrometres, quaternions with 9
// decimals (qw ≥ 0, so that equal rotations print equally).
std::string toTumText(const Trajectory& trajectory);

// Parses TUM text; '#' lines and blank lines are skipped. A malformed line throws
// std::runtime_error naming `file` and the line number.
Trajectory parseTum(const std::string& text, const std::string& file);
Trajectory readTum(const std::string& path);

}  // namespace isg::eval
