#include "recordings/rosbag_export.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <vector>

#include "common/input_error.hpp"
#include "formats/dataset_check.hpp"
#include "formats/dataset_reader.hpp"
#include "formats/ros_messages.hpp"
#include "formats/rosbag_writer.hpp"

namespace isg::recordings {

namespace {

using namespace rosbag_names;

// The dataset's messages as ROS 1 messages in the bag.
class RosbagVisitor : public DatasetMessageVisitor {
 public:
  RosbagVisitor(const formats::DatasetReader& dataset, const std::string& bag_path, bool overwrite,
                const std::function<formats::RosTime(double)>& stamp,
                const formats::CloudConvention& convention)
      : bag(bag_path, overwrite), stamp_(stamp), convention_(convention) {
    tf_static_topic = bag.connect(kTfStaticTopic, formats::ros1::tfMessageType(), true);
    metadata_topic = bag.connect(kMetadataTopic, formats::ros1::stringType(), true);
    // A dataset without odometry (a handheld carrier) has no odom → base_link transforms either.
    const bool has_odometry = !dataset.odometry().empty();
    odometry_topic = has_odometry ? bag.connect(kOdometryTopic, formats::ros1::odometryType()) : -1;
    tf_topic = has_odometry ? bag.connect(kTfTopic, formats::ros1::tfMessageType()) : -1;
    imu_topic = dataset.imu().empty() ? -1 : bag.connect(kImuTopic, formats::ros1::imuType());
    cloud_topic = bag.connect(kCloudTopic, formats::ros1::pointCloud2Type());
    ground_truth_topic = dataset.groundTruth().empty()
                             ? -1
                             : bag.connect(kGroundTruthTopic, formats::ros1::odometryType());
  }

  void mounts(double t, const std::vector<std::pair<std::string, Eigen::Isometry3d>>& mounts,
              const std::string& made) override {
    const formats::RosTime time = stamp_(t);
    std::vector<formats::ros1::StampedTransform> transforms;
    for (const auto& [frame, pose] : mounts) transforms.push_back({time, kBaseFrame, frame, pose});
    bag.write(tf_static_topic, time, formats::ros1::tfMessage(transforms));
    bag.write(metadata_topic, time, formats::ros1::stringMessage(made));
  }
  void odometry(int i, double t, const Eigen::Isometry3d& pose, const BodyTwist& twist) override {
    const formats::RosTime time = stamp_(t);
    bag.write(odometry_topic, time,
              formats::ros1::odometry(pose, twist.linear, twist.angular, time, std::uint32_t(i),
                                      kOdometryFrame, kBaseFrame));
    bag.write(tf_topic, time, formats::ros1::tfMessage({{time, kOdometryFrame, kBaseFrame, pose}}));
  }
  void imu(int i, double t, const sensors::ImuSample& sample,
           const ImuVariances& variances) override {
    const formats::RosTime time = stamp_(t);
    bag.write(imu_topic, time,
              formats::ros1::imu(sample, time, std::uint32_t(i), kImuFrame, variances.gyroscope,
                                 variances.accelerometer));
  }
  void cloud(int i, double t, const sensors::Scan& scan) override {
    const formats::RosTime time = stamp_(t);
    bag.write(
        cloud_topic, time,
        formats::ros1::pointCloud2(scan.points, time, std::uint32_t(i), kLidarFrame, convention_));
  }
  void groundTruth(int i, double t, const Eigen::Isometry3d& pose,
                   const BodyTwist& twist) override {
    const formats::RosTime time = stamp_(t);
    bag.write(ground_truth_topic, time,
              formats::ros1::odometry(pose, twist.linear, twist.angular, time, std::uint32_t(i),
                                      kPlanFrame, kBaseFrame));
  }

  formats::RosbagWriter bag;
  int tf_static_topic = -1, metadata_topic = -1, odometry_topic = -1, tf_topic = -1, imu_topic = -1,
      cloud_topic = -1, ground_truth_topic = -1;

 private:
  std::function<formats::RosTime(double)> stamp_;
  formats::CloudConvention convention_;
};

}  // namespace

ExportSummary exportRosbag(const std::string& dataset_dir, const std::string& bag_path,
                           const RosbagExportOptions& options,
                           const std::function<void(int, int)>& progress) {
  const auto start = std::chrono::steady_clock::now();
  formats::DatasetReader dataset(dataset_dir);
  // A bag of files that disagree with their metadata would carry the lie (IMU covariances come
  // from the rate, topics from what is declared): the first disagreement is said instead.
  formats::checkDatasetAgainstMetadata(dataset);
  const auto stamp = [&](double t) {
    try {
      return formats::RosTime::fromSeconds(t, options.stamp_offset);
    } catch (const std::invalid_argument&) {
      throw common::InputError(dataset_dir, "",
                               "time " + std::to_string(t) + " s plus the stamp offset of " +
                                   std::to_string(options.stamp_offset) +
                                   " s is not a ROS time (0 to 2^32 s)");
    }
  };
  const formats::CloudConvention convention =
      exportCloudConvention(dataset, options.velodyne_layout);
  RosbagVisitor visitor(dataset, bag_path, options.overwrite, stamp, convention);
  visitDatasetMessages(dataset, visitor, progress);
  formats::RosbagWriter& bag = visitor.bag;
  bag.close();

  ExportSummary summary;
  summary.cloud_layout = describeCloudConvention(convention);
  const char* topics[] = {kTfStaticTopic, kOdometryTopic,    kTfTopic,      kImuTopic,
                          kCloudTopic,    kGroundTruthTopic, kMetadataTopic};
  const int connections[] = {
      visitor.tf_static_topic, visitor.odometry_topic,     visitor.tf_topic,      visitor.imu_topic,
      visitor.cloud_topic,     visitor.ground_truth_topic, visitor.metadata_topic};
  for (int i = 0; i < 7; ++i) {
    if (connections[i] >= 0) summary.messages[topics[i]] = bag.counts()[connections[i]];
  }
  summary.bytes = bag.bytesWritten();
  summary.dataset_seconds = dataset.duration();
  summary.wall_seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return summary;
}

}  // namespace isg::recordings
