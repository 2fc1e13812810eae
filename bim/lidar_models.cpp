#include "bim/lidar_models.hpp"

#include "bim/scenario.hpp"

namespace isg::bim {

const std::vector<LidarModelDefaults>& lidarModelDefaults() {
  static const std::vector<LidarModelDefaults> models = {
      // The VLP-16's manual: 100 m; the noise as measured against the real fixtures
      // (docs/simulation.md).
      {"vlp16", 0.4, 100.0, 0.007, 100.0},
      // The VLP-32C's datasheet: 200 m, ±3 cm accuracy (taken as 3 σ: assumed); the ROS driver's
      // 0.4 m gate.
      {"vlp32c", 0.4, 200.0, 0.01, 200.0},
      // Hesai's published XT32 figures, not checked against a datasheet here: 0.05–120 m, 80 m
      // at 10 %, 0.5 cm precision.
      {"pandar-xt32", 0.05, 120.0, 0.005, 80.0},
      // Assumed: 0.3–50 m, 20 m at 10 %, the OS1's ±1.5 cm.
      {"os0-64", 0.3, 50.0, 0.015, 20.0},
      // The OS1 datasheet: 0.8–120 m, 40 m at 10 %, ±1.5 cm repeatability at high SNR.
      {"os1-64", 0.8, 120.0, 0.015, 40.0},
      {"os1-128", 0.8, 120.0, 0.015, 40.0},
  };
  return models;
}

const LidarModelDefaults* findLidarModelDefaults(std::string_view name) {
  for (const auto& m : lidarModelDefaults()) {
    if (m.name == name) return &m;
  }
  return nullptr;
}

void useLidarModel(LidarConfig& lidar, const LidarModelDefaults& model) {
  lidar.model = model.name;
  lidar.min_range_m = model.min_range_m;
  lidar.max_range_m = model.max_range_m;
  lidar.range_noise_m = model.range_noise_m;
  lidar.detection_range_m = model.detection_range_m;
}

}  // namespace isg::bim
