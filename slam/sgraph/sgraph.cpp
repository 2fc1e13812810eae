#include "slam/sgraph/sgraph.hpp"

#include <ceres/ceres.h>
#include <numbers>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <map>
#include <set>

#include "bim/optimizer/agraph_factors.hpp"
#include "bim/optimizer/plane_manifold.hpp"
#include "common/angles.hpp"
#include "slam/sgraph/confirmed_spans.hpp"
#include "slam/sgraph/sgraph_factors.hpp"

namespace isg::slam {

namespace {

double seconds(std::chrono::steady_clock::time_point since) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - since).count();
}

}  // namespace

Eigen::Isometry3d SGraph::Keyframe::pose() const {
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  T.linear() = orientation.normalized().toRotationMatrix();
  T.translation() = position;
  return T;
}

SGraph::SGraph(const Eigen::Isometry3d& R_T_L, const SGraphOptions& options)
    : R_T_L_(R_T_L), options_(options) {
  if (options.threads > 1) pool_ = std::make_shared<ThreadPool>(options.threads);
}

void SGraph::addOdometry(const sensors::Odometry& odometry) {
  odometry_.push(odometry);
  latest_odometry_ = odometry;
}

std::optional<sensors::Odometry> SGraph::latestPose() const {
  if (!latest_odometry_) return std::nullopt;
  if (keyframes_.empty()) {
    sensors::Odometry out = *latest_odometry_;
    out.M_T_R = start_correction_ * out.M_T_R;
    return out;
  }
  const Keyframe& k = keyframes_.back();
  sensors::Odometry out = *latest_odometry_;
  out.M_T_R = k.pose() * k.odometry.inverse() * latest_odometry_->M_T_R;
  return out;
}

std::optional<Eigen::Isometry3d> SGraph::poseAt(double t) const {
  const auto odometry = odometry_.at(t);
  if (!odometry) return std::nullopt;
  // The last keyframe at or before t.
  const auto it = std::upper_bound(keyframes_.begin(), keyframes_.end(), t,
                                   [](double s, const Keyframe& k) { return s < k.stamp; });
  if (it == keyframes_.begin()) return start_correction_ * *odometry;
  const Keyframe& k = *(it - 1);
  return k.pose() * k.odometry.inverse() * *odometry;
}

bool SGraph::wouldKeyframe(double stamp) const {
  const auto odometry_at_scan = odometry_.at(stamp);
  if (!odometry_at_scan) return false;  // no odometry yet for this instant
  if (keyframes_.empty()) return true;
  const Eigen::Isometry3d delta = keyframes_.back().odometry.inverse() * *odometry_at_scan;
  const double moved = delta.translation().head<2>().norm();
  const double turned = std::abs(common::yawOf(delta.linear()));
  return moved >= options_.keyframe_distance || turned >= options_.keyframe_angle;
}

int SGraph::floorOfKeyframe(double stamp, const Eigen::Isometry3d& odometry_at_scan,
                            const Eigen::Isometry3d& initial, Keyframe& keyframe) {
  // Level: little height since the keyframe before, or (a segment's first keyframe) in the
  // odometry's last two seconds.
  bool level = true;
  if (!keyframes_.empty()) {
    level = std::abs(initial.translation().z() - keyframes_.back().position.z()) <
            options_.floors.level_step;
  } else if (const auto before = odometry_.at(stamp - 2.0)) {
    level = std::abs(odometry_at_scan.translation().z() - before->translation().z()) <
            options_.floors.level_step;
  }
  const int floor = floorOf(initial.translation().z(), level);
  keyframe.floor = floor;
  keyframe.climbing = !level;
  if (floor >= 0) current_floor_ = floor;
  return floor;
}

SightProfile SGraph::sightOf(const sensors::Scan& scan, int floor,
                             const Eigen::Isometry3d& M_T_R) const {
  if (const auto floor_z = floorHeight(floor)) {
    const double floor_R = *floor_z - M_T_R.translation().z();
    return sightProfile(scan, R_T_L_, floor_R - 0.1, floor_R + 2.0);
  }
  const double sensor_z = R_T_L_.translation().z();
  return sightProfile(scan, R_T_L_, sensor_z - 0.3, sensor_z + 0.3);
}

void SGraph::noteLowestSeen(const sensors::Scan& scan, int floor, const Eigen::Isometry3d& M_T_L) {
  // The scan's low points: its 0.5 % quantile of height in M (a few stray points lower still,
  // noise or a reflection, do not count).
  const Eigen::RowVector3d z_row = M_T_L.linear().row(2);
  std::vector<double> heights;
  heights.reserve(scan.points.size());
  for (const auto& p : scan.points) {
    heights.push_back(z_row.dot(Eigen::Vector3d(p.x, p.y, p.z)) + M_T_L.translation().z());
  }
  const auto low = heights.begin() + std::ptrdiff_t(heights.size() / 200);
  std::nth_element(heights.begin(), low, heights.end());
  Floor& f = floors_[floor];
  f.lowest_seen = f.lowest_seen ? std::min(*f.lowest_seen, *low) : *low;
}

void SGraph::observeFloorPlane(const PlaneObservation& observation, int floor,
                               const Eigen::Isometry3d& M_T_L, const Eigen::Isometry3d& initial) {
  // The floor: a horizontal plane well below the sensor, facing up.
  const bim::Plane in_M = observation.plane.transformed(M_T_L);
  // Its height where it was seen (its centroid), not where the plane meets M's z axis: a floor
  // seen far off in a ring's arc has a normal a few degrees off, which tilts the plane by
  // decimetres at M's origin.
  const double z = (M_T_L * observation.centroid).z();
  if (in_M.normal.z() > 0.9 && z < M_T_L.translation().z() - 0.3 &&
      observation.points < options_.extraction.min_inliers) {
    auto& sparse = floors_[floor].sparse_planes;  // kept sorted: floorHeight's median
    const std::pair<double, int> plane(z, observation.points);
    sparse.insert(std::upper_bound(sparse.begin(), sparse.end(), plane), plane);
  } else if (in_M.normal.z() > 0.9 && z < M_T_L.translation().z() - 0.3) {
    floors_[floor].plane_sum += z;
    ++floors_[floor].plane_count;
    robot_above_floor_sum_ += initial.translation().z() - z;
    ++robot_above_floor_count_;
  }
}

void SGraph::observeWall(const PlaneObservation& observation, int floor, int index,
                         const Eigen::Isometry3d& M_T_L, std::vector<MapPlane>& walls,
                         Keyframe& keyframe) {
  const PlaneObservation in_map = toMap(observation, M_T_L);
  int plane = associate(in_map, walls, options_.association);
  if (plane < 0) {
    Plane created;
    created.map = newMapPlane(in_map, options_.association.max_length);
    created.parameters = bim::toVector(in_map.plane);
    created.floor = floor;
    planes_.push_back(created);
    walls.push_back(created.map);
    plane = int(planes_.size()) - 1;
  }
  Plane& p = planes_[plane];
  extend(p.map, in_map, options_.association.max_length);
  addHeights(p.map, in_map);
  ++p.map.observations;
  p.observed_by.push_back(index);
  walls[plane] = p.map;
  keyframe.observations.emplace_back(plane, observation);
}

void SGraph::detectRoomsInWindow(int index) {
  // Walls seen now may complete rooms the robot stood in a little earlier: look again from every
  // keyframe of the window.
  std::vector<PlaneObservation> weighted;
  for (const auto& p : planes_) {
    if (p.merged_into >= 0) continue;
    PlaneObservation o;
    o.plane = p.map.plane;
    o.orientation = PlaneOrientation::kVertical;
    o.points = int(10 * p.map.observations * std::max(0.5, (p.map.end - p.map.start).norm()));
    weighted.push_back(o);
  }
  const double dominant = dominantYaw(weighted);
  std::map<int, std::vector<MapPlane>> walls_now;  // per floor
  for (int k = std::max(0, index - options_.window + 1); k <= index; ++k) {
    const int on = keyframes_[k].floor;
    if (on < 0) continue;
    auto it = walls_now.find(on);
    if (it == walls_now.end()) it = walls_now.emplace(on, activeWalls(on)).first;
    detectRooms(k, dominant, it->second);
  }
}

bool SGraph::addScan(sensors::Scan scan) {
  const auto start = std::chrono::steady_clock::now();
  if (!wouldKeyframe(scan.stamp)) return false;
  const Eigen::Isometry3d odometry_at_scan = *odometry_.at(scan.stamp);
  sensors::StageClock deskew_clock(stage_times_, "deskew");
  deskew(scan, odometry_, R_T_L_);
  deskew_clock.stop();

  Keyframe keyframe;
  keyframe.stamp = scan.stamp;
  keyframe.odometry = odometry_at_scan;
  if (!attitude_.empty() && options_.sigma_gravity > 0.0) {
    // R's up = R_R_M · z = R_R_I · (M_R_I)ᵀ · z: the filter's yaw does not enter.
    keyframe.up = R_R_I_ * attitude_.M_R_I_at(scan.stamp).transpose() * Eigen::Vector3d::UnitZ();
  }
  Eigen::Isometry3d initial =
      keyframes_.empty()
          ? start_correction_ * odometry_at_scan
          : keyframes_.back().pose() * keyframes_.back().odometry.inverse() * odometry_at_scan;
  if (options_.registration.enabled) {
    sensors::StageClock clock(stage_times_, "registration");
    keyframe.cloud = downsampleScan(scan, options_.registration);
    clock.stop();
    if (!keyframes_.empty()) initial = registerKeyframe(keyframe, initial);
  }
  keyframe.position = initial.translation();
  keyframe.orientation = Eigen::Quaterniond(initial.rotation());
  const int index = int(keyframes_.size());
  const int floor = floorOfKeyframe(scan.stamp, odometry_at_scan, initial, keyframe);
  const Eigen::Isometry3d M_T_L = initial * R_T_L_;
  if (floor >= 0 && !keyframe.climbing && !scan.points.empty()) {
    noteLowestSeen(scan, floor, M_T_L);
    keyframe.sight = sightOf(scan, floor, initial);
  }
  // The map as association sees it, kept in step as this keyframe's observations change it: the
  // walls of its own floor only.
  std::vector<MapPlane> walls = activeWalls(floor);
  sensors::StageClock extraction_clock(stage_times_, "extraction");
  // On the stairs the scan mixes two floors: no planes are taken from it.
  const std::vector<PlaneObservation> observations =
      floor >= 0 ? extractPlanes(scan, options_.extraction) : std::vector<PlaneObservation>{};
  const double planes_s = extraction_clock.stop();
  sensors::StageClock association_clock(stage_times_, "association");
  for (const auto& observation : observations) {
    if (observation.orientation == PlaneOrientation::kHorizontal) {
      observeFloorPlane(observation, floor, M_T_L, initial);
    } else if (observation.orientation == PlaneOrientation::kVertical) {
      observeWall(observation, floor, index, M_T_L, walls, keyframe);
    }
  }
  association_clock.stop();
  keyframes_.push_back(std::move(keyframe));
  // Only the latest keyframes' clouds make the local map: older ones are let go.
  const int stale = int(keyframes_.size()) - 1 - options_.registration.local_map_keyframes;
  if (stale >= 0) std::vector<Eigen::Vector3f>().swap(keyframes_[stale].cloud);
  Timing timing;
  timing.extraction_s = seconds(start);
  timing.planes_s = planes_s;
  sensors::StageClock optimisation_clock(stage_times_, "optimisation");
  const WindowSize window = optimise(std::max(1, int(keyframes_.size()) - options_.window), true,
                                     options_.max_iterations);
  mergeDuplicatePlanes(std::max(0, index - options_.window + 1));
  timing.solve_s = optimisation_clock.stop();
  timing.window_residuals = window.residual_blocks;
  timing.window_parameters = window.parameter_blocks;
  sensors::StageClock rooms_clock(stage_times_, "rooms");
  detectRoomsInWindow(index);
  timing.optimisation_s = timing.solve_s + rooms_clock.stop();
  timings_.push_back(timing);
  keyframe_scan_ = std::make_shared<const sensors::Scan>(std::move(scan));
  return true;
}

std::pair<double, double> SGraph::odometrySigmas(double distance) const {
  return {options_.sigma_odometry_translation_floor +
              options_.sigma_odometry_translation_per_metre * std::sqrt(distance),
          options_.sigma_odometry_rotation_floor +
              options_.sigma_odometry_rotation_per_metre * std::sqrt(distance)};
}

Eigen::Isometry3d SGraph::registerKeyframe(Keyframe& keyframe, const Eigen::Isometry3d& predicted) {
  const ScanRegistrationOptions& options = options_.registration;
  const int n = int(keyframes_.size());
  std::vector<LocalMap::Part> parts;
  for (int k = std::max(0, n - options.local_map_keyframes); k < n; ++k) {
    if (!keyframes_[k].cloud.empty())
      parts.push_back({&keyframes_[k].cloud, keyframes_[k].pose() * R_T_L_});
  }
  if (parts.empty() || keyframe.cloud.empty()) return predicted;
  sensors::StageClock map_clock(stage_times_, "local map");
  const LocalMap map(parts, options, pool_.get());
  map_clock.stop();
  sensors::StageClock clock(stage_times_, "registration");
  const Keyframe& previous = keyframes_.back();
  const double distance = (previous.odometry.inverse() * keyframe.odometry).translation().norm();
  const auto [sigma_t, sigma_r] = odometrySigmas(distance);
  const Eigen::Matrix3d prior =
      Eigen::Vector3d(1.0 / (sigma_t * sigma_t), 1.0 / (sigma_t * sigma_t),
                      1.0 / (sigma_r * sigma_r))
          .asDiagonal();
  const RegistrationResult result =
      registerScan(keyframe.cloud, predicted, R_T_L_, map, prior, options, pool_.get());
  KeyframeRegistration& r = keyframe.registration;
  r.attempted = true;
  r.agrees = result.agrees;
  r.inlier_share = result.inlier_share;
  r.inlier_share_predicted = result.inlier_share_predicted;
  if (!result.agrees) return predicted;
  r.correction = result.correction;
  const Eigen::Isometry3d corrected = result.apply(predicted);
  // The motion from the previous keyframe in its heading frame, and the registration's
  // information turned into that frame: e_M = R(yaw_i) · e_i.
  const double yaw_i = common::yawOf(previous.pose().linear());
  const Eigen::Matrix2d R_i = Eigen::Rotation2Dd(yaw_i).toRotationMatrix();
  const Eigen::Vector2d moved = corrected.translation().head<2>() - previous.position.head<2>();
  r.measured.head<2>() = R_i.transpose() * moved;
  r.measured.z() = common::wrapAngle(common::yawOf(corrected.linear()) - yaw_i);
  Eigen::Matrix3d R3 = Eigen::Matrix3d::Identity();
  R3.topLeftCorner<2, 2>() = R_i;
  const Eigen::Matrix3d information =
      options.factor_information_share * (R3.transpose() * result.information * R3);
  // Directions the scan does not see (a corridor's axis) have no information: a tiny floor keeps
  // the square root defined without adding any.
  const Eigen::LLT<Eigen::Matrix3d> llt(information + 1e-9 * Eigen::Matrix3d::Identity());
  if (llt.info() != Eigen::Success) {
    r.agrees = false;
    return predicted;
  }
  r.sqrt_information = llt.matrixU();
  return corrected;
}

void SGraph::optimiseAll(bool with_hook, int max_iterations) {
  optimise(1, with_hook, max_iterations);
}

void SGraph::startNewSegment(double stamp, const std::string& reason) {
  if (keyframes_.empty()) return;
  Segment ended;
  ended.start = segment_start_;
  ended.end = stamp;
  ended.keyframes = int(keyframes_.size());
  ended.planes = int(planes_.size());
  ended.rooms = int(confirmedRooms().size());
  ended.reason = reason;
  segments_.push_back(ended);
  for (const auto& kf : keyframes_) {
    past_keyframes_.push_back(
        {kf.stamp, kf.pose(), kf.odometry, kf.sight, int(segments_.size()) - 1});
  }
  // M continues: the new segment's first keyframe at the latest estimate.
  const Keyframe& last = keyframes_.back();
  start_correction_ = last.pose() * last.odometry.inverse();
  keyframes_.clear();
  planes_.clear();
  rooms_.clear();
  floors_.clear();
  current_floor_ = -1;
  segment_start_ = stamp;
}

namespace {

ceres::Problem::Options windowProblemOptions() {
  ceres::Problem::Options options;
  // The manifolds and the loss live in the window, not in the problem.
  options.manifold_ownership = ceres::DO_NOT_TAKE_OWNERSHIP;
  options.loss_function_ownership = ceres::DO_NOT_TAKE_OWNERSHIP;
  return options;
}

}  // namespace

// The problem of one window optimisation, with the manifolds and the loss it uses and the
// keyframes whose poses it holds.
struct SGraph::Window {
  explicit Window(double huber_scale) : problem(windowProblemOptions()), huber(huber_scale) {}
  ceres::Problem problem;
  ceres::EigenQuaternionManifold quaternion;
  bim::PlaneManifold plane_manifold;
  ceres::HuberLoss huber;
  std::set<int> held;  // keyframes in the problem whose poses do not move

  void addPose(Keyframe& kf, int k, bool fixed) {
    problem.AddParameterBlock(kf.position.data(), 3);
    problem.AddParameterBlock(kf.orientation.coeffs().data(), 4, &quaternion);
    if (fixed) {
      problem.SetParameterBlockConstant(kf.position.data());
      problem.SetParameterBlockConstant(kf.orientation.coeffs().data());
      held.insert(k);
    }
  }
};

void SGraph::addKeyframeFactors(Window& w, int first) {
  const int n = int(keyframes_.size());
  w.addPose(keyframes_[first - 1], first - 1, true);
  for (int k = first; k < n; ++k) {
    w.addPose(keyframes_[k], k, false);
    const Keyframe& a = keyframes_[k - 1];
    const Keyframe& b = keyframes_[k];
    const Eigen::Isometry3d delta = a.odometry.inverse() * b.odometry;
    const auto [sigma_t, sigma_r] = odometrySigmas(delta.translation().norm());
    w.problem.AddResidualBlock(
        OdometryFactor::create(delta, sigma_t, sigma_r), nullptr, keyframes_[k - 1].position.data(),
        keyframes_[k - 1].orientation.coeffs().data(), keyframes_[k].position.data(),
        keyframes_[k].orientation.coeffs().data());
    if (b.onFloor() && options_.sigma_floor_height > 0.0) {
      w.problem.AddResidualBlock(
          HeightFactor::create(floors_[b.floor].first_z, options_.sigma_floor_height), nullptr,
          keyframes_[k].position.data());
    }
    if (b.up) {
      w.problem.AddResidualBlock(GravityFactor::create(*b.up, options_.sigma_gravity), nullptr,
                                 keyframes_[k].orientation.coeffs().data());
    }
    const KeyframeRegistration& registration = b.registration;
    if (registration.attempted && registration.agrees) {
      w.problem.AddResidualBlock(
          ScanMatchFactor::create(registration.measured, registration.sqrt_information), &w.huber,
          keyframes_[k - 1].position.data(), keyframes_[k - 1].orientation.coeffs().data(),
          keyframes_[k].position.data(), keyframes_[k].orientation.coeffs().data());
    }
  }
}

std::set<int> SGraph::addPlaneFactors(Window& w, int first) {
  // Planes seen in the window, their observations from the window, and a few older, held ones.
  const int n = int(keyframes_.size());
  std::set<int> planes;
  for (int k = first; k < n; ++k) {
    for (const auto& [plane, observation] : keyframes_[k].observations) planes.insert(plane);
  }
  for (int plane : planes) {
    Plane& p = planes_[plane];
    w.problem.AddParameterBlock(p.parameters.data(), 4, &w.plane_manifold);
    int anchors = 0;
    for (auto it = p.observed_by.rbegin(); it != p.observed_by.rend(); ++it) {
      const int k = *it;
      if (k < first) {
        // Newest first: once the anchors are taken, every observation left is older still.
        if (anchors >= options_.anchors_per_plane) break;
        ++anchors;
        if (!w.held.count(k)) w.addPose(keyframes_[k], k, true);
      }
      for (const auto& [observed, observation] : keyframes_[k].observations) {
        if (observed != plane) continue;
        w.problem.AddResidualBlock(
            PosePlaneFactor::create(bim::toVector(observation.plane), R_T_L_,
                                    options_.sigma_plane_angle, options_.sigma_plane_distance),
            &w.huber, keyframes_[k].position.data(), keyframes_[k].orientation.coeffs().data(),
            p.parameters.data());
      }
    }
  }
  return planes;
}

std::vector<int> SGraph::addRoomFactors(ceres::Problem& problem, const std::set<int>& planes) {
  // Rooms whose planes are all in the problem: their centres follow the room factors.
  std::vector<int> active_rooms;
  for (int r = 0; r < int(rooms_.size()); ++r) {
    Room& room = rooms_[r];
    const auto& pairs = room.candidate.pairs;
    const int count = room.candidate.four_wall ? 2 : 1;
    bool all = true;
    for (int i = 0; i < count; ++i)
      all = all && planes.count(pairs[i][0]) && planes.count(pairs[i][1]);
    if (!all) continue;
    active_rooms.push_back(r);
    if (room.candidate.four_wall) {
      problem.AddResidualBlock(
          bim::FourWallRoomFactor::create(options_.sigma_room), nullptr, room.centre.data(),
          planes_[pairs[0][0]].parameters.data(), planes_[pairs[0][1]].parameters.data(),
          planes_[pairs[1][0]].parameters.data(), planes_[pairs[1][1]].parameters.data());
    } else {
      const Eigen::Vector2d axis_point = keyframes_[room.keyframes.front()].position.head<2>();
      problem.AddResidualBlock(bim::TwoWallRoomFactor::create(axis_point, options_.sigma_room),
                               nullptr, room.centre.data(), planes_[pairs[0][0]].parameters.data(),
                               planes_[pairs[0][1]].parameters.data());
    }
  }
  return active_rooms;
}

SGraph::WindowSize SGraph::optimise(int first, bool with_hook, int max_iterations) {
  const int n = int(keyframes_.size());
  if (n < 2) return {};
  first = std::clamp(first, 1, n - 1);  // keyframe 0 fixes the gauge (M)
  Window w(options_.huber);
  addKeyframeFactors(w, first);
  const std::set<int> planes = addPlaneFactors(w, first);
  const std::vector<int> active_rooms = addRoomFactors(w.problem, planes);
  addFloorFactors(w.problem, active_rooms);
  if (with_hook && window_hook_) window_hook_(w.problem, planes, active_rooms);
  ceres::Solver::Options solver;
  solver.linear_solver_type = ceres::SPARSE_NORMAL_CHOLESKY;
  solver.max_num_iterations = max_iterations;
  solver.num_threads = 1;
  ceres::Solver::Summary summary;
  ceres::Solve(solver, &w.problem, &summary);
  for (int plane : planes) {
    Plane& p = planes_[plane];
    p.map.plane = bim::toPlane(p.parameters);
  }
  return {w.problem.NumResidualBlocks(), w.problem.NumParameterBlocks()};
}

void SGraph::tieToFloor(int room) {
  Room& tied = rooms_[room];
  Floor& floor = floors_[tied.floor];
  if (floor.rooms_tied == 0) floor.centre = tied.centre;
  tied.floor_offset = tied.centre - floor.centre;
  ++floor.rooms_tied;
  Eigen::Vector2d sum = Eigen::Vector2d::Zero();
  for (const Room& r : rooms_) {
    if (r.floor == tied.floor && r.floor_offset) sum += *r.floor_offset;
  }
  const Eigen::Vector2d shift = sum / double(floor.rooms_tied);
  floor.centre += shift;
  for (Room& r : rooms_) {
    if (r.floor == tied.floor && r.floor_offset) *r.floor_offset -= shift;
  }
}

void SGraph::addFloorFactors(ceres::Problem& problem, const std::vector<int>& active_rooms) {
  if (options_.floors.room_sigma <= 0.0 || active_rooms.empty()) return;
  const std::vector<int> confirmed = confirmedRooms();
  std::map<int, std::vector<int>> by_floor;
  for (int r : active_rooms) {
    const int floor = rooms_[r].floor;
    if (floor < 0 || floor >= int(floors_.size())) continue;
    if (!std::binary_search(confirmed.begin(), confirmed.end(), r)) continue;
    if (!rooms_[r].floor_offset) tieToFloor(r);
    by_floor[floor].push_back(r);
  }
  for (const auto& [floor, rooms] : by_floor) {
    // One room alone with its floor's node is not constrained by it.
    if (rooms.size() < 2) continue;
    double* centre = floors_[floor].centre.data();
    problem.AddParameterBlock(centre, 2);
    for (int r : rooms) {
      problem.AddResidualBlock(
          FloorRoomFactor::create(*rooms_[r].floor_offset, options_.floors.room_sigma), nullptr,
          centre, rooms_[r].centre.data());
    }
  }
}

MapPlane SGraph::wallOf(const Plane& p) {
  MapPlane wall = p.map;
  if (p.merged_into >= 0) {
    // Never associated, never a room's wall: normal upwards, extent nowhere.
    wall.plane = {Eigen::Vector3d::UnitZ(), 1e9};
    wall.start = wall.end = Eigen::Vector2d::Constant(1e9);
  }
  return wall;
}

std::vector<MapPlane> SGraph::activeWalls(int floor) const {
  std::vector<MapPlane> walls;
  walls.reserve(planes_.size());
  for (const auto& p : planes_) {
    walls.push_back(wallOf(p));
    if (floor >= 0 && p.floor != floor) {
      walls.back().plane = {Eigen::Vector3d::UnitZ(), 1e9};
      walls.back().start = walls.back().end = Eigen::Vector2d::Constant(1e9);
    }
  }
  return walls;
}

int SGraph::floorOf(double z, bool level) {
  const FloorOptions& options = options_.floors;
  if (floors_.empty()) {
    // The first floor, once the robot is off the stairs.
    if (!level) return -1;
    floors_.push_back(Floor::firstStoodOn(z));
    return 0;
  }
  // The nearest floor, the current one on a tie.
  int nearest = current_floor_ >= 0 ? current_floor_ : 0;
  for (int f = 0; f < int(floors_.size()); ++f) {
    if (std::abs(z - floors_[f].robot_z) < std::abs(z - floors_[nearest].robot_z)) nearest = f;
  }
  const double apart = std::abs(z - floors_[nearest].robot_z);
  if (apart <= options.tolerance) {
    // Only level keyframes follow the odometry's drift: one on the first steps must not lift
    // the floor towards the next one.
    if (level) floors_[nearest].robot_z = z;
    ++floors_[nearest].keyframes;
    return nearest;
  }
  if (level && apart >= options.min_separation) {
    floors_.push_back(Floor::firstStoodOn(z));
    return int(floors_.size()) - 1;
  }
  return -1;
}

void SGraph::mergeDuplicatePlanes(int first_keyframe) {
  std::set<int> recent;
  for (int k = first_keyframe; k < int(keyframes_.size()); ++k) {
    for (const auto& [plane, observation] : keyframes_[k].observations) recent.insert(plane);
  }
  // Floor by floor: planes of two floors are never one surface.
  std::set<int> floors;
  for (int j : recent) floors.insert(planes_[j].floor);
  for (int floor : floors) mergeDuplicatePlanes(recent, floor);
}

void SGraph::mergeDuplicatePlanes(const std::set<int>& recent, int floor) {
  // The map as association sees it, made once (a copy per recent plane made this stage grow
  // with the map) and kept equal to activeWalls(floor) as merges change it.
  std::vector<MapPlane> walls = activeWalls(floor);
  AssociationOptions strict = options_.association;
  strict.max_angle_deg = 5.0;
  strict.max_distance = 0.06;
  for (int j : recent) {
    Plane& pj = planes_[j];
    if (pj.merged_into >= 0 || pj.floor != floor) continue;
    // Compare j, as one more observation, with every other active plane.
    PlaneObservation as_observation;
    as_observation.plane = pj.map.plane;
    as_observation.start = Eigen::Vector3d(pj.map.start.x(), pj.map.start.y(), 0.0);
    as_observation.end = Eigen::Vector3d(pj.map.end.x(), pj.map.end.y(), 0.0);
    as_observation.centroid = 0.5 * (as_observation.start + as_observation.end);
    const bim::Plane own = walls[j].plane;
    walls[j].plane = {Eigen::Vector3d::UnitZ(), 1e9};  // not with itself
    const int i = associate(as_observation, walls, strict);
    walls[j].plane = own;
    if (i < 0) continue;
    // Keep the plane observed most; move the other's observations over.
    const int keep = planes_[i].map.observations >= pj.map.observations ? i : j;
    const int drop = keep == i ? j : i;
    Plane& kept = planes_[keep];
    Plane& dropped = planes_[drop];
    for (int k : dropped.observed_by) {
      for (auto& [plane, observation] : keyframes_[k].observations) {
        if (plane == drop) plane = keep;
      }
      kept.observed_by.push_back(k);
    }
    std::sort(kept.observed_by.begin(), kept.observed_by.end());
    kept.observed_by.erase(std::unique(kept.observed_by.begin(), kept.observed_by.end()),
                           kept.observed_by.end());
    PlaneObservation extent;
    extent.start = Eigen::Vector3d(dropped.map.start.x(), dropped.map.start.y(), 0.0);
    extent.end = Eigen::Vector3d(dropped.map.end.x(), dropped.map.end.y(), 0.0);
    extend(kept.map, extent, options_.association.max_length);
    kept.map.observations += dropped.map.observations;
    mergeHeights(kept.map, dropped.map);
    dropped.merged_into = keep;
    dropped.observed_by.clear();
    walls[keep] = wallOf(kept);
    walls[drop] = wallOf(dropped);
    // Rooms built on the dropped plane now stand on the kept one.
    for (auto& room : rooms_) {
      for (auto& pair : room.candidate.pairs) {
        for (int& p : pair) {
          if (p == drop) p = keep;
        }
      }
    }
  }
}

void SGraph::detectRooms(int keyframe, double dominant, const std::vector<MapPlane>& walls) {
  if (walls.size() < 2) return;
  const Eigen::Vector2d point = keyframes_[keyframe].position.head<2>();
  const auto candidate = detectRoom(point, walls, dominant, options_.rooms);
  if (!candidate) return;
  auto same_planes = [](const RoomCandidate& a, const RoomCandidate& b) {
    if (a.four_wall != b.four_wall) return false;
    std::vector<int> pa, pb;
    for (int i = 0; i < (a.four_wall ? 2 : 1); ++i) {
      pa.insert(pa.end(), {a.pairs[i][0], a.pairs[i][1]});
      pb.insert(pb.end(), {b.pairs[i][0], b.pairs[i][1]});
    }
    std::sort(pa.begin(), pa.end());
    std::sort(pb.begin(), pb.end());
    return pa == pb;
  };
  // A corridor's centre moves along its axis with the keyframe it is seen from: the same
  // corridor has the same direction, mid-plane and width.
  auto same_corridor = [this](const Room& room, const RoomCandidate& c) {
    if (room.candidate.four_wall || c.four_wall) return false;
    const bim::Plane& a = planes_[room.candidate.pairs[0][0]].map.plane;
    const bim::Plane& b = planes_[c.pairs[0][0]].map.plane;
    if (std::abs(a.normal.dot(b.normal)) < std::cos(10.0 * std::numbers::pi / 180.0)) return false;
    const Eigen::Vector2d n = a.normal.head<2>().normalized();
    return std::abs(n.dot(room.centre - c.centre)) < 0.2 &&
           std::abs(room.candidate.widths[0] - c.widths[0]) < 0.2;
  };
  const int floor = keyframes_[keyframe].floor;
  for (auto& room : rooms_) {
    if (room.floor != floor) continue;
    // The same room: the same walls, or (walls re-associated since) the same place and shape.
    const bool close = room.candidate.four_wall && candidate->four_wall &&
                       (room.centre - candidate->centre).norm() < 0.5 &&
                       std::abs(room.candidate.widths[0] - candidate->widths[0]) < 0.3 &&
                       std::abs(room.candidate.widths[1] - candidate->widths[1]) < 0.3;
    if (same_planes(room.candidate, *candidate) || close || same_corridor(room, *candidate)) {
      if (std::find(room.keyframes.begin(), room.keyframes.end(), keyframe) ==
          room.keyframes.end()) {
        room.keyframes.push_back(keyframe);
      }
      return;
    }
  }
  Room room;
  room.candidate = *candidate;
  room.centre = candidate->centre;
  room.keyframes = {keyframe};
  room.floor = floor;
  rooms_.push_back(room);
}

std::vector<int> SGraph::confirmedRooms() const {
  // Inside a room: in front of all its walls.
  auto contains = [this](const Room& room, const Eigen::Vector2d& point) {
    for (int i = 0; i < (room.candidate.four_wall ? 2 : 1); ++i) {
      for (int plane : room.candidate.pairs[i]) {
        if (planes_[plane].map.plane.signedDistance({point.x(), point.y(), 1.0}) <= 0) return false;
      }
    }
    return true;
  };
  auto area = [](const Room& r) {
    return r.candidate.four_wall ? r.candidate.widths[0] * r.candidate.widths[1] : 1e300;
  };
  std::vector<int> out;
  for (int i = 0; i < int(rooms_.size()); ++i) {
    const Room& room = rooms_[i];
    // Corridors must be stood in twice; four-wall rooms are already checked by their walls' cover.
    if (!room.candidate.four_wall && room.keyframes.size() < 2) continue;
    bool encloses_smaller = false;
    for (int j = 0; j < int(rooms_.size()) && !encloses_smaller; ++j) {
      const Room& other = rooms_[j];
      encloses_smaller = j != i && other.floor == room.floor && other.candidate.four_wall &&
                         room.candidate.four_wall && area(other) < area(room) - 0.5 &&
                         contains(room, other.centre);
    }
    if (!encloses_smaller) out.push_back(i);
  }
  return out;
}

std::optional<double> SGraph::floorHeight(int floor) const {
  if (floor < 0) floor = current_floor_;
  if (floor < 0 || floor >= int(floors_.size())) return std::nullopt;
  const Floor& f = floors_[floor];
  if (f.plane_count > 0) return f.plane_sum / f.plane_count;
  // The robot stands as high above every floor it walks on, and the floors seen well before (of
  // any segment, never this one: it has no well-supported plane) tell how high.
  std::optional<double> carried;
  if (robot_above_floor_count_ > 0) {
    carried = f.robot_z - robot_above_floor_sum_ / robot_above_floor_count_;
  }
  // The support-weighted median of the sparse floor surfaces (of those near the carried height,
  // when it is known).
  auto near = [&](double z) {
    return !carried || std::abs(z - *carried) <= options_.floors.carried_tolerance;
  };
  long support = 0;
  for (const auto& [z, points] : f.sparse_planes) support += near(z) ? points : 0;
  long below = 0;
  for (const auto& [z, points] : f.sparse_planes) {
    if (!near(z)) continue;
    below += points;
    if (2 * below >= support) return z;
  }
  // Not seen from this floor yet: the carried height, when known.
  return carried;
}

std::optional<double> SGraph::floorBound(int floor) const {
  if (floor < 0) floor = current_floor_;
  if (floor < 0 || floor >= int(floors_.size())) return std::nullopt;
  return floors_[floor].lowest_seen;
}

std::optional<Eigen::Vector2d> SGraph::floorCentre(int floor) const {
  if (floor < 0) floor = current_floor_;
  if (floor < 0 || floor >= int(floors_.size()) || floors_[floor].rooms_tied == 0) {
    return std::nullopt;
  }
  return floors_[floor].centre;
}

std::vector<std::pair<Eigen::Vector2d, Eigen::Vector2d>> SGraph::spansOf(int plane) const {
  std::vector<std::pair<Eigen::Vector2d, Eigen::Vector2d>> spans;
  std::vector<int> keyframes = planes_[plane].observed_by;  // once each: all of theirs are taken
  std::sort(keyframes.begin(), keyframes.end());
  keyframes.erase(std::unique(keyframes.begin(), keyframes.end()), keyframes.end());
  for (int k : keyframes) {
    const Eigen::Isometry3d M_T_L = keyframes_[k].pose() * R_T_L_;
    for (const auto& [observed, observation] : keyframes_[k].observations) {
      if (observed != plane) continue;
      const Eigen::Vector2d from = (M_T_L * observation.start).head<2>();
      const Eigen::Vector2d to = (M_T_L * observation.end).head<2>();
      if (observation.pieces.empty()) spans.emplace_back(from, to);
      for (const auto& [a, b] : observation.pieces) {
        spans.emplace_back(from + a * (to - from), from + b * (to - from));
      }
    }
  }
  return spans;
}

MapDiagnostics SGraph::diagnostics() const {
  MapDiagnostics out;
  out.keyframes = past_keyframes_;
  out.current_segment = past_keyframes_.size();
  for (const auto& kf : keyframes_) {
    out.keyframes.push_back({kf.stamp, kf.pose(), kf.odometry, kf.sight, int(segments_.size())});
  }
  out.planes = planes_.size();
  for (std::size_t i = 0; i < planes_.size(); ++i) {
    const MapPlane& p = planes_[i].map;
    if (planes_[i].merged_into >= 0 || !seenAsWall(p, options_.rooms.min_wall_height)) continue;
    const auto [start, end] = endsOnPlane(p);
    MapWall wall{int(i),  p.plane.normal, p.plane.d,      start, end,
                 p.z_min, p.z_max,        p.observations, {},    {}};
    wall.confirmed = confirmedSpans(p, spansOf(int(i)), options_.confirmation);
    for (int k : planes_[i].observed_by) wall.keyframes.push_back(int(past_keyframes_.size()) + k);
    out.walls.push_back(std::move(wall));
  }
  for (int r : confirmedRooms()) {
    const Room& room = rooms_[r];
    out.rooms.push_back({room.centre, room.candidate.four_wall, room.candidate.widths});
  }
  out.timings = timings_;
  return out;
}

nlohmann::json SGraph::toJson() const {
  nlohmann::json keyframes = nlohmann::json::array(), planes = nlohmann::json::array();
  for (const auto& k : keyframes_) {
    const Eigen::Quaterniond q = k.orientation.normalized();
    nlohmann::json observed = nlohmann::json::array();
    for (const auto& [plane, observation] : k.observations) observed.push_back(plane);
    keyframes.push_back({{"stamp", k.stamp},
                         {"position", {k.position.x(), k.position.y(), k.position.z()}},
                         {"orientation_xyzw", {q.x(), q.y(), q.z(), q.w()}},
                         {"floor", k.floor},
                         {"planes", k.observations.size()},
                         {"plane_ids", observed},
                         {"registration",
                          {{"attempted", k.registration.attempted},
                           {"agrees", k.registration.agrees},
                           {"inlier_share", k.registration.inlier_share},
                           {"inlier_share_predicted", k.registration.inlier_share_predicted}}}});
  }
  for (std::size_t i = 0; i < planes_.size(); ++i) {
    const auto& p = planes_[i];
    const auto [start, end] = endsOnPlane(p.map);
    planes.push_back(
        {{"id", i},
         {"n", {p.map.plane.normal.x(), p.map.plane.normal.y(), p.map.plane.normal.z()}},
         {"d", p.map.plane.d},
         {"start", {start.x(), start.y()}},
         {"end", {end.x(), end.y()}},
         {"floor", p.floor},
         {"observations", p.map.observations}});
  }
  nlohmann::json rooms = nlohmann::json::array();
  for (int i : confirmedRooms()) {
    const auto& r = rooms_[i];
    nlohmann::json pairs = nlohmann::json::array();
    for (int k = 0; k < (r.candidate.four_wall ? 2 : 1); ++k) {
      pairs.push_back({r.candidate.pairs[k][0], r.candidate.pairs[k][1]});
    }
    nlohmann::json widths = r.candidate.four_wall
                                ? nlohmann::json{r.candidate.widths[0], r.candidate.widths[1]}
                                : nlohmann::json{r.candidate.widths[0]};
    rooms.push_back({{"id", i},
                     {"kind", r.candidate.four_wall ? "four_wall" : "two_wall"},
                     {"centre", {r.centre.x(), r.centre.y()}},
                     {"plane_pairs", pairs},
                     {"widths", widths},
                     {"floor", r.floor},
                     {"keyframes", r.keyframes.size()}});
  }
  nlohmann::json segments = nlohmann::json::array();
  for (const auto& segment : segments_) {
    segments.push_back({{"start", segment.start},
                        {"end", segment.end},
                        {"keyframes", segment.keyframes},
                        {"planes", segment.planes},
                        {"rooms", segment.rooms},
                        {"ended_because", segment.reason}});
  }
  nlohmann::json out = {{"frame", "M"},         {"keyframes", keyframes},
                        {"planes", planes},     {"rooms", rooms},
                        {"segments", segments}, {"segment_start", segment_start_}};
  if (const auto floor = floorCentre()) out["floor"] = {{"centre", {floor->x(), floor->y()}}};
  nlohmann::json floors = nlohmann::json::array();
  for (int f = 0; f < int(floors_.size()); ++f) {
    nlohmann::json floor = {
        {"id", f}, {"robot_z", floors_[f].robot_z}, {"keyframes", floors_[f].keyframes}};
    if (const auto height = floorHeight(f)) floor["height"] = *height;
    if (const auto centre = floorCentre(f)) floor["centre"] = {centre->x(), centre->y()};
    floors.push_back(floor);
  }
  out["floors"] = floors;
  out["current_floor"] = current_floor_;
  return out;
}

}  // namespace isg::slam
