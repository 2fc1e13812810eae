#include "sensors/rosbag_export.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <vector>

#include "bim/input_error.hpp"
#include "sensors/dataset_check.hpp"
#include "sensors/dataset_reader.hpp"
#include "sensors/ros_messages.hpp"
#include "sensors/rosbag_writer.hpp"

namespace isg::sensors {

namespace {

using namespace rosbag_names;

// The twist of `child` between two poses of it, in `child`: the backward difference, which is
// what an odometry source knows at the later time.
struct Twist {
  Eigen::Vector3d linear = Eigen::Vector3d::Zero();
  Eigen::Vector3d angular = Eigen::Vector3d::Zero();
};
Twist twistBetween(const StampedPose& before, const StampedPose& after) {
  const double dt = after.t - before.t;
  if (!(dt > 0.0)) return {};
  const Eigen::Isometry3d step = before.pose.inverse() * after.pose;
  const Eigen::AngleAxisd turn(step.linear());
  Twist out;
  out.linear =
      after.pose.linear().transpose() * (after.pose.translation() - before.pose.translation()) / dt;
  out.angular = turn.angle() * turn.axis() / dt;
  return out;
}

// What goes into the bag, in time order: one entry per message (a pose also makes its /tf).
enum class Kind { kTfStatic, kOdometry, kImu, kCloud, kGroundTruth };
struct Entry {
  double t;
  Kind kind;
  int index;
};

}  // namespace

RosbagSummary exportRosbag(const std::string& dataset_dir, const std::string& bag_path,
                           const RosbagExportOptions& options,
                           const std::function<void(int, int)>& progress) {
  const auto start = std::chrono::steady_clock::now();
  DatasetReader dataset(dataset_dir);
  // A bag of files that disagree with their metadata would carry the lie (IMU covariances come
  // from the rate, topics from what is declared): the first disagreement is said instead.
  checkDatasetAgainstMetadata(dataset);
  const auto stamp = [&](double t) {
    try {
      return RosTime::fromSeconds(t, options.stamp_offset);
    } catch (const std::invalid_argument&) {
      throw bim::InputError(dataset_dir, "",
                            "time " + std::to_string(t) + " s plus the stamp offset of " +
                                std::to_string(options.stamp_offset) +
                                " s is not a ROS time (0 to 2^32 s)");
    }
  };

  std::vector<Entry> entries;
  for (int i = 0; i < int(dataset.odometry().size()); ++i)
    entries.push_back({dataset.odometry()[i].t, Kind::kOdometry, i});
  for (int i = 0; i < int(dataset.imu().size()); ++i)
    entries.push_back({dataset.imu()[i].t, Kind::kImu, i});
  for (int i = 0; i < dataset.scanCount(); ++i)
    entries.push_back({dataset.scanStamp(i), Kind::kCloud, i});
  for (int i = 0; i < int(dataset.groundTruth().size()); ++i)
    entries.push_back({dataset.groundTruth()[i].t, Kind::kGroundTruth, i});
  // The mounts come first, at the first message's time.
  double earliest = 0.0;
  for (std::size_t i = 0; i < entries.size(); ++i) {
    earliest = i == 0 ? entries[i].t : std::min(earliest, entries[i].t);
  }
  entries.push_back({earliest, Kind::kTfStatic, 0});
  std::stable_sort(entries.begin(), entries.end(), [](const Entry& a, const Entry& b) {
    return a.t != b.t ? a.t < b.t : a.kind < b.kind;
  });

  RosbagWriter bag(bag_path, options.overwrite);
  const int tf_static = bag.connect(kTfStaticTopic, ros1::tfMessageType(), true);
  const int metadata = bag.connect(kMetadataTopic, ros1::stringType(), true);
  // A dataset without odometry (a handheld carrier) has no odom → base_link transforms either.
  const bool has_odometry = !dataset.odometry().empty();
  const int odometry = has_odometry ? bag.connect(kOdometryTopic, ros1::odometryType()) : -1;
  const int tf = has_odometry ? bag.connect(kTfTopic, ros1::tfMessageType()) : -1;
  const int imu = dataset.imu().empty() ? -1 : bag.connect(kImuTopic, ros1::imuType());
  const int cloud = bag.connect(kCloudTopic, ros1::pointCloud2Type());
  const int ground_truth =
      dataset.groundTruth().empty() ? -1 : bag.connect(kGroundTruthTopic, ros1::odometryType());
  // Per-sample variances of the discretised white noise: density² × rate.
  double gyroscope_variance = 0.0, accelerometer_variance = 0.0;
  if (const auto& noise = dataset.imuNoise()) {
    gyroscope_variance = std::pow(noise->gyroscope_noise_density, 2) * noise->rate_hz;
    accelerometer_variance = std::pow(noise->accelerometer_noise_density, 2) * noise->rate_hz;
  }

  // Pose i of `poses` as nav_msgs/Odometry of base_link in `frame`.
  auto writePose = [&](int connection, const Trajectory& poses, int i, const char* frame) {
    const Twist twist = i > 0 ? twistBetween(poses[i - 1], poses[i]) : Twist{};
    const RosTime t = stamp(poses[i].t);
    bag.write(connection, t,
              ros1::odometry(poses[i].pose, twist.linear, twist.angular, t, std::uint32_t(i), frame,
                             kBaseFrame));
  };
  int scans_done = 0;
  for (const Entry& e : entries) {
    switch (e.kind) {
      case Kind::kTfStatic: {
        const RosTime t = stamp(e.t);
        std::vector<ros1::StampedTransform> mounts = {
            {t, kBaseFrame, kLidarFrame, dataset.R_T_L()}};
        if (imu >= 0) mounts.push_back({t, kBaseFrame, kImuFrame, dataset.R_T_I()});
        bag.write(tf_static, t, ros1::tfMessage(mounts));
        // The same bag whichever PCD encoding the dataset has.
        nlohmann::json made = dataset.metadata();
        if (made.is_object() && made.contains("lidar") && made["lidar"].is_object()) {
          made["lidar"].erase("pcd_data");
        }
        bag.write(metadata, t, ros1::stringMessage(made.dump()));
        break;
      }
      case Kind::kOdometry: {
        const RosTime t = stamp(e.t);
        writePose(odometry, dataset.odometry(), e.index, kOdometryFrame);
        bag.write(
            tf, t,
            ros1::tfMessage({{t, kOdometryFrame, kBaseFrame, dataset.odometry()[e.index].pose}}));
        break;
      }
      case Kind::kImu: {
        const RosTime t = stamp(e.t);
        bag.write(imu, t,
                  ros1::imu(dataset.imu()[e.index], t, std::uint32_t(e.index), kImuFrame,
                            gyroscope_variance, accelerometer_variance));
        break;
      }
      case Kind::kCloud: {
        const sensors::Scan scan = dataset.scan(e.index);
        const RosTime t = stamp(e.t);
        bag.write(cloud, t, ros1::pointCloud2(scan.points, t, std::uint32_t(e.index), kLidarFrame));
        if (progress) progress(++scans_done, dataset.scanCount());
        break;
      }
      case Kind::kGroundTruth:
        writePose(ground_truth, dataset.groundTruth(), e.index, kPlanFrame);
        break;
    }
  }
  bag.close();

  RosbagSummary summary;
  const char* topics[] = {kTfStaticTopic, kOdometryTopic,    kTfTopic,      kImuTopic,
                          kCloudTopic,    kGroundTruthTopic, kMetadataTopic};
  const int connections[] = {tf_static, odometry, tf, imu, cloud, ground_truth, metadata};
  for (int i = 0; i < 7; ++i) {
    if (connections[i] >= 0) summary.messages[topics[i]] = bag.counts()[connections[i]];
  }
  summary.bytes = bag.bytesWritten();
  summary.dataset_seconds = dataset.duration();
  summary.wall_seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return summary;
}

}  // namespace isg::sensors
