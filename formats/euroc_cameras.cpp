#include "formats/euroc_cameras.hpp"

#include <png.h>
#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <map>
#include <memory>
#include <sstream>

#include "common/input_error.hpp"
#include "formats/file_bytes.hpp"
#include "formats/frame_size.hpp"

namespace isg::formats {

namespace fs = std::filesystem;

namespace {

// One field of a sensor.yaml, converted; a missing or mistyped field names its key.
template <typename T>
T field(const YAML::Node& root, const char* key, const fs::path& file) {
  const YAML::Node node = root[key];
  if (!node) throw common::InputError(file.string(), std::string("/") + key, "missing");
  try {
    return node.as<T>();
  } catch (const YAML::Exception&) {
    throw common::InputError(file.string(), std::string("/") + key, "not of the expected type");
  }
}

// `count` numbers at `key`; `where` is the key's parent's pointer ("" at the top).
std::vector<double> numbers(const YAML::Node& root, const char* key, std::size_t count,
                            const fs::path& file, const std::string& where = "") {
  const YAML::Node node = root[key];
  if (!node) throw common::InputError(file.string(), where + "/" + key, "missing");
  std::vector<double> values;
  try {
    values = node.as<std::vector<double>>();
  } catch (const YAML::Exception&) {
    throw common::InputError(file.string(), where + "/" + key, "not a list of numbers");
  }
  if (values.size() != count) {
    throw common::InputError(
        file.string(), where + "/" + key,
        "has " + std::to_string(values.size()) + " numbers, expected " + std::to_string(count));
  }
  return values;
}

// sensor.yaml as isg simulate writes it (EuRoC's fields, Kalibr's distortion names).
EurocCamera readSensorYaml(const std::string& name, const fs::path& file) {
  YAML::Node root;
  try {
    root = YAML::LoadFile(file.string());
  } catch (const YAML::Exception& e) {
    throw common::InputError(file.string(), "", std::string("not YAML: ") + e.what());
  }
  EurocCamera camera;
  camera.name = name;
  camera.depth = bool(root["depth_scale_m"]);
  if (camera.depth && field<double>(root, "depth_scale_m", file) != 0.001) {
    throw common::InputError(file.string(), "/depth_scale_m", "only millimetres (0.001) are read");
  }
  camera.rate_hz = field<double>(root, "rate_hz", file);
  if (!root["T_BS"] || !root["T_BS"].IsMap()) {
    throw common::InputError(file.string(), "/T_BS", "missing, or not a map with data");
  }
  const std::vector<double> T = numbers(root["T_BS"], "data", 16, file, "/T_BS");
  for (int r = 0; r < 4; ++r) {
    for (int c = 0; c < 4; ++c) camera.I_T_C.matrix()(r, c) = T[4 * r + c];
  }
  const std::vector<double> size = numbers(root, "resolution", 2, file);
  const std::vector<double> k = numbers(root, "intrinsics", 4, file);
  CameraCalibration& calibration = camera.calibration;
  calibration.width = int(size[0]);
  calibration.height = int(size[1]);
  if (!(size[0] >= 1 && size[1] >= 1 && size[0] <= 1 << 14 && size[1] <= 1 << 14)) {
    throw common::InputError(file.string(), "/resolution", "not an image size");
  }
  calibration.fx = k[0];
  calibration.fy = k[1];
  calibration.cx = k[2];
  calibration.cy = k[3];
  const auto model = field<std::string>(root, "distortion_model", file);
  if (model == "equidistant") {
    calibration.distortion_model = "equidistant";
    calibration.distortion = numbers(root, "distortion_coefficients", 4, file);
  } else if (model == "radial-tangential" || model == "radtan") {
    // ROS's plumb_bob has k3 after EuRoC's k1 k2 p1 p2.
    calibration.distortion_model = "plumb_bob";
    calibration.distortion = numbers(root, "distortion_coefficients", 4, file);
    calibration.distortion.push_back(0.0);
  } else {
    throw common::InputError(file.string(), "/distortion_model",
                             "\"" + model + "\" is not equidistant or radial-tangential");
  }
  return camera;
}

// data.csv: "#timestamp [ns],filename" then one row per frame, each image in data/.
void readFrameList(EurocCamera& camera, const fs::path& folder) {
  const fs::path file = folder / "data.csv";
  std::ifstream in(file);
  if (!in) throw common::InputError(file.string(), "", "cannot be read");
  std::string line;
  int row = 0;
  while (std::getline(in, line)) {
    ++row;
    if (!line.empty() && line.back() == '\r') line.pop_back();
    if (line.empty() || line[0] == '#') continue;
    const std::size_t comma = line.find(',');
    const std::string where = "line " + std::to_string(row);
    EurocFrame frame;
    std::size_t used = 0;
    try {
      frame.stamp_ns = std::stoll(line.substr(0, comma), &used);
    } catch (const std::exception&) {
      used = std::string::npos;
    }
    if (comma == std::string::npos || used != comma || frame.stamp_ns < 0) {
      throw common::InputError(file.string(), where, "not \"<timestamp ns>,<file name>\"");
    }
    const std::string name = line.substr(comma + 1);
    if (name.empty() || name.find('/') != std::string::npos || name == "." || name == "..") {
      throw common::InputError(file.string(), where, "\"" + name + "\" is not a file name");
    }
    frame.path = (folder / "data" / name).string();
    if (!fs::is_regular_file(frame.path)) {
      throw common::InputError(file.string(), where, "its image " + frame.path + " is missing");
    }
    if (!camera.frames.empty() && frame.stamp_ns <= camera.frames.back().stamp_ns) {
      throw common::InputError(file.string(), where, "stamps do not increase");
    }
    camera.frames.push_back(frame);
  }
}

// The whole seconds the EuRoC stamps are ahead of the simulation's clock: mav0/imu0 holds the
// dataset's IMU samples (imu.csv) stamped as EuRoC stamps, so its first stamp less the dataset's
// first IMU time is the offset.
std::int64_t stampOffsetSeconds(const fs::path& mav0, double first_imu_t) {
  const fs::path file = mav0 / "imu0" / "data.csv";
  std::ifstream in(file);
  if (!in) {
    throw common::InputError(file.string(), "",
                             "cannot be read: it ties the cameras' stamps to the dataset's clock");
  }
  std::string line;
  int row = 0;
  while (std::getline(in, line)) {
    ++row;
    if (line.empty() || line[0] == '#') continue;
    std::int64_t ns = 0;
    try {
      ns = std::stoll(line.substr(0, line.find(',')));
    } catch (const std::exception&) {
      throw common::InputError(file.string(), "line " + std::to_string(row),
                               "does not start with a timestamp in nanoseconds");
    }
    const double offset = double(ns) * 1e-9 - first_imu_t;
    const std::int64_t whole = std::llround(offset);
    if (std::abs(offset - double(whole)) > 1e-3) {
      throw common::InputError(file.string(), "line " + std::to_string(row),
                               "its first stamp is not the dataset's first IMU time (" +
                                   std::to_string(first_imu_t) +
                                   " s) plus whole seconds: is mav0 from another run?");
    }
    return whole;
  }
  throw common::InputError(file.string(), "", "has no IMU sample");
}

}  // namespace

std::vector<EurocCamera> readEurocCameras(const std::string& dataset_dir, double first_imu_t) {
  const fs::path mav0 = fs::path(dataset_dir) / "mav0";
  if (!fs::is_directory(mav0)) return {};
  std::map<std::string, fs::path> folders;  // by name: the order is the same everywhere
  for (const fs::directory_entry& entry : fs::directory_iterator(mav0)) {
    const fs::path sensor = entry.path() / "sensor.yaml";
    if (!entry.is_directory() || !fs::is_regular_file(sensor)) continue;
    YAML::Node root;
    try {
      root = YAML::LoadFile(sensor.string());
    } catch (const YAML::Exception& e) {
      throw common::InputError(sensor.string(), "", std::string("not YAML: ") + e.what());
    }
    if (root["sensor_type"] && root["sensor_type"].as<std::string>("") == "camera") {
      folders[entry.path().filename().string()] = entry.path();
    }
  }
  std::vector<EurocCamera> cameras;
  for (const auto& [name, folder] : folders) {
    cameras.push_back(readSensorYaml(name, folder / "sensor.yaml"));
    readFrameList(cameras.back(), folder);
  }
  if (cameras.empty()) return cameras;
  if (std::all_of(cameras.begin(), cameras.end(), [](const EurocCamera& c) { return c.depth; })) {
    throw common::InputError(mav0.string(), "",
                             "has depth images but no camera they are registered to");
  }
  const std::int64_t offset_ns = stampOffsetSeconds(mav0, first_imu_t) * 1000000000LL;
  for (EurocCamera& camera : cameras) {
    for (EurocFrame& frame : camera.frames) frame.t = double(frame.stamp_ns - offset_ns) * 1e-9;
  }
  return cameras;
}

std::string readDepthPng(const std::string& path, int width, int height) {
  const std::unique_ptr<std::istream> in = openBinaryFile(path);
  std::string bytes((std::istreambuf_iterator<char>(*in)), std::istreambuf_iterator<char>());
  if (in->bad()) throw common::InputError(path, "", "cannot be read");
  // libpng's simplified reader, as for the colour frames: its header only (signature, IHDR);
  // a 16-bit grey file without transparency is its linear Y format.
  png_image image;
  std::memset(&image, 0, sizeof image);
  image.version = PNG_IMAGE_VERSION;
  if (!png_image_begin_read_from_memory(&image, bytes.data(), bytes.size())) {
    throw common::InputError(path, "", std::string("not a PNG image: ") + image.message);
  }
  const png_uint_32 format = image.format, image_width = image.width, image_height = image.height;
  png_image_free(&image);
  if (format != PNG_FORMAT_LINEAR_Y) {
    throw common::InputError(path, "", "not a 16-bit grey depth image");
  }
  requireFrameSize(path, long(image_width), long(image_height), width, height);
  return bytes;
}

}  // namespace isg::formats
