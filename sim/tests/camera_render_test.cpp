#include <gtest/gtest.h>
#include <png.h>
#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <optional>
#include <sstream>

#include "bim/camera_projection.hpp"
#include "common/tum.hpp"
#include "sensors/mount_transform.hpp"
#include "sim/euroc_writer.hpp"
#include "sim/fisheye_camera.hpp"
#include "sim/mujoco_world.hpp"
#include "sim/renderer.hpp"
#include "sim/simulation.hpp"
#include "worlds/mjcf_generator.hpp"
#include "worlds/reference_plans.hpp"

namespace isg::sim {
namespace {

namespace fs = std::filesystem;

// D1 with one camera of `model` (the scenario's JSON for the camera's other fields in `extra`).
bim::Scenario d1WithCamera(const std::string& model, const std::string& extra = "") {
  bim::Scenario scenario = worlds::loadScenarioOrBuiltin("builtin:d1", nullptr);
  const std::string text = R"([{"model": ")" + model + "\"" + extra + "}]";
  const nlohmann::json document = common::parseJsonText(text, "cameras.json");
  const common::JsonSource source{"cameras.json", nullptr};
  scenario.cameras = bim::parseCameras(common::JsonNode(document, "", source));
  return scenario;
}

// The distance along the optical axis to what pixel (u, v) looks at, by mj_ray through the
// building and its ceilings (what the camera draws); 0 when the ray meets nothing.
double rayDepth(MujocoWorld& world, const Eigen::Isometry3d& B_T_C, const bim::PinholeIntrinsics& k,
                double u, double v) {
  const Eigen::Vector3d in_camera((u - k.cx) / k.fx, (v - k.cy) / k.fy, 1.0);
  const Eigen::Vector3d direction = (B_T_C.linear() * in_camera).normalized();
  const Eigen::Vector3d from = B_T_C.translation();
  const auto mask = groupArray((1u << worlds::kBuildingGroup) | (1u << worlds::kCeilingGroup));
  int geom = -1;
  const double range = mj_ray(&world.model(), &world.data(), from.data(), direction.data(),
                              mask.data(), 1, -1, &geom);
  return range < 0 ? 0.0 : range / in_camera.norm();
}

// Depth differs from its neighbours by less than 2 cm: not an edge, where a pixel's centre and
// its rendered fragment may lie on different surfaces.
bool smooth(const std::vector<float>& depth, int width, int height, int u, int v) {
  const float d = depth[std::size_t(v) * width + u];
  for (int dv = -1; dv <= 1; ++dv) {
    for (int du = -1; du <= 1; ++du) {
      const int uu = std::clamp(u + du, 0, width - 1), vv = std::clamp(v + dv, 0, height - 1);
      if (std::abs(depth[std::size_t(vv) * width + uu] - d) > 0.02f) return false;
    }
  }
  return true;
}

TEST(CameraRender, DepthPixelsLieWhereMjRayMeetsTheSamePixelRays) {
  Simulation sim(d1WithCamera("realsense-d435"));
  const bim::CameraConfig& camera = sim.scenario().cameras[0];
  const bim::PinholeIntrinsics& k = camera.model.intrinsics;
  Renderer renderer(sim.world().model(), k.width, k.height, Renderer::Sampling::kPixelCentres);
  int compared = 0, edges = 0;
  double worst = 0.0;
  for (double t : {2.0, 15.0, 40.0}) {
    const Eigen::Isometry3d B_T_C =
        sim.baseMotion().pose(t) * sensors::mountTransform(camera.mount);
    std::vector<float> depth;
    const Image image = renderer.camera(sim.world().data(), B_T_C, k, 30.0, &depth);
    ASSERT_EQ(image.rgb.size(), std::size_t(3) * k.width * k.height);
    ASSERT_EQ(depth.size(), std::size_t(k.width) * k.height);
    for (int v = 3; v < k.height; v += 12) {
      for (int u = 5; u < k.width; u += 12) {
        if (!smooth(depth, k.width, k.height, u, v)) {
          ++edges;
          continue;
        }
        const double expected = rayDepth(sim.world(), B_T_C, k, u, v);
        ASSERT_GT(expected, 0.0) << "a closed building: every ray meets something";
        const double rendered = depth[std::size_t(v) * k.width + u];
        worst = std::max(worst, std::abs(rendered - expected));
        ASSERT_NEAR(rendered, expected, 1e-3) << "t " << t << " pixel " << u << ", " << v;
        ++compared;
      }
    }
  }
  // Most of the sampled pixels lie on a surface, not on its edge.
  EXPECT_GT(compared, 5 * edges);
  EXPECT_GT(compared, 3000);
  RecordProperty("worst_depth_error_m", std::to_string(worst));
}

// A pinhole whose principal point is off the image's centre draws the world shifted by as much:
// the frustum follows cx, cy.
TEST(CameraRender, AnOffCentrePrincipalPointShiftsTheImage) {
  Simulation sim(d1WithCamera("pinhole", R"(, "width": 160, "height": 120)"));
  bim::PinholeIntrinsics k = sim.scenario().cameras[0].model.intrinsics;
  k.cx += 10.0;
  k.cy -= 6.0;
  Renderer renderer(sim.world().model(), k.width, k.height, Renderer::Sampling::kPixelCentres);
  const Eigen::Isometry3d B_T_C =
      sim.baseMotion().pose(15.0) * sensors::mountTransform(sim.scenario().cameras[0].mount);
  std::vector<float> depth;
  renderer.camera(sim.world().data(), B_T_C, k, 30.0, &depth);
  int compared = 0;
  for (int v = 2; v < k.height - 2; v += 4) {
    for (int u = 2; u < k.width - 2; u += 4) {
      if (!smooth(depth, k.width, k.height, u, v)) continue;
      EXPECT_NEAR(depth[std::size_t(v) * k.width + u], rayDepth(sim.world(), B_T_C, k, u, v), 1e-3);
      ++compared;
    }
  }
  EXPECT_GT(compared, 300);
}

// The 360° rig's front lens through its cube map: each pixel's range against mj_ray along the
// ray the lens model gives that pixel (bim::pixelRay), so the remap follows the lens model.
TEST(CameraRender, AFisheyePixelSeesAlongItsLensModelsRay) {
  Simulation sim(d1WithCamera("insta360-one-rs"));
  const bim::CameraModel& lens = sim.scenario().cameras[0].model;
  FisheyeCamera camera(sim.world().model(), lens, 1);
  EXPECT_EQ(camera.faceSize(), 924);  // twice the focal length, 461.6 px
  // Upright, 1.2 m above the floor, looking along x.
  Eigen::Isometry3d B_T_C = Eigen::Isometry3d::Identity();
  B_T_C.translation() = sim.baseMotion().pose(10.0).translation() + Eigen::Vector3d(0, 0, 0.8);
  B_T_C.linear() << 0, 0, 1, -1, 0, 0, 0, -1, 0;
  std::vector<float> range;
  const Image image = camera.render(sim.world().data(), B_T_C, 50.0, &range);
  ASSERT_EQ(image.width, 1472);
  const auto mask = groupArray((1u << worlds::kBuildingGroup) | (1u << worlds::kCeilingGroup));
  int compared = 0, outside = 0;
  for (int v = 4; v < 1440; v += 23) {
    for (int u = 4; u < 1472; u += 23) {
      const auto ray = bim::pixelRay(lens, Eigen::Vector2d(u, v));
      const float r = range[std::size_t(v) * 1472 + u];
      if (!ray) {
        EXPECT_EQ(r, 0.0f);
        EXPECT_EQ(image.rgb[3 * (std::size_t(v) * 1472 + u)], 0);  // black outside the circle
        ++outside;
        continue;
      }
      // Away from edges: the neighbours' ranges within 2 cm.
      bool smooth = true;
      for (int d : {-2, 2}) {
        smooth &= std::abs(range[std::size_t(v) * 1472 + u + d] - r) < 0.02f;
        smooth &= std::abs(range[std::size_t(v + d) * 1472 + u] - r) < 0.02f;
      }
      if (!smooth) continue;
      const Eigen::Vector3d direction = B_T_C.linear() * *ray;
      const Eigen::Vector3d from = B_T_C.translation();
      int geom = -1;
      const double expected = mj_ray(&sim.world().model(), &sim.world().data(), from.data(),
                                     direction.data(), mask.data(), 1, -1, &geom);
      ASSERT_NEAR(r, expected, 2e-3) << u << ", " << v;
      ++compared;
    }
  }
  EXPECT_GT(compared, 2000);
  EXPECT_GT(outside, 100);  // the corners of the image
}

// Where the rendered range image jumps along row `v` near column `u`: the sub-pixel column at
// which the range crosses halfway between the plateaus 6 px to either side; nullopt when they
// differ by less than 0.5 m (no edge there).
std::optional<double> rangeEdgeInRow(const std::vector<float>& range, int width, int v, double u) {
  const int u0 = int(std::lround(u));
  const auto at = [&](int c) { return double(range[std::size_t(v) * width + c]); };
  const double left = at(u0 - 6), right = at(u0 + 6);
  if (std::abs(left - right) < 0.5) return std::nullopt;
  const double mid = 0.5 * (left + right);
  for (int c = u0 - 6; c < u0 + 6; ++c) {
    if ((at(c) - mid) * (at(c + 1) - mid) <= 0.0 && at(c) != at(c + 1)) {
      return c + (mid - at(c)) / (at(c + 1) - at(c));
    }
  }
  return std::nullopt;
}

// A plan corner through the fisheye model against the rendered edge: D1's door D1 (in wall W5
// at y = 2.2 m, 0.15 m thick; its opening x = 1.55 … 2.45 m, 2.1 m high) seen from the corridor
// by the rig's front lens looking along the corridor (+x), the jambs 35° and 50° off its axis.
// From x = 0.55 m the silhouettes are the left jamb's corridor-side corner (1.55, 2.125) and the
// right jamb's office-side corner (2.45, 2.275), each a vertical line of the plan. Row by row,
// the line's projection (bim::projectToPixel) and the column where the rendered range jumps
// (the office behind the doorway) agree within 1 px.
TEST(CameraRender, APlanCornerThroughTheFisheyeModelLiesOnTheRenderedEdge) {
  Simulation sim(d1WithCamera("insta360-one-rs"));
  const bim::CameraModel& lens = sim.scenario().cameras[0].model;
  FisheyeCamera camera(sim.world().model(), lens, 1);
  Eigen::Isometry3d B_T_C = Eigen::Isometry3d::Identity();
  B_T_C.translation() = Eigen::Vector3d(0.55, 1.0, 1.2);
  B_T_C.linear() << 0, 0, 1, -1, 0, 0, 0, -1, 0;  // z along +x, x along −y, y down
  std::vector<float> range;
  camera.render(sim.world().data(), B_T_C, 50.0, &range);
  const int width = lens.intrinsics.width;
  const auto pixelOf = [&](const Eigen::Vector2d& xy, double z) {
    return *bim::projectToPixel(lens, B_T_C.inverse() * Eigen::Vector3d(xy.x(), xy.y(), z));
  };
  double worst = 0.0;
  int rows = 0;
  for (const Eigen::Vector2d corner :
       {Eigen::Vector2d(1.55, 2.125), Eigen::Vector2d(2.45, 2.275)}) {
    // Image rows the edge crosses between 0.3 m and 1.9 m above the floor (below the lintel).
    const int v_top = int(std::ceil(pixelOf(corner, 1.9).y()));
    const int v_bottom = int(std::floor(pixelOf(corner, 0.3).y()));
    ASSERT_GT(v_bottom - v_top, 100);
    for (int v = v_top; v <= v_bottom; v += 7) {
      // The height at which the corner's line meets row v exactly (v falls as z rises).
      double lo = 0.3, hi = 1.9;
      for (int i = 0; i < 60; ++i) {
        const double z = 0.5 * (lo + hi);
        (pixelOf(corner, z).y() > v ? lo : hi) = z;
      }
      const double u = pixelOf(corner, 0.5 * (lo + hi)).x();
      const auto edge = rangeEdgeInRow(range, width, v, u);
      ASSERT_TRUE(edge.has_value()) << "no edge near u = " << u << " in row " << v;
      EXPECT_NEAR(*edge, u, 1.0) << "row " << v << " of the corner at " << corner.transpose();
      worst = std::max(worst, std::abs(*edge - u));
      ++rows;
    }
  }
  EXPECT_GT(rows, 30);
  std::printf("a plan corner against the rendered edge: %d rows, worst %.2f px\n", rows, worst);
}

// Reads a PNG with libpng's decoder: its size, bit depth and colour type, and its samples.
struct DecodedPng {
  int width = 0, height = 0, bit_depth = 0, colour_type = 0;
  std::vector<unsigned> samples;
};
// Decodes the PNG `file` with libpng's reader; an empty result when it cannot.
DecodedPng decodePng(FILE* file) {
  DecodedPng out;
  png_structp png = png_create_read_struct(PNG_LIBPNG_VER_STRING, nullptr, nullptr, nullptr);
  png_infop info = png_create_info_struct(png);
  if (setjmp(png_jmpbuf(png))) {
    png_destroy_read_struct(&png, &info, nullptr);
    return DecodedPng{};
  }
  png_init_io(png, file);
  png_read_png(png, info, PNG_TRANSFORM_IDENTITY, nullptr);
  out.width = int(png_get_image_width(png, info));
  out.height = int(png_get_image_height(png, info));
  out.bit_depth = png_get_bit_depth(png, info);
  out.colour_type = png_get_color_type(png, info);
  const png_bytepp rows = png_get_rows(png, info);
  const int channels = png_get_channels(png, info);
  for (int y = 0; y < out.height; ++y) {
    for (int x = 0; x < out.width * channels; ++x) {
      out.samples.push_back(
          out.bit_depth == 16 ? (unsigned(rows[y][2 * x]) << 8) | rows[y][2 * x + 1] : rows[y][x]);
    }
  }
  png_destroy_read_struct(&png, &info, nullptr);
  return out;
}

DecodedPng readPng(const fs::path& path) {
  FILE* file = std::fopen(path.c_str(), "rb");
  if (file == nullptr) return DecodedPng{};
  DecodedPng out = decodePng(file);
  std::fclose(file);
  return out;
}

std::vector<std::vector<std::string>> readCsv(const fs::path& path) {
  std::vector<std::vector<std::string>> rows;
  std::ifstream in(path);
  std::string line;
  while (std::getline(in, line)) {
    if (line.empty() || line[0] == '#') continue;
    std::vector<std::string> cells;
    std::stringstream cells_in(line);
    std::string cell;
    while (std::getline(cells_in, cell, ',')) cells.push_back(cell);
    rows.push_back(cells);
  }
  return rows;
}

// How long the EuRoC test's walk is: 2 s at 10 frames/s, or with ISG_EUROC_TEST_SECONDS=N
// (N ≥ 2) N seconds at the D435's own 30 frames/s, as the notes measure the 20 s run with.
struct EurocTestLength {
  int seconds = 2;
  int rate_hz = 10;
  static EurocTestLength fromEnvironment() {
    EurocTestLength length;
    if (const char* text = std::getenv("ISG_EUROC_TEST_SECONDS")) {
      length.seconds = std::max(2, std::atoi(text));
      length.rate_hz = 30;
    }
    return length;
  }
  int frames() const { return seconds * rate_hz + 1; }
};

TEST(EurocWriter, WritesTheEurocLayoutThatItsReadersExpect) {
  // 2 s of D1 with a D435 at 10 Hz and the IMU at 200 Hz (longer: EurocTestLength).
  const EurocTestLength length = EurocTestLength::fromEnvironment();
  Simulation sim(
      d1WithCamera("realsense-d435", ", \"rate_hz\": " + std::to_string(length.rate_hz)));
  const fs::path dir = fs::path(::testing::TempDir()) / "euroc_layout";
  fs::remove_all(dir);
  fs::create_directories(dir);
  EurocOptions options;
  options.duration = length.seconds;
  int last_done = 0, last_total = 0;
  const EurocSummary summary = writeEuroc(sim, dir.string(), options, [&](int done, int total) {
    last_done = done;
    last_total = total;
  });
  const int frames = length.frames();
  EXPECT_EQ(summary.frames, frames);
  EXPECT_EQ(summary.depth_frames, frames);
  EXPECT_EQ(last_done, frames);
  EXPECT_EQ(last_total, frames);
  EXPECT_EQ(summary.imu_samples, std::size_t(length.seconds * 200 + 1));
  const fs::path mav0 = dir / "mav0";

  // Every image listed, stamped in nanoseconds from the offset, decodes at its size.
  const auto cam_rows = readCsv(mav0 / "cam0" / "data.csv");
  const auto depth_rows = readCsv(mav0 / "depth0" / "data.csv");
  ASSERT_EQ(cam_rows.size(), std::size_t(frames));
  ASSERT_EQ(depth_rows, cam_rows);  // registered: the same stamps
  EXPECT_EQ(cam_rows[0][0], "1000000000000000000");
  EXPECT_EQ(cam_rows[length.rate_hz][0], "1000000001000000000");
  EXPECT_EQ(cam_rows[length.rate_hz][1], "1000000001000000000.png");
  const DecodedPng rgb = readPng(mav0 / "cam0" / "data" / cam_rows[10][1]);
  EXPECT_EQ(rgb.width, 640);
  EXPECT_EQ(rgb.height, 480);
  EXPECT_EQ(rgb.bit_depth, 8);
  EXPECT_EQ(rgb.colour_type, PNG_COLOR_TYPE_RGB);
  const DecodedPng depth = readPng(mav0 / "depth0" / "data" / depth_rows[10][1]);
  EXPECT_EQ(depth.bit_depth, 16);
  EXPECT_EQ(depth.colour_type, PNG_COLOR_TYPE_GRAY);
  ASSERT_EQ(depth.samples.size(), 640u * 480u);

  // The camera's ground truth, stamped as its images (seconds, to the nanosecond).
  const common::Trajectory truth = common::readTum((mav0 / "cam0.tum").string());
  ASSERT_EQ(truth.size(), std::size_t(frames));
  std::ifstream tum_text(mav0 / "cam0.tum");
  std::string line;
  std::getline(tum_text, line);  // the comment
  std::getline(tum_text, line);
  std::getline(tum_text, line);
  EXPECT_EQ(line.substr(0, line.find(' ')),
            cam_rows[1][0].substr(0, 10) + "." + cam_rows[1][0].substr(10));

  // The depth images, noise on, against mj_ray from the camera's pose in cam0.tum: in every
  // other frame the median within 2 cm; and the noise as the model says: over the pixels 1.5 m away
  // or more (where the millimetre steps are small beside σ), the errors over σ(z) spread as a unit
  // normal (the median absolute error 0.674 σ, within 10 %).
  const YAML::Node cam_yaml = YAML::LoadFile((mav0 / "cam0" / "sensor.yaml").string());
  EXPECT_EQ(cam_yaml["sensor_type"].as<std::string>(), "camera");
  EXPECT_EQ(cam_yaml["resolution"][0].as<int>(), 640);
  EXPECT_EQ(cam_yaml["T_BS"]["data"].size(), 16u);
  const bim::CameraConfig& camera = sim.scenario().cameras[0];
  const bim::PinholeIntrinsics& k = camera.model.intrinsics;
  EXPECT_NEAR(cam_yaml["intrinsics"][0].as<double>(), k.fx, 1e-6);
  std::vector<double> normalised, absolute;
  double worst_bias = 0.0;
  const auto median = [](std::vector<double> values) {
    std::nth_element(values.begin(), values.begin() + values.size() / 2, values.end());
    return values[values.size() / 2];
  };
  for (std::size_t f = 0; f < depth_rows.size(); f += 2) {
    const DecodedPng image = readPng(mav0 / "depth0" / "data" / depth_rows[f][1]);
    ASSERT_EQ(image.samples.size(), 640u * 480u);
    const Eigen::Isometry3d& B_T_C = truth[f].pose;
    EXPECT_TRUE(B_T_C.isApprox(
        sim.baseMotion().pose(double(f) / length.rate_hz) * sensors::mountTransform(camera.mount),
        1e-5));
    std::vector<double> errors;
    for (int v = 0; v < 480; v += 10) {
      for (int u = 0; u < 640; u += 10) {
        const unsigned mm = image.samples[std::size_t(v) * 640 + u];
        if (mm == 0) continue;
        const double z = rayDepth(sim.world(), B_T_C, k, u, v);
        errors.push_back(mm * 1e-3 - z);
        absolute.push_back(std::abs(errors.back()));
        if (z > 1.5) normalised.push_back(absolute.back() / camera.model.depth->sigma(z));
      }
    }
    ASSERT_GT(errors.size(), 1000u);
    // Each frame's depth lies on the building: its errors' median within 2 cm of 0 (a frame
    // seeing far down a corridor has a larger spread, σ(z) growing with z², but no bias).
    const double bias = median(errors);
    EXPECT_LT(std::abs(bias), 0.02) << "frame " << f;
    worst_bias = std::max(worst_bias, std::abs(bias));
  }
  // Over the walk, the errors' median size within 2 cm.
  const double median_error = median(absolute);
  EXPECT_LT(median_error, 0.02);
  std::printf(
      "depth against mj_ray, %zu frames: median |error| %.4f m, worst frame's median "
      "error %.4f m\n",
      (depth_rows.size() + 1) / 2, median_error, worst_bias);
  ASSERT_GT(normalised.size(), 5000u);
  std::nth_element(normalised.begin(), normalised.begin() + normalised.size() / 2,
                   normalised.end());
  EXPECT_NEAR(normalised[normalised.size() / 2], 0.674, 0.067);

  // The IMU and the ground truth: one row per sample, the state the IMU's pose in B.
  const auto imu_rows = readCsv(mav0 / "imu0" / "data.csv");
  const auto state_rows = readCsv(mav0 / "state_groundtruth_estimate0" / "data.csv");
  ASSERT_EQ(imu_rows.size(), std::size_t(length.seconds * 200 + 1));
  ASSERT_EQ(state_rows.size(), imu_rows.size());
  EXPECT_EQ(imu_rows[1].size(), 7u);
  EXPECT_EQ(state_rows[1].size(), 17u);
  EXPECT_EQ(state_rows[200][0], "1000000001000000000");
  const Eigen::Vector3d p_at_1 = (sim.baseMotion().pose(1.0) * sim.R_T_I()).translation();
  EXPECT_NEAR(std::stod(state_rows[200][1]), p_at_1.x(), 1e-9);
  EXPECT_NEAR(std::stod(state_rows[200][2]), p_at_1.y(), 1e-9);
  const YAML::Node imu_yaml = YAML::LoadFile((mav0 / "imu0" / "sensor.yaml").string());
  EXPECT_DOUBLE_EQ(imu_yaml["rate_hz"].as<double>(), 200.0);
  EXPECT_DOUBLE_EQ(imu_yaml["gyroscope_noise_density"].as<double>(),
                   sim.scenario().imu.gyroscope_noise_density);

  // Kalibr's camera chain: T_cam_imu is the inverse of the camera's T_BS.
  const YAML::Node chain = YAML::LoadFile((mav0 / "camchain.yaml").string());
  const YAML::Node T_cam_imu = chain["cam0"]["T_cam_imu"];
  Eigen::Matrix4d A, B;
  for (int r = 0; r < 4; ++r) {
    for (int c = 0; c < 4; ++c) {
      A(r, c) = T_cam_imu[r][c].as<double>();
      B(r, c) = cam_yaml["T_BS"]["data"][4 * r + c].as<double>();
    }
  }
  EXPECT_TRUE((A * B).isApprox(Eigen::Matrix4d::Identity(), 1e-9));
  EXPECT_EQ(chain["cam0"]["resolution"][1].as<int>(), 480);
  fs::remove_all(dir);
}

}  // namespace
}  // namespace isg::sim
