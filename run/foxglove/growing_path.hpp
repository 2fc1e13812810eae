#pragma once

#include <Eigen/Geometry>
#include <optional>
#include <string>

#include "formats/ros_time.hpp"

namespace isg::run {

// A path that only grows, as the text of a foxglove.PosesInFrame: a pose kept once the robot has
// moved `spacing` from the last one kept, and always the latest. Each kept pose is serialised
// once, so a message of n poses costs a copy of its text, not n poses built again: a run's file
// carries the whole path every second.
class GrowingPath {
 public:
  explicit GrowingPath(double spacing) : spacing_(spacing) {}

  void add(const Eigen::Isometry3d& pose);
  bool empty() const { return !latest_; }
  // Poses in the message: those kept, and the latest when it was not kept.
  int size() const { return kept_ + (latest_ && !latest_kept_ ? 1 : 0); }
  // The foxglove.PosesInFrame message's JSON text.
  std::string message(formats::RosTime stamp, const std::string& frame) const;

 private:
  double spacing_;
  std::string kept_text_;  // the kept poses' JSON objects, comma-separated
  int kept_ = 0;
  Eigen::Vector3d last_kept_ = Eigen::Vector3d::Zero();
  std::optional<Eigen::Isometry3d> latest_;
  bool latest_kept_ = false;
};

}  // namespace isg::run
