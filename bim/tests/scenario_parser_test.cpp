#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <numbers>

#include "bim/scenario.hpp"

namespace isg::bim {
namespace {

const std::string kScenarioPlans = std::string(ISG_SOURCE_DIR) + "/worlds/plans/";

TEST(ScenarioParser, BarePlanGetsEveryDefault) {
  const Scenario s = loadScenario(kScenarioPlans + "d1.json");
  EXPECT_EQ(s.seed, 0u);
  EXPECT_EQ(s.robot.level, "L0");
  EXPECT_EQ(s.robot.start_room, "R1");  // the level's first room
  EXPECT_FALSE(s.robot.start_pose);
  EXPECT_EQ(s.robot.route.kind, Route::Kind::kTour);
  EXPECT_DOUBLE_EQ(s.robot.speed, 0.5);
  EXPECT_DOUBLE_EQ(s.lidar.rate_hz, 10.0);
  EXPECT_DOUBLE_EQ(s.lidar.range_noise_m, 0.007);
  EXPECT_DOUBLE_EQ(s.lidar.min_range_m, 0.4);
  EXPECT_DOUBLE_EQ(s.lidar.grazing_cutoff_deg, 80.0);
  EXPECT_DOUBLE_EQ(s.lidar.detection_range_m, 100.0);
  EXPECT_TRUE(s.lidar.body_occlusion);
  EXPECT_DOUBLE_EQ(s.lidar.reflectivity.wall, 0.5);
  EXPECT_DOUBLE_EQ(s.lidar.reflectivity.ceiling, 0.8);
  EXPECT_DOUBLE_EQ(s.lidar.max_range_m, 100.0);
  EXPECT_DOUBLE_EQ(s.lidar.mount[2], 0.25);
  EXPECT_EQ(s.lidar.stamp, LidarStamp::kFirstFiring);
  EXPECT_EQ(s.lidar.cut, LidarCut::kAngle);
  EXPECT_EQ(s.lidar.cut_angle_deg, 0.0);
  EXPECT_EQ(s.lidar.azimuth_jitter_deg, 0.0);
  EXPECT_EQ(s.lidar.returns, LidarReturns::kStrongest);
  EXPECT_DOUBLE_EQ(s.odometry.rate_hz, 50.0);
  EXPECT_DOUBLE_EQ(s.odometry.translation_noise, 0.02);
  EXPECT_DOUBLE_EQ(s.odometry.heading_noise_deg_per_m, 0.5);
  EXPECT_DOUBLE_EQ(s.imu.rate_hz, 200.0);
  EXPECT_EQ(s.imu.mount, (std::array<double, 6>{0, 0, 0, 0, 0, 0}));
  EXPECT_DOUBLE_EQ(s.imu.gyroscope_noise_density, 1.6968e-4);
  EXPECT_DOUBLE_EQ(s.imu.accelerometer_random_walk, 3.0e-3);
  EXPECT_DOUBLE_EQ(s.imu.gravity, 9.81);
  EXPECT_TRUE(s.as_built.empty());
}

TEST(ScenarioParser, HandheldCarrierGetsAWalkersDefaults) {
  const Scenario s = loadScenario(kScenarioPlans + "d2.handheld.json");
  EXPECT_EQ(s.robot.carrier, Carrier::kHandheld);
  EXPECT_DOUBLE_EQ(s.robot.speed, kHandheldSpeed);
  EXPECT_DOUBLE_EQ(s.robot.gait.bob_m, 0.025);
  EXPECT_DOUBLE_EQ(s.robot.gait.sway_m, 0.025);
  EXPECT_DOUBLE_EQ(s.robot.gait.head_turn_deg, 15.0);
  EXPECT_FALSE(s.lidar.body_occlusion);  // no robot body to shadow the sensor
  // The legged base keeps its trot: no sideways sway, no head turns.
  const Scenario legged = loadScenario(kScenarioPlans + "d2.asbuilt.json");
  EXPECT_EQ(legged.robot.carrier, Carrier::kLegged);
  EXPECT_DOUBLE_EQ(legged.robot.gait.sway_m, 0.0);
  EXPECT_DOUBLE_EQ(legged.robot.gait.head_turn_deg, 0.0);
  EXPECT_TRUE(legged.lidar.body_occlusion);
  // The same as-built world otherwise.
  EXPECT_EQ(s.as_built.clutter.size(), legged.as_built.clutter.size());
}

TEST(ScenarioParser, ReferenceScenarioResolvesItsPlanRelativeToItself) {
  const Scenario s = loadScenario(kScenarioPlans + "d1.asbuilt.json");
  EXPECT_EQ(s.plan.name, "D1 three offices and a corridor");
  EXPECT_EQ(std::filesystem::path(s.plan_file).filename(), "d1.json");
  EXPECT_EQ(s.seed, 1u);
  ASSERT_EQ(s.as_built.wall_shifts.size(), 1u);
  EXPECT_EQ(s.as_built.wall_shifts[0].wall, "W6");
  EXPECT_DOUBLE_EQ(s.as_built.wall_shifts[0].offset, 0.05);
  ASSERT_EQ(s.as_built.clutter.size(), 2u);
  EXPECT_EQ(s.as_built.clutter[1].center, Eigen::Vector3d(10.8, 4.0, 0.5));
  EXPECT_DOUBLE_EQ(s.as_built.clutter[1].yaw, 0.2);
  EXPECT_EQ(s.as_built.clutter[1].level, "L0");
  EXPECT_EQ(s.as_built.closed_doors, std::vector<std::string>{"D5"});
}

TEST(ScenarioParser, InlinePlanAndExplicitRobot) {
  const auto dir = std::filesystem::temp_directory_path() / "isg_scenario_parser_test";
  std::filesystem::create_directories(dir);
  const auto path = (dir / "inline.json").string();
  std::ofstream(path) << R"({
    "format": "isg.scenario", "version": 1, "seed": 42,
    "plan": {"format": "isg.plan", "version": 1, "levels": [{"id": "G", "height": 2.5,
      "walls": [{"id": "A", "start": [0, 0], "end": [5, 0], "thickness": 0.2}]}]},
    "robot": {"start": {"pose": [1.0, 2.0, 0.5]}, "route": {"waypoints": [[1, 2], [3, 2]]},
              "speed": 0.8},
    "lidar": {"rate_hz": 20, "mount": [0.1, 0, 0.3, 0, 0, 0]},
    "imu": {"rate_hz": 400, "mount": [0, 0.05, 0.1, 0, 0, 3.14159], "gyroscope_random_walk": 0,
            "gravity": 9.80665},
    "as_built": {"extra_walls": [{"start": [0, 3], "end": [2, 3], "thickness": 0.1}]}
  })";
  const Scenario s = loadScenario(path);
  EXPECT_EQ(s.plan_file, "<inline>");
  EXPECT_EQ(s.seed, 42u);
  EXPECT_EQ(s.robot.level, "G");
  EXPECT_EQ(*s.robot.start_pose, Eigen::Vector3d(1.0, 2.0, 0.5));
  EXPECT_EQ(s.robot.route.kind, Route::Kind::kWaypoints);
  EXPECT_EQ(s.robot.route.waypoints.size(), 2u);
  EXPECT_DOUBLE_EQ(s.lidar.rate_hz, 20.0);
  EXPECT_DOUBLE_EQ(s.lidar.mount[0], 0.1);
  EXPECT_DOUBLE_EQ(s.imu.rate_hz, 400.0);
  EXPECT_DOUBLE_EQ(s.imu.mount[5], 3.14159);
  EXPECT_DOUBLE_EQ(s.imu.gyroscope_random_walk, 0.0);
  EXPECT_DOUBLE_EQ(s.imu.gyroscope_noise_density, 1.6968e-4);  // the default
  EXPECT_DOUBLE_EQ(s.imu.gravity, 9.80665);
  ASSERT_EQ(s.as_built.extra_walls.size(), 1u);
  EXPECT_EQ(s.as_built.extra_walls[0].id, "extra0");
  EXPECT_EQ(s.as_built.extra_walls[0].level, "G");
  std::filesystem::remove_all(dir);
}

TEST(ScenarioParser, ATrajectoryRouteReadsItsWalkBesideTheScenario) {
  const auto dir = std::filesystem::temp_directory_path() / "isg_scenario_parser_walk";
  std::filesystem::create_directories(dir / "walks");
  // A walk on a Unix epoch clock, with a comment line: stamps from 0, lines as in the file.
  std::ofstream(dir / "walks" / "w.tum") << "# t x y z qx qy qz qw\n"
                                            "1700000000.0 1 1 0 0 0 0 1\n"
                                            "1700000000.5 1.25 1 0 0 0 0.7071068 0.7071068\n";
  const std::string scenario = R"({
    "format": "isg.scenario", "version": 1,
    "plan": {"format": "isg.plan", "version": 1, "levels": [{"id": "G", "height": 2.5,
      "walls": [{"id": "A", "start": [0, 0], "end": [5, 0], "thickness": 0.2}]}]},
    "robot": {"carrier": "handheld", "route": {"trajectory": "walks/w.tum",
              "orientation": "file"}}})";
  std::ofstream(dir / "s.json") << scenario;
  const Scenario s = loadScenario((dir / "s.json").string());
  EXPECT_EQ(s.robot.route.kind, Route::Kind::kTrajectory);
  EXPECT_EQ(s.robot.route.trajectory_file, (dir / "walks" / "w.tum").string());
  EXPECT_TRUE(s.robot.route.file_orientation);
  EXPECT_FALSE(s.robot.start_room.has_value());
  ASSERT_EQ(s.robot.route.walk.size(), 2u);
  EXPECT_EQ(s.robot.route.walk[0].t, 0.0);
  EXPECT_NEAR(s.robot.route.walk[1].t, 0.5, 1e-6);
  EXPECT_EQ(s.robot.route.walk[1].line, 3);
  EXPECT_EQ(s.robot.route.walk[1].xy, Eigen::Vector2d(1.25, 1.0));
  EXPECT_NEAR(s.robot.route.walk[1].yaw, std::numbers::pi / 2, 1e-6);
  // The same document that is no file (a built-in scenario's way) cannot name a walk.
  const nlohmann::json document = common::parseJsonText(scenario, "inline.json");
  const common::JsonSource source{"inline.json", nullptr};
  try {
    parseScenario(common::JsonNode(document, "", source),
                  [](const common::JsonNode& n) -> LoadedPlan { n.fail("no plan files"); });
    ADD_FAILURE() << "accepted";
  } catch (const common::InputError& e) {
    EXPECT_EQ(e.pointer(), "/robot/route/trajectory");
    EXPECT_EQ(e.reason(),
              "a trajectory route is read from a file beside its scenario's file; this scenario "
              "is not read from one");
  }
  std::filesystem::remove_all(dir);
}

}  // namespace
}  // namespace isg::bim
