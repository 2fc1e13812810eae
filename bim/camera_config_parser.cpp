#include <algorithm>
#include <cctype>
#include <cmath>
#include <numbers>
#include <set>

#include "bim/scenario.hpp"

namespace isg::bim {

namespace {

// The largest image rendered: MuJoCo draws into the world's offscreen buffer
// (worlds/mjcf_generator.cpp gives it 1920 × 1080).
constexpr int kMaxCameraWidth = 1920;
constexpr int kMaxCameraHeight = 1080;

// [x, y, z, roll, pitch, yaw], written as that array (as the LiDAR's and IMU's mounts are) or as
// {"xyz": [x, y, z], "rpy": [roll, pitch, yaw]}; radians.
std::array<double, 6> parseCameraMount(const common::JsonNode& node) {
  std::array<double, 6> mount{};
  if (node.isObject()) {
    node.expectObject({"xyz", "rpy"});
    const Eigen::Vector3d xyz = node.field("xyz").point3();
    const Eigen::Vector3d rpy = node.field("rpy").point3();
    mount = {xyz.x(), xyz.y(), xyz.z(), rpy.x(), rpy.y(), rpy.z()};
  } else {
    const auto values = node.numbers(6);
    std::copy(values.begin(), values.end(), mount.begin());
  }
  if (std::max({std::abs(mount[0]), std::abs(mount[1]), std::abs(mount[2])}) > 10.0) {
    node.fail("the camera must be mounted within 10 m of the robot's reference point");
  }
  return mount;
}

std::string knownModels() {
  std::string list;
  for (const auto& name : cameraModelNames())
    list += (list.empty() ? "" : ", ") + common::inQuotes(name);
  return list;
}

// A camera's name names its folder in an EuRoC dataset (mav0/<name>/).
void checkCameraName(const common::JsonNode& node, const std::string& name) {
  const bool plain = std::all_of(name.begin(), name.end(), [](char c) {
    return std::isalnum(static_cast<unsigned char>(c)) || c == '_' || c == '-';
  });
  if (!plain || name.empty() || name.size() > 64) {
    node.fail("a camera's name is 1 to 64 letters, digits, '_' or '-' (it names a folder)");
  }
  const bool depth_folder =
      name.size() > 5 && name.rfind("depth", 0) == 0 &&
      std::all_of(name.begin() + 5, name.end(), [](char c) { return c >= '0' && c <= '9'; });
  if (depth_folder || name == "imu0" || name == "state_groundtruth_estimate0") {
    node.fail("camera name " + common::inQuotes(name) + " is an EuRoC folder of its own");
  }
}

// A pinhole's own image: its resolution and horizontal field of view.
PinholeIntrinsics parsePinholeImage(const common::JsonNode& node, const PinholeIntrinsics& k) {
  int width = k.width, height = k.height;
  double hfov = 2.0 * std::atan(0.5 * k.width / k.fx) * 180.0 / std::numbers::pi;
  for (const char* key : {"width", "height"}) {
    if (auto v = node.optionalField(key); v && std::floor(v->number()) != v->number()) {
      v->fail("expected a whole number of pixels");
    }
  }
  if (auto v = node.optionalField("width")) width = int(v->numberInRange(16, kMaxCameraWidth));
  if (auto v = node.optionalField("height")) height = int(v->numberInRange(16, kMaxCameraHeight));
  if (auto v = node.optionalField("hfov_deg")) hfov = v->numberInRange(10.0, 150.0);
  return pinholeFromFov(width, height, hfov);
}

// A rig's lenses, each a camera placed by the rig's calibration from the IMU: named
// <name><i> when the entry has a name, else cam<index>, cam<index + 1>, …
std::vector<CameraConfig> parseRig(const common::JsonNode& node, const CameraRig& rig,
                                   const std::string& model_name, std::size_t index) {
  if (node.has("mount")) {
    node.field("mount").fail(common::inQuotes(model_name) +
                             " is a rig whose lenses its calibration places from its IMU: move "
                             "the rig with \"imu\": {\"mount\": …}");
  }
  std::optional<std::string> prefix;
  if (auto v = node.optionalField("name")) {
    prefix = v->identifier();
    checkCameraName(*v, *prefix + "0");
  }
  std::vector<CameraConfig> lenses;
  for (std::size_t i = 0; i < rig.lenses.size(); ++i) {
    CameraConfig camera;
    camera.model = rig.lenses[i].model;
    camera.I_T_C = rig.lenses[i].I_T_C;
    camera.name = prefix ? *prefix + std::to_string(i) : "cam" + std::to_string(index + i);
    camera.rig = model_name;
    if (auto v = node.optionalField("rate_hz"))
      camera.model.rate_hz = v->numberInRange(0.1, 1000.0);
    lenses.push_back(std::move(camera));
  }
  return lenses;
}

// One entry of "cameras": one camera, or a rig's lenses.
std::vector<CameraConfig> parseCamera(const common::JsonNode& node, std::size_t index) {
  node.expectObject({"model", "name", "rate_hz", "mount", "width", "height", "hfov_deg"});
  const common::JsonNode model_node = node.field("model");
  const std::string model_name = model_node.string();
  const auto model = cameraModel(model_name);
  const auto rig = cameraRig(model_name);
  if (!model && !rig) {
    model_node.fail("unknown camera model " + common::inQuotes(model_name) +
                    " (known: " + knownModels() + ")");
  }
  // A named camera's image is the sensor's; a pinhole's is the scenario's to choose.
  const bool pinhole = model_name == "pinhole";
  for (const char* key : {"width", "height", "hfov_deg"}) {
    if (!pinhole && node.has(key)) {
      node.field(key).fail("only a \"pinhole\" camera takes its own " + std::string(key) + " (" +
                           common::inQuotes(model_name) + " has the sensor's)");
    }
  }
  if (rig) return parseRig(node, *rig, model_name, index);
  CameraConfig camera;
  camera.model = *model;
  camera.name = "cam" + std::to_string(index);
  if (auto v = node.optionalField("name")) {
    camera.name = v->identifier();
    checkCameraName(*v, camera.name);
  }
  if (auto v = node.optionalField("rate_hz")) camera.model.rate_hz = v->numberInRange(0.1, 1000.0);
  if (auto v = node.optionalField("mount")) camera.mount = parseCameraMount(*v);
  if (pinhole) camera.model.intrinsics = parsePinholeImage(node, camera.model.intrinsics);
  return {camera};
}

}  // namespace

std::vector<CameraConfig> parseCameras(const common::JsonNode& node) {
  std::vector<CameraConfig> cameras;
  std::set<std::string> names;
  const auto entries = node.elements(0, 8, "cameras");
  bool rig_seen = false;
  for (std::size_t i = 0; i < entries.size(); ++i) {
    std::vector<CameraConfig> parsed = parseCamera(entries[i], cameras.size());
    if (!parsed.front().rig.empty()) {
      if (rig_seen) {
        entries[i].fail(
            "a scenario carries one camera rig (its lenses are placed from the "
            "scenario's one IMU)");
      }
      rig_seen = true;
    }
    for (CameraConfig& camera : parsed) {
      if (!names.insert(camera.name).second) {
        entries[i].fail("camera name " + common::inQuotes(camera.name) + " is used twice");
      }
      cameras.push_back(std::move(camera));
    }
  }
  return cameras;
}

}  // namespace isg::bim
