#include <algorithm>
#include <cmath>
#include <filesystem>
#include <initializer_list>
#include <set>
#include <sstream>

#include "bim/as_built_wall.hpp"
#include "bim/box_grid.hpp"
#include "bim/column.hpp"
#include "bim/facade.hpp"
#include "bim/lidar_models.hpp"
#include "bim/limits.hpp"
#include "bim/plan_geometry.hpp"
#include "bim/plan_parser.hpp"
#include "bim/plan_point.hpp"
#include "bim/polygon.hpp"
#include "bim/recorded_walk.hpp"
#include "bim/scenario.hpp"
#include "common/json_reader.hpp"

namespace isg::bim {

namespace {

const Level& levelNamed(const Plan& plan, const common::JsonNode& node) {
  const std::string id = node.identifier();
  const Level* level = plan.findLevel(id);
  if (level == nullptr) node.fail("no level " + common::inQuotes(id) + " in the plan");
  return *level;
}

std::string roomOnLevel(const Level& level, const common::JsonNode& node) {
  const std::string id = node.identifier();
  if (level.findRoom(id) == nullptr) {
    node.fail("no room " + common::inQuotes(id) + " on level " + common::inQuotes(level.id));
  }
  return id;
}

// A pose [x, y, yaw] on a level: in range and not inside a wall.
Eigen::Vector3d poseOnLevel(const Level& level, const common::JsonNode& pose_node,
                            const char* what) {
  const auto pose = pose_node.numbers(3);
  if (std::max(std::abs(pose[0]), std::abs(pose[1])) > limits::kMaxCoordinate) {
    pose_node.fail(std::string(what) + " is out of range: points must lie within ±" +
                   common::formatNumber(limits::kMaxCoordinate) + " m of the origin");
  }
  if (std::abs(pose[2]) > 100.0) pose_node.fail("the yaw must be within ±100 rad");
  const Eigen::Vector2d xy(pose[0], pose[1]);
  for (const auto& g : computeLevelGeometry(level).walls) {
    if (containsPoint(g.footprint(), xy)) {
      pose_node.fail(std::string(what) + " is inside " + (g.column ? "column " : "wall ") +
                     common::inQuotes(g.wall->id));
    }
  }
  for (const auto& column : level.columns) {
    if (column.round() && containsPoint(columnFootprint(column), xy)) {
      pose_node.fail(std::string(what) + " is inside column " + common::inQuotes(column.id));
    }
  }
  return Eigen::Vector3d(pose[0], pose[1], pose[2]);
}

// Kidnaps may put the robot down on any level: a room names its own, a pose is on the robot's
// level unless "level" says another.
std::vector<Kidnap> parseKidnaps(const common::JsonNode& node, const Plan& plan,
                                 const Level& robot_level) {
  std::vector<Kidnap> out;
  for (const auto& item : node.elements(0, limits::kMaxKidnaps, "kidnaps")) {
    item.expectObject({"time", "to"});
    Kidnap kidnap;
    const common::JsonNode time = item.field("time");
    kidnap.time = time.numberInRange(0.0, limits::kMaxRobotSeconds, true);
    if (kidnap.time <= 0.0) time.fail("a kidnap must come after the start (time > 0)");
    if (!out.empty() && kidnap.time <= out.back().time) {
      time.fail("kidnaps must be in time order: " + common::formatNumber(kidnap.time) +
                " s is not after " + common::formatNumber(out.back().time) + " s");
    }
    const common::JsonNode to = item.field("to");
    to.expectObject({"room", "pose", "level"});
    if (to.has("room") == to.has("pose")) to.fail("give exactly one of \"room\" and \"pose\"");
    if (to.has("room")) {
      if (to.has("level")) {
        to.field("level").fail("a room names its level: give \"level\" only with \"pose\"");
      }
      const common::JsonNode room = to.field("room");
      const Level* level = plan.levelOfRoom(room.identifier());
      if (level == nullptr)
        room.fail("no room " + common::inQuotes(room.identifier()) + " in the plan");
      kidnap.room = room.identifier();
      kidnap.level = level->id;
    } else {
      const Level& level = to.has("level") ? levelNamed(plan, to.field("level")) : robot_level;
      kidnap.pose = poseOnLevel(level, to.field("pose"), "kidnap position");
      kidnap.level = level.id;
    }
    out.push_back(kidnap);
  }
  return out;
}

std::array<double, 6> parseMount(const common::JsonNode& node, const std::string& sensor);

// One of the names of `values` (in order: value i is named names[i]); anything else fails
// naming them all.
template <typename Value>
Value namedValue(const common::JsonNode& node, std::initializer_list<const char*> names,
                 std::initializer_list<Value> values) {
  const std::string text = node.string();
  std::string expected;
  auto value = values.begin();
  std::size_t i = 0;
  for (const char* name : names) {
    if (text == name) return *value;
    ++value;
    const char* separator = i == 0 ? "" : i + 1 == names.size() ? " or " : ", ";
    expected += separator + common::inQuotes(name);
    ++i;
  }
  node.fail("unknown value " + common::inQuotes(text) + " (expected " + expected + ")");
}

// {"trajectory": FILE, "orientation", "path_of", "rig", "crossed"}: a recorded walk replayed.
void parseTrajectoryRoute(const common::JsonNode& route_node, const Level& level,
                          const WalkLoader& load_walk, Route& route) {
  const common::JsonNode trajectory = route_node.field("trajectory");
  route.kind = Route::Kind::kTrajectory;
  trajectory.nonEmptyString();
  if (auto orientation = route_node.optionalField("orientation")) {
    const std::string mode = orientation->string();
    if (mode != "travel" && mode != "file") {
      orientation->fail("unknown orientation " + common::inQuotes(mode) +
                        " (expected \"travel\" or \"file\")");
    }
    route.file_orientation = mode == "file";
  }
  route.sensor_path = route.file_orientation;
  if (auto path_of = route_node.optionalField("path_of")) {
    route.sensor_path = namedValue(*path_of, {"body", "sensor"}, {false, true});
    if (route.sensor_path && !route.file_orientation) {
      path_of->fail(
          "a sensor's path carries its orientation: give \"orientation\": \"file\" with it");
    }
  }
  if (auto rig = route_node.optionalField("rig")) {
    if (!route.sensor_path)
      rig->fail("\"rig\" goes with a sensor's path (\"path_of\": \"sensor\")");
    route.rig = parseMount(*rig, "LiDAR");
  }
  if (auto crossed = route_node.optionalField("crossed")) {
    route.crossed =
        namedValue(*crossed, {"not_built", "opening", "refuse"},
                   {CrossedSolids::kNotBuilt, CrossedSolids::kOpening, CrossedSolids::kRefuse});
  }
  if (!load_walk) {
    trajectory.fail(
        "a trajectory route is read from a file beside its scenario's file; "
        "this scenario is not read from one");
  }
  LoadedWalk loaded = load_walk(trajectory, level);
  route.trajectory_file = std::move(loaded.file);
  route.walk = std::move(loaded.walk);
  route.recording_start = loaded.recording_start;
  route.bridged = std::move(loaded.bridged);
}

// robot.route: "tour", or an object with rooms, waypoints or a recorded walk's trajectory file.
void parseRoute(const common::JsonNode& route_node, const Plan& plan, const Level& level,
                const WalkLoader& load_walk, Route& route) {
  if (route_node.isString()) {
    const std::string kind = route_node.string();
    if (kind != "tour")
      route_node.fail("unknown route " + common::inQuotes(kind) + " (expected \"tour\")");
    return;
  }
  route_node.expectObject(
      {"rooms", "waypoints", "trajectory", "orientation", "path_of", "rig", "crossed"});
  if (int(route_node.has("rooms")) + int(route_node.has("waypoints")) +
          int(route_node.has("trajectory")) !=
      1) {
    route_node.fail(
        "give \"tour\", {\"rooms\": [...]}, {\"waypoints\": [...]} or "
        "{\"trajectory\": \"WALK.tum\"}");
  }
  for (const char* key : {"orientation", "path_of", "rig", "crossed"}) {
    if (route_node.has(key) && !route_node.has("trajectory")) {
      route_node.field(key).fail(common::inQuotes(key) + " goes with \"trajectory\" only");
    }
  }
  if (route_node.has("trajectory")) {
    parseTrajectoryRoute(route_node, level, load_walk, route);
  } else if (auto rooms = route_node.optionalField("rooms")) {
    route.kind = Route::Kind::kRooms;
    for (const auto& r : rooms->elements(1, limits::kMaxScenarioItems, "rooms"))
      // A route may go to rooms on other levels, by stairs (sim/route_planner.hpp).
      route.rooms.push_back(plan.levelOfRoom(r.identifier()) != nullptr ? r.identifier()
                                                                        : roomOnLevel(level, r));
  } else {
    route.kind = Route::Kind::kWaypoints;
    const common::JsonNode waypoints = route_node.field("waypoints");
    for (const auto& w : waypoints.elements(1, limits::kMaxScenarioItems, "waypoints")) {
      route.waypoints.push_back(planPoint(w));
    }
  }
}

// robot.gait: each field of the walker's (or the legged base's) gait within its range.
void parseGait(const common::JsonNode& gait, GaitSettings& g) {
  gait.expectObject({"frequency_hz", "bob_m", "roll_deg", "pitch_deg", "sway_m", "head_turn_deg"});
  if (auto v = gait.optionalField("frequency_hz")) g.frequency_hz = v->numberInRange(0.1, 10.0);
  if (auto v = gait.optionalField("bob_m")) g.bob_m = v->numberInRange(0.0, 0.2);
  if (auto v = gait.optionalField("roll_deg")) g.roll_deg = v->numberInRange(0.0, 20.0);
  if (auto v = gait.optionalField("pitch_deg")) g.pitch_deg = v->numberInRange(0.0, 20.0);
  if (auto v = gait.optionalField("sway_m")) g.sway_m = v->numberInRange(0.0, 0.2);
  if (auto v = gait.optionalField("head_turn_deg")) g.head_turn_deg = v->numberInRange(0.0, 60.0);
}

// An open floor (bim/facade.hpp) starts at the most open point of its inside
// (sim/route_planner.hpp) unless robot.start gives one; a roomed level in its first room.
std::optional<std::string> defaultStart(const Level& level) {
  if (isOpenFloor(level)) return std::nullopt;
  return level.rooms.front().id;
}

// robot.start: a room or a pose on the robot's level, exactly one of them.
void parseStart(const std::optional<common::JsonNode>& start, const Level& level,
                RobotConfig& robot) {
  if (!start) {
    robot.start_room = defaultStart(level);
    return;
  }
  start->expectObject({"room", "pose"});
  const bool has_room = start->has("room");
  const bool has_pose = start->has("pose");
  if (has_room == has_pose) start->fail("give exactly one of \"room\" and \"pose\"");
  if (has_room) {
    robot.start_room = roomOnLevel(level, start->field("room"));
  } else {
    robot.start_pose = poseOnLevel(level, start->field("pose"), "start position");
  }
}

// A replayed walk is where and when its file says: nothing else may place, pace or break it.
void checkTrajectoryAlone(const common::JsonNode& node, RobotConfig& robot) {
  const std::pair<const char*, const char*> others[] = {
      {"start", "it starts at its file's first pose"},
      {"speed", "its file's times pace it"},
      {"kidnap", "it is one unbroken walk"}};
  for (const auto& [key, why] : others) {
    if (node.has(key)) {
      node.field(key).fail(std::string("robot.") + key +
                           " does not go with a trajectory route: " + why);
    }
  }
  robot.start_room.reset();
}

RobotConfig parseRobot(const std::optional<common::JsonNode>& node, const Plan& plan,
                       const WalkLoader& load_walk) {
  RobotConfig robot;
  robot.level = plan.levels.front().id;
  if (!node) {
    robot.start_room = defaultStart(plan.levels.front());
    return robot;
  }
  node->expectObject(
      {"carrier", "level", "start", "route", "speed", "clearance", "gait", "kidnap"});
  if (auto carrier = node->optionalField("carrier")) {
    const std::string name = carrier->string();
    if (name == "handheld") {
      robot.carrier = Carrier::kHandheld;
      robot.gait = handheldGait();
      robot.speed = kHandheldSpeed;
    } else if (name != "legged") {
      carrier->fail("unknown carrier " + common::inQuotes(name) +
                    " (expected \"legged\" or \"handheld\")");
    }
  }
  const Level* level = &plan.levels.front();
  if (auto l = node->optionalField("level")) {
    level = &levelNamed(plan, *l);
    robot.level = level->id;
  }
  parseStart(node->optionalField("start"), *level, robot);
  if (auto route = node->optionalField("route"))
    parseRoute(*route, plan, *level, load_walk, robot.route);
  if (auto speed = node->optionalField("speed")) robot.speed = speed->numberInRange(0.01, 3.0);
  if (auto clearance = node->optionalField("clearance")) {
    robot.clearance = clearance->numberInRange(0.2, 2.0);
  }
  if (auto gait = node->optionalField("gait")) parseGait(*gait, robot.gait);
  if (auto kidnap = node->optionalField("kidnap"))
    robot.kidnap = parseKidnaps(*kidnap, plan, *level);
  if (robot.route.kind == Route::Kind::kTrajectory) checkTrajectoryAlone(*node, robot);
  return robot;
}

// [x, y, z, roll, pitch, yaw] of a sensor on the robot base.
std::array<double, 6> parseMount(const common::JsonNode& node, const std::string& sensor) {
  const auto values = node.numbers(6);
  if (std::max({std::abs(values[0]), std::abs(values[1]), std::abs(values[2])}) > 10.0) {
    node.fail("the " + sensor + " must be mounted within 10 m of the robot's reference point");
  }
  std::array<double, 6> mount;
  std::copy(values.begin(), values.end(), mount.begin());
  return mount;
}

// One of a few named values; anything else fails naming them all.
template <typename Enum>
Enum oneOf(const common::JsonNode& node, std::initializer_list<Enum> values,
           const char* (*name)(Enum)) {
  const std::string text = node.string();
  std::string expected;
  for (Enum value : values) {
    if (text == name(value)) return value;
    expected += (expected.empty() ? "" : ", ") + common::inQuotes(name(value));
  }
  node.fail("unknown value " + common::inQuotes(text) + " (expected one of " + expected + ")");
}

SurfaceReflectivity parseReflectivity(const common::JsonNode& node) {
  node.expectObject({"wall", "floor", "ceiling", "door", "clutter", "stair"});
  SurfaceReflectivity reflectivity;
  const std::pair<const char*, double*> kinds[] = {
      {"wall", &reflectivity.wall},       {"floor", &reflectivity.floor},
      {"ceiling", &reflectivity.ceiling}, {"door", &reflectivity.door},
      {"clutter", &reflectivity.clutter}, {"stair", &reflectivity.stair}};
  for (const auto& [name, value] : kinds) {
    if (auto v = node.optionalField(name)) *value = v->numberInRange(0.0, 1.0);
  }
  return reflectivity;
}

LidarConfig parseLidar(const common::JsonNode& node) {
  node.expectObject({"model", "rate_hz", "range_noise_m", "min_range_m", "max_range_m", "dropout",
                     "grazing_cutoff_deg", "detection_range_m", "body_occlusion", "reflectivity",
                     "mount", "stamp", "cut", "cut_angle_deg", "azimuth_jitter_deg", "returns"});
  LidarConfig lidar;
  // The model first: its figures are the defaults the fields below may change.
  if (auto v = node.optionalField("model")) {
    const std::string name = v->string();
    const LidarModelDefaults* model = findLidarModelDefaults(name);
    if (!model) {
      std::string names;
      for (const auto& m : lidarModelDefaults()) names += (names.empty() ? "" : ", ") + m.name;
      v->fail("unknown LiDAR model " + common::inQuotes(name) + " (known: " + names + ")");
    }
    useLidarModel(lidar, *model);
  }
  if (auto v = node.optionalField("rate_hz")) lidar.rate_hz = v->numberInRange(5.0, 20.0);
  if (auto v = node.optionalField("range_noise_m"))
    lidar.range_noise_m = v->numberInRange(0.0, 1.0);
  if (auto v = node.optionalField("min_range_m")) lidar.min_range_m = v->numberInRange(0.0, 100.0);
  if (auto v = node.optionalField("max_range_m")) {
    lidar.max_range_m = v->numberInRange(limits::kMinSize, 1000.0);
    if (lidar.max_range_m <= lidar.min_range_m) {
      v->fail("max_range_m " + common::formatNumber(lidar.max_range_m) +
              " is not above min_range_m " + common::formatNumber(lidar.min_range_m));
    }
  } else if (lidar.max_range_m <= lidar.min_range_m) {
    node.field("min_range_m")
        .fail("min_range_m must be below max_range_m (" + common::formatNumber(lidar.max_range_m) +
              ")");
  }
  if (auto v = node.optionalField("dropout")) lidar.dropout = v->numberInRange(0.0, 1.0, true);
  if (auto v = node.optionalField("grazing_cutoff_deg")) {
    lidar.grazing_cutoff_deg = v->numberInRange(1.0, 90.0);
  }
  if (auto v = node.optionalField("detection_range_m")) {
    lidar.detection_range_m = v->numberInRange(limits::kMinSize, 1000.0);
  }
  if (auto v = node.optionalField("body_occlusion")) lidar.body_occlusion = v->boolean();
  if (auto v = node.optionalField("reflectivity")) lidar.reflectivity = parseReflectivity(*v);
  if (auto v = node.optionalField("mount")) lidar.mount = parseMount(*v, "LiDAR");
  if (auto v = node.optionalField("stamp")) {
    lidar.stamp = oneOf(*v, {LidarStamp::kFirstFiring, LidarStamp::kLastPacket}, lidarStampName);
  }
  if (auto v = node.optionalField("cut")) {
    lidar.cut = oneOf(*v, {LidarCut::kAngle, LidarCut::kPackets}, lidarCutName);
  }
  if (auto v = node.optionalField("cut_angle_deg")) {
    lidar.cut_angle_deg = v->numberInRange(0.0, 360.0, true);
    if (lidar.cut != LidarCut::kAngle) v->fail("cut_angle_deg needs \"cut\": \"angle\"");
  }
  if (auto v = node.optionalField("azimuth_jitter_deg")) {
    lidar.azimuth_jitter_deg = v->numberInRange(0.0, 1.0);
  }
  if (auto v = node.optionalField("returns")) {
    lidar.returns = oneOf(*v, {LidarReturns::kStrongest, LidarReturns::kLast, LidarReturns::kDual},
                          lidarReturnsName);
  }
  return lidar;
}

OdometryConfig parseOdometry(const common::JsonNode& node) {
  node.expectObject(
      {"rate_hz", "translation_noise", "heading_noise_deg_per_m", "heading_bias_deg_per_m"});
  OdometryConfig odometry;
  if (auto v = node.optionalField("rate_hz")) odometry.rate_hz = v->numberInRange(1.0, 1000.0);
  if (auto v = node.optionalField("translation_noise")) {
    odometry.translation_noise = v->numberInRange(0.0, 1.0);
  }
  if (auto v = node.optionalField("heading_noise_deg_per_m")) {
    odometry.heading_noise_deg_per_m = v->numberInRange(0.0, 90.0);
  }
  if (auto v = node.optionalField("heading_bias_deg_per_m")) {
    odometry.heading_bias_deg_per_m = v->numberInRange(-90.0, 90.0);
  }
  return odometry;
}

// `imu` holds the defaults (EuRoC's, or a camera rig's IMU); what the node says replaces them.
ImuConfig parseImu(const common::JsonNode& node, ImuConfig imu) {
  node.expectObject({"rate_hz", "mount", "gyroscope_noise_density", "gyroscope_random_walk",
                     "accelerometer_noise_density", "accelerometer_random_walk", "gravity"});
  if (auto v = node.optionalField("rate_hz")) imu.rate_hz = v->numberInRange(10.0, 2000.0);
  if (auto v = node.optionalField("mount")) imu.mount = parseMount(*v, "IMU");
  if (auto v = node.optionalField("gyroscope_noise_density"))
    imu.gyroscope_noise_density = v->numberInRange(0.0, 1.0);
  if (auto v = node.optionalField("gyroscope_random_walk"))
    imu.gyroscope_random_walk = v->numberInRange(0.0, 1.0);
  if (auto v = node.optionalField("accelerometer_noise_density"))
    imu.accelerometer_noise_density = v->numberInRange(0.0, 10.0);
  if (auto v = node.optionalField("accelerometer_random_walk"))
    imu.accelerometer_random_walk = v->numberInRange(0.0, 10.0);
  if (auto v = node.optionalField("gravity")) imu.gravity = v->numberInRange(0.0, 30.0);
  return imu;
}

// A list of ids that must all name walls (or doors) of the plan, each at most once.
template <typename Finder>
std::vector<std::string> parseIdList(const common::JsonNode& node, const char* what,
                                     Finder exists) {
  std::vector<std::string> ids;
  std::set<std::string> seen;
  for (const auto& item : node.elements()) {
    const std::string id = item.identifier();
    if (!exists(id))
      item.fail(std::string("no ") + what + " " + common::inQuotes(id) + " in the plan");
    if (!seen.insert(id).second) item.fail(common::inQuotes(id) + " is listed twice");
    ids.push_back(id);
  }
  return ids;
}

std::string optionalLevel(const common::JsonNode& node, const Plan& plan,
                          const std::string& fallback) {
  if (auto l = node.optionalField("level")) return levelNamed(plan, *l).id;
  return fallback;
}

ExtraWall parseExtraWall(const common::JsonNode& item, const Plan& plan,
                         const std::string& robot_level, std::size_t index) {
  item.expectObject({"start", "end", "thickness", "height", "base", "level"});
  ExtraWall wall;
  wall.id = "extra" + std::to_string(index);
  wall.level = optionalLevel(item, plan, robot_level);
  wall.start = planPoint(item.field("start"));
  wall.end = planPoint(item.field("end"));
  if ((wall.end - wall.start).norm() < limits::kMinSize) {
    item.field("end").fail("zero-length wall: end equals start");
  }
  wall.thickness = item.field("thickness").numberInRange(limits::kMinSize, limits::kMaxThickness);
  if (auto h = item.optionalField("height")) {
    wall.height = h->numberInRange(limits::kMinSize, limits::kMaxHeight);
  }
  if (auto b = item.optionalField("base")) wall.base = b->numberInRange(0.0, limits::kMaxHeight);
  const double top = wall.height.value_or(plan.findLevel(wall.level)->height);
  if (wall.base >= top) item.field("base").fail("base is not below the wall's top");
  return wall;
}

// The wall a shift or a turn names: a wall of the plan, named once in its list (`verb`: "shifted",
// "rotated"), not also missing.
std::string changedWall(const common::JsonNode& wall, const Plan& plan, const AsBuilt& as_built,
                        std::set<std::string>& seen, const char* verb) {
  const std::string id = wall.identifier();
  if (plan.levelOfWall(id) == nullptr)
    wall.fail("no wall " + common::inQuotes(id) + " in the plan");
  if (!seen.insert(id).second) wall.fail(common::inQuotes(id) + " is " + verb + " twice");
  for (const auto& missing : as_built.missing_walls) {
    if (missing == id) wall.fail(common::inQuotes(id) + " is also in missing_walls");
  }
  return id;
}

WallRotation parseWallRotation(const common::JsonNode& item, const Plan& plan,
                               const AsBuilt& as_built, std::set<std::string>& seen) {
  item.expectObject({"wall", "angle_deg", "about"});
  WallRotation rotation;
  rotation.wall = changedWall(item.field("wall"), plan, as_built, seen, "rotated");
  rotation.angle_deg =
      item.field("angle_deg")
          .numberInRange(-limits::kMaxWallRotationDeg, limits::kMaxWallRotationDeg);
  if (auto about = item.optionalField("about")) {
    if (!about->isString()) {
      // A point of the axis in metres from its start.
      const Level* level = plan.levelOfWall(rotation.wall);
      const Wall* wall = level != nullptr ? level->findWall(rotation.wall) : nullptr;
      rotation.about = WallRotation::About::kAlong;
      rotation.along_m = about->numberInRange(0.0, wall ? (wall->end - wall->start).norm() : 0.0);
      return rotation;
    }
    const std::string name = about->string();
    if (name == "start") {
      rotation.about = WallRotation::About::kStart;
    } else if (name == "end") {
      rotation.about = WallRotation::About::kEnd;
    } else if (name != "centre") {
      about->fail(
          "unknown point " + common::inQuotes(name) +
          " (expected \"start\", \"centre\", \"end\" or metres along the wall from its start)");
    }
  }
  return rotation;
}

// A wall built in part: the parts that stand, in order along it. A part may not end inside a door
// or a window (where would the opening's frame be?); an opening wholly in a part not built goes
// with it.
ShortenedWall parseShortenedWall(const common::JsonNode& item, const Plan& plan,
                                 const AsBuilt& as_built, std::set<std::string>& seen) {
  item.expectObject({"wall", "built"});
  ShortenedWall shortened;
  shortened.wall = changedWall(item.field("wall"), plan, as_built, seen, "shortened");
  const Level& level = *plan.levelOfWall(shortened.wall);
  const Wall& wall = *level.findWall(shortened.wall);
  const double length = (wall.end - wall.start).norm();
  const std::string wall_length =
      " (wall " + common::inQuotes(wall.id) + " is " + common::formatNumber(length) + " m long)";
  const common::JsonNode built = item.field("built");
  double previous_end = -1.0;
  for (const auto& part : built.elements(1, limits::kMaxScenarioItems, "built parts")) {
    const auto ends = part.elements(2, 2, "ends");
    const double from = ends[0].number(), to = ends[1].number();
    for (const auto& [end, value] : {std::pair{ends[0], from}, std::pair{ends[1], to}}) {
      if (value < 0.0 || value > length) {
        end.fail("must be in [0, " + common::formatNumber(length) + "], got " +
                 common::formatNumber(value) + wall_length);
      }
    }
    if (to - from < limits::kMinSize) {
      part.fail("a part from " + common::formatNumber(from) + " to " + common::formatNumber(to) +
                " m: its end must lie past its start");
    }
    if (from <= previous_end) {
      ends[0].fail("the parts must be in order along the wall and apart: this one starts at " +
                   common::formatNumber(from) + " m, where the one before ends at " +
                   common::formatNumber(previous_end) + " m");
    }
    previous_end = to;
    shortened.built.push_back({from, to});
  }
  if (shortened.built.size() == 1 && shortened.built[0].first < limits::kMinSize &&
      shortened.built[0].second > length - limits::kMinSize) {
    built.fail("the whole wall is built" + wall_length + ": nothing is shortened");
  }
  const auto checkOpening = [&](const std::string& kind, const std::string& id, double offset,
                                double width) {
    const double lo = offset - 0.5 * width, hi = offset + 0.5 * width;
    for (std::size_t k = 0; k < shortened.built.size(); ++k) {
      for (const double end : {shortened.built[k].first, shortened.built[k].second}) {
        if (end > lo + limits::kMinSize && end < hi - limits::kMinSize) {
          built.fail("part " + std::to_string(k) + " ends at " + common::formatNumber(end) +
                     " m, inside " + kind + " " + common::inQuotes(id) + " (" +
                     common::formatNumber(lo) + "–" + common::formatNumber(hi) +
                     " m along the wall): end it beside the opening");
        }
      }
    }
  };
  for (const auto& door : level.doors) {
    if (door.wall == wall.id) checkOpening("door", door.id, door.offset, door.width);
  }
  for (const auto& window : level.windows) {
    if (window.wall == wall.id) checkOpening("window", window.id, window.offset, window.width);
  }
  return shortened;
}

Clutter parseClutter(const common::JsonNode& item, const Plan& plan,
                     const std::string& robot_level) {
  item.expectObject({"shape", "center", "size", "yaw", "level"});
  Clutter clutter;
  const common::JsonNode shape = item.field("shape");
  if (shape.string() != "box") {
    shape.fail("unknown shape " + common::inQuotes(shape.string()) + " (expected \"box\")");
  }
  clutter.level = optionalLevel(item, plan, robot_level);
  const common::JsonNode center = item.field("center");
  clutter.center = center.point3();
  if (clutter.center.cwiseAbs().maxCoeff() > limits::kMaxCoordinate) {
    center.fail("out of range: points must lie within ±" +
                common::formatNumber(limits::kMaxCoordinate) + " m of the origin");
  }
  const common::JsonNode size = item.field("size");
  clutter.size = size.point3();
  if (clutter.size.minCoeff() < limits::kMinSize ||
      clutter.size.maxCoeff() > limits::kMaxLevelExtent) {
    size.fail("every extent must be in [" + common::formatNumber(limits::kMinSize) + ", " +
              common::formatNumber(limits::kMaxLevelExtent) + "] m");
  }
  if (auto yaw = item.optionalField("yaw")) clutter.yaw = yaw->numberInRange(-100.0, 100.0);
  return clutter;
}

AsBuilt parseAsBuilt(const common::JsonNode& node, const Plan& plan,
                     const std::string& robot_level) {
  node.expectObject({"missing_walls", "extra_walls", "wall_shifts", "wall_rotations",
                     "shortened_walls", "closed_doors", "clutter", "missing_columns",
                     "moved_columns"});
  AsBuilt as_built;
  auto is_wall = [&](const std::string& id) { return plan.levelOfWall(id) != nullptr; };
  auto is_column = [&](const std::string& id) {
    return std::any_of(plan.levels.begin(), plan.levels.end(),
                       [&](const Level& level) { return level.findColumn(id) != nullptr; });
  };
  if (auto v = node.optionalField("missing_columns")) {
    as_built.missing_columns = parseIdList(*v, "column", is_column);
  }
  if (auto v = node.optionalField("moved_columns")) {
    std::set<std::string> seen;
    for (const auto& item : v->elements(0, limits::kMaxScenarioItems, "moved columns")) {
      item.expectObject({"column", "offset"});
      ColumnMove move;
      const common::JsonNode column = item.field("column");
      move.column = column.identifier();
      if (!is_column(move.column)) {
        column.fail("no column " + common::inQuotes(move.column) + " in the plan");
      }
      if (!seen.insert(move.column).second) {
        column.fail(common::inQuotes(move.column) + " is moved twice");
      }
      if (std::find(as_built.missing_columns.begin(), as_built.missing_columns.end(),
                    move.column) != as_built.missing_columns.end()) {
        column.fail(common::inQuotes(move.column) + " is also in missing_columns");
      }
      const common::JsonNode offset = item.field("offset");
      move.offset = offset.point2();
      if (move.offset.norm() > limits::kMaxWallShift) {
        offset.fail("a column moves at most " + common::formatNumber(limits::kMaxWallShift) + " m");
      }
      as_built.moved_columns.push_back(move);
    }
  }
  auto is_door = [&](const std::string& id) { return plan.levelOfDoor(id) != nullptr; };
  if (auto v = node.optionalField("missing_walls")) {
    as_built.missing_walls = parseIdList(*v, "wall", is_wall);
  }
  if (auto v = node.optionalField("closed_doors")) {
    as_built.closed_doors = parseIdList(*v, "door", is_door);
  }
  if (auto v = node.optionalField("extra_walls")) {
    for (const auto& item : v->elements(0, limits::kMaxScenarioItems, "extra walls")) {
      as_built.extra_walls.push_back(
          parseExtraWall(item, plan, robot_level, as_built.extra_walls.size()));
    }
  }
  if (auto v = node.optionalField("wall_shifts")) {
    std::set<std::string> seen;
    for (const auto& item : v->elements()) {
      item.expectObject({"wall", "offset"});
      WallShift shift;
      shift.wall = changedWall(item.field("wall"), plan, as_built, seen, "shifted");
      shift.offset =
          item.field("offset").numberInRange(-limits::kMaxWallShift, limits::kMaxWallShift);
      as_built.wall_shifts.push_back(shift);
    }
  }
  if (auto v = node.optionalField("wall_rotations")) {
    std::set<std::string> seen;
    for (const auto& item : v->elements()) {
      as_built.wall_rotations.push_back(parseWallRotation(item, plan, as_built, seen));
    }
  }
  if (auto v = node.optionalField("shortened_walls")) {
    std::set<std::string> seen;
    for (const auto& item : v->elements(0, limits::kMaxScenarioItems, "shortened walls")) {
      as_built.shortened_walls.push_back(parseShortenedWall(item, plan, as_built, seen));
    }
  }
  if (auto v = node.optionalField("clutter")) {
    for (const auto& item : v->elements(0, limits::kMaxScenarioItems, "clutter boxes")) {
      as_built.clutter.push_back(parseClutter(item, plan, robot_level));
    }
  }
  return as_built;
}

// With its extra walls, clutter and shifted walls, each level must still fit in a square of
// limits::kMaxLevelExtent: the world and the route grid are built over it.
void checkAsBuiltExtent(const common::JsonNode& node, const Plan& plan, const AsBuilt& as_built) {
  for (const auto& level : plan.levels) {
    std::vector<Eigen::Vector2d> points;
    for (const auto& w : level.walls) {
      points.push_back(w.start);
      points.push_back(w.end);
    }
    for (const auto& r : level.rooms)
      points.insert(points.end(), r.outline.begin(), r.outline.end());
    for (const auto& w : as_built.extra_walls) {
      if (w.level != level.id) continue;
      points.push_back(w.start);
      points.push_back(w.end);
    }
    for (const auto& c : as_built.clutter) {
      if (c.level != level.id) continue;
      const double reach = 0.5 * c.size.head<2>().norm();
      points.push_back(c.center.head<2>() - Eigen::Vector2d::Constant(reach));
      points.push_back(c.center.head<2>() + Eigen::Vector2d::Constant(reach));
    }
    for (const auto& w : level.walls) {
      const Wall built = builtWall(w, as_built);
      points.push_back(built.start);
      points.push_back(built.end);
    }
    double shift = 0.0;
    for (const auto& s : as_built.wall_shifts) {
      if (plan.levelOfWall(s.wall) == &level) shift = std::max(shift, std::abs(s.offset));
    }
    for (const auto& m : as_built.moved_columns) {
      if (level.findColumn(m.column) != nullptr) shift = std::max(shift, m.offset.norm());
    }
    const Box2 box = Box2::around(points).grown(shift);
    const Eigen::Vector2d size = box.hi - box.lo;
    if (size.maxCoeff() > limits::kMaxLevelExtent) {
      node.fail("with its as-built changes level " + common::inQuotes(level.id) + " spans " +
                common::formatNumber(size.x()) + " m × " + common::formatNumber(size.y()) +
                " m; at most " + common::formatNumber(limits::kMaxLevelExtent) +
                " m on a side is supported (docs/formats.md, Limits)");
    }
  }
}

Scenario scenarioFromPlan(Plan plan, const std::string& path) {
  Scenario scenario;
  scenario.source = path;
  scenario.plan_file = path;
  scenario.plan = std::move(plan);
  scenario.robot = parseRobot(std::nullopt, scenario.plan, {});
  return scenario;
}

}  // namespace

AsBuilt parseAsBuiltJson(const common::JsonNode& node, const Plan& plan,
                         const std::string& robot_level) {
  return parseAsBuilt(node, plan, robot_level);
}

Scenario parseScenario(const common::JsonNode& root, const PlanLoader& load_plan,
                       const WalkLoader& load_walk) {
  const std::string& path = root.source().file;
  if (root.isObject() && root.has("format") && root.field("format").isString() &&
      root.field("format").string() == kPlanFormat) {
    return scenarioFromPlan(parsePlan(root), path);
  }
  root.expectObject({"$schema", "format", "version", "name", "plan", "seed", "robot", "lidar",
                     "odometry", "imu", "cameras", "as_built"});
  if (root.has("format") && root.field("format").isString() &&
      root.field("format").string() != kScenarioFormat) {
    root.field("format").fail("unknown format " + common::inQuotes(root.field("format").string()) +
                              " (expected \"isg.plan\" or \"isg.scenario\")");
  }
  common::checkFormatAndVersion(root, kScenarioFormat, kScenarioVersion);
  if (auto name = root.optionalField("name")) name->text();

  Scenario scenario;
  scenario.source = path;
  const common::JsonNode plan_node = root.field("plan");
  if (plan_node.isString()) {
    plan_node.text();
    plan_node.nonEmptyString();
    LoadedPlan loaded = load_plan(plan_node);
    scenario.plan = std::move(loaded.plan);
    scenario.plan_file = std::move(loaded.file);
  } else if (plan_node.isObject()) {
    scenario.plan_file = "<inline>";
    scenario.plan = parsePlan(plan_node);
  } else {
    plan_node.fail("expected a plan file name or an inline plan object, got " +
                   common::describeJsonType(plan_node.raw()));
  }

  if (auto seed = root.optionalField("seed")) scenario.seed = seed->unsignedInteger();
  scenario.robot = parseRobot(root.optionalField("robot"), scenario.plan, load_walk);
  if (auto lidar = root.optionalField("lidar")) scenario.lidar = parseLidar(*lidar);
  if (auto odometry = root.optionalField("odometry")) scenario.odometry = parseOdometry(*odometry);
  if (scenario.robot.carrier == Carrier::kHandheld) {
    // A person carries no odometer and has no robot body in the LiDAR's view.
    if (auto odometry = root.optionalField("odometry")) {
      odometry->fail("a handheld carrier has no odometry (robot.carrier is \"handheld\")");
    }
    const auto lidar = root.optionalField("lidar");
    if (lidar && lidar->has("body_occlusion") && lidar->field("body_occlusion").boolean()) {
      lidar->field("body_occlusion")
          .fail(
              "a handheld carrier has no robot body to occlude the LiDAR (robot.carrier is "
              "\"handheld\")");
    }
    scenario.lidar.body_occlusion = false;
  }
  if (auto cameras = root.optionalField("cameras")) scenario.cameras = parseCameras(*cameras);
  // A camera rig brings its IMU: its rate and noise are the defaults.
  for (const CameraConfig& camera : scenario.cameras) {
    if (camera.rig.empty()) continue;
    const RigImu rig_imu = cameraRig(camera.rig)->imu;
    scenario.imu.rate_hz = rig_imu.rate_hz;
    scenario.imu.gyroscope_noise_density = rig_imu.gyroscope_noise_density;
    scenario.imu.gyroscope_random_walk = rig_imu.gyroscope_random_walk;
    scenario.imu.accelerometer_noise_density = rig_imu.accelerometer_noise_density;
    scenario.imu.accelerometer_random_walk = rig_imu.accelerometer_random_walk;
    scenario.imu.mount = rig_imu.mount;
  }
  if (auto imu = root.optionalField("imu")) scenario.imu = parseImu(*imu, scenario.imu);
  if (auto as_built = root.optionalField("as_built")) {
    scenario.as_built = parseAsBuilt(*as_built, scenario.plan, scenario.robot.level);
    checkAsBuiltExtent(*as_built, scenario.plan, scenario.as_built);
  }
  return scenario;
}

Scenario loadScenario(const std::string& path, common::Warnings* warnings) {
  const nlohmann::json document = common::readJsonFile(path);
  const common::JsonSource source{path, warnings};
  return parseScenario(
      common::JsonNode(document, "", source),
      [&](const common::JsonNode& plan_name) {
        const std::filesystem::path plan_path =
            (std::filesystem::path(path).parent_path() / plan_name.string()).lexically_normal();
        if (!std::filesystem::exists(plan_path)) {
          plan_name.fail("plan file " + common::inQuotes(plan_path.string()) + " does not exist");
        }
        return LoadedPlan{loadPlan(plan_path.string(), warnings), plan_path.string()};
      },
      [&](const common::JsonNode& walk_name, const Level& level) {
        const std::filesystem::path walk_path =
            (std::filesystem::path(path).parent_path() / walk_name.string()).lexically_normal();
        if (!std::filesystem::exists(walk_path)) {
          walk_name.fail("trajectory file " + common::inQuotes(walk_path.string()) +
                         " does not exist");
        }
        LoadedWalk loaded = readRecordedWalk(walk_path.string(), level, walk_name);
        loaded.file = walk_path.string();
        return loaded;
      });
}

}  // namespace isg::bim
