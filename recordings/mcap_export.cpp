#include "recordings/mcap_export.hpp"

#include <chrono>
#include <cmath>
#include <limits>

#include "common/input_error.hpp"
#include "formats/dataset_check.hpp"
#include "formats/dataset_reader.hpp"
#include "formats/ros2_messages.hpp"
#include "formats/rosbag_writer.hpp"

namespace isg::recordings {

namespace {

using namespace rosbag_names;

// The QoS a latched topic is offered with in ROS 2 (transient local, reliable, the last message
// kept), as rosbag2 records it in a channel's metadata: `ros2 bag play` gives late subscribers
// /tf_static and the metadata.
const char* kLatchedQos =
    "- history: 1\n  depth: 1\n  reliability: 1\n  durability: 1\n  deadline:\n    sec: 0\n"
    "    nsec: 0\n  lifespan:\n    sec: 0\n    nsec: 0\n  liveliness: 1\n"
    "  liveliness_lease_duration:\n    sec: 0\n    nsec: 0\n"
    "  avoid_ros_namespace_conventions: false\n";

// The dataset's messages as ROS 2 messages in the MCAP file.
class McapVisitor : public DatasetMessageVisitor {
 public:
  McapVisitor(const formats::DatasetReader& dataset,
              const std::vector<formats::EurocCamera>& cameras, const std::string& path,
              const formats::McapWriterOptions& options,
              const std::function<formats::ros2::Time(double)>& stamp,
              const formats::CloudConvention& convention)
      : mcap(path, options), stamp_(stamp), convention_(convention) {
    auto schemaOf = [&](const formats::ros2::MessageType& type) {
      return mcap.addSchema(type.name, "ros2msg", type.definition);
    };
    const std::uint16_t tf_schema = schemaOf(formats::ros2::tfMessageType());
    const std::uint16_t odometry_schema = schemaOf(formats::ros2::odometryType());
    const std::map<std::string, std::string> latched = {{"offered_qos_profiles", kLatchedQos}};
    topics[kTfStaticTopic] = mcap.addChannel(tf_schema, kTfStaticTopic, "cdr", latched);
    topics[kMetadataTopic] =
        mcap.addChannel(schemaOf(formats::ros2::stringType()), kMetadataTopic, "cdr", latched);
    // A dataset without odometry (a handheld carrier) has no odom → base_link transforms either.
    if (!dataset.odometry().empty()) {
      topics[kOdometryTopic] = mcap.addChannel(odometry_schema, kOdometryTopic, "cdr");
      topics[kTfTopic] = mcap.addChannel(tf_schema, kTfTopic, "cdr");
    }
    if (!dataset.imu().empty()) {
      topics[kImuTopic] = mcap.addChannel(schemaOf(formats::ros2::imuType()), kImuTopic, "cdr");
    }
    topics[kCloudTopic] =
        mcap.addChannel(schemaOf(formats::ros2::pointCloud2Type()), kCloudTopic, "cdr");
    if (!cameras.empty()) {
      const std::uint16_t image_schema = schemaOf(formats::ros2::compressedImageType());
      const std::uint16_t info_schema = schemaOf(formats::ros2::cameraInfoType());
      for (const formats::EurocCamera& camera : cameras) {
        topics[imageTopic(camera.name)] =
            mcap.addChannel(image_schema, imageTopic(camera.name), "cdr");
        topics[cameraInfoTopic(camera.name)] =
            mcap.addChannel(info_schema, cameraInfoTopic(camera.name), "cdr");
      }
    }
    if (!dataset.groundTruth().empty()) {
      topics[kGroundTruthTopic] = mcap.addChannel(odometry_schema, kGroundTruthTopic, "cdr");
    }
  }

  void mounts(double t, const std::vector<std::pair<std::string, Eigen::Isometry3d>>& mounts,
              const std::string& made) override {
    const formats::ros2::Time time = stamp_(t);
    std::vector<formats::ros2::StampedTransform> transforms;
    for (const auto& [frame, pose] : mounts) transforms.push_back({time, kBaseFrame, frame, pose});
    write(kTfStaticTopic, time, formats::ros2::tfMessage(transforms));
    write(kMetadataTopic, time, formats::ros2::stringMessage(made));
  }
  void odometry(int, double t, const Eigen::Isometry3d& pose, const BodyTwist& twist) override {
    const formats::ros2::Time time = stamp_(t);
    write(kOdometryTopic, time,
          formats::ros2::odometry(pose, twist.linear, twist.angular, time, kOdometryFrame,
                                  kBaseFrame));
    write(kTfTopic, time, formats::ros2::tfMessage({{time, kOdometryFrame, kBaseFrame, pose}}));
  }
  void imu(int, double t, const sensors::ImuSample& sample,
           const ImuVariances& variances) override {
    const formats::ros2::Time time = stamp_(t);
    write(
        kImuTopic, time,
        formats::ros2::imu(sample, time, kImuFrame, variances.gyroscope, variances.accelerometer));
  }
  void cloud(int, double t, const sensors::Scan& scan) override {
    const formats::ros2::Time time = stamp_(t);
    write(kCloudTopic, time,
          formats::ros2::pointCloud2(scan.points, time, kLidarFrame, convention_));
  }
  void image(int, int, double t, const CameraImage& image) override {
    const formats::ros2::Time time = stamp_(t);
    const std::string& name = image.camera->name;
    write(imageTopic(name), time,
          formats::ros2::compressedImage(image.format, image.data, time, name));
    write(cameraInfoTopic(name), time,
          formats::ros2::cameraInfo(image.camera->calibration, time, name));
  }
  void groundTruth(int, double t, const Eigen::Isometry3d& pose, const BodyTwist& twist) override {
    const formats::ros2::Time time = stamp_(t);
    write(kGroundTruthTopic, time,
          formats::ros2::odometry(pose, twist.linear, twist.angular, time, kPlanFrame, kBaseFrame));
  }

  formats::McapWriter mcap;
  std::map<std::string, std::uint16_t> topics;  // → channel

 private:
  void write(const std::string& topic, formats::ros2::Time time, const std::string& data) {
    mcap.write(topics.at(topic), time.nanoseconds(), data);
  }
  std::function<formats::ros2::Time(double)> stamp_;
  formats::CloudConvention convention_;
};

}  // namespace

ExportSummary exportMcap(const std::string& dataset_dir, const std::string& mcap_path,
                         const McapExportOptions& options,
                         const std::function<void(int, int)>& progress) {
  const auto start = std::chrono::steady_clock::now();
  formats::DatasetReader dataset(dataset_dir);
  // As for the ROS 1 bag: files that disagree with their metadata are refused, not carried.
  formats::checkDatasetAgainstMetadata(dataset);
  const auto stamp = [&](double t) {
    formats::RosTime time;
    try {
      time = formats::RosTime::fromSeconds(t, options.stamp_offset);
    } catch (const std::invalid_argument&) {
      time.sec = std::numeric_limits<std::uint32_t>::max();
    }
    if (time.sec > std::uint32_t(std::numeric_limits<std::int32_t>::max())) {
      throw common::InputError(dataset_dir, "",
                               "time " + std::to_string(t) + " s plus the stamp offset of " +
                                   std::to_string(options.stamp_offset) +
                                   " s is not a ROS 2 time (0 to 2^31 s)");
    }
    return formats::ros2::Time{std::int32_t(time.sec), time.nsec};
  };
  formats::McapWriterOptions writer;
  writer.compression = options.compression;
  writer.overwrite = options.overwrite;
  const formats::CloudConvention convention =
      exportCloudConvention(dataset, options.velodyne_layout);
  const std::vector<formats::EurocCamera> cameras =
      formats::readEurocCameras(dataset_dir, dataset.imu().empty() ? 0.0 : dataset.imu().front().t);
  McapVisitor visitor(dataset, cameras, mcap_path, writer, stamp, convention);
  visitDatasetMessages(dataset, cameras, visitor, progress);
  visitor.mcap.close();

  ExportSummary summary;
  summary.cloud_layout = describeCloudConvention(convention);
  for (const auto& [topic, channel] : visitor.topics) {
    summary.messages[topic] = visitor.mcap.counts()[channel];
  }
  summary.bytes = visitor.mcap.bytesWritten();
  summary.dataset_seconds = dataset.duration();
  summary.wall_seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return summary;
}

}  // namespace isg::recordings
