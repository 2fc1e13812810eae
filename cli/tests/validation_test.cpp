// Every validation rule of docs/formats.md, fed to the real `isg world` as a bad file: the message
// names the file, the JSON pointer and what is wrong, the exit code is 1, nothing is written.
#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <nlohmann/json.hpp>

#include "bim/tests/test_plans.hpp"
#include "cli/tests/cli_runner.hpp"

namespace isg::cli {
namespace {

using nlohmann::json;

// The two-room plan of the bim tests: every case below breaks one rule of it.
json validPlan() { return bim::testing::twoRoomPlanJson(); }

json validScenario() {
  return json::parse(R"({
    "format": "isg.scenario", "version": 1, "plan": "plan.json", "seed": 7,
    "robot": {"level": "L0", "start": {"room": "R1"}, "route": "tour", "speed": 0.5},
    "lidar": {"rate_hz": 10, "range_noise_m": 0.01, "min_range_m": 0.9, "max_range_m": 100.0,
              "dropout": 0.0, "mount": [0.0, 0.0, 0.25, 0.0, 0.0, 0.0]},
    "odometry": {"rate_hz": 50, "translation_noise": 0.02, "heading_noise_deg_per_m": 0.5},
    "as_built": {
      "missing_walls": [], "extra_walls": [{"start": [1, 1], "end": [1, 2], "thickness": 0.1}],
      "wall_shifts": [{"wall": "W5", "offset": 0.05}], "closed_doors": ["D1"],
      "clutter": [{"shape": "box", "center": [4, 3, 0.5], "size": [1, 1, 1], "yaw": 0.3}]
    }
  })");
}

struct Case {
  std::string name;
  // Which file is fed to `isg world`: "plan.json" or "scenario.json" (which names plan.json).
  std::string input;
  std::function<void(json& plan, json& scenario)> mutate;
  std::string expected;  // the whole of stderr after "isg world: error: "
  std::function<std::string(std::string)> edit_text = nullptr;  // on plan.json's text
};

std::ostream& operator<<(std::ostream& out, const Case& c) { return out << c.name; }

std::vector<Case> cases() {
  auto walls = [](json& p) -> json& { return p["levels"][0]["walls"]; };
  auto doors = [](json& p) -> json& { return p["levels"][0]["doors"]; };
  auto level = [](json& p) -> json& { return p["levels"][0]; };
  auto rooms = [](json& p) -> json& { return p["levels"][0]["rooms"]; };
  return {
      // --- plan: format and version
      {"UnknownFormat", "plan.json", [](json& p, json&) { p["format"] = "isg.blueprint"; },
       "plan.json: /format: unknown format \"isg.blueprint\" (expected \"isg.plan\" or "
       "\"isg.scenario\")"},
      {"UnknownVersion", "plan.json", [](json& p, json&) { p["version"] = 2; },
       "plan.json: /version: unsupported version 2 (this build reads version 1)"},
      {"MissingFormat", "plan.json", [](json& p, json&) { p.erase("format"); },
       "plan.json: /format: missing required field"},
      // --- missing or mistyped fields
      {"MissingField", "plan.json", [=](json& p, json&) { walls(p)[3].erase("thickness"); },
       "plan.json: /levels/0/walls/3/thickness: missing required field"},
      {"MistypedNumber", "plan.json", [=](json& p, json&) { walls(p)[3]["thickness"] = "0.2"; },
       "plan.json: /levels/0/walls/3/thickness: expected a number, got a string"},
      {"MistypedPoint", "plan.json",
       [=](json& p, json&) {
         walls(p)[1]["end"] = {6, 4, 0};
       },
       "plan.json: /levels/0/walls/1/end: expected an array of 2 numbers, got 3 elements"},
      {"MistypedArray", "plan.json", [=](json& p, json&) { p["levels"][0]["rooms"] = "R1"; },
       "plan.json: /levels/0/rooms: expected an array, got a string"},
      {"NoLevels", "plan.json", [](json& p, json&) { p["levels"] = json::array(); },
       "plan.json: /levels: expected at least 1 element, got 0"},
      {"NonFiniteNumber", "plan.json", [](json&, json&) {},
       "plan.json: /levels/0/walls/4/thickness: number overflow parsing '1e999' at line 1, column "
       "692 (numbers must be finite)",
       [](std::string text) {
         const std::string key = "\"thickness\":0.1";
         return text.replace(text.find(key), key.size(), "\"thickness\":1e999");
       }},
      {"InvalidJson", "plan.json", [](json&, json&) {},
       "plan.json: invalid JSON at line 1, column 2: syntax error while parsing object key - "
       "unexpected ','; expected string literal",
       [](std::string text) { return "{," + text; }},
      // --- walls
      {"ZeroLengthWall", "plan.json",
       [=](json& p, json&) {
         walls(p)[1]["end"] = {6, 0};
       },
       "plan.json: /levels/0/walls/1/end: zero-length wall: end equals start [6, 0]"},
      {"ZeroThickness", "plan.json", [=](json& p, json&) { walls(p)[2]["thickness"] = 0; },
       "plan.json: /levels/0/walls/2/thickness: must be in [0.001, 10], got 0"},
      {"NegativeThickness", "plan.json", [=](json& p, json&) { walls(p)[2]["thickness"] = -0.1; },
       "plan.json: /levels/0/walls/2/thickness: must be in [0.001, 10], got -0.1"},
      {"BaseAboveTop", "plan.json", [=](json& p, json&) { walls(p)[4]["base"] = 2.8; },
       "plan.json: /levels/0/walls/4/base: base 2.8 is not below the wall's top at 2.8"},
      // --- doors
      {"DoorPastWallEnd", "plan.json", [=](json& p, json&) { doors(p)[0]["offset"] = 3.7; },
       "plan.json: /levels/0/doors/0/offset: opening from 3.25 to 4.15 m along the wall does not "
       "fit inside wall \"W5\" (length 4 m)"},
      {"DoorBeforeWallStart", "plan.json", [=](json& p, json&) { doors(p)[1]["offset"] = 0.4; },
       "plan.json: /levels/0/doors/1/offset: opening from -0.1 to 0.9 m along the wall does not "
       "fit inside wall \"W1\" (length 6 m)"},
      {"DoorTallerThanWall", "plan.json", [=](json& p, json&) { doors(p)[0]["height"] = 2.9; },
       "plan.json: /levels/0/doors/0/height: door is 2.9 m high, taller than wall \"W5\" (2.8 m "
       "above its base)"},
      {"DoorTallerThanRaisedWall", "plan.json", [=](json& p, json&) { walls(p)[4]["base"] = 1.0; },
       "plan.json: /levels/0/doors/0/height: door is 2.1 m high, taller than wall \"W5\" (1.8 m "
       "above its base)"},
      {"OverlappingDoors", "plan.json",
       [=](json& p, json&) {
         doors(p).push_back(
             {{"id", "D3"}, {"wall", "W5"}, {"offset", 2.5}, {"width", 0.9}, {"height", 2.0}});
       },
       "plan.json: /levels/0/doors/2/offset: opening overlaps door \"D1\" on wall \"W5\""},
      // Windows: W2 is 4 m long and 3 m high; D2 opens W1 from 4.0 to 5.0 m.
      {"WindowOnUnknownWall", "plan.json",
       [=](json& p, json&) {
         level(p)["windows"] = {{{"id", "V1"},
                                 {"wall", "W9"},
                                 {"offset", 2.0},
                                 {"width", 1.0},
                                 {"sill", 0.9},
                                 {"height", 1.2}}};
       },
       "plan.json: /levels/0/windows/0/wall: no wall \"W9\" on level \"L0\""},
      {"WindowOutsideItsWall", "plan.json",
       [=](json& p, json&) {
         level(p)["windows"] = {{{"id", "V1"},
                                 {"wall", "W2"},
                                 {"offset", 3.8},
                                 {"width", 1.0},
                                 {"sill", 0.9},
                                 {"height", 1.2}}};
       },
       "plan.json: /levels/0/windows/0/offset: opening from 3.3 to 4.3 m along the wall does not "
       "fit inside wall \"W2\" (length 4 m)"},
      {"WindowAboveItsWall", "plan.json",
       [=](json& p, json&) {
         level(p)["windows"] = {{{"id", "V1"},
                                 {"wall", "W2"},
                                 {"offset", 2.0},
                                 {"width", 1.0},
                                 {"sill", 1.9},
                                 {"height", 1.2}}};
       },
       "plan.json: /levels/0/windows/0/height: window reaches 3.1 m above the wall's base, above "
       "the top of wall \"W2\" (3 m above its base)"},
      {"WindowOverlappingADoor", "plan.json",
       [=](json& p, json&) {
         level(p)["windows"] = {{{"id", "V1"},
                                 {"wall", "W1"},
                                 {"offset", 5.2},
                                 {"width", 0.8},
                                 {"sill", 0.9},
                                 {"height", 1.2}}};
       },
       "plan.json: /levels/0/windows/0/offset: opening overlaps door \"D2\" on wall \"W1\""},
      {"DoorOnUnknownWall", "plan.json", [=](json& p, json&) { doors(p)[0]["wall"] = "W9"; },
       "plan.json: /levels/0/doors/0/wall: no wall \"W9\" on level \"L0\""},
      {"DoorToUnknownRoom", "plan.json",
       [=](json& p, json&) {
         doors(p)[1]["rooms"] = {"R2", "R7"};
       },
       "plan.json: /levels/0/doors/1/rooms/1: no room \"R7\" on level \"L0\" (use \"outside\" for "
       "the outside)"},
      {"DoorJoiningOneRoom", "plan.json",
       [=](json& p, json&) {
         doors(p)[1]["rooms"] = {"R2", "R2"};
       },
       "plan.json: /levels/0/doors/1/rooms: a door joins two different rooms, got \"R2\" twice"},
      {"DoorWithThreeRooms", "plan.json",
       [=](json& p, json&) {
         doors(p)[1]["rooms"] = {"R1", "R2", "outside"};
       },
       "plan.json: /levels/0/doors/1/rooms: a door joins exactly 2 rooms, got 3"},
      // --- rooms
      {"OutlineTooShort", "plan.json",
       [=](json& p, json&) {
         rooms(p)[0]["outline"] = {{0.1, 0.1}, {2.95, 0.1}};
       },
       "plan.json: /levels/0/rooms/0/outline: an outline needs at least 3 vertices, got 2"},
      {"SelfIntersectingOutline", "plan.json",
       [=](json& p, json&) {
         rooms(p)[0]["outline"] = {{0.1, 0.1}, {2.95, 3.9}, {2.95, 0.1}, {0.1, 3.9}};
       },
       "plan.json: /levels/0/rooms/0/outline: self-intersecting outline: edge 0 [0.1, 0.1]→[2.95, "
       "3.9] meets edge 2 [2.95, 0.1]→[0.1, 3.9]"},
      {"RepeatedVertex", "plan.json",
       [=](json& p, json&) {
         rooms(p)[0]["outline"] = {{0.1, 0.1}, {2.95, 0.1}, {2.95, 0.1}, {0.1, 3.9}};
       },
       "plan.json: /levels/0/rooms/0/outline: zero-length edge 1: vertex 1 repeats at [2.95, 0.1]"},
      {"ReservedRoomId", "plan.json", [=](json& p, json&) { rooms(p)[0]["id"] = "outside"; },
       "plan.json: /levels/0/rooms/0/id: \"outside\" is reserved for the outside of the building"},
      // --- ids
      {"DuplicateId", "plan.json", [=](json& p, json&) { rooms(p)[1]["id"] = "W3"; },
       "plan.json: /levels/0/rooms/1/id: duplicate id \"W3\" (first used at "
       "/levels/0/walls/2/id)"},
      {"EmptyId", "plan.json", [=](json& p, json&) { walls(p)[0]["id"] = ""; },
       "plan.json: /levels/0/walls/0/id: must not be empty"},
      // --- scenario
      {"MissingPlanFile", "scenario.json", [](json&, json& s) { s["plan"] = "nowhere.json"; },
       "scenario.json: /plan: plan file \"nowhere.json\" does not exist"},
      {"ErrorInsideReferencedPlan", "scenario.json",
       [=](json& p, json&) { walls(p)[0]["thickness"] = 0; },
       "plan.json: /levels/0/walls/0/thickness: must be in [0.001, 10], got 0"},
      {"ErrorInsideInlinePlan", "scenario.json",
       [=](json& p, json& s) {
         walls(p)[0]["thickness"] = 0;
         s["plan"] = p;
       },
       "scenario.json: /plan/levels/0/walls/0/thickness: must be in [0.001, 10], got 0"},
      {"ScenarioUnknownVersion", "scenario.json", [](json&, json& s) { s["version"] = 3; },
       "scenario.json: /version: unsupported version 3 (this build reads version 1)"},
      {"NegativeSeed", "scenario.json", [](json&, json& s) { s["seed"] = -1; },
       "scenario.json: /seed: must be >= 0, got -1"},
      {"UnknownLevel", "scenario.json", [](json&, json& s) { s["robot"]["level"] = "L9"; },
       "scenario.json: /robot/level: no level \"L9\" in the plan"},
      {"UnknownStartRoom", "scenario.json",
       [](json&, json& s) { s["robot"]["start"]["room"] = "R9"; },
       "scenario.json: /robot/start/room: no room \"R9\" on level \"L0\""},
      {"StartRoomAndPose", "scenario.json",
       [](json&, json& s) {
         s["robot"]["start"]["pose"] = {1, 1, 0};
       },
       "scenario.json: /robot/start: give exactly one of \"room\" and \"pose\""},
      {"StartInsideWall", "scenario.json",
       [](json&, json& s) {
         s["robot"]["start"] = {{"pose", {3.02, 1.0, 0.0}}};
       },
       "scenario.json: /robot/start/pose: start position is inside wall \"W5\""},
      {"UnknownRoute", "scenario.json", [](json&, json& s) { s["robot"]["route"] = "spiral"; },
       "scenario.json: /robot/route: unknown route \"spiral\" (expected \"tour\")"},
      {"RouteToUnknownRoom", "scenario.json",
       [](json&, json& s) {
         s["robot"]["route"] = {{"rooms", {"R1", "R5"}}};
       },
       "scenario.json: /robot/route/rooms/1: no room \"R5\" on level \"L0\""},
      {"KidnapNotAList", "scenario.json", [](json&, json& s) { s["robot"]["kidnap"] = 5; },
       "scenario.json: /robot/kidnap: expected an array, got a number"},
      {"KidnapAtTheStart", "scenario.json",
       [](json&, json& s) {
         s["robot"]["kidnap"] = {{{"time", 0}, {"to", {{"room", "R2"}}}}};
       },
       "scenario.json: /robot/kidnap/0/time: a kidnap must come after the start (time > 0)"},
      {"KidnapsOutOfOrder", "scenario.json",
       [](json&, json& s) {
         s["robot"]["kidnap"] = {{{"time", 20}, {"to", {{"room", "R2"}}}},
                                 {{"time", 10}, {"to", {{"room", "R3"}}}}};
       },
       "scenario.json: /robot/kidnap/1/time: kidnaps must be in time order: 10 s is not after "
       "20 s"},
      {"KidnapToUnknownRoom", "scenario.json",
       [](json&, json& s) {
         s["robot"]["kidnap"] = {{{"time", 10}, {"to", {{"room", "R9"}}}}};
       },
       "scenario.json: /robot/kidnap/0/to/room: no room \"R9\" in the plan"},
      {"KidnapToRoomWithLevel", "scenario.json",
       [](json&, json& s) {
         s["robot"]["kidnap"] = {{{"time", 10}, {"to", {{"room", "R2"}, {"level", "L0"}}}}};
       },
       "scenario.json: /robot/kidnap/0/to/level: a room names its level: give \"level\" only "
       "with \"pose\""},
      {"KidnapToUnknownLevel", "scenario.json",
       [](json&, json& s) {
         s["robot"]["kidnap"] = {
             {{"time", 10}, {"to", {{"pose", {1.0, 1.0, 0.0}}, {"level", "L4"}}}}};
       },
       "scenario.json: /robot/kidnap/0/to/level: no level \"L4\" in the plan"},
      {"KidnapToRoomAndPose", "scenario.json",
       [](json&, json& s) {
         s["robot"]["kidnap"] = {
             {{"time", 10}, {"to", {{"room", "R2"}, {"pose", {1.0, 1.0, 0.0}}}}}};
       },
       "scenario.json: /robot/kidnap/0/to: give exactly one of \"room\" and \"pose\""},
      {"KidnapIntoAWall", "scenario.json",
       [](json&, json& s) {
         s["robot"]["kidnap"] = {{{"time", 10}, {"to", {{"pose", {3.02, 1.0, 0.0}}}}}};
       },
       "scenario.json: /robot/kidnap/0/to/pose: kidnap position is inside wall \"W5\""},
      {"UnknownCarrier", "scenario.json", [](json&, json& s) { s["robot"]["carrier"] = "wheeled"; },
       "scenario.json: /robot/carrier: unknown carrier \"wheeled\" (expected \"legged\" or "
       "\"handheld\")"},
      {"HandheldWithOdometry", "scenario.json",
       [](json&, json& s) {
         s["robot"]["carrier"] = "handheld";
         s["odometry"] = {{"rate_hz", 50}};
       },
       "scenario.json: /odometry: a handheld carrier has no odometry (robot.carrier is "
       "\"handheld\")"},
      {"HandheldWithBodyOcclusion", "scenario.json",
       [](json&, json& s) {
         s["robot"]["carrier"] = "handheld";
         s.erase("odometry");
         s["lidar"] = {{"body_occlusion", true}};
       },
       "scenario.json: /lidar/body_occlusion: a handheld carrier has no robot body to occlude the "
       "LiDAR (robot.carrier is \"handheld\")"},
      {"ZeroSpeed", "scenario.json", [](json&, json& s) { s["robot"]["speed"] = 0; },
       "scenario.json: /robot/speed: must be in [0.01, 3], got 0"},
      {"LidarRate", "scenario.json", [](json&, json& s) { s["lidar"]["rate_hz"] = 40; },
       "scenario.json: /lidar/rate_hz: must be in [5, 20], got 40"},
      {"LidarRanges", "scenario.json", [](json&, json& s) { s["lidar"]["max_range_m"] = 0.5; },
       "scenario.json: /lidar/max_range_m: max_range_m 0.5 is not above min_range_m 0.9"},
      {"LidarDropout", "scenario.json", [](json&, json& s) { s["lidar"]["dropout"] = 1.0; },
       "scenario.json: /lidar/dropout: must be in [0, 1), got 1"},
      {"LidarGrazingCutoff", "scenario.json",
       [](json&, json& s) { s["lidar"]["grazing_cutoff_deg"] = 0.5; },
       "scenario.json: /lidar/grazing_cutoff_deg: must be in [1, 90], got 0.5"},
      {"LidarReflectivity", "scenario.json",
       [](json&, json& s) {
         s["lidar"]["reflectivity"] = {{"wall", 1.5}};
       },
       "scenario.json: /lidar/reflectivity/wall: must be in [0, 1], got 1.5"},
      {"LidarStamp", "scenario.json", [](json&, json& s) { s["lidar"]["stamp"] = "last"; },
       "scenario.json: /lidar/stamp: unknown value \"last\" (expected one of \"first_firing\", "
       "\"last_packet\")"},
      {"LidarReturns", "scenario.json", [](json&, json& s) { s["lidar"]["returns"] = "both"; },
       "scenario.json: /lidar/returns: unknown value \"both\" (expected one of \"strongest\", "
       "\"last\", \"dual\")"},
      {"LidarCutAngleWithPackets", "scenario.json",
       [](json&, json& s) {
         s["lidar"]["cut"] = "packets";
         s["lidar"]["cut_angle_deg"] = 90;
       },
       "scenario.json: /lidar/cut_angle_deg: cut_angle_deg needs \"cut\": \"angle\""},
      {"LidarCutAngle", "scenario.json", [](json&, json& s) { s["lidar"]["cut_angle_deg"] = 360; },
       "scenario.json: /lidar/cut_angle_deg: must be in [0, 360), got 360"},
      {"LidarMount", "scenario.json",
       [](json&, json& s) {
         s["lidar"]["mount"] = {0, 0, 0.25};
       },
       "scenario.json: /lidar/mount: expected an array of 6 numbers, got 3 elements"},
      {"OdometryNoise", "scenario.json",
       [](json&, json& s) { s["odometry"]["translation_noise"] = -0.1; },
       "scenario.json: /odometry/translation_noise: must be in [0, 1], got -0.1"},
      {"ImuRate", "scenario.json", [](json&, json& s) { s["imu"]["rate_hz"] = 5; },
       "scenario.json: /imu/rate_hz: must be in [10, 2000], got 5"},
      {"ImuMountFar", "scenario.json",
       [](json&, json& s) { s["imu"]["mount"] = {0, 12, 0, 0, 0, 0}; },
       "scenario.json: /imu/mount: the IMU must be mounted within 10 m of the robot's reference "
       "point"},
      {"ImuNoise", "scenario.json",
       [](json&, json& s) { s["imu"]["accelerometer_random_walk"] = -1; },
       "scenario.json: /imu/accelerometer_random_walk: must be in [0, 10], got -1"},
      {"MissingWallUnknown", "scenario.json",
       [](json&, json& s) { s["as_built"]["missing_walls"] = {"W8"}; },
       "scenario.json: /as_built/missing_walls/0: no wall \"W8\" in the plan"},
      {"MissingColumnUnknown", "scenario.json",
       [](json&, json& s) { s["as_built"]["missing_columns"] = {"C9"}; },
       "scenario.json: /as_built/missing_columns/0: no column \"C9\" in the plan"},
      {"MovedColumnTwice", "scenario.json",
       [](json& p, json& s) {
         p["levels"][0]["columns"] = {{{"id", "C1"}, {"center", {2, 2}}, {"size", {0.3, 0.3}}}};
         s["as_built"]["moved_columns"] = {{{"column", "C1"}, {"offset", {0.1, 0}}},
                                           {{"column", "C1"}, {"offset", {0, 0.1}}}};
       },
       "scenario.json: /as_built/moved_columns/1/column: \"C1\" is moved twice"},
      {"MovedColumnMissing", "scenario.json",
       [](json& p, json& s) {
         p["levels"][0]["columns"] = {{{"id", "C1"}, {"center", {2, 2}}, {"size", {0.3, 0.3}}}};
         s["as_built"]["missing_columns"] = {"C1"};
         s["as_built"]["moved_columns"] = {{{"column", "C1"}, {"offset", {0.1, 0}}}};
       },
       "scenario.json: /as_built/moved_columns/0/column: \"C1\" is also in missing_columns"},
      {"MovedColumnTooFar", "scenario.json",
       [](json& p, json& s) {
         p["levels"][0]["columns"] = {{{"id", "C1"}, {"center", {2, 2}}, {"size", {0.3, 0.3}}}};
         s["as_built"]["moved_columns"] = {{{"column", "C1"}, {"offset", {11, 0}}}};
       },
       "scenario.json: /as_built/moved_columns/0/offset: a column moves at most 10 m"},
      {"ShiftOfUnknownWall", "scenario.json",
       [](json&, json& s) { s["as_built"]["wall_shifts"][0]["wall"] = "W0"; },
       "scenario.json: /as_built/wall_shifts/0/wall: no wall \"W0\" in the plan"},
      {"ShiftOfMissingWall", "scenario.json",
       [](json&, json& s) { s["as_built"]["missing_walls"] = {"W5"}; },
       "scenario.json: /as_built/wall_shifts/0/wall: \"W5\" is also in missing_walls"},
      {"RotationOfUnknownWall", "scenario.json",
       [](json&, json& s) {
         s["as_built"]["wall_rotations"] = {{{"wall", "W9"}, {"angle_deg", 5}}};
       },
       "scenario.json: /as_built/wall_rotations/0/wall: no wall \"W9\" in the plan"},
      {"RotationTooLarge", "scenario.json",
       [](json&, json& s) {
         s["as_built"]["wall_rotations"] = {{{"wall", "W3"}, {"angle_deg", 50}}};
       },
       "scenario.json: /as_built/wall_rotations/0/angle_deg: must be in [-45, 45], got 50"},
      {"RotationAboutUnknownPoint", "scenario.json",
       [](json&, json& s) {
         s["as_built"]["wall_rotations"] = {
             {{"wall", "W3"}, {"angle_deg", 5}, {"about", "middle"}}};
       },
       "scenario.json: /as_built/wall_rotations/0/about: unknown point \"middle\" (expected "
       "\"start\", \"centre\", \"end\" or metres along the wall from its start)"},
      {"RotationAboutAPointOffTheWall", "scenario.json",
       [](json&, json& s) {
         s["as_built"]["wall_rotations"] = {{{"wall", "W3"}, {"angle_deg", 5}, {"about", 7}}};
       },
       "scenario.json: /as_built/wall_rotations/0/about: must be in [0, 6], got 7"},
      {"RotationTwice", "scenario.json",
       [](json&, json& s) {
         s["as_built"]["wall_rotations"] = {{{"wall", "W3"}, {"angle_deg", 5}},
                                            {{"wall", "W3"}, {"angle_deg", -5}}};
       },
       "scenario.json: /as_built/wall_rotations/1/wall: \"W3\" is rotated twice"},
      {"RotationOfMissingWall", "scenario.json",
       [](json&, json& s) {
         s["as_built"]["missing_walls"] = {"W3"};
         s["as_built"]["wall_rotations"] = {{{"wall", "W3"}, {"angle_deg", 5}}};
       },
       "scenario.json: /as_built/wall_rotations/0/wall: \"W3\" is also in missing_walls"},
      {"ShortenedUnknownWall", "scenario.json",
       [](json&, json& s) {
         s["as_built"]["shortened_walls"] = {{{"wall", "W9"}, {"built", {{0, 1}}}}};
       },
       "scenario.json: /as_built/shortened_walls/0/wall: no wall \"W9\" in the plan"},
      {"ShortenedPastItsEnd", "scenario.json",
       [](json&, json& s) {
         s["as_built"]["shortened_walls"] = {{{"wall", "W3"}, {"built", {{0, 7}}}}};
       },
       "scenario.json: /as_built/shortened_walls/0/built/0/1: must be in [0, 6], got 7 (wall "
       "\"W3\" is 6 m long)"},
      {"ShortenedEmptyPart", "scenario.json",
       [](json&, json& s) {
         s["as_built"]["shortened_walls"] = {{{"wall", "W3"}, {"built", {{2, 2}}}}};
       },
       "scenario.json: /as_built/shortened_walls/0/built/0: a part from 2 to 2 m: its end must lie "
       "past its start"},
      {"ShortenedOutOfOrder", "scenario.json",
       [](json&, json& s) {
         s["as_built"]["shortened_walls"] = {{{"wall", "W3"}, {"built", {{2, 4}, {1, 1.5}}}}};
       },
       "scenario.json: /as_built/shortened_walls/0/built/1/0: the parts must be in order along "
       "the wall and apart: this one starts at 1 m, where the one before ends at 4 m"},
      {"ShortenedNotAtAll", "scenario.json",
       [](json&, json& s) {
         s["as_built"]["shortened_walls"] = {{{"wall", "W3"}, {"built", {{0, 6}}}}};
       },
       "scenario.json: /as_built/shortened_walls/0/built: the whole wall is built (wall \"W3\" "
       "is 6 m long): nothing is shortened"},
      {"ShortenedThroughADoor", "scenario.json",
       [](json&, json& s) {
         s["as_built"]["shortened_walls"] = {{{"wall", "W1"}, {"built", {{0, 4.5}}}}};
       },
       "scenario.json: /as_built/shortened_walls/0/built: part 0 ends at 4.5 m, inside door "
       "\"D2\" (4–5 m along the wall): end it beside the opening"},
      {"ShortenedTwice", "scenario.json",
       [](json&, json& s) {
         s["as_built"]["shortened_walls"] = {{{"wall", "W3"}, {"built", {{0, 1}}}},
                                             {{"wall", "W3"}, {"built", {{2, 3}}}}};
       },
       "scenario.json: /as_built/shortened_walls/1/wall: \"W3\" is shortened twice"},
      {"ShortenedMissingWall", "scenario.json",
       [](json&, json& s) {
         s["as_built"]["missing_walls"] = {"W3"};
         s["as_built"]["shortened_walls"] = {{{"wall", "W3"}, {"built", {{0, 1}}}}};
       },
       "scenario.json: /as_built/shortened_walls/0/wall: \"W3\" is also in missing_walls"},
      {"ClosedUnknownDoor", "scenario.json",
       [](json&, json& s) {
         s["as_built"]["closed_doors"] = {"D1", "D9"};
       },
       "scenario.json: /as_built/closed_doors/1: no door \"D9\" in the plan"},
      {"ClosedDoorTwice", "scenario.json",
       [](json&, json& s) {
         s["as_built"]["closed_doors"] = {"D1", "D1"};
       },
       "scenario.json: /as_built/closed_doors/1: \"D1\" is listed twice"},
      {"ExtraWallZeroLength", "scenario.json",
       [](json&, json& s) {
         s["as_built"]["extra_walls"][0]["end"] = {1, 1};
       },
       "scenario.json: /as_built/extra_walls/0/end: zero-length wall: end equals start"},
      {"ClutterShape", "scenario.json",
       [](json&, json& s) { s["as_built"]["clutter"][0]["shape"] = "sphere"; },
       "scenario.json: /as_built/clutter/0/shape: unknown shape \"sphere\" (expected \"box\")"},
      {"ClutterSize", "scenario.json",
       [](json&, json& s) {
         s["as_built"]["clutter"][0]["size"] = {1, 0, 1};
       },
       "scenario.json: /as_built/clutter/0/size: every extent must be in [0.001, 1000] m"},
      // --- what MuJoCo and the XML of a world can hold (docs/formats.md, Limits)
      {"ControlCharacterInId", "plan.json",
       [=](json& p, json&) { walls(p)[0]["id"] = std::string("W\0x", 3); },
       "plan.json: /levels/0/walls/0/id: control character U+0000 at byte 1 (not allowed in "
       "ids)"},
      {"ControlCharacterInName", "plan.json",
       [=](json& p, json&) { rooms(p)[0]["name"] = "Office\n2"; },
       "plan.json: /levels/0/rooms/0/name: control character U+000A at byte 6 (control "
       "characters are not allowed)"},
      {"ControlCharacterInPlanPath", "scenario.json",
       [](json&, json& s) { s["plan"] = std::string("plan\0.json", 10); },
       "scenario.json: /plan: control character U+0000 at byte 4 (control characters are not "
       "allowed)"},
      {"UnderflowingThickness", "plan.json",
       [=](json& p, json&) { walls(p)[2]["thickness"] = 1e-300; },
       "plan.json: /levels/0/walls/2/thickness: must be in [0.001, 10], got 1e-300"},
      {"FarCoordinate", "plan.json",
       [=](json& p, json&) {
         walls(p)[0]["end"] = {1e6, 0};
       },
       "plan.json: /levels/0/walls/0/end: coordinate 1e+06 is out of range: points must lie "
       "within ±10000 m of the origin"},
      {"LevelTooLarge", "plan.json",
       [=](json& p, json&) {
         walls(p)[0]["end"] = {2000, 0};
       },
       "plan.json: /levels/0: level \"L0\" spans 2000 m × 4 m; at most 1000 m on a side is "
       "supported (docs/formats.md, Limits)"},
      {"TooManyWalls", "plan.json",
       [=](json& p, json&) {
         json many = json::array();
         for (int i = 0; i < 20001; ++i) {
           many.push_back({{"id", "X" + std::to_string(i)},
                           {"start", {0.01 * i, 0}},
                           {"end", {0.01 * i, 1}},
                           {"thickness", 0.005}});
         }
         walls(p) = many;
       },
       "plan.json: /levels/0/walls: 20001 walls; at most 20000 are supported (docs/formats.md, "
       "Limits)"},
      {"TooManyOutlineVertices", "plan.json",
       [=](json& p, json&) {
         json outline = json::array();
         for (int i = 0; i < 100001; ++i) {
           const double a = 2 * 3.14159265358979 * i / 100001;
           outline.push_back({2 + std::cos(a), 2 + std::sin(a)});
         }
         rooms(p)[0]["outline"] = outline;
       },
       "plan.json: /levels/0/rooms/0/outline: 100001 vertices; at most 100000 are supported "
       "(docs/formats.md, Limits)"},
      {"WallShiftTooFar", "scenario.json",
       [](json&, json& s) { s["as_built"]["wall_shifts"][0]["offset"] = 50; },
       "scenario.json: /as_built/wall_shifts/0/offset: must be in [-10, 10], got 50"},
      {"AsBuiltTooLarge", "scenario.json",
       [](json&, json& s) {
         s["as_built"]["extra_walls"][0]["end"] = {1, 2000};
       },
       "scenario.json: /as_built: with its as-built changes level \"L0\" spans 6.1 m × 2000.1 "
       "m; at most 1000 m on a side is supported (docs/formats.md, Limits)"},
  };
}

class Validation : public ::testing::TestWithParam<Case> {};

TEST_P(Validation, BadFileIsRejectedWithItsLocationAndNothingIsWritten) {
  const Case& c = GetParam();
  testing::Sandbox sandbox("validation_" + c.name);
  json plan = validPlan();
  json scenario = validScenario();
  c.mutate(plan, scenario);
  std::string plan_text = plan.dump();
  if (c.edit_text) plan_text = c.edit_text(plan_text);
  sandbox.write("plan.json", plan_text);
  sandbox.write("scenario.json", scenario.dump(2));
  const std::size_t files_before = sandbox.fileCount();

  const testing::RunResult result = sandbox.run("world " + c.input + " -o world.xml");

  EXPECT_EQ(result.exit_code, 1);
  EXPECT_EQ(result.err, "isg world: error: " + c.expected + "\n");
  EXPECT_TRUE(result.out.empty());
  EXPECT_FALSE(sandbox.exists("world.xml"));
  EXPECT_EQ(sandbox.fileCount(), files_before);  // no temporary left behind either
}

INSTANTIATE_TEST_SUITE_P(EveryRule, Validation, ::testing::ValuesIn(cases()),
                         [](const ::testing::TestParamInfo<Case>& param) {
                           return param.param.name;
                         });

TEST(ValidInput, TheBaseFilesAreValidSoEachCaseFailsForItsOwnReason) {
  testing::Sandbox sandbox("validation_base");
  sandbox.write("plan.json", validPlan().dump());
  sandbox.write("scenario.json", validScenario().dump());
  for (const char* input : {"plan.json", "scenario.json"}) {
    const auto result = sandbox.run(std::string("world ") + input + " -o world.xml");
    EXPECT_EQ(result.exit_code, 0) << result.err;
    EXPECT_TRUE(sandbox.exists("world.xml"));
    std::filesystem::remove(sandbox.dir() / "world.xml");
  }
}

TEST(ValidInput, MissingInputFile) {
  testing::Sandbox sandbox("validation_missing");
  const auto result = sandbox.run("world nothing.json -o world.xml");
  EXPECT_EQ(result.exit_code, 1);
  EXPECT_EQ(result.err,
            "isg world: error: nothing.json: cannot open file: No such file or directory\n");
  EXPECT_FALSE(sandbox.exists("world.xml"));
}

TEST(ValidInput, UnknownFieldIsAWarningAndTheWorldIsWritten) {
  testing::Sandbox sandbox("validation_unknown_field");
  json plan = validPlan();
  plan["levels"][0]["walls"][0]["material"] = "concrete";
  sandbox.write("plan.json", plan.dump());
  const auto result = sandbox.run("world plan.json -o world.xml");
  EXPECT_EQ(result.exit_code, 0);
  EXPECT_EQ(result.err.substr(0, result.err.find('\n') + 1),
            "isg world: warning: plan.json: /levels/0/walls/0/material: unknown field "
            "\"material\" (ignored)\n");
  EXPECT_TRUE(sandbox.exists("world.xml"));
}

TEST(ValidInput, DevicesAndFoldersAreNotRead) {
  testing::Sandbox sandbox("validation_devices");
  auto result = sandbox.run("check /dev/zero");
  EXPECT_EQ(result.exit_code, 1);
  EXPECT_EQ(result.err, "isg check: error: /dev/zero: not a regular file\n");
  std::filesystem::create_directories(sandbox.dir() / "folder.json");
  result = sandbox.run("world folder.json -o world.xml");
  EXPECT_EQ(result.exit_code, 1);
  EXPECT_EQ(result.err, "isg world: error: folder.json: is a directory, not a file\n");
  EXPECT_FALSE(sandbox.exists("world.xml"));
}

TEST(ValidInput, AHugeOutlineIsCheckedQuickly) {
  // 100 000 vertices on a circle inside the first room: near-linear checks accept it at once
  // (the timing is the test's timeout, not an assertion).
  testing::Sandbox sandbox("validation_huge_outline");
  json plan = validPlan();
  json outline = json::array();
  for (int i = 0; i < 100000; ++i) {
    const double a = 2 * 3.14159265358979 * i / 100000;
    outline.push_back({2 + std::cos(a), 2 + std::sin(a)});
  }
  plan["levels"][0]["rooms"][0]["outline"] = outline;
  sandbox.write("plan.json", plan.dump());
  const auto result = sandbox.run("check plan.json");
  EXPECT_EQ(result.exit_code, 0) << result.err;
}

TEST(ValidInput, UnwritableOutputIsABadInputError) {
  testing::Sandbox sandbox("validation_unwritable");
  sandbox.write("plan.json", validPlan().dump());
  // Missing folders are made; a file where a folder must be is not.
  const auto result = sandbox.run("world plan.json -o plan.json/dir/world.xml");
  EXPECT_EQ(result.exit_code, 1);
  EXPECT_EQ(result.err,
            "isg world: error: plan.json/dir/world.xml: cannot write: plan.json is not a "
            "directory\n");
  EXPECT_EQ(sandbox.run("world plan.json -o no/such/dir/world.xml").exit_code, 0);
  EXPECT_TRUE(sandbox.exists("no/such/dir/world.xml"));
}

}  // namespace
}  // namespace isg::cli
