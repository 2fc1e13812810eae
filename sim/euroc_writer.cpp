#include "sim/euroc_writer.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <memory>
#include <span>
#include <sstream>
#include <stdexcept>

#include "common/input_error.hpp"
#include "common/tum.hpp"
#include "sensors/mount_transform.hpp"
#include "sim/fast_random.hpp"
#include "sim/fisheye_camera.hpp"
#include "sim/png_frames.hpp"
#include "sim/renderer.hpp"

namespace isg::sim {

namespace fs = std::filesystem;

namespace {

// The RGB images' noise: each channel of each pixel gets a Gaussian draw of this many grey
// levels (of 255), as a camera's read and shot noise at indoor light roughly are.
constexpr double kRgbNoiseLevels = 2.0;
// How far the depth buffer reaches for cameras without a depth model.
constexpr double kFarM = 100.0;

std::ofstream openText(const fs::path& path) {
  std::ofstream out(path);
  if (!out) throw common::InputError(path.string(), "", "cannot write");
  out << std::setprecision(17);
  return out;
}

// A 4 × 4 matrix as EuRoC's sensor.yaml writes it (row-major, one list).
std::string matrixData(const Eigen::Isometry3d& T) {
  std::ostringstream out;
  out << std::setprecision(12);
  for (int r = 0; r < 4; ++r) {
    for (int c = 0; c < 4; ++c) out << (r || c ? ", " : "") << T.matrix()(r, c);
  }
  return out.str();
}

// A 4 × 4 matrix as Kalibr's camchain.yaml writes it (a list of rows).
std::string matrixRows(const Eigen::Isometry3d& T, const char* indent) {
  std::ostringstream out;
  out << std::setprecision(12);
  for (int r = 0; r < 4; ++r) {
    out << indent << "- [";
    for (int c = 0; c < 4; ++c) out << (c ? ", " : "") << T.matrix()(r, c);
    out << "]\n";
  }
  return out.str();
}

struct CameraStream {
  const bim::CameraConfig* config = nullptr;
  Eigen::Isometry3d R_T_C;
  Eigen::Isometry3d I_T_C;   // the camera in EuRoC's body frame, the IMU's
  std::string depth_folder;  // "depth0", … or empty
  int frames = 0;
};

std::string intrinsicsList(const bim::PinholeIntrinsics& k) {
  std::ostringstream out;
  out << std::setprecision(12) << "[" << k.fx << ", " << k.fy << ", " << k.cx << ", " << k.cy
      << "]";
  return out.str();
}

// A pinhole renders no distortion; a fisheye lens has its four equidistant coefficients.
std::string distortionList(const bim::CameraModel& model) {
  if (!model.fisheye) return "[0.0, 0.0, 0.0, 0.0]";
  std::ostringstream out;
  out << std::setprecision(17) << "[" << model.fisheye->k[0] << ", " << model.fisheye->k[1] << ", "
      << model.fisheye->k[2] << ", " << model.fisheye->k[3] << "]";
  return out.str();
}

void writeCameraYaml(const fs::path& path, const CameraStream& camera, const std::string& comment,
                     bool depth) {
  const bim::PinholeIntrinsics& k = camera.config->model.intrinsics;
  std::ofstream out = openText(path);
  out << "# General sensor definitions.\n"
      << "sensor_type: camera\n"
      << "comment: " << comment << "\n"
      << "# Sensor extrinsics wrt. the body-frame (the IMU's).\n"
      << "T_BS:\n  cols: 4\n  rows: 4\n  data: [" << matrixData(camera.I_T_C) << "]\n"
      << "# Camera specific definitions.\n"
      << "rate_hz: " << camera.config->model.rate_hz << "\n"
      << "resolution: [" << k.width << ", " << k.height << "]\n"
      << "camera_model: pinhole\n"
      << "intrinsics: " << intrinsicsList(k) << " #fu, fv, cu, cv\n"
      << "distortion_model: "
      << (camera.config->model.fisheye ? "equidistant" : "radial-tangential") << "\n"
      << "distortion_coefficients: " << distortionList(camera.config->model) << "\n";
  if (depth) {
    const bim::DepthModel& d = *camera.config->model.depth;
    out << "# Depth: 16-bit, millimetres along the optical axis, 0 where not measured.\n"
        << "depth_scale_m: 0.001\n"
        << "depth_min_m: " << d.min_m << "\n"
        << "depth_max_m: " << d.max_m << "\n";
  }
}

void writeCamchain(const fs::path& path, const std::vector<CameraStream>& cameras) {
  std::ofstream out = openText(path);
  for (std::size_t i = 0; i < cameras.size(); ++i) {
    const CameraStream& c = cameras[i];
    const bim::PinholeIntrinsics& k = c.config->model.intrinsics;
    out << "cam" << i << ":\n"
        << "  T_cam_imu:\n"
        << matrixRows(c.I_T_C.inverse(), "  ");
    if (i > 0) {
      out << "  T_cn_cnm1:\n" << matrixRows(c.I_T_C.inverse() * cameras[i - 1].I_T_C, "  ");
    }
    out << "  camera_model: pinhole\n"
        << "  intrinsics: " << intrinsicsList(k) << "\n"
        << "  distortion_model: " << (c.config->model.fisheye ? "equidistant" : "radtan") << "\n"
        << "  distortion_coeffs: " << distortionList(c.config->model) << "\n"
        << "  resolution: [" << k.width << ", " << k.height << "]\n"
        << "  rostopic: /" << c.config->name << "/image_raw\n"
        << "  timeshift_cam_imu: 0.0\n";
  }
}

// Nanoseconds of the dataset clock at simulated time t.
std::int64_t stampNs(std::uint64_t offset_s, double t) {
  return std::int64_t(offset_s) * 1000000000LL + std::llround(t * 1e9);
}

// A TUM row of `pose` stamped `ns` nanoseconds, the seconds written exactly from the integer (a
// double would lose the nanoseconds of a stamp near 10⁹ s).
std::string tumRow(std::int64_t ns, const Eigen::Isometry3d& pose) {
  const common::StampedPose stamped{0.0, pose};
  const std::string row = common::toTumText(std::span<const common::StampedPose>(&stamped, 1));
  char seconds[40];
  std::snprintf(seconds, sizeof seconds, "%lld.%09lld", static_cast<long long>(ns / 1000000000),
                static_cast<long long>(ns % 1000000000));
  return seconds + row.substr(row.find(' '));
}

void writeImu(Simulation& simulation, const fs::path& root, double duration,
              const EurocOptions& options, EurocSummary& summary) {
  const bim::ImuConfig& imu = simulation.scenario().imu;
  fs::create_directories(root / "imu0");
  fs::create_directories(root / "state_groundtruth_estimate0");
  {
    std::ofstream yaml = openText(root / "imu0" / "sensor.yaml");
    yaml << "# General sensor definitions.\n"
         << "sensor_type: imu\n"
         << "comment: simulated IMU (isg simulate, docs/simulation.md)\n"
         << "# Sensor extrinsics wrt. the body-frame.\n"
         << "T_BS:\n  cols: 4\n  rows: 4\n  data: [" << matrixData(Eigen::Isometry3d::Identity())
         << "]\n"
         << "rate_hz: " << imu.rate_hz << "\n"
         << "# inertial sensor noise model parameters (static)\n"
         << "gyroscope_noise_density: " << imu.gyroscope_noise_density << "\n"
         << "gyroscope_random_walk: " << imu.gyroscope_random_walk << "\n"
         << "accelerometer_noise_density: " << imu.accelerometer_noise_density << "\n"
         << "accelerometer_random_walk: " << imu.accelerometer_random_walk << "\n";
  }
  std::ofstream data = openText(root / "imu0" / "data.csv");
  data << "#timestamp [ns],w_RS_S_x [rad s^-1],w_RS_S_y [rad s^-1],w_RS_S_z [rad s^-1],"
          "a_RS_S_x [m s^-2],a_RS_S_y [m s^-2],a_RS_S_z [m s^-2]\n";
  std::ofstream states = openText(root / "state_groundtruth_estimate0" / "data.csv");
  states << "#timestamp, p_RS_R_x [m], p_RS_R_y [m], p_RS_R_z [m], q_RS_w [], q_RS_x [], "
            "q_RS_y [], q_RS_z [], v_RS_R_x [m s^-1], v_RS_R_y [m s^-1], v_RS_R_z [m s^-1], "
            "b_w_RS_S_x [rad s^-1], b_w_RS_S_y [rad s^-1], b_w_RS_S_z [rad s^-1], b_a_RS_S_x [m "
            "s^-2], b_a_RS_S_y [m s^-2], b_a_RS_S_z [m s^-2]\n";
  const BaseMotion& motion = simulation.baseMotion();
  const Eigen::Isometry3d& R_T_I = simulation.R_T_I();
  ImuStream stream = simulation.imuStream(duration);
  constexpr double kVelocityStep = 1e-3;  // s, either side: the velocity by central difference
  for (;;) {
    std::vector<ImuStream::Bias> biases;
    const auto samples = stream.next(4096, &biases);
    if (samples.empty()) break;
    for (std::size_t i = 0; i < samples.size(); ++i) {
      const ImuSample& s = samples[i];
      const std::int64_t ns = stampNs(options.stamp_offset_s, s.t);
      data << ns << ',' << s.gyroscope.x() << ',' << s.gyroscope.y() << ',' << s.gyroscope.z()
           << ',' << s.accelerometer.x() << ',' << s.accelerometer.y() << ',' << s.accelerometer.z()
           << '\n';
      const Eigen::Isometry3d B_T_I = motion.pose(s.t) * R_T_I;
      const double t0 = std::max(0.0, s.t - kVelocityStep), t1 = s.t + kVelocityStep;
      const Eigen::Vector3d v =
          ((motion.pose(t1) * R_T_I).translation() - (motion.pose(t0) * R_T_I).translation()) /
          (t1 - t0);
      Eigen::Quaterniond q(B_T_I.linear());
      if (q.w() < 0) q.coeffs() *= -1.0;
      const Eigen::Vector3d p = B_T_I.translation();
      states << ns << ',' << p.x() << ',' << p.y() << ',' << p.z() << ',' << q.w() << ',' << q.x()
             << ',' << q.y() << ',' << q.z() << ',' << v.x() << ',' << v.y() << ',' << v.z() << ','
             << biases[i].gyroscope.x() << ',' << biases[i].gyroscope.y() << ','
             << biases[i].gyroscope.z() << ',' << biases[i].accelerometer.x() << ','
             << biases[i].accelerometer.y() << ',' << biases[i].accelerometer.z() << '\n';
      ++summary.imu_samples;
    }
  }
  if (!data || !states) throw common::InputError((root / "imu0").string(), "", "cannot write");
}

// A draw of unit variance about 0, near-Gaussian: the sum of the four 16-bit words of one 64-bit
// draw (Irwin–Hall with n = 4, its tails ending at ±3.46 σ), scaled. Image noise needs the
// shape and the spread, not the far tails, and a frame needs a million of them: one draw each
// instead of the polar method's two or more, which made the noise most of a frame's cost.
double nearNormal(Xoshiro256& rng) {
  const std::uint64_t bits = rng();
  const double sum = double(bits & 0xffffu) + double((bits >> 16) & 0xffffu) +
                     double((bits >> 32) & 0xffffu) + double(bits >> 48);
  constexpr double kMean = 2.0 * 65535.0;       // 4 × 65535 / 2
  constexpr double kSigma = 37837.22723720648;  // √(4 × (65536² − 1) / 12)
  return (sum - kMean) / kSigma;
}

// The RGB image with its noise, and the depth image in millimetres: the rendered depth with the
// model's error drawn per pixel, 0 outside its range.
void addNoise(std::vector<unsigned char>& rgb, const std::vector<float>& depth,
              const std::optional<bim::DepthModel>& model, Xoshiro256& rng,
              std::vector<std::uint16_t>* depth_mm) {
  for (unsigned char& c : rgb) {
    const double value = c + kRgbNoiseLevels * nearNormal(rng);
    c = static_cast<unsigned char>(std::clamp(std::lround(value), 0L, 255L));
  }
  if (!model || depth_mm == nullptr) return;
  depth_mm->resize(depth.size());
  for (std::size_t i = 0; i < depth.size(); ++i) {
    const double z = depth[i];
    if (z < model->min_m || z > model->max_m) {
      (*depth_mm)[i] = 0;
      continue;
    }
    const double measured = z + model->sigma(z) * nearNormal(rng);
    (*depth_mm)[i] =
        static_cast<std::uint16_t>(std::clamp(std::lround(measured * 1000.0), 1L, 65535L));
  }
}

// A camera's images: a pinhole's straight from the renderer, a fisheye's through its cube map.
class CameraImages {
 public:
  CameraImages(const mjModel& world, const bim::CameraModel& model, std::uint64_t seed)
      : model_(model) {
    if (model.fisheye) {
      fisheye_ = std::make_unique<FisheyeCamera>(world, model, seed);
    } else {
      pinhole_ = std::make_unique<Renderer>(world, model.intrinsics.width, model.intrinsics.height,
                                            Renderer::Sampling::kPixelCentres);
      pinhole_->enableSurfaceTextures(seed);
    }
  }
  Image render(mjData& data, const Eigen::Isometry3d& B_T_C, double far,
               std::vector<float>* depth) const {
    if (fisheye_) return fisheye_->render(data, B_T_C, far, nullptr);
    return pinhole_->camera(data, B_T_C, model_.intrinsics, far, depth);
  }

 private:
  const bim::CameraModel& model_;
  std::unique_ptr<Renderer> pinhole_;
  std::unique_ptr<FisheyeCamera> fisheye_;
};

// Everything writeEuroc writes, into `root`.
EurocSummary writeMav0(Simulation& simulation, const fs::path& root, double duration,
                       const EurocOptions& options, const FrameProgress& progress) {
  const bim::Scenario& scenario = simulation.scenario();
  EurocSummary summary;

  std::vector<CameraStream> cameras;
  int depth_count = 0, total = 0;
  for (const bim::CameraConfig& config : scenario.cameras) {
    CameraStream c;
    c.config = &config;
    c.R_T_C =
        config.I_T_C ? simulation.R_T_I() * *config.I_T_C : sensors::mountTransform(config.mount);
    c.I_T_C = simulation.R_T_I().inverse() * c.R_T_C;
    if (config.model.depth) c.depth_folder = "depth" + std::to_string(depth_count++);
    c.frames = int(std::floor(duration * config.model.rate_hz + 1e-9)) + 1;
    total += c.frames;
    cameras.push_back(c);
  }
  writeImu(simulation, root, duration, options, summary);

  mjData& data = simulation.world().data();
  const BaseMotion& motion = simulation.baseMotion();
  for (std::size_t ci = 0; ci < cameras.size(); ++ci) {
    const CameraStream& camera = cameras[ci];
    const bim::CameraConfig& config = *camera.config;
    const bim::PinholeIntrinsics& k = config.model.intrinsics;
    const fs::path folder = root / config.name;
    fs::create_directories(folder / "data");
    writeCameraYaml(folder / "sensor.yaml", camera,
                    config.model.name + " (isg simulate, docs/sensors.md)", false);
    std::ofstream csv = openText(folder / "data.csv");
    csv << "#timestamp [ns],filename\n";
    std::ofstream depth_csv;
    if (!camera.depth_folder.empty()) {
      fs::create_directories(root / camera.depth_folder / "data");
      writeCameraYaml(root / camera.depth_folder / "sensor.yaml", camera,
                      config.model.name + " depth, registered to " + config.name, true);
      depth_csv = openText(root / camera.depth_folder / "data.csv");
      depth_csv << "#timestamp [ns],filename\n";
    }
    std::ofstream tum = openText(root / (config.name + ".tum"));
    tum << "# B_T_C of " << config.name << " (optical frame: z forward, x right, y down) at each "
        << "frame, stamped as its image (seconds)\n";
    const CameraImages images(simulation.world().model(), config.model, scenario.seed);
    const double far = config.model.depth ? config.model.depth->max_m * 1.5 : kFarM;
    std::vector<float> depth;
    std::vector<std::uint16_t> depth_mm;
    for (int f = 0; f < camera.frames; ++f) {
      const double t = f / config.model.rate_hz;
      const Eigen::Isometry3d B_T_C = motion.pose(t) * camera.R_T_C;
      tum << tumRow(stampNs(options.stamp_offset_s, t), B_T_C);
      Image image = images.render(data, B_T_C, far, config.model.depth ? &depth : nullptr);
      Xoshiro256 rng(deriveSeed(scenario.seed, kCameraNoiseStream, (std::uint64_t(ci) << 32) | f));
      addNoise(image.rgb, depth, config.model.depth, rng,
               camera.depth_folder.empty() ? nullptr : &depth_mm);
      const std::string name = std::to_string(stampNs(options.stamp_offset_s, t)) + ".png";
      writeRgbFrame(folder / "data" / name, k.width, k.height, image.rgb);
      csv << stampNs(options.stamp_offset_s, t) << ',' << name << '\n';
      if (!camera.depth_folder.empty()) {
        writeGray16Frame(root / camera.depth_folder / "data" / name, k.width, k.height, depth_mm);
        depth_csv << stampNs(options.stamp_offset_s, t) << ',' << name << '\n';
        ++summary.depth_frames;
      }
      ++summary.frames;
      if (progress) progress(summary.frames, total);
    }
    if (!csv || !tum || (depth_csv.is_open() && !depth_csv)) {
      throw common::InputError(folder.string(), "", "cannot write");
    }
  }
  writeCamchain(root / "camchain.yaml", cameras);
  return summary;
}

}  // namespace

EurocSummary writeEuroc(Simulation& simulation, const std::string& dataset_dir,
                        const EurocOptions& options, const FrameProgress& progress) {
  if (simulation.scenario().cameras.empty()) {
    throw std::invalid_argument("the scenario has no camera (\"cameras\", docs/formats.md)");
  }
  const auto started = std::chrono::steady_clock::now();
  const double duration = options.duration < 0.0
                              ? simulation.duration()
                              : std::min(options.duration, simulation.duration());
  const fs::path root = fs::path(dataset_dir) / "mav0";
  fs::remove_all(root);
  fs::create_directories(root);
  try {
    EurocSummary summary = writeMav0(simulation, root, duration, options, progress);
    summary.wall_seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
    return summary;
  } catch (...) {
    std::error_code ignored;
    fs::remove_all(root, ignored);
    throw;
  }
}

}  // namespace isg::sim
