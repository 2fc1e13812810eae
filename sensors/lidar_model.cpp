#include "sensors/lidar_model.hpp"

#include <algorithm>
#include <cmath>
#include <numeric>

#include "sensors/vlp16_layout.hpp"

namespace isg::sensors {

namespace {

// Rings by elevation (0 = lowest; ties in firing order), as the localizer reads them.
void numberRings(std::vector<LidarBeam>& beams) {
  std::vector<int> order(beams.size());
  std::iota(order.begin(), order.end(), 0);
  std::stable_sort(order.begin(), order.end(), [&](int a, int b) {
    return beams[std::size_t(a)].elevation_deg < beams[std::size_t(b)].elevation_deg;
  });
  for (std::size_t r = 0; r < order.size(); ++r) beams[std::size_t(order[r])].ring = int(r);
}

LidarModel vlp16() {
  LidarModel m;
  m.name = "vlp16";
  m.title = "Velodyne VLP-16";
  for (int l = 0; l < Vlp16Layout::kLasers; ++l) {
    m.beams.push_back({Vlp16Layout::kElevationDeg[std::size_t(l)], 0.0,
                       Vlp16Layout::kVerticalOffsetMm[std::size_t(l)],
                       Vlp16Layout::kFiringInterval * l, Vlp16Layout::ring(l)});
  }
  m.sequence_s = Vlp16Layout::kSequenceDuration;
  m.sequences_per_data_block = 2;
  m.sequences_per_packet_single = 24;
  m.sequences_per_packet_dual = 12;
  m.range_resolution_m = 0.002;
  m.half_divergence_rad = 1.5e-3;
  return m;
}

// The VLP-32C: elevations and azimuth offsets of the Velodyne ROS driver's calibration
// (velodyne_pointcloud/params/VeloView-VLP-32C.yaml), lasers fired in pairs every 2.304 µs of a
// 55.296 µs sequence and one sequence a data block of 12 a packet (the driver's timing table from
// the manual), 4 mm range steps (the calibration's distance_resolution).
LidarModel vlp32c() {
  static constexpr double kElevation[32] = {
      -25.0,  -1.0,   -1.667, -15.639, -11.31, 0.0,    -0.667, -8.843, -7.254, 0.333,  -0.333,
      -6.148, -5.333, 1.333,  0.667,   -4.0,   -4.667, 1.667,  1.0,    -3.667, -3.333, 3.333,
      2.333,  -2.667, -3.0,   7.0,     4.667,  -2.333, -2.0,   15.0,   10.333, -1.333};
  static constexpr double kAzimuth[32] = {
      -1.4, 4.2, -1.4, 1.4, -1.4, 1.4, -4.2, 1.4, -1.4, 4.2, -1.4, 1.4, -4.2, 1.4, -4.2, 1.4,
      -1.4, 4.2, -1.4, 4.2, -4.2, 1.4, -1.4, 1.4, -1.4, 1.4, -1.4, 4.2, -4.2, 1.4, -1.4, 1.4};
  LidarModel m;
  m.name = "vlp32c";
  m.title = "Velodyne VLP-32C";
  for (int l = 0; l < 32; ++l) {
    // The driver's rot_correction turns a beam clockwise (the head's sense): the opposite of the
    // counter-clockwise azimuth here.
    m.beams.push_back({kElevation[l], -kAzimuth[l], 0.0, 2.304e-6 * (l / 2), 0});
  }
  numberRings(m.beams);
  m.sequence_s = 55.296e-6;
  m.sequences_per_packet_single = 12;
  m.sequences_per_packet_dual = 6;
  m.range_resolution_m = 0.004;
  m.half_divergence_rad = 1.5e-3;  // assumed: the VLP-16's
  return m;
}

// The Pandar XT32: channel 1 at +15° down to channel 32 at −16° in 1° steps, no azimuth offsets,
// channel i fired 0.368 + 1.512 (i − 1) µs into a 50 µs block, 8 blocks a packet (4 in dual
// return), 4 mm range steps: the Hesai SDK's PandarXT tables (HesaiLidar_General_SDK,
// pandarXT.h).
LidarModel pandarXt32() {
  LidarModel m;
  m.name = "pandar-xt32";
  m.title = "Hesai PandarXT-32";
  for (int c = 0; c < 32; ++c) {
    m.beams.push_back({15.0 - c, 0.0, 0.0, 0.368e-6 + 1.512e-6 * c, 0});
  }
  numberRings(m.beams);
  m.sequence_s = 50e-6;
  m.sequences_per_packet_single = 8;
  m.sequences_per_packet_dual = 4;
  m.range_resolution_m = 0.004;
  m.half_divergence_rad = 1.0e-3;  // assumed
  m.driver_layout = DriverCloudLayout::kHesai;
  return m;
}

// An Ouster OS sensor in its 1024×10 mode: `beams` uniform over ±`half_fov_deg` (the datasheet's
// field of view; a unit's calibration differs by hundredths of a degree), the four-column stagger
// of azimuth offsets of the ouster-sdk's sample units' metadata, every beam of a column fired at
// once, 1024 columns a turn whatever the rate, 16 columns a packet, ranges in millimetres, beams
// leaving from a circle about the axis (lidar_origin_to_beam_origin_mm).
LidarModel ouster(const char* name, const char* title, int beams, double half_fov_deg,
                  const double (&stagger)[4], double origin_radius_mm, double divergence_deg) {
  LidarModel m;
  m.name = name;
  m.title = title;
  for (int b = 0; b < beams; ++b) {
    const double elevation = half_fov_deg - 2.0 * half_fov_deg * b / (beams - 1);
    m.beams.push_back({elevation, stagger[b % 4], 0.0, 0.0, 0});
  }
  numberRings(m.beams);
  m.columns_per_turn = 1024;
  m.sequences_per_packet_single = 16;
  m.sequences_per_packet_dual = 16;
  m.range_resolution_m = 0.001;
  m.beam_origin_radius_mm = origin_radius_mm;
  m.driver_layout = DriverCloudLayout::kOuster;
  m.half_divergence_rad = 0.5 * divergence_deg * 3.14159265358979323846 / 180.0;
  return m;
}

std::vector<LidarModel> makeModels() {
  std::vector<LidarModel> models = {vlp16(), vlp32c(), pandarXt32()};
  // OS0: a 90° field of view (the ouster-sdk's OS0-128 sample: +44.3° to −46.2°).
  LidarModel os0 =
      ouster("os0-64", "Ouster OS0-64", 64, 45.0, {10.5, 3.5, -3.5, -10.5}, 27.1, 0.35);
  // OS1: the datasheet's ±16.6° for 64 beams and ±22.5° for 128, 0.13° and 0.18° divergence.
  LidarModel os1_64 =
      ouster("os1-64", "Ouster OS1-64", 64, 16.6, {3.1, 0.9, -1.2, -3.4}, 12.2, 0.13);
  LidarModel os1_128 =
      ouster("os1-128", "Ouster OS1-128", 128, 22.5, {4.2, 1.4, -1.4, -4.2}, 15.8, 0.18);
  models.push_back(os0);
  models.push_back(os1_64);
  models.push_back(os1_128);
  return models;
}

}  // namespace

std::vector<std::uint16_t> LidarModel::driverRings() const {
  std::vector<std::uint16_t> out(beams.size());
  for (std::size_t b = 0; b < beams.size(); ++b) {
    out[std::size_t(beams[b].ring)] =
        std::uint16_t(driver_layout == DriverCloudLayout::kVelodyne ? beams[b].ring : int(b));
  }
  return out;
}

int LidarModel::sequencesPerTurn(double rate_hz) const {
  if (columns_per_turn > 0) return columns_per_turn;
  return int(std::floor(1.0 / (rate_hz * sequence_s)));
}

double LidarModel::sequenceDuration(double rate_hz) const {
  return columns_per_turn > 0 ? 1.0 / (rate_hz * columns_per_turn) : sequence_s;
}

const std::vector<LidarModel>& lidarModels() {
  static const std::vector<LidarModel> models = makeModels();
  return models;
}

const LidarModel* findLidarModel(std::string_view name) {
  for (const auto& m : lidarModels()) {
    if (m.name == name) return &m;
  }
  return nullptr;
}

std::string lidarModelList() {
  std::string out;
  for (const auto& m : lidarModels()) out += (out.empty() ? "" : ", ") + m.name;
  return out;
}

}  // namespace isg::sensors
