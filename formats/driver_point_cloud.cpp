#include "formats/driver_point_cloud.hpp"

#include <algorithm>
#include <cmath>
#include <cstring>

#include "formats/velodyne_point_layout.hpp"

namespace isg::formats {

namespace {

constexpr std::uint8_t kUint16 = 4, kUint32 = 6, kFloat32 = 7, kFloat64 = 8;
constexpr std::uint32_t kAlignedPointStep = 48;  // PCL's EIGEN_ALIGN16 points of 33–48 bytes

template <typename T>
void put(unsigned char* at, T value) {
  std::memcpy(at, &value, sizeof(T));
}

// x y z at 0/4/8 and intensity at 16: the 16-byte-aligned PCL points both Hesai's and Ouster's
// drivers publish.
void putAlignedXyzIntensity(unsigned char* at, const sensors::ScanPoint& p) {
  put(at + 0, p.x);
  put(at + 4, p.y);
  put(at + 8, p.z);
  put(at + 16, p.intensity);
}

std::uint16_t driverRing(const CloudConvention& convention, std::uint16_t ring) {
  return ring < convention.driver_rings.size() ? convention.driver_rings[ring] : ring;
}

}  // namespace

CloudConvention CloudConvention::of(const sensors::LidarModel& model) {
  CloudConvention convention;
  convention.layout = model.driver_layout;
  if (model.driver_layout != sensors::DriverCloudLayout::kVelodyne) {
    convention.driver_rings = model.driverRings();
  }
  return convention;
}

PackedCloud packCloud(const std::vector<sensors::ScanPoint>& points,
                      const CloudConvention& convention, std::uint32_t stamp_sec,
                      std::uint32_t stamp_nsec) {
  PackedCloud cloud;
  switch (convention.layout) {
    case sensors::DriverCloudLayout::kVelodyne: {
      cloud.fields = {{"x", 0, kFloat32},          {"y", 4, kFloat32},    {"z", 8, kFloat32},
                      {"intensity", 12, kFloat32}, {"ring", 16, kUint16}, {"time", 18, kFloat32}};
      cloud.point_step = kVelodynePointStep;
      cloud.data.assign(std::size_t(cloud.point_step) * points.size(), '\0');
      packVelodynePoints(points, cloud.data.data());
      if (!convention.driver_rings.empty()) {
        for (std::size_t i = 0; i < points.size(); ++i) {
          put(reinterpret_cast<unsigned char*>(cloud.data.data()) + i * cloud.point_step + 16,
              driverRing(convention, points[i].ring));
        }
      }
      return cloud;
    }
    case sensors::DriverCloudLayout::kHesai: {
      cloud.fields = {{"x", 0, kFloat32},          {"y", 4, kFloat32},
                      {"z", 8, kFloat32},          {"intensity", 16, kFloat32},
                      {"timestamp", 24, kFloat64}, {"ring", 32, kUint16}};
      cloud.point_step = kAlignedPointStep;
      cloud.data.assign(std::size_t(cloud.point_step) * points.size(), '\0');
      const double stamp = double(stamp_sec) + 1e-9 * double(stamp_nsec);
      auto* at = reinterpret_cast<unsigned char*>(cloud.data.data());
      for (const sensors::ScanPoint& p : points) {
        putAlignedXyzIntensity(at, p);
        put(at + 24, stamp + double(p.time));
        put(at + 32, driverRing(convention, p.ring));
        at += cloud.point_step;
      }
      return cloud;
    }
    case sensors::DriverCloudLayout::kOuster: {
      cloud.fields = {
          {"x", 0, kFloat32},          {"y", 4, kFloat32},       {"z", 8, kFloat32},
          {"intensity", 16, kFloat32}, {"t", 20, kUint32},       {"reflectivity", 24, kUint16},
          {"ring", 26, kUint16},       {"ambient", 28, kUint16}, {"range", 32, kUint32}};
      cloud.point_step = kAlignedPointStep;
      cloud.data.assign(std::size_t(cloud.point_step) * points.size(), '\0');
      auto* at = reinterpret_cast<unsigned char*>(cloud.data.data());
      for (const sensors::ScanPoint& p : points) {
        putAlignedXyzIntensity(at, p);
        // Ouster's t counts from the turn's first column: a time before the stamp is clamped.
        put(at + 20, std::uint32_t(std::clamp(std::llround(double(p.time) * 1e9), 0LL,
                                              (long long)UINT32_MAX)));
        put(at + 24, std::uint16_t(std::clamp(std::lround(double(p.intensity)), 0L, 65535L)));
        put(at + 26, driverRing(convention, p.ring));
        put(at + 28, std::uint16_t(0));
        const double range_mm =
            1000.0 * std::sqrt(double(p.x) * p.x + double(p.y) * p.y + double(p.z) * p.z);
        put(at + 32, std::uint32_t(std::min(std::llround(range_mm), (long long)UINT32_MAX)));
        at += cloud.point_step;
      }
      return cloud;
    }
  }
  return cloud;
}

}  // namespace isg::formats
