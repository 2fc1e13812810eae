#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "bim/camera_projection.hpp"
#include "bim/plan_parser.hpp"
#include "bim/scenario.hpp"

namespace isg::bim {
namespace {

// A scenario on D1's plan with `cameras` as given (JSON text).
Scenario parseWithCameras(const std::string& cameras) {
  const std::string text = R"({"format": "isg.scenario", "version": 1, "plan": "d1.json",
                                "cameras": )" +
                           cameras + "}";
  const nlohmann::json document = common::parseJsonText(text, "s.json");
  const common::JsonSource source{"s.json", nullptr};
  return parseScenario(common::JsonNode(document, "", source), [](const common::JsonNode&) {
    return LoadedPlan{loadPlan(std::string(ISG_SOURCE_DIR) + "/worlds/plans/d1.json", nullptr),
                      "d1.json"};
  });
}

// The pointer and reason of the error parsing `cameras` raises.
std::pair<std::string, std::string> errorOf(const std::string& cameras) {
  try {
    parseWithCameras(cameras);
  } catch (const common::InputError& e) {
    return {e.pointer(), e.reason()};
  }
  return {"", "accepted"};
}

TEST(CameraConfig, TheRealSenseD435HasItsDatasheetsImageAndDepth) {
  const Scenario s = parseWithCameras(R"([{"model": "realsense-d435"}])");
  ASSERT_EQ(s.cameras.size(), 1u);
  const CameraConfig& c = s.cameras[0];
  EXPECT_EQ(c.name, "cam0");
  EXPECT_EQ(c.model.intrinsics.width, 640);
  EXPECT_EQ(c.model.intrinsics.height, 480);
  // 69.4° across 16:9, cropped to 4:3: the 640 pixels span 2·atan(320 / f).
  const double f = c.model.intrinsics.fx;
  EXPECT_NEAR(f, 1920.0 / 2.0 / std::tan(34.5 * std::numbers::pi / 180.0) * 640.0 / 1440.0, 1e-9);
  EXPECT_NEAR(f, 620.8, 0.1);
  EXPECT_EQ(c.model.intrinsics.fy, f);
  EXPECT_DOUBLE_EQ(c.model.intrinsics.cx, 319.5);
  EXPECT_DOUBLE_EQ(c.model.rate_hz, 30.0);
  ASSERT_TRUE(c.model.depth.has_value());
  // Intel's error model at 2 m: 2² · 0.08 / (447 px · 0.05 m) = 14.3 mm, under the datasheet's
  // 2 % of the distance.
  EXPECT_NEAR(c.model.depth->sigma(2.0), 4.0 * 0.08 / (c.model.depth->focal_px * 0.05), 1e-12);
  EXPECT_NEAR(c.model.depth->sigma(2.0), 0.0143, 0.0002);
  EXPECT_LT(c.model.depth->sigma(2.0), 0.02 * 2.0);
  EXPECT_DOUBLE_EQ(c.model.depth->min_m, 0.28);
  EXPECT_DOUBLE_EQ(c.model.depth->max_m, 10.0);
}

TEST(CameraConfig, APinholeTakesItsImageRateAndMount) {
  const Scenario s = parseWithCameras(R"([
      {"model": "pinhole", "name": "front", "width": 320, "height": 200, "hfov_deg": 90,
       "rate_hz": 15, "mount": {"xyz": [0.3, 0, 0.2], "rpy": [-1.5707963, 0, -1.5707963]}},
      {"model": "pinhole", "mount": [0, 0, 1, 0, 0, 0]}])");
  ASSERT_EQ(s.cameras.size(), 2u);
  const PinholeIntrinsics& k = s.cameras[0].model.intrinsics;
  EXPECT_EQ(k.width, 320);
  EXPECT_EQ(k.height, 200);
  EXPECT_NEAR(k.fx, 160.0, 1e-9);  // 90° across 320 pixels
  EXPECT_DOUBLE_EQ(k.cx, 159.5);
  EXPECT_DOUBLE_EQ(k.cy, 99.5);
  EXPECT_DOUBLE_EQ(s.cameras[0].model.rate_hz, 15.0);
  EXPECT_EQ(s.cameras[0].name, "front");
  EXPECT_DOUBLE_EQ(s.cameras[0].mount[2], 0.2);
  EXPECT_DOUBLE_EQ(s.cameras[0].mount[3], -1.5707963);
  EXPECT_EQ(s.cameras[1].name, "cam1");  // named by its place in the list
  EXPECT_DOUBLE_EQ(s.cameras[1].mount[2], 1.0);
  EXPECT_FALSE(s.cameras[1].model.depth.has_value());
}

TEST(CameraConfig, BadCamerasAreRefusedNamingWhereAndWhy) {
  EXPECT_EQ(errorOf(R"([{"model": "kinect"}])"),
            std::make_pair(std::string("/cameras/0/model"),
                           std::string("unknown camera model \"kinect\" (known: \"pinhole\", "
                                       "\"realsense-d435\", \"insta360-one-rs\")")));
  EXPECT_EQ(errorOf(R"([{"model": "realsense-d435", "width": 1280}])"),
            std::make_pair(std::string("/cameras/0/width"),
                           std::string("only a \"pinhole\" camera takes its own width "
                                       "(\"realsense-d435\" has the sensor's)")));
  EXPECT_EQ(
      errorOf(R"([{"model": "pinhole"}, {"model": "pinhole", "name": "cam0"}])"),
      std::make_pair(std::string("/cameras/1"), std::string("camera name \"cam0\" is used twice")));
  EXPECT_EQ(errorOf(R"([{"model": "pinhole", "name": "../x"}])").first, "/cameras/0/name");
  EXPECT_EQ(errorOf(R"([{"model": "pinhole", "name": "depth0"}])"),
            std::make_pair(std::string("/cameras/0/name"),
                           std::string("camera name \"depth0\" is an EuRoC folder of its own")));
  EXPECT_EQ(errorOf(R"([{"model": "pinhole", "width": 4000}])").first, "/cameras/0/width");
  EXPECT_EQ(errorOf(R"([{"model": "pinhole", "width": 320.5}])"),
            std::make_pair(std::string("/cameras/0/width"),
                           std::string("expected a whole number of pixels")));
  EXPECT_EQ(errorOf(R"([{"model": "pinhole", "mount": {"xyz": [20, 0, 0], "rpy": [0, 0, 0]}}])"),
            std::make_pair(std::string("/cameras/0/mount"),
                           std::string("the camera must be mounted within 10 m of the robot's "
                                       "reference point")));
}

TEST(CameraConfig, The360RigBringsItsTwoLensesAndItsImu) {
  const Scenario s = parseWithCameras(R"([{"model": "pinhole"}, {"model": "insta360-one-rs"}])");
  ASSERT_EQ(s.cameras.size(), 3u);
  EXPECT_EQ(s.cameras[1].name, "cam1");  // numbered on from the cameras before it
  EXPECT_EQ(s.cameras[2].name, "cam2");
  const CameraConfig& front = s.cameras[1];
  EXPECT_EQ(front.rig, "insta360-one-rs");
  ASSERT_TRUE(front.model.fisheye.has_value());
  EXPECT_EQ(front.model.intrinsics.width, 1472);
  EXPECT_EQ(front.model.intrinsics.height, 1440);
  EXPECT_DOUBLE_EQ(front.model.intrinsics.fx, 461.6398879418857);
  EXPECT_DOUBLE_EQ(front.model.fisheye->k[0], 0.03442918444998219);
  EXPECT_DOUBLE_EQ(front.model.rate_hz, 30.0);
  // The calibration's T_cam_imu inverted: the front lens looks along the IMU's −y, the back one
  // along +y, 4 cm apart (the rig is about 4.6 cm thick).
  ASSERT_TRUE(front.I_T_C && s.cameras[2].I_T_C);
  EXPECT_NEAR(front.I_T_C->linear().col(2).y(), -1.0, 1e-3);
  EXPECT_NEAR(s.cameras[2].I_T_C->linear().col(2).y(), 1.0, 1e-3);
  EXPECT_NEAR((front.I_T_C->translation() - s.cameras[2].I_T_C->translation()).norm(), 0.040,
              0.002);
  EXPECT_TRUE((front.I_T_C->inverse() * *front.I_T_C).isApprox(Eigen::Isometry3d::Identity()));
  // Its IMU: 1000 Hz and the calibration's noise, unless the scenario's imu says otherwise.
  EXPECT_DOUBLE_EQ(s.imu.rate_hz, 1000.0);
  EXPECT_DOUBLE_EQ(s.imu.gyroscope_noise_density, 0.00047032046);
  EXPECT_DOUBLE_EQ(s.imu.accelerometer_random_walk, 0.00130039805);
  EXPECT_NEAR(s.imu.mount[4], std::numbers::pi / 2, 1e-12);
  const std::string text = R"({"format": "isg.scenario", "version": 1, "plan": "d1.json",
      "imu": {"rate_hz": 400}, "cameras": [{"model": "insta360-one-rs", "name": "fe"}]})";
  const nlohmann::json document = common::parseJsonText(text, "s.json");
  const common::JsonSource source{"s.json", nullptr};
  const Scenario own = parseScenario(common::JsonNode(document, "", source), [](auto&) {
    return LoadedPlan{loadPlan(std::string(ISG_SOURCE_DIR) + "/worlds/plans/d1.json", nullptr),
                      "d1.json"};
  });
  EXPECT_DOUBLE_EQ(own.imu.rate_hz, 400.0);
  EXPECT_DOUBLE_EQ(own.imu.gyroscope_noise_density, 0.00047032046);
  EXPECT_EQ(own.cameras[0].name, "fe0");
  EXPECT_EQ(own.cameras[1].name, "fe1");
}

TEST(CameraConfig, ARigIsPlacedByItsImuAndComesOnce) {
  EXPECT_EQ(errorOf(R"([{"model": "insta360-one-rs", "mount": [0, 0, 1, 0, 0, 0]}])").first,
            "/cameras/0/mount");
  EXPECT_EQ(errorOf(R"([{"model": "insta360-one-rs"}, {"model": "insta360-one-rs"}])"),
            std::make_pair(std::string("/cameras/1"),
                           std::string("a scenario carries one camera rig (its lenses are placed "
                                       "from the scenario's one IMU)")));
  EXPECT_EQ(errorOf(R"([{"model": "insta360-one-rs", "hfov_deg": 120}])").first,
            "/cameras/0/hfov_deg");
}

// The equidistant model by hand: a ray 60° off the axis lands at θd = θ(1 + k1θ² + … + k4θ⁸).
TEST(CameraProjection, TheFisheyeModelAgainstAHandCalculation) {
  const CameraModel lens = cameraRig("insta360-one-rs")->lenses[0].model;
  const double theta = std::numbers::pi / 3;
  const auto& k = lens.fisheye->k;
  const double theta_d = theta * (1 + k[0] * std::pow(theta, 2) + k[1] * std::pow(theta, 4) +
                                  k[2] * std::pow(theta, 6) + k[3] * std::pow(theta, 8));
  // A point 60° off the axis, straight to the right (+x).
  const auto uv = projectToPixel(lens, Eigen::Vector3d(std::sin(theta), 0.0, std::cos(theta)));
  ASSERT_TRUE(uv);
  EXPECT_NEAR(uv->x(), lens.intrinsics.cx + lens.intrinsics.fx * theta_d, 1e-9);
  EXPECT_NEAR(uv->y(), lens.intrinsics.cy, 1e-9);
  // 99° off the axis, behind the lens's plane, is still in its image; 101° is not.
  auto at = [&](double deg) {
    const double a = deg * std::numbers::pi / 180.0;
    return projectToPixel(lens, Eigen::Vector3d(0.0, std::sin(a), std::cos(a)));
  };
  EXPECT_TRUE(at(99.0).has_value());
  EXPECT_FALSE(at(101.0).has_value());
  // Every pixel's ray projects back onto the pixel.
  for (double u = 0; u < 1472; u += 97) {
    for (double v = 0; v < 1440; v += 89) {
      const auto ray = pixelRay(lens, Eigen::Vector2d(u, v));
      if (!ray) continue;
      const auto back = projectToPixel(lens, *ray);
      ASSERT_TRUE(back);
      EXPECT_NEAR((*back - Eigen::Vector2d(u, v)).norm(), 0.0, 1e-6) << u << ", " << v;
    }
  }
  // And a pinhole's.
  const CameraModel pinhole = *cameraModel("realsense-d435");
  const auto p = projectToPixel(pinhole, Eigen::Vector3d(0.5, -0.25, 2.0));
  EXPECT_NEAR(p->x(), 319.5 + pinhole.intrinsics.fx * 0.25, 1e-9);
  EXPECT_NEAR(p->y(), 239.5 - pinhole.intrinsics.fy * 0.125, 1e-9);
}

}  // namespace
}  // namespace isg::bim
