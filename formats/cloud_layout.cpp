#include "formats/cloud_layout.hpp"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <initializer_list>

namespace isg::formats {

namespace {

std::size_t sizeOf(std::uint8_t datatype) {
  switch (datatype) {
    case 1:
    case 2:
      return 1;
    case 3:
    case 4:
      return 2;
    case 5:
    case 6:
    case 7:
      return 4;
    case 8:
      return 8;
    default:
      return 0;
  }
}

bool isInteger(std::uint8_t datatype) { return datatype >= 1 && datatype <= 6; }

template <typename T>
double as(const char* at) {
  T value;
  std::memcpy(&value, at, sizeof(T));
  return double(value);
}

double valueAt(const char* point, const ros1::PointField& field) {
  const char* at = point + field.offset;
  switch (field.datatype) {
    case 1:
      return as<std::int8_t>(at);
    case 2:
      return as<std::uint8_t>(at);
    case 3:
      return as<std::int16_t>(at);
    case 4:
      return as<std::uint16_t>(at);
    case 5:
      return as<std::int32_t>(at);
    case 6:
      return as<std::uint32_t>(at);
    case 7:
      return as<float>(at);
    default:
      return as<double>(at);
  }
}

std::optional<ros1::PointField> find(const ros1::PointCloud2& cloud,
                                     std::initializer_list<const char*> names) {
  for (const char* name : names) {
    for (const auto& field : cloud.fields) {
      if (field.name != name) continue;
      if (sizeOf(field.datatype) == 0) {
        throw ros1::MessageError("the field `" + field.name + "` has the unknown datatype " +
                                 std::to_string(int(field.datatype)));
      }
      if (field.count != 1) {
        throw ros1::MessageError("the field `" + field.name + "` has count " +
                                 std::to_string(field.count) + " (1 expected)");
      }
      if (std::uint64_t(field.offset) + sizeOf(field.datatype) > cloud.point_step) {
        throw ros1::MessageError("the field `" + field.name + "` at offset " +
                                 std::to_string(field.offset) + " lies outside the point_step of " +
                                 std::to_string(cloud.point_step) + " bytes");
      }
      return field;
    }
  }
  return std::nullopt;
}

}  // namespace

std::string CloudLayout::describe() const {
  std::string out = "x y z";
  if (intensity) out += " " + intensity->name;
  if (ring) out += " " + ring->name;
  if (time) out += " " + time->name;
  if (time && time->name == "time" && ring) out += " (the Velodyne driver's layout)";
  if (time && time->name == "t") out += " (Ouster's layout)";
  if (time && time->name == "timestamp" && ring && ring->name == "ring") out += " (Hesai's layout)";
  if (time && (time->name == "offset_time" ||
               (time->name == "timestamp" && ring && ring->name == "line"))) {
    out += " (Livox's layout)";
  }
  if (!time) out += " (no per-point time: the scans are not deskewed)";
  return out;
}

CloudLayout cloudLayout(const ros1::PointCloud2& cloud) {
  if (cloud.is_bigendian) throw ros1::MessageError("a big-endian cloud (not read)");
  CloudLayout layout;
  layout.x = find(cloud, {"x"});
  layout.y = find(cloud, {"y"});
  layout.z = find(cloud, {"z"});
  if (!layout.x || !layout.y || !layout.z) {
    std::string names;
    for (const auto& f : cloud.fields) names += (names.empty() ? "" : " ") + f.name;
    throw ros1::MessageError("the cloud has no x, y and z fields (its fields: " +
                             (names.empty() ? std::string("none") : names) + ")");
  }
  layout.intensity = find(cloud, {"intensity", "reflectivity"});
  layout.ring = find(cloud, {"ring", "channel", "laser_id", "line"});
  layout.time = find(cloud, {"time", "t", "offset_time", "timestamp", "time_offset"});
  return layout;
}

std::vector<sensors::ScanPoint> cloudPoints(const ros1::PointCloud2& cloud,
                                            const CloudLayout& layout) {
  const std::uint64_t count = std::uint64_t(cloud.height) * cloud.width;
  if (cloud.point_step == 0 && count > 0) throw ros1::MessageError("point_step is 0");
  // Rows may be padded (row_step ≥ width × point_step); each row starts at row × row_step.
  const std::uint64_t row_step =
      std::max<std::uint64_t>(cloud.row_step, std::uint64_t(cloud.width) * cloud.point_step);
  const std::uint64_t needed =
      count == 0 ? 0
                 : (cloud.height - 1) * row_step + std::uint64_t(cloud.width) * cloud.point_step;
  if (needed > cloud.data.size()) {
    throw ros1::MessageError(std::to_string(cloud.height) + " × " + std::to_string(cloud.width) +
                             " points need " + std::to_string(needed) + " bytes, the data has " +
                             std::to_string(cloud.data.size()));
  }
  const double stamp = double(cloud.header.stamp.sec) + 1e-9 * cloud.header.stamp.nsec;
  const double time_scale = layout.time && isInteger(layout.time->datatype) ? 1e-9 : 1.0;
  // A floating time since the epoch is in seconds (Hesai) or, as Livox's PointCloud2 `timestamp`,
  // in nanoseconds (or ms, µs): the unit is the one that puts the cloud's first such time within
  // 1 s of its stamp, and holds for the whole cloud.
  double epoch_unit = 0.0;
  const auto sinceEpoch = [&](double raw) {
    if (epoch_unit == 0.0) {
      epoch_unit = 1.0;
      for (const double unit : {1.0, 1e-3, 1e-6, 1e-9}) {
        if (std::abs(raw * unit - stamp) <= 1.0) {
          epoch_unit = unit;
          break;
        }
      }
    }
    return raw * epoch_unit - stamp;
  };
  std::vector<sensors::ScanPoint> points;
  points.reserve(std::size_t(count));
  for (std::uint32_t row = 0; row < cloud.height; ++row) {
    for (std::uint32_t col = 0; col < cloud.width; ++col) {
      const char* p = cloud.data.data() + row * row_step + std::uint64_t(col) * cloud.point_step;
      const double x = valueAt(p, *layout.x), y = valueAt(p, *layout.y), z = valueAt(p, *layout.z);
      if (!std::isfinite(x) || !std::isfinite(y) || !std::isfinite(z)) continue;
      if (x == 0.0 && y == 0.0 && z == 0.0) continue;
      const double raw = layout.time ? valueAt(p, *layout.time) : 0.0;
      double time = raw * time_scale;
      if (!std::isfinite(time)) continue;
      if (std::abs(time) > 1e6) time = time_scale == 1.0 ? sinceEpoch(raw) : time - stamp;
      if (std::abs(time) > 1.0) {
        throw ros1::MessageError("a point's `" + layout.time->name + "` is " +
                                 std::to_string(time) +
                                 " s from the cloud's stamp (a turn lasts well under 1 s): not a "
                                 "time this reads");
      }
      const double intensity = layout.intensity ? valueAt(p, *layout.intensity) : 0.0;
      const double ring = layout.ring ? valueAt(p, *layout.ring) : 0.0;
      points.push_back(
          {float(x), float(y), float(z), std::isfinite(intensity) ? float(intensity) : 0.0f,
           std::uint16_t(std::isfinite(ring) ? std::clamp(ring, 0.0, 65535.0) : 0.0), float(time)});
    }
  }
  return points;
}

std::vector<std::uint16_t> ringsByElevation(const std::vector<sensors::ScanPoint>& points) {
  std::vector<double> sine_sum;
  std::vector<std::size_t> count;
  for (const sensors::ScanPoint& p : points) {
    const double r = std::sqrt(double(p.x) * p.x + double(p.y) * p.y + double(p.z) * p.z);
    if (!(r > 0.0)) continue;
    if (p.ring >= count.size()) {
      count.resize(std::size_t(p.ring) + 1, 0);
      sine_sum.resize(std::size_t(p.ring) + 1, 0.0);
    }
    sine_sum[p.ring] += double(p.z) / r;
    ++count[p.ring];
  }
  std::vector<std::uint16_t> rings;  // seen, by number
  for (std::size_t r = 0; r < count.size(); ++r) {
    if (count[r] > 0) rings.push_back(std::uint16_t(r));
  }
  if (rings.size() < 2) return {};
  std::vector<std::uint16_t> by_elevation = rings;
  std::stable_sort(by_elevation.begin(), by_elevation.end(), [&](std::uint16_t a, std::uint16_t b) {
    return sine_sum[a] / double(count[a]) < sine_sum[b] / double(count[b]);
  });
  if (by_elevation == rings) return {};
  std::vector<std::uint16_t> renumbered(count.size());
  for (std::size_t r = 0; r < count.size(); ++r) renumbered[r] = std::uint16_t(r);
  for (std::size_t i = 0; i < rings.size(); ++i) renumbered[by_elevation[i]] = rings[i];
  return renumbered;
}

}  // namespace isg::formats
