#pragma once

#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

namespace isg::sensors {

// One laser (beam) of a spinning LiDAR, in firing order.
struct LidarBeam {
  double elevation_deg = 0.0;
  // Added to the head's azimuth when the beam fires (counter-clockwise, degrees): the VLP-32C's
  // and Ouster's beams are spread about the column, the VLP-16's and Hesai's are not.
  double azimuth_offset_deg = 0.0;
  double vertical_offset_mm = 0.0;  // the beam's origin above (+) the optical centre (VLP-16)
  double firing_offset_s = 0.0;     // from the start of its firing sequence (column)
  int ring = 0;                     // by elevation, 0 = lowest (the localizer's convention)
};

// The point layout and ring numbering of a model's ROS driver (docs/formats.md, "Exporting
// recordings"), which exported clouds follow.
enum class DriverCloudLayout {
  kVelodyne,  // velodyne_pointcloud: x y z intensity ring time; rings by elevation, 0 = lowest
  kHesai,     // Hesai's driver: x y z intensity timestamp ring; ring = channel, 0 = top
  kOuster,    // ouster-ros: x y z intensity t reflectivity ring ambient range; ring = beam, 0 = top
};

// A spinning LiDAR as the simulator fires it and the localizer reads it (docs/simulation.md,
// "LiDAR models", says where each figure comes from): its beams, its timing, how its packets group
// the firing sequences. The figures a scenario may change (range gate, noise, detection range) are
// the scenario's, with each model's defaults in bim/lidar_models.hpp.
struct LidarModel {
  std::string name;   // "vlp16", as a scenario names it
  std::string title;  // "Velodyne VLP-16"
  std::vector<LidarBeam> beams;
  // One firing sequence (all beams once: a column) lasts this, whatever the rate (Velodyne,
  // Hesai: the turn has as many sequences as fit); 0 when the turn has a fixed number of columns.
  double sequence_s = 0.0;
  int columns_per_turn = 0;  // > 0: a fixed number of sequences a turn (Ouster's 1024×10 mode)
  // Sequences reported under one azimuth (a VLP-16 data block holds two), and per packet.
  int sequences_per_data_block = 1;
  int sequences_per_packet_single = 12, sequences_per_packet_dual = 6;
  double range_resolution_m = 0.002;    // ranges are reported in steps of this
  double half_divergence_rad = 1.5e-3;  // half the beam's horizontal divergence
  double beam_origin_radius_mm = 0.0;   // beams leave from a circle this wide about the axis
  DriverCloudLayout driver_layout = DriverCloudLayout::kVelodyne;

  int lasers() const { return int(beams.size()); }
  // The driver's ring number of each ring by elevation: the ring itself for Velodyne's driver, the
  // beam's channel (its index in firing order) for Hesai's and Ouster's.
  std::vector<std::uint16_t> driverRings() const;
  // Firing sequences in one turn at `rate_hz`, and how long each lasts.
  int sequencesPerTurn(double rate_hz) const;
  double sequenceDuration(double rate_hz) const;
};

// The models the simulator knows: vlp16 (the default), vlp32c, pandar-xt32, os0-64, os1-64,
// os1-128.
const std::vector<LidarModel>& lidarModels();
// The model named `name`; nullptr when there is none by that name.
const LidarModel* findLidarModel(std::string_view name);
// "vlp16, vlp32c, …" for messages.
std::string lidarModelList();

}  // namespace isg::sensors
