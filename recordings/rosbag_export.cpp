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
  RosbagVisitor(const formats::DatasetReader& dataset,
                const std::vector<formats::EurocCamera>& cameras, const std::string& bag_path,
                bool overwrite, const std::function<formats::RosTime(double)>& stamp,
                const formats::CloudConvention& convention)
      : bag(bag_path, overwrite), stamp_(stamp), convention_(convention) {
    connect(kTfStaticTopic, formats::ros1::tfMessageType(), true);
    connect(kMetadataTopic, formats::ros1::stringType(), true);
    // A dataset without odometry (a handheld carrier) has no odom → base_link transforms either.
    if (!dataset.odometry().empty()) {
      connect(kOdometryTopic, formats::ros1::odometryType());
      connect(kTfTopic, formats::ros1::tfMessageType());
    }
    if (!dataset.imu().empty()) connect(kImuTopic, formats::ros1::imuType());
    connect(kCloudTopic, formats::ros1::pointCloud2Type());
    for (const formats::EurocCamera& camera : cameras) {
      connect(imageTopic(camera.name), formats::ros1::compressedImageType());
      connect(cameraInfoTopic(camera.name), formats::ros1::cameraInfoType());
    }
    if (!dataset.groundTruth().empty()) connect(kGroundTruthTopic, formats::ros1::odometryType());
  }

  void mounts(double t, const std::vector<std::pair<std::string, Eigen::Isometry3d>>& mounts,
              const std::string& made) override {
    const formats::RosTime time = stamp_(t);
    std::vector<formats::ros1::StampedTransform> transforms;
    for (const auto& [frame, pose] : mounts) transforms.push_back({time, kBaseFrame, frame, pose});
    write(kTfStaticTopic, time, formats::ros1::tfMessage(transforms));
    write(kMetadataTopic, time, formats::ros1::stringMessage(made));
  }
  void odometry(int i, double t, const Eigen::Isometry3d& pose, const BodyTwist& twist) override {
    const formats::RosTime time = stamp_(t);
    write(kOdometryTopic, time,
          formats::ros1::odometry(pose, twist.linear, twist.angular, time, std::uint32_t(i),
                                  kOdometryFrame, kBaseFrame));
    write(kTfTopic, time, formats::ros1::tfMessage({{time, kOdometryFrame, kBaseFrame, pose}}));
  }
  void imu(int i, double t, const sensors::ImuSample& sample,
           const ImuVariances& variances) override {
    const formats::RosTime time = stamp_(t);
    write(kImuTopic, time,
          formats::ros1::imu(sample, time, std::uint32_t(i), kImuFrame, variances.gyroscope,
                             variances.accelerometer));
  }
  void cloud(int i, double t, const sensors::Scan& scan) override {
    const formats::RosTime time = stamp_(t);
    write(
        kCloudTopic, time,
        formats::ros1::pointCloud2(scan.points, time, std::uint32_t(i), kLidarFrame, convention_));
  }
  void image(int, int i, double t, const CameraImage& image) override {
    const formats::RosTime time = stamp_(t);
    const std::string& name = image.camera->name;
    write(imageTopic(name), time,
          formats::ros1::compressedImage(image.format, image.data, time, std::uint32_t(i), name));
    write(cameraInfoTopic(name), time,
          formats::ros1::cameraInfo(image.camera->calibration, time, std::uint32_t(i), name));
  }
  void groundTruth(int i, double t, const Eigen::Isometry3d& pose,
                   const BodyTwist& twist) override {
    const formats::RosTime time = stamp_(t);
    write(kGroundTruthTopic, time,
          formats::ros1::odometry(pose, twist.linear, twist.angular, time, std::uint32_t(i),
                                  kPlanFrame, kBaseFrame));
  }

  formats::RosbagWriter bag;
  std::map<std::string, int> topics;  // → connection

 private:
  void connect(const std::string& topic, const formats::RosMessageType& type,
               bool latched = false) {
    topics[topic] = bag.connect(topic, type, latched);
  }
  void write(const std::string& topic, formats::RosTime time, const std::string& data) {
    bag.write(topics.at(topic), time, data);
  }
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
  const std::vector<formats::EurocCamera> cameras =
      formats::readEurocCameras(dataset_dir, dataset.imu().empty() ? 0.0 : dataset.imu().front().t);
  RosbagVisitor visitor(dataset, cameras, bag_path, options.overwrite, stamp, convention);
  visitDatasetMessages(dataset, cameras, visitor, progress);
  formats::RosbagWriter& bag = visitor.bag;
  bag.close();

  ExportSummary summary;
  summary.cloud_layout = describeCloudConvention(convention);
  for (const auto& [topic, connection] : visitor.topics) {
    summary.messages[topic] = bag.counts()[connection];
  }
  summary.bytes = bag.bytesWritten();
  summary.dataset_seconds = dataset.duration();
  summary.wall_seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return summary;
}

}  // namespace isg::recordings
