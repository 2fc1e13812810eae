#include "recordings/dataset_messages.hpp"

#include <algorithm>
#include <cmath>

#include "formats/jpeg_frame.hpp"

namespace isg::recordings {

namespace {

BodyTwist twistBetween(const common::StampedPose& before, const common::StampedPose& after) {
  const double dt = after.t - before.t;
  if (!(dt > 0.0)) return {};
  const Eigen::Isometry3d step = before.pose.inverse() * after.pose;
  const Eigen::AngleAxisd turn(step.linear());
  BodyTwist out;
  out.linear =
      after.pose.linear().transpose() * (after.pose.translation() - before.pose.translation()) / dt;
  out.angular = turn.angle() * turn.axis() / dt;
  return out;
}

// One entry per message, in the order ties are broken.
enum class Kind { kMounts, kOdometry, kImu, kCloud, kImage, kGroundTruth };
struct Entry {
  double t;
  Kind kind;
  int index;
  int camera = 0;  // for kImage
};

CameraImage imageOf(const formats::EurocCamera& camera, int i) {
  const std::string& path = camera.frames[i].path;
  const int width = camera.calibration.width, height = camera.calibration.height;
  if (camera.depth) {
    return {&camera, rosbag_names::kDepthPngFormat, formats::readDepthPng(path, width, height)};
  }
  return {&camera, rosbag_names::kJpegFormat, formats::rgbPngFileToJpeg(path, width, height)};
}

}  // namespace

formats::CloudConvention exportCloudConvention(const formats::DatasetReader& dataset,
                                               bool velodyne_layout) {
  if (velodyne_layout) return {};
  const nlohmann::json& metadata = dataset.metadata();
  const auto lidar = metadata.find("lidar");
  if (lidar == metadata.end() || !lidar->is_object()) return {};
  const auto name = lidar->find("scenario_model");
  if (name == lidar->end() || !name->is_string()) return {};
  const sensors::LidarModel* model = sensors::findLidarModel(name->get<std::string>());
  return model ? formats::CloudConvention::of(*model) : formats::CloudConvention{};
}

std::string describeCloudConvention(const formats::CloudConvention& convention) {
  switch (convention.layout) {
    case sensors::DriverCloudLayout::kHesai:
      return "Hesai's (x y z intensity timestamp ring; ring = channel, 0 = top)";
    case sensors::DriverCloudLayout::kOuster:
      return "Ouster's (ouster-ros: x y z intensity t reflectivity ring ambient range; ring = "
             "beam, 0 = top)";
    case sensors::DriverCloudLayout::kVelodyne:
      break;
  }
  return "the Velodyne driver's (x y z intensity ring time; ring 0 = lowest)";
}

void visitDatasetMessages(formats::DatasetReader& dataset,
                          const std::vector<formats::EurocCamera>& cameras,
                          DatasetMessageVisitor& visitor,
                          const std::function<void(int, int)>& progress) {
  std::vector<Entry> entries;
  for (int i = 0; i < int(dataset.odometry().size()); ++i)
    entries.push_back({dataset.odometry()[i].t, Kind::kOdometry, i});
  for (int i = 0; i < int(dataset.imu().size()); ++i)
    entries.push_back({dataset.imu()[i].t, Kind::kImu, i});
  for (int i = 0; i < dataset.scanCount(); ++i)
    entries.push_back({dataset.scanStamp(i), Kind::kCloud, i});
  int items = dataset.scanCount();
  for (int c = 0; c < int(cameras.size()); ++c) {
    for (int i = 0; i < int(cameras[c].frames.size()); ++i, ++items) {
      entries.push_back({cameras[c].frames[i].t, Kind::kImage, i, c});
    }
  }
  for (int i = 0; i < int(dataset.groundTruth().size()); ++i)
    entries.push_back({dataset.groundTruth()[i].t, Kind::kGroundTruth, i});
  // The mounts come first, at the first message's time.
  double earliest = 0.0;
  for (std::size_t i = 0; i < entries.size(); ++i) {
    earliest = i == 0 ? entries[i].t : std::min(earliest, entries[i].t);
  }
  entries.push_back({earliest, Kind::kMounts, 0});
  std::stable_sort(entries.begin(), entries.end(), [](const Entry& a, const Entry& b) {
    if (a.t != b.t) return a.t < b.t;
    return a.kind != b.kind ? a.kind < b.kind : a.camera < b.camera;
  });

  ImuVariances variances;
  if (const auto& noise = dataset.imuNoise()) {
    variances.gyroscope = std::pow(noise->gyroscope_noise_density, 2) * noise->rate_hz;
    variances.accelerometer = std::pow(noise->accelerometer_noise_density, 2) * noise->rate_hz;
  }
  int items_done = 0;
  auto twistOf = [](const common::Trajectory& poses, int i) {
    return i > 0 ? twistBetween(poses[i - 1], poses[i]) : BodyTwist{};
  };
  for (const Entry& e : entries) {
    switch (e.kind) {
      case Kind::kMounts: {
        std::vector<std::pair<std::string, Eigen::Isometry3d>> mounts = {
            {rosbag_names::kLidarFrame, dataset.R_T_L()}};
        if (!dataset.imu().empty()) mounts.emplace_back(rosbag_names::kImuFrame, dataset.R_T_I());
        for (const formats::EurocCamera& camera : cameras) {
          mounts.emplace_back(camera.name, dataset.R_T_I() * camera.I_T_C);
        }
        nlohmann::json made = dataset.metadata();
        if (made.is_object() && made.contains("lidar") && made["lidar"].is_object()) {
          made["lidar"].erase("pcd_data");
        }
        visitor.mounts(e.t, mounts, made.dump());
        break;
      }
      case Kind::kOdometry:
        visitor.odometry(e.index, e.t, dataset.odometry()[e.index].pose,
                         twistOf(dataset.odometry(), e.index));
        break;
      case Kind::kImu:
        visitor.imu(e.index, e.t, dataset.imu()[e.index], variances);
        break;
      case Kind::kCloud:
        visitor.cloud(e.index, e.t, dataset.scan(e.index));
        if (progress) progress(++items_done, items);
        break;
      case Kind::kImage:
        visitor.image(e.camera, e.index, e.t, imageOf(cameras[e.camera], e.index));
        if (progress) progress(++items_done, items);
        break;
      case Kind::kGroundTruth:
        visitor.groundTruth(e.index, e.t, dataset.groundTruth()[e.index].pose,
                            twistOf(dataset.groundTruth(), e.index));
        break;
    }
  }
}

}  // namespace isg::recordings
