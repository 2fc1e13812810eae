#include "formats/dataset_metadata.hpp"

#include <algorithm>
#include <map>
#include <stdexcept>

namespace isg::formats::dataset {

namespace {

using json = nlohmann::ordered_json;

// The keys of metadata.json in the order docs/formats.md gives them, the document's own and each
// section's ("" is the document). A key not named here follows those named, in the order given.
const std::map<std::string, std::vector<std::string>>& keyOrder() {
  static const std::map<std::string, std::vector<std::string>> order{
      {"",
       {"format", "version", "generator", "scenario", "plan_file", "seed", "duration_s", "frames",
        "extrinsics", "lidar", "odometry", "imu", "groundtruth_rate_hz", "robot", "plan",
        "as_built", "imported_from"}},
      {"frames", {"B", "M", "R", "L", "I"}},
      {"extrinsics", {"R_T_L", "R_T_I"}},
      {"lidar",
       {"model",
        "rate_hz",
        "scans",
        "sequences_per_turn",
        "sequences_per_cloud",
        "stamp",
        "cut",
        "cut_angle_deg",
        "azimuth_jitter_deg",
        "returns",
        "scan_period_s",
        "point_time_s",
        "fields",
        "firing_interval_s",
        "sequence_duration_s",
        "elevation_deg_by_laser",
        "vertical_offset_mm_by_laser",
        "ring",
        "rotation",
        "range_noise_m",
        "range_quantum_m",
        "min_range_m",
        "max_range_m",
        "dropout",
        "grazing_cutoff_deg",
        "detection_range_m",
        "body_occlusion",
        "reflectivity",
        "intensity",
        "lost_returns",
        "pcd_data",
        "pcd_fields"}},
      {"odometry",
       {"rate_hz", "translation_noise", "heading_noise_deg_per_m", "heading_bias_deg_per_m",
        "model", "topic", "chain"}},
      {"imu",
       {"file", "rate_hz", "samples", "frame", "columns", "gravity_m_s2", "gyroscope_noise_density",
        "gyroscope_random_walk", "accelerometer_noise_density", "accelerometer_random_walk",
        "noise_units", "kidnaps"}},
  };
  return order;
}

// `object`'s keys in the order of `section`'s table; the others after, as they were.
json ordered(const json& object, const std::string& section) {
  if (!object.is_object()) return object;
  const auto table = keyOrder().find(section);
  json out = json::object();
  if (table != keyOrder().end()) {
    for (const auto& key : table->second) {
      if (object.contains(key)) out[key] = object[key];
    }
  }
  for (const auto& item : object.items()) {
    if (!out.contains(item.key())) out[item.key()] = item.value();
  }
  return out;
}

// `extra`'s keys added to `section`; one `section` already has is a producer writing a field of
// the format's own.
void addDescription(json& section, const json& extra, const std::string& name) {
  for (const auto& item : extra.items()) {
    if (section.contains(item.key())) {
      throw std::logic_error("metadata.json: the description sets " + name + "/" + item.key() +
                             ", which the dataset format writes itself");
    }
    section[item.key()] = item.value();
  }
}

}  // namespace

json metadataJson(const Metadata& m, const json& description) {
  json frames = json::object();
  for (const auto& [frame, what] : m.frames) frames[frame] = what;
  json extrinsics = {{"R_T_L", mountJson(m.lidar_mount, m.R_T_L)}};
  if (m.imu_mount) extrinsics["R_T_I"] = mountJson(m.imu_mount->xyz_rpy, m.imu_mount->R_T_I);
  json document = {{"format", kFormat},
                   {"version", kVersion},
                   {"generator", m.generator},
                   {"duration_s", m.duration_s},
                   {"frames", frames},
                   {"extrinsics", extrinsics},
                   {"lidar",
                    {{"model", m.lidar.model},
                     {"rate_hz", m.lidar.rate_hz},
                     {"scans", m.lidar.scans},
                     {"stamp", m.lidar.stamp},
                     {"scan_period_s", m.lidar.scan_period_s},
                     {"point_time_s", m.lidar.point_time_s},
                     {"pcd_data", pcdDataName(m.lidar.pcd_data)}}}};
  if (m.odometry) document["odometry"] = {{"rate_hz", m.odometry->rate_hz}};
  if (m.imu) {
    json imu = {
        {"file", kImu}, {"rate_hz", m.imu->rate_hz}, {"samples", m.imu->samples}, {"frame", "I"}};
    if (m.imu->gyroscope_noise_density)
      imu["gyroscope_noise_density"] = *m.imu->gyroscope_noise_density;
    if (m.imu->accelerometer_noise_density)
      imu["accelerometer_noise_density"] = *m.imu->accelerometer_noise_density;
    document["imu"] = imu;
  }
  for (const auto& item : description.items()) {
    const std::string& key = item.key();
    const bool section = keyOrder().count(key) && !key.empty();
    if (section && document.contains(key) && item.value().is_object()) {
      addDescription(document[key], item.value(), key);
    } else if (document.contains(key)) {
      throw std::logic_error("metadata.json: the description sets " + key +
                             ", which the dataset format writes itself");
    } else {
      document[key] = item.value();
    }
  }
  return inMetadataOrder(document);
}

json inMetadataOrder(const json& document) {
  json out = ordered(document, "");
  for (const auto& [section, _] : keyOrder()) {
    if (!section.empty() && out.contains(section)) out[section] = ordered(out[section], section);
  }
  return out;
}

}  // namespace isg::formats::dataset
