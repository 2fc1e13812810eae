#pragma once

#include <string>
#include <string_view>
#include <vector>

namespace isg::bim {

// What a scenario's `lidar.model` sets when the scenario does not say otherwise: the range gate,
// the range noise (1 σ) and the range out to which a 10 % target met head-on still returns
// (docs/simulation.md, "LiDAR models", says which figures are the datasheets' and which assumed).
// The beams and timing of each model are the simulator's (sensors/lidar_model.hpp), under the
// same names.
struct LidarModelDefaults {
  std::string name;
  double min_range_m = 0.4, max_range_m = 100.0, range_noise_m = 0.007, detection_range_m = 100.0;
};

// vlp16 (the default), vlp32c, pandar-xt32, os0-64, os1-64, os1-128.
const std::vector<LidarModelDefaults>& lidarModelDefaults();
// nullptr when no model has that name.
const LidarModelDefaults* findLidarModelDefaults(std::string_view name);

struct LidarConfig;
// Makes `lidar` the model's: its name and its defaults of the range gate, range noise and
// detection range (whatever `lidar` held for them).
void useLidarModel(LidarConfig& lidar, const LidarModelDefaults& model);

}  // namespace isg::bim
