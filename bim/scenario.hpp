#pragma once

#include <Eigen/Core>
#include <array>
#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "bim/camera_models.hpp"
#include "bim/plan.hpp"
#include "common/input_error.hpp"
#include "common/json_reader.hpp"

namespace isg::bim {

// The scenario model of docs/formats.md ("isg.scenario" v1): one simulated run. Parsing fills every
// default, so a bare plan becomes a scenario with the documented defaults.

// One pose of a recorded walk (robot.route {"trajectory": FILE}): its time after the file's first
// pose, its position and yaw in the plan frame of robot.level, and the line of the file it is on
// (for messages about it).
struct WalkPose {
  double t = 0.0;
  Eigen::Vector2d xy = Eigen::Vector2d::Zero();
  double yaw = 0.0;
  int line = 0;
  // The rest of the file's pose: its height above the level's floor, its roll and pitch (the
  // rotation is Rz(yaw)·Ry(pitch)·Rx(roll)). Used when the walk is a sensor's path.
  double z = 0.0, roll = 0.0, pitch = 0.0;
};

// What a replayed walk does with a planned wall or column it passes through (robot.route
// "crossed"): a site had not built it yet on the day (the default), it had left a door-wide
// opening where the walk went, or the walk is refused as today (docs/simulation.md, "Replayed
// walks").
enum class CrossedSolids { kNotBuilt, kOpening, kRefuse };

// One pass of a replayed walk through a planned wall or column, and what was taken of it.
struct WalkCrossing {
  std::string element;  // the plan's wall or column id
  bool column = false;
  Eigen::Vector2d at = Eigen::Vector2d::Zero();  // the middle of the pass, in the plan frame
  int first_line = 0;                            // the walk file's lines of the pass
  int last_line = 0;
  bool opening = false;  // taken as an opening in the wall (else: as not built)
};

struct Route {
  enum class Kind { kTour, kRooms, kWaypoints, kTrajectory };
  Kind kind = Kind::kTour;
  std::vector<std::string> rooms;
  std::vector<Eigen::Vector2d> waypoints;
  // A recorded walk replayed (kTrajectory): the file as resolved, its poses, and whether the
  // carrier faces the file's yaw ("orientation": "file") or its direction of travel (default).
  std::string trajectory_file;
  std::vector<WalkPose> walk;
  double recording_start = 0.0;  // the file's first stamp: its clock at the walk's t = 0
  std::vector<double> bridged;   // the stamps (as `walk`'s) of single glitches left out
  bool file_orientation = false;
  // Whose path the file is (robot.route "path_of"): a sensor's — a camera's, a LiDAR's: the
  // LiDAR follows the file's pose through `rig` exactly, the carrier rigid with it — or the
  // carrier body's (followed with the gait's sway). A sensor's by default with "orientation":
  // "file".
  bool sensor_path = false;
  // The simulated LiDAR in the frame of the sensor the file tracks, [x, y, z, roll, pitch, yaw].
  std::array<double, 6> rig = {0.0, 0.0, 0.0, 0.0, 0.0, 0.0};
  CrossedSolids crossed = CrossedSolids::kNotBuilt;
  // Filled when the scenario is read (worlds::takeCrossedSolids): every pass through a planned
  // wall or column, in the walk's order; the scenario's as_built already holds what they took.
  std::vector<WalkCrossing> crossings;
};

// What carries the sensors (docs/simulation.md, "Carriers"): a legged base with leg odometry, or a
// person walking with the sensors in hand (no odometry stream: the localizer has the LiDAR and the
// IMU only).
enum class Carrier { kLegged, kHandheld };
inline const char* carrierName(Carrier c) { return c == Carrier::kLegged ? "legged" : "handheld"; }

// How the carrier sways the sensors while it walks. Legged: the trot's height bob, roll and pitch
// at the gait frequency. Handheld: the walker's steps bob the sensors and pitch them at the step
// frequency, each stride (two steps) sways them sideways and rolls them, and the walker turns
// their head and hands about the way ahead.
struct GaitSettings {
  double frequency_hz = 1.8;  // trot cycles, or steps, per second
  double bob_m = 0.015;
  double roll_deg = 2.0;
  double pitch_deg = 2.0;
  double sway_m = 0.0;         // sideways, at half the step frequency (handheld)
  double head_turn_deg = 0.0;  // yaw about the way ahead, slow and irregular (handheld)
};
// The handheld carrier's defaults: a person's walk (vertical bob of the body's centre about
// ±2–3 cm, lateral sway about ±2–3 cm at 1.8 steps per second), with the sensors held on a short
// pole that the walker turns about the way ahead.
inline GaitSettings handheldGait() { return {1.8, 0.025, 2.0, 1.5, 0.025, 15.0}; }
inline constexpr double kHandheldSpeed = 0.8;  // m/s: a slow surveying walk

// The robot lifted at `time` and put down elsewhere (the kidnapped-robot problem): at a room's
// most open point with a heading drawn from the seed, or at a pose [x, y, yaw]. Exactly one of
// room and pose is set. Odometry does not see the jump; ground truth does.
struct Kidnap {
  double time = 0.0;  // seconds of robot time
  std::optional<std::string> room;
  std::optional<Eigen::Vector3d> pose;
  std::string level;  // the level the robot is put down on: the room's, or the pose's
};

// How far the robot's centre keeps from walls, clutter, closed doors and the outside when its route
// is planned, unless the scenario says (robot.clearance).
inline constexpr double kDefaultRobotClearance = 0.35;

struct RobotConfig {
  Carrier carrier = Carrier::kLegged;
  std::string level;                          // id of the level the robot walks on
  std::optional<std::string> start_room;      // start at the centre of this room ...
  std::optional<Eigen::Vector3d> start_pose;  // ... or at [x, y, yaw]; exactly one is set
  Route route;
  double speed = 0.5;                         // m/s (kHandheldSpeed for a person)
  double clearance = kDefaultRobotClearance;  // m, kept by the route planner
  GaitSettings gait;
  std::vector<Kidnap> kidnap;  // in time order
};

// Diffuse reflectivity at the VLP-16's 905 nm, in [0, 1], per kind of surface: what sets each
// return's calibrated intensity and how far it can be seen (docs/simulation.md).
struct SurfaceReflectivity {
  double wall = 0.5;  // walls the plan has and walls it lacks
  double floor = 0.3;
  double ceiling = 0.8;
  double door = 0.35;
  double clutter = 0.3;
  double stair = 0.3;
};

// The sensor's and its driver's conventions (docs/simulation.md, "Driver conventions").
// When a cloud is stamped: at its first firing (points' time from 0 to the turn's length) or, as
// the ROS 1 velodyne driver does, at the start of its last packet (times about −0.0995…+0.0013 s).
enum class LidarStamp { kFirstFiring, kLastPacket };
// Where one cloud ends: each turn from a fixed azimuth (cut_angle_deg), or every N packets as the
// ROS 1 driver does by default (N = ceil(packet rate / rotation rate): 76 packets, 1824 firing
// sequences, about 363° at 10 Hz, so each cloud starts about 3° after the last one did).
enum class LidarCut { kAngle, kPackets };
// Which echo of a firing is reported: the strongest, the last, or both (dual: the last and the
// strongest, or the second strongest when the last is the strongest).
enum class LidarReturns { kStrongest, kLast, kDual };

inline const char* lidarStampName(LidarStamp s) {
  return s == LidarStamp::kFirstFiring ? "first_firing" : "last_packet";
}
inline const char* lidarCutName(LidarCut c) { return c == LidarCut::kAngle ? "angle" : "packets"; }
inline const char* lidarReturnsName(LidarReturns r) {
  return r == LidarReturns::kStrongest ? "strongest" : r == LidarReturns::kLast ? "last" : "dual";
}

struct LidarConfig {
  // The sensor (bim/lidar_models.hpp, sensors/lidar_model.hpp): its beams and timing, and the
  // defaults of the figures below.
  std::string model = "vlp16";
  double rate_hz = 10.0;
  double range_noise_m = 0.007;
  double min_range_m = 0.4;
  double max_range_m = 100.0;
  double dropout = 0.0;
  // Returns fade beyond this angle of incidence: kept with probability cos(incidence) /
  // cos(grazing_cutoff_deg); 90 turns the fading off.
  double grazing_cutoff_deg = 80.0;
  // The range out to which a 10 % reflective surface met head-on still returns; weaker returns
  // (reflectivity × cos(incidence) / range², the LiDAR equation) are lost.
  double detection_range_m = 100.0;
  bool body_occlusion = true;  // rays that meet the robot's own body return nothing
  SurfaceReflectivity reflectivity;
  // x y z roll pitch yaw on R: the puck on a mast, its optical centre 16 cm above the body's top
  // (0.14 puts the puck on the body itself: docs/simulation.md says what that costs).
  std::array<double, 6> mount = {0.0, 0.0, 0.25, 0.0, 0.0, 0.0};
  LidarStamp stamp = LidarStamp::kFirstFiring;
  LidarCut cut = LidarCut::kAngle;
  double cut_angle_deg = 0.0;  // the azimuth each turn starts at (angle cut), clockwise from x
  // Standard deviation of the error of the azimuth each data block (two firing sequences)
  // reports; the points are placed along the reported azimuth. 0.006 on a real VLP-16.
  double azimuth_jitter_deg = 0.0;
  LidarReturns returns = LidarReturns::kStrongest;
};

struct OdometryConfig {
  double rate_hz = 50.0;
  double translation_noise = 0.02;  // std dev as a fraction of distance travelled
  double heading_noise_deg_per_m = 0.5;
  double heading_bias_deg_per_m = 0.0;
};

// An inertial unit on the base with the continuous-time noise model Kalibr documents: white noise
// of a given density and a bias that random-walks, per axis. Defaults are those published for the
// ADIS16448 MEMS unit of the EuRoC MAV dataset.
struct ImuConfig {
  double rate_hz = 200.0;
  std::array<double, 6> mount = {0.0, 0.0, 0.0, 0.0, 0.0, 0.0};  // x y z roll pitch yaw on R
  double gyroscope_noise_density = 1.6968e-4;                    // rad/s/√Hz
  double gyroscope_random_walk = 1.9393e-5;                      // rad/s²/√Hz
  double accelerometer_noise_density = 2.0e-3;                   // m/s²/√Hz
  double accelerometer_random_walk = 3.0e-3;                     // m/s³/√Hz
  double gravity = 9.81;  // m/s², along −z of the plan frame
};

// A camera the robot carries (scenario "cameras"): a model of bim/camera_models.hpp, resolved
// when the scenario is read, under a name unique in the scenario ("cam0", …) that names its
// folder in an EuRoC dataset.
struct CameraConfig {
  std::string name;
  CameraModel model;
  // x y z roll pitch yaw on R of the camera's optical frame (z forward, x right, y down). The
  // default looks straight ahead from the front of the body: the optical frame turned from R's
  // (x forward, z up) by roll −90° and yaw −90°.
  std::array<double, 6> mount = {0.35, 0.0, 0.1, -1.5707963267948966, 0.0, -1.5707963267948966};
  // A rig's lens: the rig's name, and the lens in the IMU's frame from the rig's calibration
  // (then R_T_C is R_T_I · I_T_C and `mount` is not used).
  std::string rig;
  std::optional<Eigen::Isometry3d> I_T_C;
};

struct ExtraWall {
  std::string id;     // generated: "extra0", "extra1", ... (unique in the file)
  std::string level;  // defaults to the robot's level
  Eigen::Vector2d start = Eigen::Vector2d::Zero();
  Eigen::Vector2d end = Eigen::Vector2d::Zero();
  double thickness = 0.1;
  std::optional<double> height;  // defaults to the level's
  double base = 0.0;
};

// A column built elsewhere than planned: its centre moved by `offset` (metres, in the plan's
// frame), its shape, size and turn as planned.
struct ColumnMove {
  std::string column;
  Eigen::Vector2d offset = Eigen::Vector2d::Zero();
};

struct WallShift {
  std::string wall;
  double offset = 0.0;  // metres along the wall's left normal
};

// A wall built turned by `angle_deg` (counter-clockwise seen from above) about a point of its
// axis: its start, its centre, its end, or the point `along_m` metres from its start (kAlong).
// Its doors and windows turn with it.
struct WallRotation {
  enum class About { kStart, kCentre, kEnd, kAlong };
  std::string wall;
  double angle_deg = 0.0;
  About about = About::kCentre;
  double along_m = 0.0;  // kAlong only
};
// "start", "centre", "end"; "along" for a point given in metres.
inline const char* aboutName(WallRotation::About a) {
  return a == WallRotation::About::kStart   ? "start"
         : a == WallRotation::About::kEnd   ? "end"
         : a == WallRotation::About::kAlong ? "along"
                                            : "centre";
}

// A wall built only in part (a site where it is still going up): the parts that stand, as
// [from, to] metres along its axis from its start, ascending and apart, within its length. Doors
// and windows in a part that stands stay; those in a part not built are gone with it.
struct ShortenedWall {
  std::string wall;
  std::vector<std::pair<double, double>> built;
};

struct Clutter {
  std::string level;                                 // defaults to the robot's level
  Eigen::Vector3d center = Eigen::Vector3d::Zero();  // z above the level's elevation
  Eigen::Vector3d size = Eigen::Vector3d::Ones();    // full extents
  double yaw = 0.0;
};

struct AsBuilt {
  std::vector<std::string> missing_walls;
  std::vector<ExtraWall> extra_walls;
  std::vector<WallShift> wall_shifts;
  std::vector<WallRotation> wall_rotations;
  std::vector<ShortenedWall> shortened_walls;
  std::vector<std::string> closed_doors;
  std::vector<Clutter> clutter;
  std::vector<std::string> missing_columns;  // columns not built (yet)
  std::vector<ColumnMove> moved_columns;

  bool empty() const {
    return missing_walls.empty() && extra_walls.empty() && wall_shifts.empty() &&
           wall_rotations.empty() && shortened_walls.empty() && closed_doors.empty() &&
           clutter.empty() && missing_columns.empty() && moved_columns.empty();
  }
};

struct Scenario {
  std::string source;     // the file given by the user (scenario or bare plan)
  std::string plan_file;  // where the plan came from ("<inline>" for an inline plan)
  Plan plan;
  std::uint64_t seed = 0;
  RobotConfig robot;
  LidarConfig lidar;
  OdometryConfig odometry;
  ImuConfig imu;
  std::vector<CameraConfig> cameras;
  AsBuilt as_built;
};

inline constexpr const char* kScenarioFormat = "isg.scenario";
inline constexpr int kScenarioVersion = 1;

// Reads a scenario, or a bare plan (which becomes a scenario with every default). Validation
// errors throw InputError naming the file (the plan's own file for errors inside it), the JSON
// pointer and the reason. Warnings are appended to `warnings` when given.
Scenario loadScenario(const std::string& path, common::Warnings* warnings = nullptr);

// A scenario's "as_built" object on its own (as a dataset's metadata.json records it), checked
// against `plan` as loadScenario checks it; errors name the node's file and JSON pointer.
AsBuilt parseAsBuiltJson(const common::JsonNode& node, const Plan& plan,
                         const std::string& robot_level);

// The scenario's "cameras" array: each entry's model, name, rate, mount and (a pinhole's)
// resolution and field of view, checked; errors name the entry's JSON pointer.
std::vector<CameraConfig> parseCameras(const common::JsonNode& node);

// Loads the plan a scenario names by file ("plan": "d1.json"): gets the string node, returns the
// plan and where it came from. loadScenario resolves the name relative to the scenario's file;
// built-in scenarios resolve it among the built-in plans.
struct LoadedPlan {
  Plan plan;
  std::string file;
};
using PlanLoader = std::function<LoadedPlan(const common::JsonNode& plan_name)>;

// Reads the recorded walk a route names ({"trajectory": "WALK.tum"}) for the robot's level:
// returns the file as resolved and its poses (bim/recorded_walk.hpp). loadScenario resolves the
// name relative to the scenario's file.
struct LoadedWalk {
  std::string file;
  std::vector<WalkPose> walk;
  double recording_start = 0.0;
  std::vector<double> bridged;
};
using WalkLoader = std::function<LoadedWalk(const common::JsonNode& file_name, const Level& level)>;

// Parses a scenario document, or a bare plan document (with every default). Without a walk
// loader (a built-in scenario, a document that is no file) a trajectory route is an error.
Scenario parseScenario(const common::JsonNode& root, const PlanLoader& load_plan,
                       const WalkLoader& load_walk = {});

}  // namespace isg::bim
