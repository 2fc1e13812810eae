#pragma once

#include <deque>
#include <optional>

#include "sensors/messages.hpp"

namespace isg::slam {

// Recent odometry, for the pose at any instant between two messages: positions interpolated
// linearly, rotations by slerp. Used to deskew scans (each point at its own firing instant).
class OdometryBuffer {
 public:
  explicit OdometryBuffer(double keep_seconds = 5.0) : keep_(keep_seconds) {}

  void push(const sensors::Odometry& odometry);
  // M_T_R at time t; nullopt outside the buffered span.
  std::optional<Eigen::Isometry3d> at(double t) const;
  bool empty() const { return buffer_.empty(); }
  double latest() const { return buffer_.back().stamp; }

 private:
  double keep_;
  std::deque<sensors::Odometry> buffer_;
};

// Moves every point of a scan into the LiDAR frame at the scan's stamp, using the base's motion
// from odometry: p' = (M_T_L(stamp))⁻¹ · M_T_L(stamp + time) · p. Points whose instant the buffer
// does not cover are kept as they are. Returns how many points could not be deskewed.
int deskew(sensors::Scan& scan, const OdometryBuffer& odometry, const Eigen::Isometry3d& R_T_L);

}  // namespace isg::slam
