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

// The trajectory as its TUM text carries it: each number rounded as toTumText prints it and read
// back as parseTum reads it — bit for bit parseTum(toTumText(trajectory)), without the text. A
// run quantises its streams with this once, so that the live loop and the replay of a recorded
// dataset see the very same numbers.
Trajectory quantised(const Trajectory& trajectory);
// A time as a TUM row keeps it (nanoseconds).
double quantisedTime(double t);

// Parses TUM text; '#' lines and blank lines are skipped. A malformed line throws
// std::runtime_error naming `file` and the line number.
Trajectory parseTum(const std::string& text, const std::string& file);
Trajectory readTum(const std::string& path);

}  // namespace isg::eval
