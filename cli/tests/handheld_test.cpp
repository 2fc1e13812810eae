// The handheld carrier: a person walks the building with the sensors in hand. Its datasets carry
// no odometry, and `isg run` localizes it from the LiDAR and the IMU alone.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>

#include "cli/tests/cli_runner.hpp"

namespace isg::cli {
namespace {

using ::testing::HasSubstr;

TEST(Handheld, DatasetHasNoOdometryAndTheWalkersSway) {
  const testing::Sandbox sandbox("handheld_dataset");
  const auto r = sandbox.run("simulate builtin:d1.handheld --duration 6 -o ds -q");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_FALSE(sandbox.exists("ds/odometry.tum"));
  const auto metadata = nlohmann::json::parse(sandbox.read("ds/metadata.json"));
  EXPECT_EQ(metadata["robot"]["carrier"], "handheld");
  EXPECT_FALSE(metadata.contains("odometry"));
  EXPECT_DOUBLE_EQ(metadata["robot"]["gait"]["sway_m"].get<double>(), 0.025);
  EXPECT_FALSE(metadata["lidar"]["body_occlusion"].get<bool>());
  // Held 1.2 m above the floor, give or take the 2.5 cm bob of the steps.
  std::istringstream rows(sandbox.read("ds/groundtruth.tum"));
  double lowest = 1e9, highest = -1e9;
  for (double t, x, y, z, qx, qy, qz, qw; rows >> t >> x >> y >> z >> qx >> qy >> qz >> qw;) {
    lowest = std::min(lowest, z), highest = std::max(highest, z);
  }
  EXPECT_GE(lowest, 1.2 - 0.025 - 1e-6);
  EXPECT_LE(highest, 1.2 + 0.025 + 1e-6);
  EXPECT_GT(highest - lowest, 0.03);  // it does bob
}

TEST(Handheld, ItsBagImportsBackWithTheTruthOfTheRigsBase) {
  // Without odometry the base frame is the ground truth's child, which /tf_static joins to the
  // LiDAR: the imported truth is the base's (1.2 m up), not the LiDAR's (1.45 m).
  const testing::Sandbox sandbox("handheld_bag");
  auto r = sandbox.run("simulate builtin:d1.handheld --duration 4 -o ds --rosbag ds.bag -q");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  r = sandbox.run("import ds.bag -o imported -q");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_FALSE(sandbox.exists("imported/odometry.tum"));
  std::istringstream original(sandbox.read("ds/groundtruth.tum"));
  std::istringstream imported(sandbox.read("imported/groundtruth.tum"));
  int rows = 0;
  double largest = 0.0;
  for (std::string a, b; std::getline(original, a) && std::getline(imported, b); ++rows) {
    std::istringstream va(a), vb(b);
    for (double x, y; va >> x && vb >> y;) largest = std::max(largest, std::abs(x - y));
  }
  EXPECT_EQ(rows, 401);
  EXPECT_LE(largest, 2e-9);  // the last printed digit
}

TEST(Handheld, RunLocalizesFromTheLidarAndTheImuAlone) {
  const testing::Sandbox sandbox("handheld_run");
  const auto r = sandbox.run("run builtin:d1.handheld -o run");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_THAT(r.err, HasSubstr("isg run: there is no odometry: the LiDAR and the IMU make it"));
  EXPECT_FALSE(sandbox.exists("run/odometry.tum"));
  const auto m = nlohmann::json::parse(sandbox.read("run/metrics.json"));
  ASSERT_TRUE(m["localized"].get<bool>());
  EXPECT_FALSE(m["wrongly_localized"].get<bool>());
  EXPECT_LE(m["ape_B"]["rmse"].get<double>(), 0.05);
  // Its height is known to within the 1 m of a floor although the floor is rarely in view.
  EXPECT_LT(m["max_height_error_B"].get<double>(), 1.0);
}

// The acceptance of the handheld carrier, at CI's size: a larger building (D3, a double-loaded
// corridor, eight rooms), another seed, the floor in view — height from the floor, not bounded.
TEST(Handheld, ALargerBuildingLocalizesWithItsHeightFromTheFloor) {
  const testing::Sandbox sandbox("handheld_d3");
  const auto r = sandbox.run("run builtin:d3.handheld --seed 2 -o run -q");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto m = nlohmann::json::parse(sandbox.read("run/metrics.json"));
  ASSERT_TRUE(m["localized"].get<bool>());
  EXPECT_FALSE(m["wrongly_localized"].get<bool>());
  EXPECT_LE(m["ape_B"]["rmse"].get<double>(), 0.05);
  EXPECT_LT(m["max_height_error_B"].get<double>(), 0.2);
}

}  // namespace
}  // namespace isg::cli
