#pragma once

#include <Eigen/Geometry>
#include <array>
#include <cstdint>
#include <span>
#include <stdexcept>
#include <string>
#include <vector>

#include "common/trajectory.hpp"

namespace isg::common {

// Trajectories as TUM text: one pose per line, "t tx ty tz qx qy qz qw".

// The text of a TUM file: time with nanoseconds, positions with micrometres, quaternions with 9
// decimals (qw ≥ 0, so that equal rotations print equally).
std::string toTumText(std::span<const StampedPose> trajectory);

// The trajectory as its TUM text carries it: each number rounded as toTumText prints it and read
// back as parseTum reads it — bit for bit parseTum(toTumText(trajectory)), without the text. A
// run quantises its streams with this once, so that the live loop and the replay of a recorded
// dataset see the very same numbers.
Trajectory quantised(const Trajectory& trajectory);
// The same in place.
void quantise(Trajectory& trajectory);
// A time as a TUM row keeps it (nanoseconds).
double quantisedTime(double t);
// A position as a TUM row keeps it: in steps of 1e-6 m (integers, −0 where a coordinate rounds
// to zero from below), and the position those steps read back as (steps / 1e6 each).
// quantisedPosition(p) is positionOfTumSteps(tumPositionSteps(p)).
std::array<double, 3> tumPositionSteps(const Eigen::Vector3d& position);
Eigen::Vector3d positionOfTumSteps(const std::array<double, 3>& steps);
Eigen::Vector3d quantisedPosition(const Eigen::Vector3d& position);
// A rotation as a TUM row keeps it: its unit quaternion (w ≥ 0) in steps of 1e-9, w x y z
// (integers, −0 where a coefficient rounds to zero from below) — and the rotation those steps
// read back as. quantise() is rotationOfTumSteps(tumQuaternionSteps(·)) on each pose's rotation.
std::array<double, 4> tumQuaternionSteps(const Eigen::Matrix3d& rotation);
Eigen::Matrix3d rotationOfTumSteps(const std::array<double, 4>& steps);

// A TUM file that cannot be read: which file, which line (0 for the whole file), what is wrong.
class TumError : public std::runtime_error {
 public:
  TumError(std::string file, int line, std::string reason);
  const std::string& file() const { return file_; }
  int line() const { return line_; }
  const std::string& reason() const { return reason_; }
  // "line 3: reason", or the reason alone for the whole file.
  std::string located() const;

 private:
  std::string file_;
  int line_;
  std::string reason_;
};

// The largest TUM file read (about 10^7 poses).
inline constexpr std::uintmax_t kMaxTumBytes = 1u << 30;
// The largest time (s; a Unix epoch stamp until the year 2286) and coordinate (m; 150 Earth radii)
// a TUM row may hold: beyond them errors overflow to inf and statistics to nan.
inline constexpr double kMaxTumTime = 1e10;
inline constexpr double kMaxTumCoordinate = 1e9;

// Parses TUM text; '#' lines and blank lines are skipped. A malformed line, or a time that does
// not increase, throws TumError naming `file` and the line number. An empty trajectory is
// returned as such: the caller says whether it needs poses.
// With `lines`, the line number of each pose is appended to it (for messages about one pose).
Trajectory parseTum(const std::string& text, const std::string& file,
                    std::vector<int>* lines = nullptr);
// Reads a regular file of at most kMaxTumBytes (a device or a FIFO is never read).
Trajectory readTum(const std::string& path, std::vector<int>* lines = nullptr);

}  // namespace isg::common
