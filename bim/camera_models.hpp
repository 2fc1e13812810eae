#pragma once

#include <Eigen/Geometry>
#include <array>
#include <optional>
#include <string>
#include <vector>

namespace isg::bim {

// A pinhole camera's intrinsics in OpenCV's convention: pixel (u, v) with u to the right, v down,
// the centre of the top-left pixel at (0, 0); a point (x, y, z) of the optical frame (z forward,
// x right, y down) projects to u = fx·x/z + cx, v = fy·y/z + cy. Pixels are square (fx = fy):
// what MuJoCo's renderer draws, and what the models below have.
struct PinholeIntrinsics {
  int width = 0;
  int height = 0;
  double fx = 0.0, fy = 0.0, cx = 0.0, cy = 0.0;
};

// How a depth image's values err, as a stereo camera's do: the depth z is found from a disparity
// matched to within `subpixel` pixels between imagers `baseline_m` apart, so its standard
// deviation grows with the square of the distance, σ(z) = z² · subpixel / (focal_px · baseline).
// Depths outside [min_m, max_m] are not measured (0 in the image, as the sensor reports them).
struct DepthModel {
  double min_m = 0.0;
  double max_m = 0.0;
  double subpixel = 0.0;
  double baseline_m = 0.0;
  double focal_px = 0.0;  // the depth imagers' focal length, in pixels of the depth image

  double sigma(double z) const {
    return baseline_m > 0.0 && focal_px > 0.0 ? z * z * subpixel / (focal_px * baseline_m) : 0.0;
  }
};

// A fisheye lens in Kannala and Brandt's equidistant model (Kalibr's "pinhole" camera with
// "equidistant" distortion, OpenCV's fisheye model): a ray θ from the optical axis lands at
// θd = θ (1 + k1 θ² + k2 θ⁴ + k3 θ⁶ + k4 θ⁸) from the principal point, in units of the focal
// lengths of the camera's intrinsics. Rays beyond `max_angle_rad` fall outside its image circle.
struct FisheyeLens {
  std::array<double, 4> k{};
  double max_angle_rad = 0.0;
};

// A camera model the scenario names ("cameras": [{"model": …}]): its image, its rate, and the
// depth image registered to it when it has one. docs/sensors.md ("Cameras") gives every number's
// source.
struct CameraModel {
  std::string name;
  PinholeIntrinsics intrinsics;
  double rate_hz = 30.0;
  std::optional<DepthModel> depth;
  std::optional<FisheyeLens> fisheye;  // a pinhole when absent
};

// One camera of a rig (several lenses calibrated together with the rig's IMU): its model and
// where it sits in the IMU's frame (the inverse of Kalibr's T_cam_imu).
struct RigLens {
  CameraModel model;
  Eigen::Isometry3d I_T_C = Eigen::Isometry3d::Identity();
};

// The IMU a rig was calibrated with: its rate and Kalibr's four noise parameters, and where it
// sits on the carrier by default ([x, y, z, roll, pitch, yaw], as the scenario's imu.mount):
// turned so that the rig stands upright, its first lens looking ahead.
struct RigImu {
  double rate_hz = 0.0;
  double gyroscope_noise_density = 0.0, gyroscope_random_walk = 0.0;
  double accelerometer_noise_density = 0.0, accelerometer_random_walk = 0.0;
  std::array<double, 6> mount{};
};

// A rig the scenario names: its lenses in order (cam0, cam1, …) and its IMU.
struct CameraRig {
  std::vector<RigLens> lenses;
  RigImu imu;
};
// The rig named `name` ("insta360-one-rs"); nullopt when there is none.
std::optional<CameraRig> cameraRig(const std::string& name);

// The names `cameraModel` and `cameraRig` know, in the order --help lists them.
const std::vector<std::string>& cameraModelNames();
// The model named `name`; nullopt when there is none.
std::optional<CameraModel> cameraModel(const std::string& name);

// A pinhole camera `width` × `height` whose horizontal field of view is `horizontal_fov_deg`,
// its principal point at the image's centre.
PinholeIntrinsics pinholeFromFov(int width, int height, double horizontal_fov_deg);

}  // namespace isg::bim
