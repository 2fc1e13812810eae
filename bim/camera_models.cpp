#include "bim/camera_models.hpp"

#include <cmath>
#include <numbers>

namespace isg::bim {

namespace {

// Intel RealSense D435 (Intel's D400-series datasheet; Intel's depth-quality white paper for the
// error model). The RGB imager at 640 × 480: 69° × 42° at 16:9 is cropped to 4:3, which keeps a
// horizontal field of 4:3/16:9 of its width: the focal length of the full 1920-pixel frame,
// 1920 / 2 / tan(34.5°) = 1398 px, scaled to 640 of those 1920 pixels' 1440-wide 4:3 crop.
// The depth imagers: 50 mm apart, 87° across 848 pixels (focal 447 px), matched to 0.08 pixel
// (the white paper's typical sub-pixel figure), measuring from 0.28 m (the minimum distance at
// full resolution) to 10 m (the datasheet's range). Registered to the RGB image, as the camera's
// aligned depth stream is: same pixels, same intrinsics.
CameraModel realsenseD435() {
  CameraModel model;
  model.name = "realsense-d435";
  const double full_focal = 1920.0 / 2.0 / std::tan(34.5 * std::numbers::pi / 180.0);
  const double focal = full_focal * 640.0 / 1440.0;
  model.intrinsics = {640, 480, focal, focal, 319.5, 239.5};
  model.rate_hz = 30.0;
  DepthModel depth;
  depth.min_m = 0.28;
  depth.max_m = 10.0;
  depth.subpixel = 0.08;
  depth.baseline_m = 0.050;
  depth.focal_px = 848.0 / 2.0 / std::tan(43.5 * std::numbers::pi / 180.0);
  model.depth = depth;
  return model;
}

// A generic pinhole: 640 × 480, 90° across, 30 Hz, no depth. The scenario may give its own
// resolution, field of view and rate.
CameraModel genericPinhole() {
  CameraModel model;
  model.name = "pinhole";
  model.intrinsics = pinholeFromFov(640, 480, 90.0);
  model.rate_hz = 30.0;
  return model;
}

// A lens of the Insta360 One RS 1-inch 360 Edition as the Hilti × Trimble floor-plan challenge
// of 2026 calibrated it (its repository's config/hilti_openvins/kalibr_imucam_chain.yaml, the
// "pinhole equidistant" calibration): 1472 × 1440 at 30 Hz, intrinsics, the four equidistant
// coefficients, and T_cam_imu (the IMU in the camera's frame) row by row.
RigLens insta360Lens(const std::string& name, const std::array<double, 4>& intrinsics,
                     const std::array<double, 4>& k, const std::array<double, 16>& T_cam_imu) {
  RigLens lens;
  lens.model.name = name;
  lens.model.intrinsics = {1472, 1440, intrinsics[0], intrinsics[1], intrinsics[2], intrinsics[3]};
  lens.model.rate_hz = 30.0;
  // About 200° across, as the lens is sold: 100° from the axis (θd there is 1.65, 760 px from
  // the centre, the image's corner lies at 1030 px).
  lens.model.fisheye = FisheyeLens{k, 100.0 * 3.14159265358979323846 / 180.0};
  Eigen::Matrix4d C_T_I;
  for (int i = 0; i < 16; ++i) C_T_I(i / 4, i % 4) = T_cam_imu[std::size_t(i)];
  Eigen::Isometry3d C_T_I_iso;
  C_T_I_iso.matrix() = C_T_I;
  // The calibration's rotation is orthonormal to 1e-9 or so; made exactly so.
  const Eigen::Quaterniond q(C_T_I.topLeftCorner<3, 3>());
  C_T_I_iso.linear() = q.normalized().toRotationMatrix();
  lens.I_T_C = C_T_I_iso.inverse();
  return lens;
}

CameraRig insta360OneRs() {
  CameraRig rig;
  rig.lenses.push_back(insta360Lens(
      "insta360-one-rs front",
      {461.6398879418857, 459.7153043295965, 732.9460954720965, 720.5410566713475},
      {0.03442918444998219, -0.02155491263917851, 0.0031292637056308044, -0.0005356957576266091},
      {0.017538565106728715, 0.00028626904326750635, -0.999846146556576, 0.02052394245821649,
       0.9998137173927399, -0.008064129276510124, 0.017535687392408406, 0.01409788177972009,
       -0.008057868657999734, -0.9999674434045585, -0.00042764897266889257, -0.011814695170156918,
       0.0, 0.0, 0.0, 1.0}));
  rig.lenses.push_back(insta360Lens(
      "insta360-one-rs back",
      {481.0462499931464, 478.0014012062969, 735.0624904634898, 720.0949685881241},
      {0.04694156447186486, -0.04598888193097635, 0.01197602371534633, -0.0015766998867207587},
      {0.000745820203676667, -0.00584785929408338, 0.9999826229959694, -0.019983320822875215,
       0.99995016919628, -0.009950514081923684, -0.000803986215983099, 0.01461591419235818,
       0.009955042770065814, 0.9999333926873234, 0.005840146596115453, -0.028381061462177323, 0.0,
       0.0, 0.0, 1.0}));
  // The same repository's config/hilti_openvins/kalibr_imu_chain.yaml.
  rig.imu = {1000.0, 0.00047032046, 0.00036433633, 0.00285891188, 0.00130039805, {}};
  // The front lens looks along the IMU's −y with its image's down along the IMU's +x (T_cam_imu
  // above): the IMU's x points down, its y back and its z left, Rz(90°)·Ry(90°), 25 cm up as the
  // LiDAR's default mount.
  rig.imu.mount = {0.0, 0.0, 0.25, 0.0, 0.5 * 3.14159265358979323846, 0.5 * 3.14159265358979323846};
  return rig;
}

}  // namespace

const std::vector<std::string>& cameraModelNames() {
  static const std::vector<std::string> names = {"pinhole", "realsense-d435", "insta360-one-rs"};
  return names;
}

std::optional<CameraRig> cameraRig(const std::string& name) {
  if (name == "insta360-one-rs") return insta360OneRs();
  return std::nullopt;
}

std::optional<CameraModel> cameraModel(const std::string& name) {
  if (name == "pinhole") return genericPinhole();
  if (name == "realsense-d435") return realsenseD435();
  return std::nullopt;
}

PinholeIntrinsics pinholeFromFov(int width, int height, double horizontal_fov_deg) {
  const double focal = 0.5 * width / std::tan(0.5 * horizontal_fov_deg * std::numbers::pi / 180.0);
  return {width, height, focal, focal, 0.5 * (width - 1), 0.5 * (height - 1)};
}

}  // namespace isg::bim
