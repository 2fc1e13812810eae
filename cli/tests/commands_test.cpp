// The isg command line as a user meets it: help, usage errors, and each command's output.
#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <sstream>

#include <nlohmann/json.hpp>

#include "bim/tests/test_plans.hpp"
#include "cli/tests/cli_runner.hpp"
#include "worlds/reference_plans.hpp"

namespace isg::cli {
namespace {

using ::testing::HasSubstr;
using ::testing::Not;
using ::testing::StartsWith;

TEST(Usage, HelpOnEveryCommandExitsZero) {
  testing::Sandbox sandbox("usage_help");
  for (const char* command : {"", "world ", "check ", "import ", "inspect ", "agraph ", "simulate ",
                              "render ", "vlp16 "}) {
    const auto result = sandbox.run(std::string(command) + "--help");
    EXPECT_EQ(result.exit_code, 0) << command;
    EXPECT_THAT(result.out, HasSubstr("Usage:")) << command;
  }
  EXPECT_THAT(sandbox.run("world --help").out, HasSubstr("builtin:NAME, NAME one of: d1, "));
}

TEST(Usage, BadUsageExitsTwo) {
  testing::Sandbox sandbox("usage_bad");
  auto result = sandbox.run("");
  EXPECT_EQ(result.exit_code, 2);
  EXPECT_THAT(result.err, HasSubstr("subcommand"));
  result = sandbox.run("world");
  EXPECT_EQ(result.exit_code, 2);
  EXPECT_THAT(result.err, HasSubstr("input is required"));
  result = sandbox.run("world builtin:d1 --frobnicate");
  EXPECT_EQ(result.exit_code, 2);
  result = sandbox.run("teleport");
  EXPECT_EQ(result.exit_code, 2);
}

TEST(World, WritesMjcfToStandardOutputOrAFile) {
  testing::Sandbox sandbox("world_output");
  auto result = sandbox.run("world builtin:d2");
  EXPECT_EQ(result.exit_code, 0) << result.err;
  EXPECT_THAT(result.out, HasSubstr("<mujoco model=\"D2 hall, meeting room and store\">"));
  result = sandbox.run("world builtin:d2.asbuilt -o d2.xml");
  EXPECT_EQ(result.exit_code, 0) << result.err;
  EXPECT_TRUE(result.out.empty());
  EXPECT_THAT(result.err, StartsWith("isg world: wrote d2.xml ("));
  EXPECT_THAT(sandbox.read("d2.xml"), HasSubstr("name=\"clutter/2\""));
  result = sandbox.run("world builtin:d2 --no-ceilings");
  EXPECT_THAT(result.out, ::testing::Not(HasSubstr("ceiling/L0")));
}

TEST(World, UnknownBuiltinListsTheBuiltins) {
  testing::Sandbox sandbox("world_builtin");
  const auto result = sandbox.run("world builtin:d9");
  EXPECT_EQ(result.exit_code, 1);
  EXPECT_EQ(result.err,
            "isg world: error: builtin:d9: no such built-in world (built-ins: d1, d1.asbuilt, d2, "
            "d2.asbuilt, d3, d3.asbuilt, d4, d4.asbuilt, d5, d5.asbuilt, d6, d6.asbuilt, "
            "twin-wings, twin-wings.asbuilt, twin-wings-symmetric, twin-wings-symmetric.asbuilt, "
            "hotel, hotel.asbuilt, halls, halls.asbuilt, storeys, storeys.asbuilt, twin-storeys, "
            "twin-storeys.asbuilt, d1.handheld, d2.handheld, d3.handheld, d4.handheld, "
            "d5.handheld, d6.handheld, storeys.handheld, twin-storeys.handheld)\n");
}

TEST(Check, DescribesAValidScenario) {
  testing::Sandbox sandbox("check");
  const auto result = sandbox.run("check builtin:d3.asbuilt --verbose");
  EXPECT_EQ(result.exit_code, 0) << result.err;
  EXPECT_THAT(result.out, StartsWith("builtin:d3.asbuilt: ok: plan \"D3 double-loaded corridor\" "
                                     "(builtin:d3): 1 level, 11 walls, 8 doors, 8 rooms\n"));
  EXPECT_THAT(result.out, HasSubstr("as built: 0 missing walls, 1 extra walls, 1 shifted walls, "
                                    "1 closed doors, 3 clutter boxes\n"));
  EXPECT_THAT(result.out, HasSubstr("door D8     in W4     joins R8 and outside (inferred)"));
}

TEST(Check, CountsWindowsAndTheWorldHasTheirSills) {
  testing::Sandbox sandbox("check_windows");
  nlohmann::json plan = bim::testing::twoRoomPlanJson();
  plan["levels"][0]["windows"] = nlohmann::json::parse(
      R"([{"id": "V1", "wall": "W2", "offset": 2.0, "width": 1.2, "sill": 0.9, "height": 1.2}])");
  sandbox.write("plan.json", plan.dump());
  auto result = sandbox.run("check plan.json");
  EXPECT_EQ(result.exit_code, 0) << result.err;
  EXPECT_THAT(result.out, HasSubstr("1 level, 5 walls, 2 doors, 1 window, 2 rooms\n"));
  result = sandbox.run("world plan.json");
  EXPECT_EQ(result.exit_code, 0) << result.err;
  EXPECT_THAT(result.out, HasSubstr("name=\"wall/W2/sill/V1\""));
  EXPECT_THAT(result.out, HasSubstr("name=\"wall/W2/lintel/V1\""));
}

TEST(Inspect, DefaultWorldLoadsStepsAndProbes) {
  testing::Sandbox sandbox("inspect");
  const auto result = sandbox.run("inspect --steps 100");
  EXPECT_EQ(result.exit_code, 0) << result.err;
  EXPECT_THAT(result.out, StartsWith("isg inspect: builtin:d1.asbuilt (MuJoCo 2.2.2)\n"));
  EXPECT_THAT(result.out, HasSubstr("stepped 100 times: 0.200 s of simulated time"));
  EXPECT_THAT(result.out, HasSubstr("72/72 rays hit the building"));
}

}  // namespace
}  // namespace isg::cli

namespace isg::cli {
namespace {

TEST(AGraph, WritesJsonAndSvgAndSummarises) {
  testing::Sandbox sandbox("agraph");
  const auto result = sandbox.run("agraph builtin:d1.asbuilt -o agraph.json --svg agraph.svg");
  EXPECT_EQ(result.exit_code, 0) << result.err;
  EXPECT_EQ(result.err,
            "isg agraph: 14 wall surfaces, 7 walls, 4 rooms (3 four-wall, 1 two-wall, 0 other), 5 "
            "doorways, 1 floor\n");
  const auto doc = nlohmann::json::parse(sandbox.read("agraph.json"));
  EXPECT_EQ(doc["format"], "isg.agraph");
  EXPECT_EQ(doc["nodes"]["rooms"].size(), 4u);
  EXPECT_EQ(doc["nodes"]["rooms"][3]["kind"], "two_wall");
  // From the plan, not the as-built world: W6 is where the plan has it (x = 4, faces ±0.075).
  int found = 0;
  for (const auto& s : doc["nodes"]["wall_surfaces"]) {
    if (s["id"] != "W6:left") continue;
    ++found;
    EXPECT_DOUBLE_EQ(s["closest_point"][0].get<double>(), 3.925);
  }
  EXPECT_EQ(found, 1);
  // 7 walls × 2 surface edges, 16 room–surface edges, 9 doorway–room edges, 4 floor–room edges.
  EXPECT_EQ(doc["edges"].size(), 14u + 16u + 9u + 4u);
  const std::string svg = sandbox.read("agraph.svg");
  EXPECT_THAT(svg, StartsWith("<svg xmlns=\"http://www.w3.org/2000/svg\""));
  EXPECT_THAT(svg, HasSubstr("<!-- written by isg -->"));  // what lets a second run replace it
  EXPECT_THAT(svg, HasSubstr("<title>doorway D3</title>"));
}

TEST(AGraph, UnknownLevelIsABadInput) {
  testing::Sandbox sandbox("agraph_level");
  const auto result = sandbox.run("agraph builtin:d1 --svg a.svg --level L7");
  EXPECT_EQ(result.exit_code, 1);
  EXPECT_EQ(result.err, "isg agraph: error: builtin:d1: no level \"L7\" in the plan (--level)\n");
  EXPECT_FALSE(sandbox.exists("a.svg"));
}

}  // namespace
}  // namespace isg::cli

namespace isg::cli {
namespace {

TEST(Simulate, WritesADatasetAndSummarises) {
  testing::Sandbox sandbox("simulate");
  auto result = sandbox.run("simulate builtin:d2 -o ds --duration 1 --seed 3");
  EXPECT_EQ(result.exit_code, 0) << result.err;
  EXPECT_THAT(result.out, StartsWith("isg simulate: wrote ds: 10 scans, "));
  EXPECT_THAT(result.out, HasSubstr("1.0 s of robot time in"));
  EXPECT_TRUE(sandbox.exists("ds/scans/000009.pcd"));
  EXPECT_FALSE(sandbox.exists("ds/scans/000010.pcd"));
  const auto metadata = nlohmann::json::parse(sandbox.read("ds/metadata.json"));
  EXPECT_EQ(metadata["format"], "isg.dataset");
  EXPECT_EQ(metadata["seed"], 3);
  EXPECT_EQ(metadata["plan"]["levels"][0]["rooms"].size(), 3u);
  // An existing dataset is kept unless --force.
  result = sandbox.run("simulate builtin:d2 -o ds --duration 1");
  EXPECT_EQ(result.exit_code, 1);
  EXPECT_EQ(result.err, "isg simulate: error: ds: already exists (use --force to replace it)\n");
  result = sandbox.run("simulate builtin:d2 -o ds --duration 0.5 --force");
  EXPECT_EQ(result.exit_code, 0) << result.err;
  EXPECT_FALSE(sandbox.exists("ds/scans/000005.pcd"));
}

// isg export: a dataset as a ROS 1 bag (read back by python3-rosbag in rosbag_oracle.py), and
// its bad input.
TEST(Export, WritesABagAndRefusesBadInput) {
  testing::Sandbox sandbox("export");
  ASSERT_EQ(sandbox.run("simulate builtin:d2 -o ds --duration 1 -q --rosbag ds.bag").exit_code, 0);
  ASSERT_TRUE(sandbox.exists("ds.bag"));
  auto result = sandbox.run("export ds --rosbag again.bag -q");
  EXPECT_EQ(result.exit_code, 0) << result.err;
  EXPECT_THAT(result.out, StartsWith("isg export: wrote again.bag: "));
  EXPECT_THAT(result.out, HasSubstr("/velodyne_points 10"));
  EXPECT_THAT(result.out, HasSubstr("/imu/data 201"));
  EXPECT_EQ(sandbox.read("ds.bag"), sandbox.read("again.bag"));  // same dataset, same bytes
  result = sandbox.run("export ds --rosbag again.bag -q");
  EXPECT_EQ(result.exit_code, 1);
  EXPECT_EQ(result.err,
            "isg export: error: again.bag: already exists (use --force to replace it)\n");
  result = sandbox.run("export nowhere --rosbag x.bag -q");
  EXPECT_EQ(result.exit_code, 1);
  EXPECT_EQ(result.err, "isg export: error: nowhere: not a dataset folder (no such directory)\n");
  EXPECT_FALSE(sandbox.exists("x.bag"));
  sandbox.write("ds/imu.csv", "t,ax,ay,az,gx,gy,gz\n0,0,0,9.81,0,0\n");
  result = sandbox.run("export ds --rosbag x.bag -q");
  EXPECT_EQ(result.exit_code, 1);
  EXPECT_EQ(result.err,
            "isg export: error: ds/imu.csv: line 2: expected 7 comma-separated numbers "
            "(t,ax,ay,az,gx,gy,gz), got 6\n");
  EXPECT_FALSE(sandbox.exists("x.bag"));
  // Refused before simulating: an existing bag without --force.
  result = sandbox.run("simulate builtin:d2 -o ds2 --duration 1 -q --rosbag ds.bag");
  EXPECT_EQ(result.exit_code, 1);
  EXPECT_EQ(result.err,
            "isg simulate: error: ds.bag: already exists (use --force to replace it)\n");
  EXPECT_FALSE(sandbox.exists("ds2"));
  EXPECT_EQ(sandbox.run("export --help").exit_code, 0);
}

// A scenario in a 4 × 4 m room, with `robot_or_sensor` (a JSON member) added.
std::string squareRoomScenario(const std::string& robot_or_sensor) {
  return R"({"format": "isg.scenario", "version": 1,
    "plan": {"format": "isg.plan", "version": 1, "levels": [{"id": "L0", "height": 3,
      "walls": [{"id": "A", "start": [0, 0], "end": [4, 0], "thickness": 0.2},
                {"id": "B", "start": [4, 0], "end": [4, 4], "thickness": 0.2},
                {"id": "C", "start": [4, 4], "end": [0, 4], "thickness": 0.2},
                {"id": "D", "start": [0, 4], "end": [0, 0], "thickness": 0.2}],
      "rooms": [{"id": "R", "outline": [[0.1, 0.1], [3.9, 0.1], [3.9, 3.9], [0.1, 3.9]]}]}]},
    )" + robot_or_sensor +
         "}";
}

TEST(Simulate, StartInsideClearanceIsAClearError) {
  testing::Sandbox sandbox("simulate_start");
  sandbox.write("scenario.json",
                squareRoomScenario(R"("robot": {"start": {"pose": [0.3, 2.0, 0.0]}})"));
  const auto result = sandbox.run("simulate scenario.json -o ds");
  EXPECT_EQ(result.exit_code, 1);
  EXPECT_EQ(result.err,
            "isg simulate: error: scenario.json: /robot/start: the robot cannot stand at (0.3, 2): "
            "it is less than 0.35 m from a wall, clutter or the outside of the building\n");
  EXPECT_FALSE(sandbox.exists("ds"));
}

TEST(Simulate, ALidarInsideTheBodyIsAClearError) {
  testing::Sandbox sandbox("simulate_mount");
  sandbox.write("scenario.json",
                squareRoomScenario(R"("lidar": {"mount": [0.2, 0.0, 0.05, 0.0, 0.0, 0.0]})"));
  const auto result = sandbox.run("simulate scenario.json -o ds");
  EXPECT_EQ(result.exit_code, 1);
  EXPECT_EQ(result.err,
            "isg simulate: error: scenario.json: /lidar/mount: the LiDAR sits inside the robot's "
            "body (1.10 × 0.50 × 0.18 m about the base's origin): mount it above z = 0.09 m or "
            "set body_occlusion to false\n");
  EXPECT_FALSE(sandbox.exists("ds"));
  // The same mount with the body out of the rays' way is accepted.
  sandbox.write("scenario.json", squareRoomScenario(R"("robot": {"route": {"waypoints": [[3, 2]]}},
    "lidar": {"mount": [0.2, 0.0, 0.05, 0.0, 0.0, 0.0], "body_occlusion": false})"));
  const auto accepted = sandbox.run("simulate scenario.json -o ds -q");
  EXPECT_EQ(accepted.exit_code, 0) << accepted.err;
}

TEST(Simulate, TheRos1DriversConventionsReachTheDatasetAndTheBag) {
  testing::Sandbox sandbox("simulate_conventions");
  sandbox.write("scenario.json", squareRoomScenario(R"("robot": {"route": {"waypoints": [[3, 2]]}},
    "lidar": {"stamp": "last_packet", "cut": "packets", "azimuth_jitter_deg": 0.006})"));
  const auto result = sandbox.run("simulate scenario.json -o ds --rosbag ds.bag -q");
  ASSERT_EQ(result.exit_code, 0) << result.err;
  const auto lidar = nlohmann::json::parse(sandbox.read("ds/metadata.json"))["lidar"];
  EXPECT_EQ(lidar["stamp"], "last_packet");
  EXPECT_EQ(lidar["cut"], "packets");
  EXPECT_EQ(lidar["returns"], "strongest");
  EXPECT_EQ(lidar["sequences_per_cloud"], 1824);
  EXPECT_DOUBLE_EQ(lidar["scan_period_s"].get<double>(), 1824 * 55.296e-6);
  EXPECT_DOUBLE_EQ(lidar["point_time_s"][0].get<double>(), -1800 * 55.296e-6);
  EXPECT_NEAR(lidar["point_time_s"][1].get<double>(), 24 * 55.296e-6, 1e-12);
  // scans.tum: the stamps at each cloud's last packet, a cloud every 76 packets.
  std::istringstream tum(sandbox.read("ds/scans.tum"));
  std::vector<double> stamps;
  for (std::string line; std::getline(tum, line);) {
    if (!line.empty() && line[0] != '#') stamps.push_back(std::stod(line));
  }
  ASSERT_GE(stamps.size(), 3u);
  EXPECT_NEAR(stamps[0], 1800 * 55.296e-6, 1e-9);
  EXPECT_NEAR(stamps[2] - stamps[1], 1824 * 55.296e-6, 1e-9);
  // The dataset passes the check against its metadata that an export makes.
  const auto exported = sandbox.run("export ds --rosbag again.bag -q");
  EXPECT_EQ(exported.exit_code, 0) << exported.err;
  EXPECT_TRUE(sandbox.exists("ds.bag"));
}

// --lidar: another sensor for the scenario's, named in the dataset and the run; an unknown one is
// a usage error listing the models.
TEST(Simulate, AnotherLidarModelIsNamedInTheDatasetAndTheRun) {
  testing::Sandbox sandbox("simulate_lidar_model");
  auto result = sandbox.run("simulate builtin:d1 -o ds --duration 1 --lidar os1-64 -q");
  ASSERT_EQ(result.exit_code, 0) << result.err;
  const auto lidar = nlohmann::json::parse(sandbox.read("ds/metadata.json"))["lidar"];
  EXPECT_EQ(lidar["model"], "Ouster OS1-64");
  EXPECT_EQ(lidar["scenario_model"], "os1-64");
  EXPECT_EQ(lidar["sequences_per_turn"], 1024);
  EXPECT_EQ(lidar["elevation_deg_by_laser"].size(), 64u);
  EXPECT_EQ(lidar["max_range_m"], 120.0);
  result = sandbox.run("run builtin:d1 --lidar vlp32c --duration 5 -o run -q");
  ASSERT_EQ(result.exit_code, 0) << result.err;
  EXPECT_EQ(nlohmann::json::parse(sandbox.read("run/metrics.json"))["lidar_model"], "vlp32c");
  result = sandbox.run("run builtin:d1 --duration 5 -o plain -q");
  ASSERT_EQ(result.exit_code, 0) << result.err;
  EXPECT_FALSE(nlohmann::json::parse(sandbox.read("plain/metrics.json")).contains("lidar_model"));
  result = sandbox.run("simulate builtin:d1 -o other --lidar hdl64 -q");
  EXPECT_EQ(result.exit_code, 2);
  EXPECT_THAT(result.err, HasSubstr("hdl64"));
  EXPECT_THAT(result.err, HasSubstr("os1-128"));
  EXPECT_FALSE(sandbox.exists("other"));
}

// Kidnaps the parser cannot judge: the simulator knows when the route ends and where the robot
// can stand.
TEST(Simulate, KidnapsTheRouteCannotHaveAreClearErrors) {
  testing::Sandbox sandbox("simulate_kidnap");
  const std::string plan = R"("plan": {"format": "isg.plan", "version": 1, "levels": [{"id": "L0",
      "height": 3, "walls": [{"id": "A", "start": [0, 0], "end": [8, 0], "thickness": 0.2},
                {"id": "B", "start": [8, 0], "end": [8, 4], "thickness": 0.2},
                {"id": "C", "start": [8, 4], "end": [0, 4], "thickness": 0.2},
                {"id": "D", "start": [0, 4], "end": [0, 0], "thickness": 0.2}],
      "rooms": [{"id": "R", "outline": [[0.1, 0.1], [7.9, 0.1], [7.9, 3.9], [0.1, 3.9]]}]}]})";
  sandbox.write("late.json", R"({"format": "isg.scenario", "version": 1, )" + plan + R"(,
    "robot": {"start": {"pose": [1, 2, 0]}, "route": {"waypoints": [[7, 2]]},
              "kidnap": [{"time": 30, "to": {"pose": [4, 2, 0]}}]}})");
  auto result = sandbox.run("simulate late.json -o ds");
  EXPECT_EQ(result.exit_code, 1);
  EXPECT_EQ(result.err,
            "isg simulate: error: late.json: /robot/kidnap/0/time: the robot's route ends at "
            "12.52 s, before the kidnap at 30.00 s\n");
  sandbox.write("cluttered.json", R"({"format": "isg.scenario", "version": 1, )" + plan + R"(,
    "robot": {"start": {"pose": [1, 2, 0]}, "route": {"waypoints": [[7, 2]]},
              "kidnap": [{"time": 5, "to": {"pose": [4, 3, 0]}}]},
    "as_built": {"clutter": [{"shape": "box", "center": [4, 3, 0.5], "size": [1, 1, 1]}]}})");
  result = sandbox.run("simulate cluttered.json -o ds");
  EXPECT_EQ(result.exit_code, 1);
  EXPECT_EQ(result.err,
            "isg simulate: error: cluttered.json: /robot/kidnap/0/to: the robot cannot be put "
            "down at (4, 3): it is less than 0.35 m from a wall, clutter or the outside of the "
            "building\n");
  EXPECT_FALSE(sandbox.exists("ds"));
}

TEST(Render, WritesThreePictures) {
  testing::Sandbox sandbox("render");
  const auto result = sandbox.run("render builtin:d1 -o pictures --width 320 --height 180");
  EXPECT_EQ(result.exit_code, 0) << result.err;
  EXPECT_THAT(result.out, StartsWith("isg render: wrote pictures/top.png, pictures/plan.png and "
                                     "pictures/chase.png"));
  EXPECT_EQ(sandbox.read("pictures/top.png").substr(1, 3), "PNG");
  EXPECT_EQ(sandbox.read("pictures/plan.png").substr(1, 3), "PNG");
  EXPECT_EQ(sandbox.read("pictures/chase.png").substr(1, 3), "PNG");
}

}  // namespace
}  // namespace isg::cli

namespace isg::cli {
namespace {

std::string worlds_plan_d1() { return std::string(*worlds::builtinText("d1")); }

TEST(Simulate, UnreachableRoomOnTheRouteIsAClearError) {
  testing::Sandbox sandbox("simulate_unreachable");
  // D1 as built with its offices' doors closed: office 2 can only be reached through D2 or D4.
  sandbox.write("scenario.json", R"({"format": "isg.scenario", "version": 1, "plan": "d1.json",
    "robot": {"start": {"room": "R4"}, "route": {"rooms": ["R1", "R2"]}},
    "as_built": {"closed_doors": ["D2", "D4"]}})");
  sandbox.write("d1.json", worlds_plan_d1());
  const auto result = sandbox.run("simulate scenario.json -o ds");
  EXPECT_EQ(result.exit_code, 1);
  EXPECT_THAT(result.err, StartsWith("isg simulate: error: scenario.json: /robot/route/rooms/1: "
                                     "room \"R2\" cannot be reached from ("));
  EXPECT_FALSE(sandbox.exists("ds"));
}

}  // namespace
}  // namespace isg::cli

namespace isg::cli {
namespace {

TEST(Eval, PrintsApeLikeEvoAndJson) {
  testing::Sandbox sandbox("eval");
  sandbox.write("gt.tum", "0 0 0 0 0 0 0 1\n1 1 0 0 0 0 0 1\n2 2 0 0 0 0 0 1\n3 3 0 0 0 0 0 1\n");
  // Off by 0.1, 0.2, 0.3, 0.4 m in y: rmse √(0.3/4), mean 0.25.
  sandbox.write("est.tum",
                "0 0 0.1 0 0 0 0 1\n1 1 0.2 0 0 0 0 1\n2.005 2 0.3 0 0 0 0 1\n3 3 0.4 0 0 0 0 1\n");
  auto result = sandbox.run("eval gt.tum est.tum");
  EXPECT_EQ(result.exit_code, 0) << result.err;
  EXPECT_THAT(result.out, HasSubstr("Found 4 of max. 4 possible matching timestamps"));
  EXPECT_THAT(result.out, HasSubstr("APE w.r.t. translation part (m)\n(not aligned)\n\n"
                                    "       max\t0.400000\n      mean\t0.250000\n"));
  EXPECT_THAT(result.out, HasSubstr("      rmse\t0.273861\n"));
  result = sandbox.run("eval gt.tum est.tum --json --t-max-diff 0.001");
  EXPECT_EQ(result.exit_code, 0) << result.err;
  const auto doc = nlohmann::json::parse(result.out);
  EXPECT_EQ(doc["pairs"], 3);  // 2.005 is 5 ms from 2: outside a 1 ms window
  EXPECT_NEAR(doc["ape"]["mean"].get<double>(), (0.1 + 0.2 + 0.4) / 3, 1e-9);
  // --plot: both trajectories from above and the errors over time, as evo's --plot.
  result = sandbox.run("eval gt.tum est.tum --plot plot.svg");
  EXPECT_EQ(result.exit_code, 0) << result.err;
  const std::string svg = sandbox.read("plot.svg");
  EXPECT_THAT(svg, HasSubstr("rmse 0.274 m, median 0.250 m, max 0.400 m over 4 poses"));
  EXPECT_THAT(svg, HasSubstr("position error, metres"));
  EXPECT_THAT(svg, HasSubstr("heading error, degrees"));
  EXPECT_THAT(svg, HasSubstr(">0.4</text>"));  // the error axis ends on a round tick
  // Missing folders on the way are made.
  result = sandbox.run("eval gt.tum est.tum --plot new/folder/plot.svg");
  EXPECT_EQ(result.exit_code, 0) << result.err;
  EXPECT_THAT(sandbox.read("new/folder/plot.svg"), HasSubstr("position error, metres"));
  // A parent, or an ancestor, that is a file, not a folder: nothing made.
  result = sandbox.run("eval gt.tum est.tum --plot gt.tum/plot.svg");
  EXPECT_EQ(result.exit_code, 1);
  EXPECT_EQ(result.err,
            "isg eval: error: gt.tum/plot.svg: cannot write: gt.tum is not a directory\n");
  result = sandbox.run("eval gt.tum est.tum --plot gt.tum/a/b/plot.svg");
  EXPECT_EQ(result.err,
            "isg eval: error: gt.tum/a/b/plot.svg: cannot write: gt.tum is not a directory\n");
}

TEST(Eval, BadInputNamesTheFile) {
  testing::Sandbox sandbox("eval_bad");
  sandbox.write("gt.tum", "0 0 0 0 0 0 0 1\n1 1 0 0 0 0 0 1\n");
  sandbox.write("bad.tum", "0 0 0 0 0 0 0 1\n1 1 0\n");
  sandbox.write("late.tum", "50 0 0 0 0 0 0 1\n");
  auto result = sandbox.run("eval gt.tum bad.tum");
  EXPECT_EQ(result.exit_code, 1);
  EXPECT_EQ(result.err,
            "isg eval: error: bad.tum: line 2: expected 8 numbers: t tx ty tz qx qy qz qw\n");
  result = sandbox.run("eval gt.tum missing.tum");
  EXPECT_EQ(result.exit_code, 1);
  EXPECT_EQ(result.err, "isg eval: error: missing.tum: cannot open file\n");
  result = sandbox.run("eval gt.tum late.tum");
  EXPECT_EQ(result.exit_code, 1);
  EXPECT_THAT(result.err, HasSubstr("late.tum: no pose of the estimate is within 0.010000 s"));
  result = sandbox.run("eval gt.tum gt.tum --align affine");
  EXPECT_EQ(result.exit_code, 2);
}

}  // namespace
}  // namespace isg::cli

namespace isg::cli {
namespace {

TEST(Slam, ReplaysADatasetAndWritesTheRun) {
  testing::Sandbox sandbox("slam");
  ASSERT_EQ(sandbox.run("simulate builtin:d2 -o ds --duration 12 -q").exit_code, 0);
  const auto result = sandbox.run("slam ds -o run -q");
  EXPECT_EQ(result.exit_code, 0) << result.err;
  EXPECT_THAT(result.out, StartsWith("isg slam: wrote run (s-graph on ds, seed "));
  EXPECT_THAT(result.out, HasSubstr("  not localized in the plan\n"));
  EXPECT_THAT(result.out, HasSubstr("  APE in M after SE(3) alignment: rmse "));
  EXPECT_THAT(result.out, HasSubstr("  map: "));
  EXPECT_THAT(result.out, HasSubstr(" keyframes, "));
  EXPECT_THAT(result.out, HasSubstr("  keyframes after SE(3) alignment: APE rmse "));
  for (const char* f : {"run/estimate_map.tum", "run/keyframes.tum", "run/sgraph.json",
                        "run/metrics.json", "run/report.svg", "run/estimate.tum"}) {
    EXPECT_TRUE(sandbox.exists(f)) << f;
  }
  EXPECT_EQ(sandbox.read("run/estimate.tum"), "");  // never localized in B
  const auto graph = nlohmann::json::parse(sandbox.read("run/sgraph.json"));
  EXPECT_EQ(graph["frame"], "M");
  EXPECT_GT(graph["planes"].size(), 3u);
  const auto missing = sandbox.run("slam nowhere -o run2");
  EXPECT_EQ(missing.exit_code, 1);
  EXPECT_EQ(missing.err, "isg slam: error: nowhere: not a dataset folder (no such directory)\n");
  const auto no_plan = sandbox.run("slam ds -o run3 --method is-graphs");
  EXPECT_EQ(no_plan.exit_code, 2);
  EXPECT_EQ(no_plan.err, "isg slam: --method is-graphs needs --plan PLAN\n");
  EXPECT_FALSE(sandbox.exists("run3"));
}

// The loop and the replay of a dataset recorded with the same seed give the very same result.
TEST(Run, LoopAndReplayAgreeAndTheRunFolderIsComplete) {
  testing::Sandbox sandbox("run");
  const auto loop = sandbox.run("run builtin:d1.asbuilt -o loop -q");
  ASSERT_EQ(loop.exit_code, 0) << loop.err;
  EXPECT_THAT(loop.out, StartsWith("isg run: wrote loop (is-graphs on builtin:d1.asbuilt, seed 1)\n"
                                   "  localized at t = "));
  EXPECT_THAT(loop.out, HasSubstr("x real time\n"));
  for (const char* f : {"groundtruth.tum", "odometry.tum", "estimate.tum", "estimate_states.txt",
                        "estimate_map.tum", "metrics.json", "agraph.json", "sgraph.json",
                        "report.svg", "deviations.json", "deviations.svg"}) {
    EXPECT_TRUE(sandbox.exists(std::string("loop/") + f)) << f;
  }
  const auto metrics = nlohmann::json::parse(sandbox.read("loop/metrics.json"));
  EXPECT_TRUE(metrics["localized"].get<bool>());
  EXPECT_LT(metrics["ape_B"]["rmse"].get<double>(), 0.10);
  EXPECT_EQ(metrics["matching_status"], "matched");
  const auto graph = nlohmann::json::parse(sandbox.read("loop/sgraph.json"));
  EXPECT_TRUE(graph["matching"]["localized"].get<bool>());
  EXPECT_GE(graph["matching"]["room_matches"].size(), 2u);
  EXPECT_THAT(sandbox.read("loop/report.svg"), HasSubstr("first localized pose"));

  ASSERT_EQ(sandbox.run("simulate builtin:d1.asbuilt -o ds -q").exit_code, 0);
  const auto replay = sandbox.run("slam ds --plan builtin:d1 -o replay -q");
  ASSERT_EQ(replay.exit_code, 0) << replay.err;
  EXPECT_EQ(sandbox.read("replay/estimate.tum"), sandbox.read("loop/estimate.tum"));
  EXPECT_EQ(sandbox.read("replay/estimate_map.tum"), sandbox.read("loop/estimate_map.tum"));
  EXPECT_EQ(sandbox.read("replay/estimate_states.txt"), sandbox.read("loop/estimate_states.txt"));
  EXPECT_FALSE(sandbox.read("loop/estimate.tum").empty());
  // A state for each pose of estimate.tum, at its stamp (D1 is confirmed by its walls throughout).
  const std::string estimate = sandbox.read("loop/estimate.tum");
  const std::string states = sandbox.read("loop/estimate_states.txt");
  EXPECT_EQ(std::count(states.begin(), states.end(), '\n'),
            std::count(estimate.begin(), estimate.end(), '\n') + 1);
  EXPECT_EQ(states.substr(states.find('\n') + 1, 12), estimate.substr(0, 12));
  EXPECT_THAT(states, Not(HasSubstr(" lost ")));
  EXPECT_EQ(metrics["estimate_states"]["coverage_from_first"].get<double>(), 1.0);
  // The replay places the same map in the plan: the same deviation report, wall by wall.
  EXPECT_TRUE(sandbox.exists("replay/deviations.svg"));
  const auto loop_walls = nlohmann::json::parse(sandbox.read("loop/deviations.json"))["walls"];
  EXPECT_EQ(loop_walls.size(), 7u);  // D1's walls on its level
  EXPECT_EQ(nlohmann::json::parse(sandbox.read("replay/deviations.json"))["walls"], loop_walls);
}

// The short regression suite against the committed baseline (eval/baselines/short_suite.csv),
// and a deliberately degraded run (stopped before it could localize) that must fail the check.
TEST(Table, ShortSuiteAgainstTheCommittedBaseline) {
  testing::Sandbox sandbox("table");
  for (const char* world : {"d1", "d2"}) {
    for (const char* method : {"is-graphs", "odometry"}) {
      const auto r = sandbox.run(std::string("run builtin:") + world + " --method " + method +
                                 " -o suite/" + world + "-" + method + " -q");
      ASSERT_EQ(r.exit_code, 0) << r.err;
    }
  }
  const std::string baseline = std::string(ISG_SOURCE_DIR) + "/eval/baselines/short_suite.csv";
  const auto ok = sandbox.run(
      "table suite/d1-is-graphs suite/d1-odometry "
      "suite/d2-is-graphs suite/d2-odometry --baseline '" +
      baseline + "' --tolerance 0.01");
  EXPECT_EQ(ok.exit_code, 0) << ok.err;
  EXPECT_THAT(ok.out, HasSubstr("| world | is-graphs | odometry |\n"));
  EXPECT_THAT(ok.out, HasSubstr("| *localized correctly* | 2/2 | 2/2 |\n"));
  EXPECT_THAT(ok.err, HasSubstr("no cell regressed"));

  ASSERT_EQ(sandbox.run("run builtin:d2 --duration 6 -o degraded -q").exit_code, 0);
  const auto bad = sandbox.run(
      "table suite/d1-is-graphs suite/d1-odometry degraded "
      "suite/d2-odometry --baseline '" +
      baseline + "'");
  EXPECT_EQ(bad.exit_code, 4);
  EXPECT_THAT(bad.err, HasSubstr("isg table: regression: d2 / is-graphs: failed (baseline "));
  const auto csv = sandbox.run("table degraded --format csv");
  EXPECT_EQ(csv.out, "world,is-graphs\nd2,-\nlocalized correctly,0/1\n");
  const auto missing = sandbox.run("table nowhere");
  EXPECT_EQ(missing.exit_code, 1);
  EXPECT_EQ(missing.err, "isg table: error: nowhere: not a run folder (no metrics.json)\n");
}

TEST(Run, BadInputAndUsage) {
  testing::Sandbox sandbox("run_errors");
  const auto help = sandbox.run("run --help");
  EXPECT_EQ(help.exit_code, 0);
  EXPECT_THAT(help.out, HasSubstr("builtin:d1.asbuilt"));
  const auto method = sandbox.run("run --method magic");
  EXPECT_EQ(method.exit_code, 2);
  const auto missing = sandbox.run("run nowhere.json -o r");
  EXPECT_EQ(missing.exit_code, 1);
  EXPECT_FALSE(sandbox.exists("r"));
  sandbox.write("taken", "x");
  const auto taken = sandbox.run("run builtin:d1 -o taken");
  EXPECT_EQ(taken.exit_code, 1);
  EXPECT_EQ(taken.err, "isg run: error: taken: exists and is not a folder; give a run folder\n");
  // Dead reckoning knows the true start: localized from the first pose, in B.
  const auto dead = sandbox.run("run builtin:d2 --method dead-reckoning --duration 10 -o dr -q");
  ASSERT_EQ(dead.exit_code, 0) << dead.err;
  const auto metrics = nlohmann::json::parse(sandbox.read("dr/metrics.json"));
  EXPECT_EQ(metrics["method"], "odometry");  // dead-reckoning is its old name
  EXPECT_NEAR(metrics["time_to_localize"].get<double>(), 0.0, 0.2);
  EXPECT_NEAR(metrics["ape_B"]["rmse"].get<double>(),
              metrics["ape_odometry_from_true_start"]["rmse"].get<double>(), 0.01);
  // By then it had walked (at 0.5 m/s) at most 0.1 m, standing in its start room only.
  EXPECT_LT(metrics["distance_to_localize"].get<double>(), 0.1);
  EXPECT_EQ(metrics["rooms_visited_to_localize"].get<int>(), 1);
  const auto rooms = sandbox.run("table dr --measure rooms-to-localize --format csv");
  ASSERT_EQ(rooms.exit_code, 0) << rooms.err;
  EXPECT_NE(rooms.out.find("d2,1.000"), std::string::npos) << rooms.out;
}

}  // namespace
}  // namespace isg::cli

namespace isg::cli {
namespace {

TEST(Eval, ReportsWhenTheEstimateStarts) {
  testing::Sandbox sandbox("eval_coverage");
  sandbox.write(
      "gt.tum",
      "0 0 0 0 0 0 0 1\n1 1 0 0 0 0 0 1\n2 2 0 0 0 0 0 1\n3 3 0 0 0 0 0 1\n4 4 0 0 0 0 0 1\n");
  sandbox.write("est.tum", "1 1 0 0 0 0 0 1\n2 2 0 0 0 0 0 1\n3 3 0 0 0 0 0 1\n4 4 0 0 0 0 0 1\n");
  auto result = sandbox.run("eval gt.tum est.tum");
  EXPECT_EQ(result.exit_code, 0) << result.err;
  EXPECT_THAT(result.out, HasSubstr("localized after 1.00 s, for 75.0 % of the run\n"));
  result = sandbox.run("eval gt.tum est.tum --json");
  const auto doc = nlohmann::json::parse(result.out);
  EXPECT_EQ(doc["localized"], true);
  EXPECT_DOUBLE_EQ(doc["share_localized"].get<double>(), 0.75);
}

}  // namespace
}  // namespace isg::cli

namespace isg::cli {
namespace {

// `text` with the first `from` replaced by `to` (a failure when there is none).
std::string replaced(std::string text, const std::string& from, const std::string& to) {
  const std::size_t at = text.find(from);
  EXPECT_NE(at, std::string::npos) << from;
  return at == std::string::npos ? text : text.replace(at, from.size(), to);
}

// small.ifc's text, for variants of it written in a test's sandbox.
std::string smallIfcText() {
  std::ifstream in(std::string(ISG_SOURCE_DIR) + "/ifc/tests/models/small.ifc");
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

std::string ifcModel(const std::string& name) {
  return "'" + std::string(ISG_SOURCE_DIR) + "/ifc/tests/models/" + name + "'";
}

TEST(Import, WritesAPlanCheckAcceptsAndSummarises) {
  testing::Sandbox sandbox("import_small");
  auto result = sandbox.run("import " + ifcModel("small.ifc") + " -o small.json");
  EXPECT_EQ(result.exit_code, 0) << result.err;
  // Counts of one in the singular.
  EXPECT_THAT(result.err, HasSubstr("storey \"Ground\" (0.000 m) -> level Ground: 1 wall (0 of "
                                    "another storey standing on it), 1 door, 0 windows, 1 room "
                                    "of 1 space\n"));
  EXPECT_THAT(result.err, HasSubstr("isg import: wrote small.json: 1 level, 1 wall, 1 door, 0 "
                                    "windows, 1 room; 0 elements left out or simplified\n"));
  const auto plan = nlohmann::json::parse(sandbox.read("small.json"));
  EXPECT_EQ(plan["imported_from"]["schema"], "IFC4");
  EXPECT_EQ(plan["levels"][0]["walls"][0]["id"], "7YvctVUKr0kugbFTf53O9L");
  EXPECT_EQ(plan["levels"][0]["walls"][0]["name"], "Wall A");
  EXPECT_EQ(plan["levels"][0]["doors"][0]["offset"], 2.45);
  result = sandbox.run("check small.json");
  EXPECT_EQ(result.exit_code, 0) << result.err;
  EXPECT_EQ(result.out,
            "small.json: ok: plan \"small\" (small.json): 1 level, 1 wall, 1 door, 1 room\n");
}

// When the only wall cannot be read, nothing is written and the error itself says why, element by
// element (the summary that lists them never prints), with what IFC++ said while reading; a
// length IFC requires positive but the file gives negative is said even where IFC++ builds it.
TEST(Import, EveryElementLeftOutIsNamedEvenWhenNothingIsWritten) {
  testing::Sandbox sandbox("import_bad_wall");
  const std::string small = smallIfcText();
  const auto variant = [&](const std::string& name, const std::string& from,
                           const std::string& to) {
    sandbox.write(name, replaced(small, from, to));
  };
  const std::string profile = "#78=IFCRECTANGLEPROFILEDEF(.AREA.,$,#79,5.,0.2);";
  variant("zero.ifc", profile, "#78=IFCRECTANGLEPROFILEDEF(.AREA.,$,#79,5.,0.);");
  variant("missing.ifc", "#77=IFCEXTRUDEDAREASOLID(#78,#80,#81,3.);",
          "#77=IFCEXTRUDEDAREASOLID(#999999,#80,#81,3.);");
  variant("negative.ifc", profile, "#78=IFCRECTANGLEPROFILEDEF(.AREA.,$,#79,5.,-0.3);");
  const std::string door_line =
      "dropped door 9YvctVUKr0kugbFTf53O9L \"Door 1\": it fills no opening of an imported wall "
      "(a partition or free-standing door, or its wall was left out))";
  auto r = sandbox.run("import zero.ifc -o zero.json");
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_EQ(r.err,
            "isg import: error: zero.ifc: no wall the import could read: nothing to import (2 "
            "elements left out or simplified: dropped wall 7YvctVUKr0kugbFTf53O9L \"Wall A\": no "
            "body geometry IFC++ could build (IFC requires these lengths positive: #78 "
            "IfcRectangleProfileDef YDim 0); " +
                door_line + "\n");
  r = sandbox.run("import missing.ifc -o missing.json");
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_THAT(r.err, HasSubstr("dropped wall 7YvctVUKr0kugbFTf53O9L \"Wall A\": no body geometry "
                               "IFC++ could build; " +
                               door_line));
  EXPECT_THAT(r.err, HasSubstr("; IFC++ reported 2 errors while reading (first: "
                               "#77=IfcExtrudedAreaSolid: readEntityReference: object with id "
                               "999999 not found)\n"));
  r = sandbox.run("import negative.ifc -o negative.json");
  EXPECT_EQ(r.exit_code, 0) << r.err;
  EXPECT_THAT(r.err, HasSubstr("simplified wall 7YvctVUKr0kugbFTf53O9L \"Wall A\": IFC requires "
                               "these lengths of its body positive: #78 IfcRectangleProfileDef "
                               "YDim -0.3; IFC++ builds a negative one mirrored, and that body is "
                               "used\n"));
  EXPECT_FALSE(sandbox.exists("zero.json"));
  EXPECT_FALSE(sandbox.exists("missing.json"));
}

// The plan's limit of walls a level holds is checked while the model is read: at once from the
// text when no spread over its storeys could keep to it, else as a storey's walls are counted.
TEST(Import, TooManyWallsAreRefusedWhileReading) {
  testing::Sandbox sandbox("import_many_walls");
  const std::string small = smallIfcText();
  // 25 000 copies of the wall, all in storey Ground.
  std::string walls, members;
  for (int k = 0; k < 25000; ++k) {
    const std::string id = "#" + std::to_string(1000000 + k);
    walls += id + "=IFCWALL('W" + std::to_string(100000 + k) + "',$,'Wall " + std::to_string(k) +
             "',$,$,#71,#75,$,.STANDARD.);\n";
    members += (k == 0 ? "" : ",") + id;
  }
  walls += "#999990=IFCRELCONTAINEDINSPATIALSTRUCTURE('ZZvctVUKr0kugbFTf53O9L',$,$,$,(" + members +
           "),#50);\n";
  std::string one = small;
  one.insert(one.rfind("ENDSEC;"), walls);
  sandbox.write("one.ifc", one);
  auto r = sandbox.run("import one.ifc -o one.json");
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_EQ(r.err,
            "isg import: error: one.ifc: 25001 walls in 1 storey; at most 20000 a level are "
            "supported (docs/formats.md, Limits), however they are spread\n");
  // With a second storey they could be spread; they are not.
  std::string two = one;
  two.insert(two.find("#50=IFCBUILDINGSTOREY"),
             "#49=IFCBUILDINGSTOREY('1ZvctVUKr0kugbFTf53O9L',$,'Upper',$,$,#51,$,$,.ELEMENT.,3.);"
             "\n");
  sandbox.write("two.ifc", two);
  r = sandbox.run("import two.ifc -o two.json");
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_EQ(r.err,
            "isg import: error: two.ifc: storey \"Ground\": more than 20000 walls; at most 20000 a "
            "level are supported (docs/formats.md, Limits)\n");
  EXPECT_FALSE(sandbox.exists("one.json"));
  EXPECT_FALSE(sandbox.exists("two.json"));
}

// IfcOpenShell's conventions (FreeCAD's exports): spaces contained in their storey rather than
// aggregated, and doors that no IfcRelFillsElement links to their opening. Both imported as the
// linked model is, and said.
TEST(Import, SpacesContainedAndDoorsUnlinkedAreReadAndSaid) {
  testing::Sandbox sandbox("import_conventions");
  const std::string small = smallIfcText();
  std::string contained = replaced(small, "(#70,#100),#50);", "(#70,#100,#140),#50);");
  contained = replaced(contained,
                       "#160=IFCRELAGGREGATES('EYvctVUKr0kugbFTf53O9L',$,$,$,#50,(#140));\n", "");
  sandbox.write("contained.ifc", contained);
  auto r = sandbox.run("import contained.ifc -o contained.json");
  EXPECT_EQ(r.exit_code, 0) << r.err;
  EXPECT_THAT(r.err, HasSubstr("simplified space DYvctVUKr0kugbFTf53O9L \"101\": contained in its "
                               "storey (IfcRelContainedInSpatialStructure) rather than aggregated "
                               "(IfcRelAggregates): taken as a space of the storey\n"));
  EXPECT_THAT(r.err, HasSubstr("1 door, 0 windows, 1 room of 1 space\n"));
  // The door placed in its opening with a body, and the link removed.
  std::string unlinked =
      replaced(small, "#131=IFCRELFILLSELEMENT('CYvctVUKr0kugbFTf53O9L',$,$,$,#110,#100);\n", "");
  unlinked = replaced(unlinked, "'Door 1',$,$,#51,$,$,2.1", "'Door 1',$,$,#111,#175,$,2.1");
  unlinked.insert(unlinked.rfind("ENDSEC;"),
                  "#175=IFCPRODUCTDEFINITIONSHAPE($,$,(#176));\n"
                  "#176=IFCSHAPEREPRESENTATION(#20,'Body','SweptSolid',(#177));\n"
                  "#177=IFCEXTRUDEDAREASOLID(#178,#80,#81,2.1);\n"
                  "#178=IFCRECTANGLEPROFILEDEF(.AREA.,$,#119,0.9,0.05);\n");
  sandbox.write("unlinked.ifc", unlinked);
  r = sandbox.run("import unlinked.ifc -o unlinked.json");
  EXPECT_EQ(r.exit_code, 0) << r.err;
  EXPECT_THAT(r.err, HasSubstr("simplified door 9YvctVUKr0kugbFTf53O9L \"Door 1\": no "
                               "IfcRelFillsElement names its opening: it fills opening "
                               "AYvctVUKr0kugbFTf53O9L of wall 7YvctVUKr0kugbFTf53O9L, in which it "
                               "lies\n"));
  ASSERT_EQ(sandbox.run("import " + ifcModel("small.ifc") + " -o linked.json").exit_code, 0);
  const auto doors = [&](const std::string& file) {
    return nlohmann::json::parse(sandbox.read(file))["levels"][0]["doors"];
  };
  EXPECT_EQ(doors("unlinked.json"), doors("linked.json"));
  EXPECT_EQ(sandbox.run("check unlinked.json").err, "");
}

// A storey with walls but no IfcSpace (a building under construction) is imported by default, its
// rooms the free space its walls enclose, and said; a storey whose walls are all another's is not.
TEST(Import, AStoreyWithoutSpacesGetsTheRoomsItsWallsEnclose) {
  testing::Sandbox sandbox("import_no_spaces");
  const auto r = sandbox.run("import " + ifcModel("storey_without_spaces.ifc") + " -o plan.json");
  EXPECT_EQ(r.exit_code, 0) << r.err;
  EXPECT_THAT(r.err, HasSubstr("simplified storey FYvctVUKr0kugbFTf53O9L \"Upper\": no space "
                               "(IfcSpace) in it: its rooms are the free spaces its walls enclose, "
                               "doors closed (1 room; 0 pockets under 1.000 m² left out)\n"));
  EXPECT_THAT(r.err, HasSubstr("storey \"Upper\" (3.000 m) -> level Upper: 4 walls (0 of another "
                               "storey standing on it), 0 doors, 0 windows, 1 room of 0 spaces\n"));
  const auto plan = nlohmann::json::parse(sandbox.read("plan.json"));
  ASSERT_EQ(plan["levels"].size(), 2u);
  EXPECT_EQ(plan["levels"][1]["rooms"][0]["id"], "Upper-room-1");
  EXPECT_EQ(plan["levels"][1]["rooms"][0]["outline"],
            nlohmann::json::parse("[[0.1, 0.1], [3.9, 0.1], [3.9, 2.9], [0.1, 2.9]]"));
  const auto check = sandbox.run("check plan.json");
  EXPECT_EQ(check.exit_code, 0);
  EXPECT_EQ(check.err, "");
}

TEST(Import, ReplacesOnlyAPlanItWroteAndOnlyWithForce) {
  testing::Sandbox sandbox("import_force");
  sandbox.write("mine.json", "{\"format\": \"isg.plan\", \"version\": 1, \"levels\": []}\n");
  auto result = sandbox.run("import " + ifcModel("small.ifc") + " -o mine.json --force");
  EXPECT_EQ(result.exit_code, 1);
  EXPECT_THAT(result.err, HasSubstr("mine.json"));
  EXPECT_EQ(sandbox.read("mine.json"),
            "{\"format\": \"isg.plan\", \"version\": 1, \"levels\": []}\n");
  EXPECT_EQ(sandbox.run("import " + ifcModel("small.ifc") + " -o p.json -q").exit_code, 0);
  result = sandbox.run("import " + ifcModel("small.ifc") + " -o p.json -q");
  EXPECT_EQ(result.exit_code, 1);
  EXPECT_THAT(result.err, HasSubstr("--force"));
  EXPECT_EQ(sandbox.run("import " + ifcModel("small.ifc") + " -o p.json -q --force").exit_code, 0);
}

TEST(Import, BadModelsExitOneAndWriteNothing) {
  testing::Sandbox sandbox("import_bad");
  sandbox.write("plan.ifc", "{\"format\": \"isg.plan\"}");
  auto result = sandbox.run("import plan.ifc -o out.json");
  EXPECT_EQ(result.exit_code, 1);
  EXPECT_EQ(result.err,
            "isg import: error: plan.ifc: not an IFC file: an IFC (STEP, ISO "
            "10303-21) file starts with \"ISO-10303-21;\"\n");
  sandbox.write("new.ifc",
                "ISO-10303-21;\nHEADER;\nFILE_SCHEMA(('IFC4X3_ADD2'));\nENDSEC;\nDATA;\nENDSEC;\n"
                "END-ISO-10303-21;\n");
  result = sandbox.run("import new.ifc -o out.json");
  EXPECT_EQ(result.exit_code, 1);
  EXPECT_EQ(result.err,
            "isg import: error: new.ifc: schema IFC4X3_ADD2 is not supported: the "
            "import reads IFC2X3 and IFC4 (export the model as one of them)\n");
  result = sandbox.run("import missing.ifc -o out.json");
  EXPECT_EQ(result.exit_code, 1);
  EXPECT_THAT(result.err, StartsWith("isg import: error: missing.ifc: "));
  // A model that makes IFC++ crash (found by ci/fuzz) is a bad model like any other.
  result = sandbox.run("import " + ifcModel("bad/ifcpp_null_polyline_point.ifc") + " -o out.json");
  EXPECT_EQ(result.exit_code, 1);
  EXPECT_THAT(result.err, HasSubstr(": IFC++ stopped with signal "));
  EXPECT_FALSE(sandbox.exists("out.json"));
  result = sandbox.run("import " + ifcModel("small.ifc") + " -o out.json --storey Attic");
  EXPECT_EQ(result.exit_code, 1);
  EXPECT_THAT(result.err, HasSubstr("no storey named \"Attic\" (--storey); its storeys: "
                                    "\"Ground\"\n"));
  EXPECT_FALSE(sandbox.exists("out.json"));
}

TEST(Vlp16, ReportsARealRecordingsReturnsAndWritesNothing) {
  testing::Sandbox sandbox("vlp16");
  const std::string data = std::string(ISG_SOURCE_DIR) + "/formats/tests/data/vlp16-real/";
  auto result = sandbox.run("vlp16 '" + data + "nebula-vlp16-indoor.db3'");
  EXPECT_EQ(result.exit_code, 0) << result.err;
  EXPECT_THAT(result.out, HasSubstr(": 603 data packets (dual return), 0 position packets"));
  EXPECT_THAT(result.out, HasSubstr("shots without an echo: 49.3 %; by ring (-15 ... +15 deg): "
                                    "100 99 85 78 77 58 53 48 34 32 23 26 22 18 19 17 %"));
  EXPECT_THAT(result.out, HasSubstr("reflectivity: median 33, 99th percentile 100, max 121"));
  EXPECT_THAT(result.out, HasSubstr("per complete turn (3 of them): 14848 returns over 0.1000 s"));
  result = sandbox.run("vlp16 --json '" + data + "rust-lidar-utils-vlp16-outdoor.pcap'");
  EXPECT_EQ(result.exit_code, 0) << result.err;
  EXPECT_THAT(result.out, HasSubstr("\"data_packets\": 84,"));
  EXPECT_THAT(result.out, HasSubstr("\"position_packets\": 16,"));
  EXPECT_THAT(result.out, HasSubstr("\"return_mode\": \"strongest\","));
  EXPECT_TRUE(std::filesystem::is_empty(sandbox.dir()));

  result = sandbox.run("vlp16 '" + data + "nebula-vlp16-indoor.db3' --topic /points");
  EXPECT_EQ(result.exit_code, 1);
  EXPECT_EQ(result.err, "isg vlp16: error: " + data +
                            "nebula-vlp16-indoor.db3: no topic /points (the bag has: "
                            "/velodyne_packets)\n");
  result = sandbox.run("vlp16 missing.pcap");
  EXPECT_EQ(result.exit_code, 1);
  EXPECT_THAT(result.err, StartsWith("isg vlp16: error: missing.pcap: "));
  result = sandbox.run("vlp16 '" + data + "nebula-vlp16-indoor.db3' --min-range 5 --max-range 2");
  EXPECT_EQ(result.exit_code, 2);
}

// A level the tour cannot reach (its flight blocked) is a warning naming the flight and why, and
// is listed in the dataset's skipped_levels.
TEST(Simulate, ALevelTheTourCannotReachIsWarnedAndListed) {
  testing::Sandbox sandbox("tour_skipped_level");
  auto scenario = nlohmann::json::parse(
      std::ifstream(std::string(ISG_SOURCE_DIR) + "/worlds/plans/storeys.asbuilt.json"));
  scenario["plan"] = std::string(ISG_SOURCE_DIR) + "/worlds/plans/storeys.json";
  scenario["as_built"]["clutter"] = nlohmann::json::parse(
      R"([{"shape": "box", "center": [7.6, 0.85, 0.4], "size": [2.6, 1.0, 0.8], "yaw": 0}])");
  sandbox.write("blocked.json", scenario.dump(2));
  const auto r = sandbox.run("simulate blocked.json --duration 2 -o ds -q");
  EXPECT_EQ(r.exit_code, 0) << r.err;
  EXPECT_THAT(r.err, HasSubstr("isg simulate: warning: level L1 cannot be reached (flight \"S1\" "
                               "cannot be reached from ("));
  EXPECT_THAT(r.err, HasSubstr(") or stepped off, keeping 0.35 m from walls and clutter); the tour "
                               "skips it\n"));
  const auto metadata = nlohmann::json::parse(sandbox.read("ds/metadata.json"));
  EXPECT_EQ(metadata["robot"]["skipped_levels"], nlohmann::json::parse(R"(["L1"])"));
}

// An input path the system cannot follow (a symlink loop) is bad input, exit 1, named: never an
// internal error.
TEST(Inputs, ASymbolicLinkLoopIsBadInputNamed) {
  testing::Sandbox sandbox("input_loop");
  std::filesystem::create_symlink("loop", sandbox.dir() / "loop");
  for (const std::string& arguments :
       {std::string("check loop"), std::string("slam loop -o r"),
        std::string("export loop --rosbag x.bag"), std::string("import loop -o p.json"),
        std::string("table loop"), std::string("run loop -o r"), std::string("world loop")}) {
    const auto r = sandbox.run(arguments);
    EXPECT_EQ(r.exit_code, 1) << arguments << ": " << r.err;
    EXPECT_THAT(r.err, HasSubstr("loop")) << arguments;
    EXPECT_THAT(r.err, HasSubstr("Too many levels of symbolic links")) << arguments;
    EXPECT_THAT(r.err, Not(HasSubstr("internal error"))) << arguments;
  }
}

// --compression says how the MCAP file is compressed: without --mcap it would be ignored unsaid.
TEST(Usage, CompressionWithoutMcapIsAUsageError) {
  testing::Sandbox sandbox("compression_alone");
  for (const std::string& arguments :
       {std::string("run builtin:d1 --duration 1 --compression lz4 -o r -q"),
        std::string("simulate builtin:d1 --duration 1 --compression none -o ds -q"),
        std::string("export ds --rosbag b.bag --compression zstd")}) {
    const auto r = sandbox.run(arguments);
    EXPECT_EQ(r.exit_code, 2) << arguments;
    EXPECT_THAT(r.err, HasSubstr("--compression requires --mcap")) << arguments;
  }
  EXPECT_FALSE(sandbox.exists("r"));
  EXPECT_FALSE(sandbox.exists("ds"));
}

}  // namespace
}  // namespace isg::cli
