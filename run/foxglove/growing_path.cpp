#include "run/foxglove/growing_path.hpp"

#include "formats/foxglove_json.hpp"

namespace isg::run {

void GrowingPath::add(const Eigen::Isometry3d& pose) {
  latest_ = pose;
  latest_kept_ = kept_ == 0 || (pose.translation() - last_kept_).norm() >= spacing_;
  if (!latest_kept_) return;
  if (kept_ > 0) kept_text_ += ',';
  kept_text_ += formats::foxglove::pose(pose).dump();
  last_kept_ = pose.translation();
  ++kept_;
}

std::string GrowingPath::message(formats::RosTime stamp, const std::string& frame) const {
  // The keys in the order nlohmann::json writes them (sorted), as every other message.
  std::string text = "{\"frame_id\":" + nlohmann::json(frame).dump() + ",\"poses\":[";
  text += kept_text_;
  if (latest_ && !latest_kept_) {
    if (kept_ > 0) text += ',';
    text += formats::foxglove::pose(*latest_).dump();
  }
  text += "],\"timestamp\":" + formats::foxglove::time(stamp).dump() + "}";
  return text;
}

}  // namespace isg::run
