#pragma once

#include <Eigen/Geometry>
#include <deque>
#include <functional>
#include <memory>
#include <nlohmann/json.hpp>
#include <numbers>
#include <optional>
#include <set>
#include <utility>
#include <vector>

#include "sensors/messages.hpp"
#include "sensors/stage_times.hpp"
#include "slam/map_diagnostics.hpp"
#include "slam/odometry_buffer.hpp"
#include "slam/sgraph/attitude_filter.hpp"
#include "slam/sgraph/confirmed_spans.hpp"
#include "slam/sgraph/plane_extraction.hpp"
#include "slam/sgraph/plane_map.hpp"
#include "slam/sgraph/room_detection.hpp"
#include "slam/sgraph/scan_registration.hpp"
#include "slam/thread_pool.hpp"

namespace ceres {
class Problem;
}

namespace isg::slam {

// The floors layer (docs/slam.md, "Floors"): which floor a keyframe stands on, from the height of
// the robot in M. Storeys are at least 2 m apart (a flight of stairs leaves 2 m of headroom,
// docs/formats.md), ramps and thresholds within a floor a few centimetres.
struct FloorOptions {
  // A keyframe within this of a floor's height stands on it (the first steps of a flight too).
  double tolerance = 0.5;  // m
  // A keyframe this far from every floor, level with the keyframe before it, starts a new floor;
  // one farther than `tolerance` but not yet that far (or still climbing) is on the stairs.
  double min_separation = 1.5;  // m
  double level_step = 0.1;      // m of height between consecutive keyframes that are level
  // A floor seen only sparsely (far off, from a sensor held high), once the robot's height above
  // its floors is known from another: only level surfaces within this of the height that gives
  // are taken for it. At the foot of a flight the treads just walked are level surfaces below the
  // sensor too, and outweighed the floor (a hand-held walk put a floor 1 m high).
  double carried_tolerance = 0.3;  // m
  // Each confirmed room is tied to its floor's node by the offset it had from it when first tied
  // (the paper's floor node constraining its floor's rooms), within this: loose beside the walls
  // (a few cm), about the odometry's drift between two rooms of a floor. 0 leaves it out.
  double room_sigma = 0.5;  // m
};

// Tuning of the S-Graph (docs/slam.md); the defaults are documented starting values.
struct SGraphOptions {
  double keyframe_distance = 1.0;  // m of odometry since the last keyframe
  double keyframe_angle = 0.5;     // rad
  PlaneExtractionOptions extraction;
  AssociationOptions association;
  double sigma_plane_angle = 2.0 * std::numbers::pi / 180.0;  // rad
  double sigma_plane_distance = 0.03;                         // m
  // Odometry between keyframes: σ = floor + per_metre · √distance (a random walk).
  double sigma_odometry_translation_floor = 0.01;
  double sigma_odometry_translation_per_metre = 0.03;
  double sigma_odometry_rotation_floor = 0.002;
  double sigma_odometry_rotation_per_metre = 0.012;
  // Gravity: each keyframe's up (its orientation's z in R) against the IMU's (AttitudeFilter),
  // when there is an IMU: what fixes roll and pitch, which walls alone let walk (and with them,
  // through the odometry's translation, the height). 0 leaves it out. M's z is taken to be up, as
  // an odometry frame's is (and ScanOdometry's, levelled by gravity at the start).
  double sigma_gravity = 1.0 * std::numbers::pi / 180.0;  // rad
  // Height on a floor: each keyframe standing on one stays at the height its floor's first
  // keyframe had (a base walks at its own height above a flat floor; the bob of a trot or a walk
  // is a few cm). Without it, a small tilt in the correction of a keyframe's predicted pose, far
  // from M's origin, lifts the map by decimetres. 0 leaves it out.
  double sigma_floor_height = 0.05;  // m
  double huber = 1.0;                // on whitened plane residuals
  int window = 25;                   // keyframes optimised after each new one; older ones are held
  int anchors_per_plane = 8;         // held older observations kept for each plane in the window
  int max_iterations = 10;
  // Threads for the graph's own loops (the registration's local map and correspondences), the
  // caller's included. Results are the same whatever the number (slam/thread_pool.hpp).
  int threads = 1;
  RoomDetectionOptions rooms;
  double sigma_room = 0.05;              // m, room-centre factors
  ScanRegistrationOptions registration;  // LiDAR odometry between keyframes
  FloorOptions floors;                   // the floors layer
  ConfirmationOptions confirmation;      // which parts of a wall the map confirms built
};

// What LiDAR odometry made of one keyframe (slam/sgraph/scan_registration.hpp).
struct KeyframeRegistration {
  bool attempted = false;  // a local map to register against existed
  bool agrees = true;      // the scan agreed with the local map (no factor otherwise)
  double inlier_share = 0.0;
  double inlier_share_predicted = 0.0;
  Eigen::Vector3d correction = Eigen::Vector3d::Zero();  // applied to the odometry prediction
  // The factor to the previous keyframe: motion (x, y in its heading frame, yaw) and S.
  Eigen::Vector3d measured = Eigen::Vector3d::Zero();
  Eigen::Matrix3d sqrt_information = Eigen::Matrix3d::Zero();
};

// The S-Graph's keyframe and wall layers: keyframe poses in M constrained by odometry, wall
// planes observed from them. Each new keyframe triggers an optimisation over a sliding window of
// recent keyframes and the planes they see, anchored by older observations of those planes:
// the cost of one optimisation stays bounded however long the run.
class SGraph {
 public:
  SGraph(const Eigen::Isometry3d& R_T_L, const SGraphOptions& options = {});

  void addOdometry(const sensors::Odometry& odometry);
  // The IMU: its mount on the base, then its samples in time order, up to each scan's turn end
  // before that scan (options.sigma_gravity).
  void setImuMount(const Eigen::Isometry3d& R_T_I) { R_R_I_ = R_T_I.linear(); }
  void addImu(const sensors::ImuSample& sample) { attitude_.add(sample); }
  // Deskews the scan with odometry and, when the robot has moved enough since the last keyframe,
  // makes a keyframe of it. Returns whether it did.
  bool addScan(sensors::Scan scan);
  // Whether addScan(scan at `stamp`) would make a keyframe of it (and so read it): odometry covers
  // the instant and the robot moved or turned enough since the last keyframe.
  bool wouldKeyframe(double stamp) const;

  struct Keyframe {
    double stamp = 0.0;
    // The floor it stands on (index into floors()), or -1 on the stairs: a view that mixes two
    // floors, kept for odometry and registration but not for planes or rooms.
    int floor = -1;
    // Its height differs from the keyframe before's by the floors' level_step or more: on a
    // flight (on its first or last steps when it still has a floor).
    bool climbing = false;
    // Standing on a floor, not on a flight: its scan sees one floor, as the recent map does.
    bool onFloor() const { return floor >= 0 && !climbing; }
    Eigen::Isometry3d odometry = Eigen::Isometry3d::Identity();  // M_T_R by odometry alone
    Eigen::Vector3d position = Eigen::Vector3d::Zero();          // estimate
    Eigen::Quaterniond orientation = Eigen::Quaterniond::Identity();
    std::vector<std::pair<int, PlaneObservation>> observations;  // (map plane, observation in L)
    KeyframeRegistration registration;
    std::optional<Eigen::Vector3d> up;   // gravity's up in R by the IMU, when there is one
    std::vector<Eigen::Vector3f> cloud;  // downsampled scan in L; kept for the local map only
    SightProfile sight;                  // standing on a floor: how far it saw (MapKeyframe)
    Eigen::Isometry3d pose() const;
  };
  struct Plane {
    MapPlane map;
    Eigen::Vector4d parameters;    // [n, d] in M, optimised
    std::vector<int> observed_by;  // keyframe indices
    int merged_into = -1;          // >= 0: found to be the same surface as that plane
    int floor = 0;                 // the floor it was seen from; never merged across floors
  };

  struct Room {
    RoomCandidate candidate;
    Eigen::Vector2d centre = Eigen::Vector2d::Zero();  // ρ, optimised with the room factor
    std::vector<int> keyframes;                        // keyframes that stood in it
    int floor = 0;
    // ρ − ξ of its floor when first tied to it (confirmed, in a window); none before.
    std::optional<Eigen::Vector2d> floor_offset;
  };
  // The floor node of the paper's fourth layer: one per floor the robot stood on, at the height
  // of the robot there; its centre ξ, optimised with the rooms tied to it, stays the centre of
  // their offsets (FloorOptions::room_sigma).
  struct Floor {
    double robot_z = 0.0;  // M, of its latest level keyframe (follows the odometry's drift)
    double first_z = 0.0;  // M, of its first keyframe: the height its keyframes are held at
    // M: the lowest of its keyframes' scans' low points (each scan's 0.5 % quantile of height):
    // nothing is seen below a floor, so the floor is no higher than this.
    std::optional<double> lowest_seen;
    double plane_sum = 0.0;  // floor planes seen below the sensor from it
    int plane_count = 0;
    // Floor surfaces seen with less support than a wall needs (far off, from a sensor held
    // high), as (height in M, support): their support-weighted median is the floor's height when
    // no well-supported floor plane was seen — robust to the tops of boxes and tables among them.
    // Sorted by height.
    std::vector<std::pair<double, int>> sparse_planes;
    int keyframes = 0;
    Eigen::Vector2d centre = Eigen::Vector2d::Zero();  // ξ, once a room is tied to it
    int rooms_tied = 0;
    // A floor first stood on at height z (M), by one keyframe.
    static Floor firstStoodOn(double z) {
      Floor floor;
      floor.robot_z = floor.first_z = z;
      floor.keyframes = 1;
      return floor;
    }
  };
  const std::vector<Floor>& floors() const { return floors_; }
  // The floor of the latest keyframe that stood on one (-1 before any).
  int currentFloor() const { return current_floor_; }
  // A floor's node ξ (the current floor by default), once a room is tied to it.
  std::optional<Eigen::Vector2d> floorCentre(int floor = -1) const;

  const std::deque<Keyframe>& keyframes() const { return keyframes_; }
  // Every room candidate seen so far, and the confirmed ones: not enclosing a smaller four-wall
  // candidate (a rectangle over two rooms whose dividing wall was not yet mapped when it was
  // found), and for corridors stood in at two keyframes or more.
  const std::deque<Room>& roomCandidates() const { return rooms_; }
  std::vector<int> confirmedRooms() const;
  const std::deque<Plane>& planes() const { return planes_; }
  // The graph's own threads (options.threads > 1), for work beside it on the same thread that
  // splits into items the same way with any number of threads (the matcher's verifications);
  // null: none.
  ThreadPool* pool() const { return pool_.get(); }
  // M_T_R at the latest odometry: the last keyframe's estimate and the odometry since it.
  std::optional<sensors::Odometry> latestPose() const;
  // M_T_R at time t (within the buffered odometry), corrected by the last keyframe before it.
  std::optional<Eigen::Isometry3d> poseAt(double t) const;
  nlohmann::json toJson() const;

  // Ends the current segment and starts a fresh, empty map (the odometry buffer stays): what a
  // localizer does when the world stopped agreeing with its graph (kidnapped, lost). The new
  // segment's first keyframe continues M from the latest pose, so M stays one frame. The old
  // segment's keyframes stay in diagnostics() and toJson()'s "segments".
  void startNewSegment(double stamp, const std::string& reason);
  int segment() const { return int(segments_.size()); }

  // Optimises every keyframe (the first held), plane and room of the segment at once, with or
  // without the window hook's factors: a contradiction is judged on a map not optimised under
  // the answer it contradicts (docs/matching.md).
  void optimiseAll(bool with_hook, int max_iterations = 20);

  // A floor's height in M (from the floor planes seen below the sensor from it, or until one is,
  // from the robot's height above another floor that was seen), once one was seen; the current
  // floor by default.
  std::optional<double> floorHeight(int floor = -1) const;
  // The most a floor's height in M can be (the current floor by default): the lowest its scans saw
  // (Floor::lowest_seen). A sensor held high sees the floor itself only far off, if at all; this
  // bound is near it once any wall has been seen down to its foot.
  std::optional<double> floorBound(int floor = -1) const;

  // More factors for every window optimisation: the iS-Graph's link to the plan. Called with the
  // problem, the plane indices in the window and the rooms whose planes all are; it may add
  // blocks of its own and factors on planeParameters / roomCentre of those.
  using WindowHook = std::function<void(ceres::Problem& problem, const std::set<int>& planes,
                                        const std::vector<int>& rooms)>;
  void setWindowHook(WindowHook hook) { window_hook_ = std::move(hook); }
  double* planeParameters(int plane) { return planes_[plane].parameters.data(); }
  double* roomCentre(int room) { return rooms_[room].centre.data(); }
  double* keyframePosition(int k) { return keyframes_[k].position.data(); }
  double* keyframeOrientation(int k) { return keyframes_[k].orientation.coeffs().data(); }
  // The latest keyframe's scan, deskewed (in L); none before the first. Shared: a copy of the
  // graph (a contradiction check) does not copy it.
  const std::shared_ptr<const sensors::Scan>& keyframeScan() const { return keyframe_scan_; }

  using Timing = KeyframeTiming;
  const std::vector<Timing>& timings() const { return timings_; }
  // Seconds in each stage of addScan over the whole run.
  const sensors::StageTimes& stageTimes() const { return stage_times_; }
  // The map as plain data (slam/map_diagnostics.hpp).
  MapDiagnostics diagnostics() const;

 private:
  // Ties a confirmed room to its floor's node: its offset from ξ now, ξ moved to the centre of
  // every tied room's offset (the others' offsets moved with it: the same constraints).
  void tieToFloor(int room);
  // The floors layer's factors for the window's active rooms (FloorRoomFactor).
  void addFloorFactors(ceres::Problem& problem, const std::vector<int>& active_rooms);
  struct WindowSize {
    int residual_blocks = 0;
    int parameter_blocks = 0;
  };
  // Optimises the keyframes from `first` on (the one before held) and what they observe;
  // returns the size of the problem solved.
  WindowSize optimise(int first, bool with_hook, int max_iterations);
  // The parts of a window's problem (optimise): keyframes first-1 … with their odometry, height,
  // gravity and registration factors; the planes they observe with their observations and a few
  // older anchors; the rooms whose planes are all in it.
  struct Window;
  void addKeyframeFactors(Window& window, int first);
  std::set<int> addPlaneFactors(Window& window, int first);
  std::vector<int> addRoomFactors(ceres::Problem& problem, const std::set<int>& planes);
  void detectRooms(int keyframe, double dominant_yaw, const std::vector<MapPlane>& walls);
  // The parts of addScan. The keyframe's floor (-1 on the stairs) and whether it is level
  // (Keyframe::climbing), from its height and the one before's.
  int floorOfKeyframe(double stamp, const Eigen::Isometry3d& odometry_at_scan,
                      const Eigen::Isometry3d& initial, Keyframe& keyframe);
  // How far the keyframe's scan saw: its returns from 0.1 m below its floor (the floor itself
  // beyond an opening) to 2 m above it, or, before the floor's height is known, within 0.3 m of
  // the sensor's height: sight lines that cross any wall at a height it stands at.
  SightProfile sightOf(const sensors::Scan& scan, int floor, const Eigen::Isometry3d& M_T_R) const;
  // The scan's low points bound its floor's height (Floor::lowest_seen).
  void noteLowestSeen(const sensors::Scan& scan, int floor, const Eigen::Isometry3d& M_T_L);
  // A horizontal plane below the sensor: the floor's height, well supported or sparse.
  void observeFloorPlane(const PlaneObservation& observation, int floor,
                         const Eigen::Isometry3d& M_T_L, const Eigen::Isometry3d& initial);
  // A wall: associated with a map plane of the floor (`walls`, kept in step) or a new one.
  void observeWall(const PlaneObservation& observation, int floor, int index,
                   const Eigen::Isometry3d& M_T_L, std::vector<MapPlane>& walls,
                   Keyframe& keyframe);
  // Where each of a wall plane's observations saw it, in M as its keyframe is now estimated (a
  // piece each where its inliers left a hole): for MapWall::confirmed. Taken as the keyframe then
  // stood, a span would keep the drift the map has since corrected, decimetres along a wall.
  std::vector<std::pair<Eigen::Vector2d, Eigen::Vector2d>> spansOf(int plane) const;
  // Rooms looked for again from every keyframe of the window ending at `index`.
  void detectRoomsInWindow(int index);
  // The floor a keyframe at height z (in M), level or not (climbing), stands on, made when it is
  // a new one; -1 on the stairs.
  int floorOf(double z, bool level);
  // Planes of the window that turned out to be the same surface (created before the optimisation
  // brought them together) are merged into the one observed most.
  void mergeDuplicatePlanes(int first_keyframe);
  void mergeDuplicatePlanes(const std::set<int>& recent, int floor);
  // Merged planes, and with floor >= 0 planes of other floors, get an empty, far-away extent.
  std::vector<MapPlane> activeWalls(int floor = -1) const;
  static MapPlane wallOf(const Plane& plane);  // one entry of activeWalls()
  // LiDAR odometry for a new keyframe predicted at `predicted`: registers its cloud to the
  // latest keyframes' and returns the corrected pose (the prediction when it cannot).
  Eigen::Isometry3d registerKeyframe(Keyframe& keyframe, const Eigen::Isometry3d& predicted);
  std::pair<double, double> odometrySigmas(double distance) const;  // translation, rotation

  Eigen::Isometry3d R_T_L_;
  Eigen::Matrix3d R_R_I_ = Eigen::Matrix3d::Identity();
  AttitudeFilter attitude_;
  SGraphOptions options_;
  OdometryBuffer odometry_;
  std::optional<sensors::Odometry> latest_odometry_;
  std::deque<Keyframe> keyframes_;
  std::deque<Plane> planes_;
  std::deque<Room> rooms_;
  std::vector<Timing> timings_;
  sensors::StageTimes stage_times_;
  // When options.threads > 1; a copy of the graph (checkForContradiction) shares it.
  std::shared_ptr<ThreadPool> pool_;
  WindowHook window_hook_;
  std::shared_ptr<const sensors::Scan> keyframe_scan_;
  Eigen::Isometry3d start_correction_ = Eigen::Isometry3d::Identity();
  struct Segment {
    double start = 0.0, end = 0.0;
    int keyframes = 0, planes = 0, rooms = 0;
    std::string reason;  // why it ended
  };
  std::vector<Segment> segments_;            // ended ones
  std::vector<MapKeyframe> past_keyframes_;  // of the ended segments, for diagnostics
  double segment_start_ = 0.0;
  std::vector<Floor> floors_;  // of this segment
  // The robot's height above the floor planes it saw, over every segment: the robot's, not the
  // map's.
  double robot_above_floor_sum_ = 0.0;
  int robot_above_floor_count_ = 0;
  int current_floor_ = -1;
};

}  // namespace isg::slam
