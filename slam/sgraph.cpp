#include "slam/sgraph.hpp"

#include <ceres/ceres.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <set>

#include "bim/plane_manifold.hpp"
#include "slam/sgraph_factors.hpp"

namespace isg::slam {

namespace {

double seconds(std::chrono::steady_clock::time_point since) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - since).count();
}

double yawOf(const Eigen::Matrix3d& R) { return std::atan2(R(1, 0), R(0, 0)); }

// Extends a map plane's extent with an observation already in M.
void extend(MapPlane& m, const PlaneObservation& o) {
  Eigen::Vector2d along(-m.plane.normal.y(), m.plane.normal.x());
  if (along.norm() < 1e-6) return;
  along.normalize();
  double lo = std::min(along.dot(m.start), along.dot(m.end));
  double hi = std::max(along.dot(m.start), along.dot(m.end));
  lo = std::min({lo, along.dot(o.start.head<2>()), along.dot(o.end.head<2>())});
  hi = std::max({hi, along.dot(o.start.head<2>()), along.dot(o.end.head<2>())});
  const Eigen::Vector2d base = -m.plane.d * m.plane.normal.head<2>();
  const Eigen::Vector2d origin = base - along.dot(base) * along;
  m.start = origin + lo * along;
  m.end = origin + hi * along;
}

}  // namespace

Eigen::Isometry3d SGraph::Keyframe::pose() const {
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  T.linear() = orientation.normalized().toRotationMatrix();
  T.translation() = position;
  return T;
}

SGraph::SGraph(const Eigen::Isometry3d& R_T_L, const SGraphOptions& options)
    : R_T_L_(R_T_L), options_(options) {}

void SGraph::addOdometry(const Odometry& odometry) {
  odometry_.push(odometry);
  latest_odometry_ = odometry;
}

std::optional<Odometry> SGraph::latestPose() const {
  if (!latest_odometry_) return std::nullopt;
  if (keyframes_.empty()) return latest_odometry_;
  const Keyframe& k = keyframes_.back();
  Odometry out = *latest_odometry_;
  out.M_T_R = k.pose() * k.odometry.inverse() * latest_odometry_->M_T_R;
  return out;
}

std::optional<Eigen::Isometry3d> SGraph::poseAt(double t) const {
  const auto odometry = odometry_.at(t);
  if (!odometry) return std::nullopt;
  // The last keyframe at or before t.
  const auto it = std::upper_bound(keyframes_.begin(), keyframes_.end(), t,
                                   [](double s, const Keyframe& k) { return s < k.stamp; });
  if (it == keyframes_.begin()) return odometry;
  const Keyframe& k = *(it - 1);
  return k.pose() * k.odometry.inverse() * *odometry;
}

bool SGraph::addScan(Scan scan) {
  const auto start = std::chrono::steady_clock::now();
  const auto odometry_at_scan = odometry_.at(scan.stamp);
  if (!odometry_at_scan) return false;  // no odometry yet for this instant
  if (!keyframes_.empty()) {
    const Eigen::Isometry3d delta = keyframes_.back().odometry.inverse() * *odometry_at_scan;
    const double moved = delta.translation().head<2>().norm();
    const double turned = std::abs(yawOf(delta.linear()));
    if (moved < options_.keyframe_distance && turned < options_.keyframe_angle) return false;
  }
  deskew(scan, odometry_, R_T_L_);

  Keyframe keyframe;
  keyframe.stamp = scan.stamp;
  keyframe.odometry = *odometry_at_scan;
  const Eigen::Isometry3d initial =
      keyframes_.empty()
          ? *odometry_at_scan
          : keyframes_.back().pose() * keyframes_.back().odometry.inverse() * *odometry_at_scan;
  keyframe.position = initial.translation();
  keyframe.orientation = Eigen::Quaterniond(initial.rotation());
  const int index = int(keyframes_.size());

  const auto cloud = preprocess(scan, options_.extraction);
  const Eigen::Isometry3d M_T_L = initial * R_T_L_;
  for (const auto& observation : extractPlanes(*cloud, options_.extraction)) {
    if (observation.orientation != PlaneOrientation::kVertical) continue;
    const PlaneObservation in_map = toMap(observation, M_T_L);
    std::vector<MapPlane> candidates;
    candidates.reserve(planes_.size());
    for (const auto& p : planes_) candidates.push_back(p.map);
    int plane = associate(in_map, candidates, options_.association);
    if (plane < 0) {
      Plane created;
      created.map = {in_map.plane, in_map.start.head<2>(), in_map.end.head<2>(), 0};
      created.parameters = bim::toVector(in_map.plane);
      planes_.push_back(created);
      plane = int(planes_.size()) - 1;
    }
    Plane& p = planes_[plane];
    extend(p.map, in_map);
    ++p.map.observations;
    p.observed_by.push_back(index);
    keyframe.observations.emplace_back(plane, observation);
  }
  keyframes_.push_back(std::move(keyframe));
  Timing timing;
  timing.extraction_s = seconds(start);
  const auto optimisation_start = std::chrono::steady_clock::now();
  optimise();
  timing.optimisation_s = seconds(optimisation_start);
  timings_.push_back(timing);
  return true;
}

void SGraph::optimise() {
  const int n = int(keyframes_.size());
  if (n < 2) return;
  const int first = std::max(1, n - options_.window);  // keyframe 0 fixes the gauge (M)
  ceres::Problem::Options problem_options;
  // The manifolds and the loss live on this stack frame, not in the problem.
  problem_options.manifold_ownership = ceres::DO_NOT_TAKE_OWNERSHIP;
  problem_options.loss_function_ownership = ceres::DO_NOT_TAKE_OWNERSHIP;
  ceres::Problem problem(problem_options);
  ceres::EigenQuaternionManifold quaternion;
  bim::PlaneManifold plane_manifold;
  ceres::HuberLoss huber(options_.huber);

  std::set<int> held;  // keyframes in the problem whose poses do not move
  auto add_pose = [&](int k, bool fixed) {
    Keyframe& kf = keyframes_[k];
    problem.AddParameterBlock(kf.position.data(), 3);
    problem.AddParameterBlock(kf.orientation.coeffs().data(), 4, &quaternion);
    if (fixed) {
      problem.SetParameterBlockConstant(kf.position.data());
      problem.SetParameterBlockConstant(kf.orientation.coeffs().data());
      held.insert(k);
    }
  };
  add_pose(first - 1, true);
  for (int k = first; k < n; ++k) {
    add_pose(k, false);
    const Keyframe& a = keyframes_[k - 1];
    const Keyframe& b = keyframes_[k];
    const Eigen::Isometry3d delta = a.odometry.inverse() * b.odometry;
    const double distance = delta.translation().norm();
    const double sigma_t = options_.sigma_odometry_translation_floor +
                           options_.sigma_odometry_translation_per_metre * std::sqrt(distance);
    const double sigma_r = options_.sigma_odometry_rotation_floor +
                           options_.sigma_odometry_rotation_per_metre * std::sqrt(distance);
    problem.AddResidualBlock(
        OdometryFactor::create(delta, sigma_t, sigma_r), nullptr, keyframes_[k - 1].position.data(),
        keyframes_[k - 1].orientation.coeffs().data(), keyframes_[k].position.data(),
        keyframes_[k].orientation.coeffs().data());
  }
  // Planes seen in the window, their observations from the window, and a few older, held ones.
  std::set<int> planes;
  for (int k = first; k < n; ++k) {
    for (const auto& [plane, observation] : keyframes_[k].observations) planes.insert(plane);
  }
  for (int plane : planes) {
    Plane& p = planes_[plane];
    problem.AddParameterBlock(p.parameters.data(), 4, &plane_manifold);
    int anchors = 0;
    for (auto it = p.observed_by.rbegin(); it != p.observed_by.rend(); ++it) {
      const int k = *it;
      if (k < first) {
        if (anchors >= options_.anchors_per_plane) continue;
        ++anchors;
        if (!held.count(k)) add_pose(k, true);
      }
      for (const auto& [observed, observation] : keyframes_[k].observations) {
        if (observed != plane) continue;
        problem.AddResidualBlock(
            PosePlaneFactor::create(bim::toVector(observation.plane), R_T_L_,
                                    options_.sigma_plane_angle, options_.sigma_plane_distance),
            &huber, keyframes_[k].position.data(), keyframes_[k].orientation.coeffs().data(),
            p.parameters.data());
      }
    }
  }
  ceres::Solver::Options solver;
  solver.linear_solver_type = ceres::SPARSE_NORMAL_CHOLESKY;
  solver.max_num_iterations = options_.max_iterations;
  solver.num_threads = 1;
  ceres::Solver::Summary summary;
  ceres::Solve(solver, &problem, &summary);
  for (int plane : planes) {
    Plane& p = planes_[plane];
    p.map.plane = bim::toPlane(p.parameters);
  }
}

nlohmann::json SGraph::toJson() const {
  nlohmann::json keyframes = nlohmann::json::array(), planes = nlohmann::json::array();
  for (const auto& k : keyframes_) {
    const Eigen::Quaterniond q = k.orientation.normalized();
    keyframes.push_back({{"stamp", k.stamp},
                         {"position", {k.position.x(), k.position.y(), k.position.z()}},
                         {"orientation_xyzw", {q.x(), q.y(), q.z(), q.w()}},
                         {"planes", k.observations.size()}});
  }
  for (std::size_t i = 0; i < planes_.size(); ++i) {
    const auto& p = planes_[i];
    planes.push_back(
        {{"id", i},
         {"n", {p.map.plane.normal.x(), p.map.plane.normal.y(), p.map.plane.normal.z()}},
         {"d", p.map.plane.d},
         {"start", {p.map.start.x(), p.map.start.y()}},
         {"end", {p.map.end.x(), p.map.end.y()}},
         {"observations", p.map.observations}});
  }
  return {{"frame", "M"}, {"keyframes", keyframes}, {"planes", planes}};
}

}  // namespace isg::slam
