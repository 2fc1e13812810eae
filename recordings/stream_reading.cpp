#include "recordings/bag_import_parts.hpp"

namespace isg::recordings::bag_import {

void Import::readCloud(const fs::path& folder, const formats::RecordedMessage& m) {
  const formats::ros1::PointCloud2 cloud = formats::recorded::decodePointCloud2(m);
  const formats::CloudLayout layout = formats::cloudLayout(cloud);
  if (scan_stamps_.empty()) {
    layout_ = layout;
  } else if (layout.describe() != layout_.describe()) {
    throw formats::ros1::MessageError("its fields (" + layout.describe() +
                                      ") are not the first cloud's (" + layout_.describe() + ")");
  }
  if (cloud.header.frame_id != lidar_frame_) {
    throw formats::ros1::MessageError("its frame \"" + cloud.header.frame_id +
                                      "\" is not the first cloud's \"" + lidar_frame_ + "\"");
  }
  if (!scan_stamps_.empty() && !(scan_stamps_.back() < cloud.header.stamp)) {
    throw formats::ros1::MessageError("its stamp is not after the previous cloud's");
  }
  writeScan(folder, cloud.header.stamp, formats::cloudPoints(cloud, layout),
            layout.time.has_value());
}

void Import::writeScan(const fs::path& folder, formats::RosTime stamp,
                       const std::vector<sensors::ScanPoint>& points, bool timed) {
  if (timed && !points.empty()) {
    const auto [lo, hi] = std::minmax_element(
        points.begin(), points.end(),
        [](const sensors::ScanPoint& a, const sensors::ScanPoint& b) { return a.time < b.time; });
    time_min_ = clouds_with_time_ == 0 ? lo->time : std::min<double>(time_min_, lo->time);
    time_max_ = clouds_with_time_ == 0 ? hi->time : std::max<double>(time_max_, hi->time);
    ++clouds_with_time_;
    // Stamped at the end of the turn when most of its points came before the stamp.
    const auto before = std::count_if(points.begin(), points.end(),
                                      [](const sensors::ScanPoint& p) { return p.time < 0.0f; });
    if (2 * std::size_t(before) > points.size()) ++clouds_stamped_at_end_;
  }
  summary_.points += points.size();
  // Rings are numbered by elevation in a dataset: the first cloud with points decides the
  // recording's renumbering, which every cloud then takes.
  if (!ring_order_decided_ && !points.empty()) {
    ring_order_ = formats::ringsByElevation(points);
    ring_order_decided_ = true;
    if (!ring_order_.empty()) {
      std::size_t top = 0;
      for (std::size_t r = 0; r < ring_order_.size(); ++r) {
        if (ring_order_[r] > ring_order_[top]) top = r;
      }
      summary_.notes.push_back(
          "rings renumbered by elevation, 0 = lowest, as datasets number them (the recording's "
          "ring " +
          std::to_string(top) + " is the top beam, now ring " + std::to_string(ring_order_[top]) +
          ")");
    }
  }
  std::vector<sensors::ScanPoint> renumbered;
  if (!ring_order_.empty()) {
    renumbered = points;
    for (auto& p : renumbered) {
      if (p.ring < ring_order_.size()) p.ring = ring_order_[p.ring];
    }
  }
  common::writeFile(
      folder / formats::dataset::kScans / formats::dataset::scanFileName(int(scan_stamps_.size())),
      formats::dataset::pcdBytes(ring_order_.empty() ? points : renumbered,
                                 formats::dataset::kDefaultPcdData));
  scan_stamps_.push_back(stamp);
}

void Import::readPackets(const fs::path& folder, const formats::RecordedMessage& m,
                         std::uint64_t index) {
  const formats::ros1::VelodyneScan scan = formats::recorded::decodeVelodyneScan(m);
  if (scan.header.frame_id != lidar_frame_) {
    throw formats::ros1::MessageError("its frame \"" + scan.header.frame_id +
                                      "\" is not the first scan's \"" + lidar_frame_ + "\"");
  }
  formats::Vlp16DecodeOptions options;  // the ROS driver's range limits
  for (std::size_t p = 0; p < scan.packets.size(); ++p) {
    const auto& packet = scan.packets[p];
    if (packet_count_ == 0) packet_origin_ = packet.stamp.sec;
    const double stamp = double(std::int64_t(packet.stamp.sec) - std::int64_t(packet_origin_)) +
                         1e-9 * packet.stamp.nsec;
    const auto* bytes = reinterpret_cast<const std::uint8_t*>(packet.data.data());
    const std::size_t before = turn_points_.size();
    const formats::Vlp16PacketHeader header = formats::decodeVlp16Packet(
        std::span(bytes, packet.data.size()), stamp, options, bag_path_,
        "topic " + summary_.lidar.topic + ", message " + std::to_string(index) + " (" +
            formats::placeOf(m) + "), packet " + std::to_string(p),
        turn_points_);
    packet_mode_ = header.mode;
    ++packet_count_;
    // Dual-return packets give each shot's last and strongest echo: the strongest is kept, so a
    // scan has one return a shot as a single-return recording's.
    const auto weak = [](const formats::Vlp16Point& q) {
      return q.echo == formats::Vlp16Echo::kNearWeak || q.echo == formats::Vlp16Echo::kFarWeak;
    };
    const auto kept =
        std::remove_if(turn_points_.begin() + std::ptrdiff_t(before), turn_points_.end(), weak);
    weak_echoes_ += std::uint64_t(turn_points_.end() - kept);
    turn_points_.erase(kept, turn_points_.end());
  }
  // Every turn but the one under way is done; the recording's first is cut short (left out).
  std::vector<formats::Vlp16Turn> turns = formats::cutIntoTurns(turn_points_);
  if (turns.size() < 2) return;
  for (std::size_t t = 0; t + 1 < turns.size(); ++t) {
    if (!packet_turns_started_) {
      packet_turns_started_ = true;
      continue;
    }
    const auto& points = turns[t].points;
    if (points.empty()) continue;
    const double first = points.front().time;
    std::vector<sensors::ScanPoint> out;
    out.reserve(points.size());
    for (const auto& q : points) {
      out.push_back({q.x, q.y, q.z, float(q.intensity), q.ring, float(q.time - first)});
    }
    const double whole = std::floor(first);
    formats::RosTime turn_stamp{packet_origin_ + std::uint32_t(whole),
                                std::uint32_t(std::llround((first - whole) * 1e9))};
    if (turn_stamp.nsec >= 1000000000u) {
      turn_stamp.sec += 1;
      turn_stamp.nsec -= 1000000000u;
    }
    writeScan(folder, turn_stamp, out, true);
  }
  turn_points_ = std::move(turns.back().points);
}

void Import::readImu(const formats::RecordedMessage& m) {
  const formats::ros1::Imu imu = formats::recorded::decodeImu(m);
  if (imu.header.frame_id != imu_frame_) {
    throw formats::ros1::MessageError("its frame \"" + imu.header.frame_id +
                                      "\" is not the first sample's \"" + imu_frame_ + "\"");
  }
  if (imu_.empty()) {
    imu_variance_ = {imu.angular_velocity_covariance[0], imu.linear_acceleration_covariance[0]};
  }
  if (!imu_.empty() && !(imu_.back().stamp < imu.header.stamp)) {
    throw formats::ros1::MessageError("its stamp is not after the previous sample's");
  }
  sensors::ImuSample sample;
  sample.accelerometer = imu.linear_acceleration;
  sample.gyroscope = imu.angular_velocity;
  imu_.push_back({imu.header.stamp, sample});
}

void Import::readPose(const formats::RecordedMessage& m) {
  const std::string& topic = m.topic->name;
  const bool odometry = topic == summary_.odometry.topic;
  const formats::ros1::StampedPose pose = findTopic(topic)->datatype == kPoseType
                                              ? formats::recorded::decodePoseStamped(m)
                                              : formats::recorded::decodeOdometry(m);
  auto& poses = odometry ? odometry_ : truth_;
  if (pose.child_frame_id != (odometry ? odometry_child_ : truth_child_)) {
    throw formats::ros1::MessageError("its child frame \"" + pose.child_frame_id +
                                      "\" is not the first message's");
  }
  if (!poses.empty() && !(poses.back().stamp < pose.header.stamp)) {
    throw formats::ros1::MessageError("its stamp is not after the previous message's");
  }
  poses.push_back({pose.header.stamp, pose.pose});
}

void Import::readStreams(const fs::path& folder,
                         const std::function<void(std::uint64_t, std::uint64_t)>& progress) {
  std::vector<std::string> topics;
  for (auto* stream :
       {&summary_.lidar, &summary_.imu, &summary_.odometry, &summary_.ground_truth}) {
    if (!stream->topic.empty()) topics.push_back(stream->topic);
  }
  // The window, in the bag's record times.
  const formats::RosTime first = bag_->startTime();
  const double begin = double(first.sec) + 1e-9 * first.nsec + options_.start;
  const double end = options_.duration ? begin + *options_.duration : INFINITY;
  const std::uint64_t total = findTopic(summary_.lidar.topic)->messages;
  std::map<std::string, std::uint64_t> index;  // per topic: the message's place on it
  fs::create_directories(folder / formats::dataset::kScans);
  bag_->read(topics, [&](const formats::RecordedMessage& m) {
    const std::string& topic = m.topic->name;
    const std::uint64_t k = index[topic]++;
    const double time = double(m.time.sec) + 1e-9 * m.time.nsec;
    if (time < begin) return true;
    if (time > end) return false;
    try {
      if (topic == summary_.lidar.topic) {
        if (packets_) {
          readPackets(folder, m, k);
        } else {
          readCloud(folder, m);
        }
        if (progress) progress(k + 1, total);
      } else if (topic == summary_.imu.topic) {
        readImu(m);
      } else if (tf_odometry_ && topic == summary_.odometry.topic) {
        for (const auto& t : formats::recorded::decodeTfMessage(m)) {
          try {
            tf_odometry_->offer(t.header.frame_id, t.child_frame_id, t.header.stamp,
                                t.parent_T_child);
          } catch (const std::invalid_argument& e) {
            throw formats::ros1::MessageError(e.what());
          }
        }
      } else {
        readPose(m);
      }
    } catch (const formats::ros1::MessageError& e) {
      failMessage(topic, k, e.what(), &m);
    }
    return true;
  });
  if (scan_stamps_.empty()) {
    fail("topic " + summary_.lidar.topic + " has no cloud" +
         (options_.start > 0 || options_.duration ? " in the window given (--start, --duration)"
                                                  : ""));
  }
}

}  // namespace isg::recordings::bag_import
