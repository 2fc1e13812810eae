// Exported clouds in the drivers' layouts: each field where the driver puts it, with the value it
// means, and read back by the import's layout reader to the points they came from; rings
// renumbered by elevation whatever a driver's numbering.
#include "formats/driver_point_cloud.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <string>

#include "formats/cloud_layout.hpp"
#include "formats/ros2_message_decode.hpp"
#include "formats/ros2_messages.hpp"
#include "formats/ros_message_decode.hpp"
#include "formats/ros_messages.hpp"

namespace isg::formats {
namespace {

template <typename T>
T fieldAt(const std::string& data, std::size_t offset) {
  T value;
  std::memcpy(&value, data.data() + offset, sizeof(T));
  return value;
}

// Three points of a 32-beam sensor, rings by elevation (0 = lowest).
std::vector<sensors::ScanPoint> threePoints() {
  return {{3.0f, 4.0f, 0.0f, 40.0f, 16, 0.0f},
          {-1.0f, 2.0f, 2.0f, 7.4f, 31, 0.0123456f},
          {0.5f, -0.5f, -1.0f, 250.0f, 0, 0.0999f}};
}

TEST(DriverPointCloud, TheModelsNameTheirDriversLayoutAndRingNumbers) {
  const auto of = [](const char* name) {
    return CloudConvention::of(*sensors::findLidarModel(name));
  };
  EXPECT_EQ(of("vlp16").layout, sensors::DriverCloudLayout::kVelodyne);
  EXPECT_TRUE(of("vlp16").driver_rings.empty());
  EXPECT_EQ(of("vlp32c").layout, sensors::DriverCloudLayout::kVelodyne);
  // Hesai's channel 0 is the top beam (+15°), 31 the lowest (−16°).
  const CloudConvention hesai = of("pandar-xt32");
  EXPECT_EQ(hesai.layout, sensors::DriverCloudLayout::kHesai);
  ASSERT_EQ(hesai.driver_rings.size(), 32u);
  EXPECT_EQ(hesai.driver_rings[0], 31);
  EXPECT_EQ(hesai.driver_rings[31], 0);
  EXPECT_EQ(hesai.driver_rings[16], 15);
  // ouster-ros's ring is the beam: 0 at the top.
  const CloudConvention os = of("os1-128");
  EXPECT_EQ(os.layout, sensors::DriverCloudLayout::kOuster);
  ASSERT_EQ(os.driver_rings.size(), 128u);
  EXPECT_EQ(os.driver_rings[0], 127);
  EXPECT_EQ(os.driver_rings[127], 0);
}

TEST(DriverPointCloud, HesaisLayoutHasSecondsSinceTheEpochAndChannels) {
  const CloudConvention hesai = CloudConvention::of(*sensors::findLidarModel("pandar-xt32"));
  const PackedCloud cloud = packCloud(threePoints(), hesai, 1700000000, 250000000);
  EXPECT_EQ(cloud.point_step, 48u);
  ASSERT_EQ(cloud.data.size(), 3u * 48u);
  ASSERT_EQ(cloud.fields.size(), 6u);
  EXPECT_STREQ(cloud.fields[4].name, "timestamp");
  EXPECT_EQ(cloud.fields[4].offset, 24u);
  EXPECT_EQ(cloud.fields[4].datatype, 8);  // float64
  EXPECT_EQ(fieldAt<float>(cloud.data, 48 + 4), 2.0f);
  EXPECT_EQ(fieldAt<float>(cloud.data, 48 + 16), 7.4f);
  EXPECT_NEAR(fieldAt<double>(cloud.data, 48 + 24), 1700000000.25 + 0.0123456, 1e-6);
  EXPECT_EQ(fieldAt<std::uint16_t>(cloud.data, 0 * 48 + 32), 15);  // ring 16 by elevation: +0°
  EXPECT_EQ(fieldAt<std::uint16_t>(cloud.data, 1 * 48 + 32), 0);   // the top
  EXPECT_EQ(fieldAt<std::uint16_t>(cloud.data, 2 * 48 + 32), 31);  // the lowest
}

TEST(DriverPointCloud, OustersLayoutHasNanosecondsRangeAndBeams) {
  const CloudConvention os = CloudConvention::of(*sensors::findLidarModel("pandar-xt32"));
  CloudConvention ouster = os;
  ouster.layout = sensors::DriverCloudLayout::kOuster;
  const PackedCloud cloud = packCloud(threePoints(), ouster, 1700000000, 0);
  EXPECT_EQ(cloud.point_step, 48u);
  ASSERT_EQ(cloud.fields.size(), 9u);
  const char* names[] = {"x",    "y",       "z",    "intensity", "t", "reflectivity",
                         "ring", "ambient", "range"};
  const std::uint32_t offsets[] = {0, 4, 8, 16, 20, 24, 26, 28, 32};
  const std::uint8_t types[] = {7, 7, 7, 7, 6, 4, 4, 4, 6};
  for (std::size_t i = 0; i < 9; ++i) {
    EXPECT_STREQ(cloud.fields[i].name, names[i]);
    EXPECT_EQ(cloud.fields[i].offset, offsets[i]);
    EXPECT_EQ(cloud.fields[i].datatype, types[i]);
  }
  EXPECT_EQ(fieldAt<std::uint32_t>(cloud.data, 0 + 20), 0u);
  EXPECT_EQ(fieldAt<std::uint32_t>(cloud.data, 48 + 20), 12345600u);  // 0.0123456 s in ns
  EXPECT_EQ(fieldAt<std::uint32_t>(cloud.data, 0 + 32), 5000u);       // |(3, 4, 0)| = 5 m in mm
  EXPECT_EQ(fieldAt<std::uint32_t>(cloud.data, 48 + 32), 3000u);      // |(−1, 2, 2)| = 3 m
  EXPECT_EQ(fieldAt<std::uint16_t>(cloud.data, 48 + 24), 7);          // reflectivity: 7.4 rounded
  EXPECT_EQ(fieldAt<std::uint16_t>(cloud.data, 96 + 24), 250);
  EXPECT_EQ(fieldAt<std::uint16_t>(cloud.data, 48 + 26), 0);  // the top beam
  EXPECT_EQ(fieldAt<std::uint16_t>(cloud.data, 96 + 28), 0);  // ambient: not simulated
}

// The import reads each layout back to the points (times to the nanosecond Ouster keeps, Hesai's
// to float64 seconds since the epoch), rings renumbered by elevation to the original numbers.
TEST(DriverPointCloud, EveryLayoutReadsBackToThePointsThroughBothRoses) {
  // A full set of rings, so that ringsByElevation sees the driver's whole numbering: 32 beams at
  // the Pandar's elevations, each at two azimuths.
  std::vector<sensors::ScanPoint> points;
  for (int ring = 0; ring < 32; ++ring) {
    const double elevation = (-16.0 + ring) * M_PI / 180.0;
    for (int k = 0; k < 2; ++k) {
      const double azimuth = 0.7 + 2.0 * k;
      const double r = 4.0 + 0.1 * ring;
      points.push_back({float(r * std::cos(elevation) * std::cos(azimuth)),
                        float(r * std::cos(elevation) * std::sin(azimuth)),
                        float(r * std::sin(elevation)), float(ring + k), std::uint16_t(ring),
                        float(0.001 * ring + 0.05 * k)});
    }
  }
  const CloudConvention hesai = CloudConvention::of(*sensors::findLidarModel("pandar-xt32"));
  CloudConvention ouster = hesai;
  ouster.layout = sensors::DriverCloudLayout::kOuster;
  for (const CloudConvention& convention : {CloudConvention{}, hesai, ouster}) {
    for (const bool ros2 : {false, true}) {
      SCOPED_TRACE(std::to_string(int(convention.layout)) + (ros2 ? " ROS 2" : " ROS 1"));
      // The decoded cloud's data is a view of the message: the message outlives it.
      const std::string message =
          ros2 ? ros2::pointCloud2(points, {1700000000, 500000000}, "lidar", convention)
               : ros1::pointCloud2(points, {1700000000, 500000000}, 3, "lidar", convention);
      const ros1::PointCloud2 cloud =
          ros2 ? ros2::decodePointCloud2(message) : ros1::decodePointCloud2(message);
      const CloudLayout layout = cloudLayout(cloud);
      std::vector<sensors::ScanPoint> back = cloudPoints(cloud, layout);
      ASSERT_EQ(back.size(), points.size());
      const std::vector<std::uint16_t> renumbered = ringsByElevation(back);
      EXPECT_EQ(renumbered.empty(), convention.driver_rings.empty());
      for (auto& p : back) {
        if (!renumbered.empty()) p.ring = renumbered[p.ring];
      }
      for (std::size_t i = 0; i < points.size(); ++i) {
        EXPECT_EQ(back[i].x, points[i].x);
        EXPECT_EQ(back[i].z, points[i].z);
        EXPECT_EQ(back[i].intensity, points[i].intensity);
        EXPECT_EQ(back[i].ring, points[i].ring);
        EXPECT_NEAR(back[i].time, points[i].time, 1e-6);
      }
    }
  }
}

TEST(DriverPointCloud, RingsAlreadyByElevationAreLeftAsTheyAre) {
  std::vector<sensors::ScanPoint> points = {
      {1, 0, -0.5f, 0, 0, 0}, {1, 0, 0.0f, 0, 1, 0}, {1, 0, 0.5f, 0, 2, 0}};
  EXPECT_TRUE(ringsByElevation(points).empty());
  // Laser ids in firing order: 0 the middle beam, 1 the lowest, 2 the top.
  points = {{1, 0, 0.0f, 0, 0, 0}, {1, 0, -0.5f, 0, 1, 0}, {1, 0, 0.5f, 0, 2, 0}};
  EXPECT_EQ(ringsByElevation(points), (std::vector<std::uint16_t>{1, 0, 2}));
  // A ring the cloud lacks (1) keeps its number; the ones it has are ranked among themselves.
  points = {{1, 0, 0.5f, 0, 0, 0}, {1, 0, -0.5f, 0, 2, 0}};
  EXPECT_EQ(ringsByElevation(points), (std::vector<std::uint16_t>{2, 1, 0}));
  EXPECT_TRUE(ringsByElevation({{1, 0, 0, 0, 5, 0}}).empty());
}

}  // namespace
}  // namespace isg::formats
