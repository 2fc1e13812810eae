#pragma once

#include <Eigen/Geometry>
#include <array>
#include <cstddef>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "formats/dataset_format.hpp"

namespace isg::formats::dataset {

// What a dataset's metadata.json says of its data, the same from every producer (isg simulate,
// isg import): the fields DatasetReader reads back and the ones that say what the files hold.
// What a producer adds to describe where the data came from (the simulated sensors' models, the
// robot and the plan; the recording and its topics) is its own, given beside it (metadataJson).
struct Metadata {
  std::string generator;    // "isg simulate 0.1.0": the command and the project's version
  double duration_s = 0.0;  // robot time the dataset covers
  // The frames B, M, R, L, I, each with what it is in this dataset (a description, or the
  // recording's frame id).
  std::vector<std::pair<std::string, std::string>> frames;
  // The LiDAR's mount on the base R ([x, y, z, roll, pitch, yaw] and R_T_L), and the IMU's.
  std::array<double, 6> lidar_mount{};
  Eigen::Isometry3d R_T_L = Eigen::Isometry3d::Identity();
  struct ImuMount {
    std::array<double, 6> xyz_rpy{};
    Eigen::Isometry3d R_T_I = Eigen::Isometry3d::Identity();
  };
  std::optional<ImuMount> imu_mount;

  struct Lidar {
    std::string model;      // "Velodyne VLP-16", "recorded"
    double rate_hz = 10.0;  // turns per second
    std::size_t scans = 0;  // files in scans/
    std::string stamp;      // "first_firing" or "last_packet": which instant a scan's stamp is
    double scan_period_s = 0.1;
    std::array<double, 2> point_time_s{0.0, 0.1};  // the span of the points' times about it
    PcdData pcd_data = kDefaultPcdData;
  } lidar;

  struct Imu {
    double rate_hz = 0.0;
    std::size_t samples = 0;
    // The white noise of its readings, when known (rad/s/√Hz, m/s²/√Hz): what the localizers
    // weigh the IMU with.
    std::optional<double> gyroscope_noise_density, accelerometer_noise_density;
  };
  std::optional<Imu> imu;  // none: no imu.csv

  struct Odometry {
    double rate_hz = 0.0;
  };
  std::optional<Odometry> odometry;  // none: no odometry.tum
};

// metadata.json's document: `metadata` and the producer's own `description`, merged section by
// section (an object in `description` under "lidar", "imu", "odometry", "frames" or
// "extrinsics" adds its keys to that section), every key in the order docs/formats.md gives
// them, a producer's keys it does not name after them in the producer's order. A description
// that sets a field of `metadata` itself is a bug (std::logic_error): each is written once, here.
nlohmann::ordered_json metadataJson(const Metadata& metadata,
                                    const nlohmann::ordered_json& description);

// An existing metadata.json document (an isg dataset exported to a bag and imported back) with
// its keys in that order.
nlohmann::ordered_json inMetadataOrder(const nlohmann::ordered_json& document);

}  // namespace isg::formats::dataset
