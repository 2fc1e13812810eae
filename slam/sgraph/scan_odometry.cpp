#include "slam/sgraph/scan_odometry.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <numbers>
#include <stdexcept>

#include "common/angles.hpp"
#include "slam/sgraph/voxel_key.hpp"

namespace isg::slam {

namespace {

// Rings whose latest voxel deskewedCloud keeps (every LiDAR model's: at most 128 lasers).
constexpr std::uint16_t kCachedRings = 128;

// std::lround for x ≥ 0 (ties away from zero), inline: glibc's lround is a library call, and it
// ran once per scan point. x - trunc(x) is exact below 2^52.
inline std::size_t roundNonNegative(double x) {
  const auto whole = std::int64_t(x);
  return std::size_t(whole + (x - double(whole) >= 0.5 ? 1 : 0));
}

Eigen::Matrix3d yawRotation(double yaw) {
  return Eigen::AngleAxisd(yaw, Eigen::Vector3d::UnitZ()).toRotationMatrix();
}

// The scan's points moved into L at the stamp by `L0_T_L` (one transform each `step` seconds of
// the turn from `first`), within the range limits, as voxel centroids (options.voxel) in the
// order each voxel was first met; of each laser's returns, every `stride`-th from its first.
// One pass over the points, no sort: the scan of every 0.1 s goes through here. `index`: the
// caller's, reused from scan to scan.
std::vector<Eigen::Vector3f> deskewedCloud(const sensors::Scan& scan,
                                           const std::vector<Eigen::Isometry3d>& L0_T_L,
                                           float first, double step, int stride,
                                           const ScanRegistrationOptions& options,
                                           VoxelIndex& index) {
  index.clear(scan.points.size() / 8 + 16);
  std::vector<std::pair<Eigen::Vector3d, int>> sums;  // per voxel: sum, count
  const double min2 = options.min_range * options.min_range;
  const double max2 = options.max_range * options.max_range;
  // Each ring's latest voxel: a laser's next return, a fraction of a degree further round, mostly
  // falls in the same voxel, and then the index (a random access into a table larger than the
  // cache) is not asked. The same voxels, met in the same order.
  struct RingVoxel {
    std::uint64_t key = VoxelIndex::kEmpty;
    int at = -1;
  };
  std::array<RingVoxel, kCachedRings> ring_voxel{};
  // Each ring's returns met so far (rings past kCachedRings share the last counter).
  std::array<int, kCachedRings + 1> ring_returns{};
  for (const auto& point : scan.points) {
    if (ring_returns[std::min(point.ring, kCachedRings)]++ % stride != 0) continue;
    const Eigen::Isometry3d& T = L0_T_L[roundNonNegative((point.time - first) / step)];
    const Eigen::Vector3d q = T * Eigen::Vector3d(point.x, point.y, point.z);
    const double range2 = q.squaredNorm();
    if (!std::isfinite(range2) || range2 < min2 || range2 > max2) continue;
    const std::uint64_t key = voxelKey(q, options.voxel);
    RingVoxel unused;
    RingVoxel& last = point.ring < kCachedRings ? ring_voxel[point.ring] : unused;
    if (last.key != key) last = {key, index.insert(key, int(sums.size()))};
    const int at = last.at;
    if (at == int(sums.size())) sums.push_back({Eigen::Vector3d::Zero(), 0});
    sums[at].first += q;
    ++sums[at].second;
  }
  std::vector<Eigen::Vector3f> out;
  out.reserve(sums.size());
  for (const auto& [sum, count] : sums) out.push_back((sum / double(count)).cast<float>());
  return out;
}

// The cloud's points thinned to one per `voxel` (the first met in each): the points registered.
// The map keeps the finer cloud; the registration's information is capped at effective_points
// anyway, and fewer points make fewer lookups.
std::vector<Eigen::Vector3f> coarser(const std::vector<Eigen::Vector3f>& cloud, double voxel,
                                     VoxelIndex& index) {
  index.clear(cloud.size() / 2 + 16);
  std::vector<Eigen::Vector3f> out;
  for (const auto& p : cloud) {
    if (index.insert(voxelKey(p.cast<double>(), voxel), int(out.size())) == int(out.size())) {
      out.push_back(p);
    }
  }
  return out;
}

}  // namespace

ScanOdometry::ScanOdometry(const Eigen::Isometry3d& R_T_L, const Eigen::Isometry3d& R_T_I,
                           const ScanOdometryOptions& options)
    : R_T_L_(R_T_L),
      R_T_I_(R_T_I),
      options_(options),
      wall_registration_(options.registration),
      attitude_(options.attitude_time_constant, options.gravity, /*estimate_bias=*/true),
      map_(options.map) {
  wall_registration_.max_normal_z = options.wall_max_normal_z;
  if (options.return_stride < 1) {
    throw std::invalid_argument("scan odometry: return_stride must be at least 1");
  }
}

void ScanOdometry::addImu(const sensors::ImuSample& sample) { attitude_.add(sample); }

Eigen::Isometry3d ScanOdometry::predict(double t) const {
  Eigen::Isometry3d out = Eigen::Isometry3d::Identity();
  const double dt = last_stamp_ ? t - *last_stamp_ : 0.0;
  if (hasImu()) {
    out.linear() = attitude_.M_R_I_at(t) * R_T_I_.linear().transpose();
  } else {
    out.linear() = yawRotation(yaw_rate_ * dt) * last_pose_.linear();
  }
  out.translation() = last_pose_.translation() + velocity_ * dt;
  return out;
}

void ScanOdometry::turnYaw(double angle) { attitude_.turnYaw(angle); }

void ScanOdometry::levelByStructure(const std::vector<Eigen::Vector3f>& cloud,
                                    Eigen::Isometry3d& predicted) {
  const Eigen::Matrix3d M_R_L = predicted.linear() * R_T_L_.linear();
  const std::optional<Eigen::Vector3d> up_in_L =
      structuralUp(cloud, M_R_L.transpose() * Eigen::Vector3d::UnitZ(), options_.structural_up);
  if (!up_in_L) return;
  const Eigen::Vector3d up_in_M = M_R_L * *up_in_L;
  const double turn = std::acos(std::clamp(up_in_M.z(), -1.0, 1.0));
  if (turn < options_.structural_up_min_turn_deg * std::numbers::pi / 180.0) return;
  const Eigen::Quaterniond level =
      Eigen::Quaterniond::FromTwoVectors(up_in_M, Eigen::Vector3d::UnitZ());
  attitude_.turnFrame(level);
  predicted.linear() = level * predicted.linear();
  // M's heading stays the base's.
  const double yaw = common::yawOf(predicted.linear());
  turnYaw(-yaw);
  predicted.linear() = yawRotation(-yaw) * predicted.linear();
  start_levelled_ = turn;
}

double ScanOdometry::heightCorrection(const std::vector<Eigen::Vector3f>& cloud,
                                      const Eigen::Isometry3d& pose) const {
  const ScanRegistrationOptions& r = options_.registration;
  const LevelOffset level = levelOffset(cloud, pose * R_T_L_, map_, r.max_correspondence_end,
                                        r.huber, options_.level_normal_z);
  if (level.points < options_.min_level_points) return 0.0;
  // The offset's information as a registration's (σ per point, at most effective_points), σ no
  // smaller than the points' own spread about it; against the prediction's prior.
  const double sigma = std::max(r.point_sigma, level.spread);
  const double information = std::min(double(level.points), r.effective_points) / (sigma * sigma);
  const double prior = 1.0 / (options_.prior_sigma_height * options_.prior_sigma_height);
  return -level.offset * information / (information + prior);
}

Eigen::Isometry3d ScanOdometry::addScan(const sensors::Scan& scan) {
  const double s = scan.stamp;
  Eigen::Isometry3d predicted = predict(s);
  if (!last_stamp_) {
    // M is the base's start pose: its heading is M's x axis, its tilt what gravity says.
    const double yaw = common::yawOf(predicted.linear());
    turnYaw(-yaw);
    predicted.linear() = yawRotation(-yaw) * predicted.linear();
    predicted.translation().setZero();
  }
  // The scan deskewed by the predicted motion (each point into L at the stamp) and downsampled.
  const Eigen::Isometry3d L0_T_M = (predicted * R_T_L_).inverse();
  float first = 0.0f, last = 0.0f;
  for (const auto& p : scan.points) first = std::min(first, p.time), last = std::max(last, p.time);
  last_span_ = last;
  constexpr double kStep = 0.005;  // s: the predicted motion is smooth within a turn
  std::vector<Eigen::Isometry3d> L0_T_L;
  for (int i = 0; i <= int(std::ceil((last - first) / kStep)); ++i) {
    L0_T_L.push_back(last_stamp_ ? L0_T_M * predict(s + first + i * kStep) * R_T_L_
                                 : Eigen::Isometry3d::Identity());
  }
  std::vector<Eigen::Vector3f> cloud = deskewedCloud(
      scan, L0_T_L, first, kStep, options_.return_stride, options_.registration, index_);
  if (!last_stamp_ && hasImu()) levelByStructure(cloud, predicted);

  Eigen::Isometry3d pose = predicted;
  if (!map_.empty() && !cloud.empty()) {
    const double sigma_yaw = hasImu() ? options_.prior_sigma_yaw_imu : options_.prior_sigma_yaw;
    const double st = options_.prior_sigma_translation;
    const Eigen::Matrix3d prior =
        Eigen::Vector3d(1.0 / (st * st), 1.0 / (st * st), 1.0 / (sigma_yaw * sigma_yaw))
            .asDiagonal();
    const std::vector<Eigen::Vector3f> registered =
        coarser(cloud, options_.registration_voxel, index_);
    const RegistrationResult result =
        registerToPlanes(registered, predicted, R_T_L_, map_, prior, wall_registration_);
    ++registered_;
    if (result.agrees) {
      ++agreed_;
      pose = result.apply(predicted);
      pose.translation().z() += heightCorrection(registered, pose);
      if (hasImu()) turnYaw(common::yawOf(pose.linear()) - common::yawOf(predicted.linear()));
    }
  }

  // The velocity over the recent scans (`velocity_window`), not from the last two: a scan's
  // registration is good to millimetres, and their differences over 0.1 s would feed back into the
  // next prediction and deskew as noise of several cm/s.
  recent_.push_back({s, pose});
  while (recent_.size() > 2 && recent_.front().first < s - options_.velocity_window) {
    recent_.pop_front();
  }
  if (recent_.size() >= 2) {
    const auto& [t0, pose0] = recent_.front();
    const double dt = s - t0;
    if (dt > 0.0) {
      velocity_ = (pose.translation() - pose0.translation()) / dt;
      velocity_.z() = 0.0;
      yaw_rate_ =
          common::wrapAngle(common::yawOf(pose.linear()) - common::yawOf(pose0.linear())) / dt;
    }
  }
  last_stamp_ = s;
  last_pose_ = pose;

  // A keyframe of the local map when the base moved or turned enough since the last one.
  bool keyframe = keyframes_.empty();
  if (!keyframe) {
    const Eigen::Isometry3d moved = keyframes_.back().M_T_R.inverse() * pose;
    keyframe = moved.translation().head<2>().norm() >= options_.keyframe_distance ||
               std::abs(common::yawOf(moved.linear())) >= options_.keyframe_angle;
  }
  if (keyframe && !cloud.empty()) {
    keyframes_.push_back({map_.contributionOf(cloud, pose * R_T_L_), pose});
    map_.add(keyframes_.back().contribution);
    while (int(keyframes_.size()) > options_.registration.local_map_keyframes) {
      map_.remove(keyframes_.front().contribution);
      keyframes_.pop_front();
    }
  }
  return pose;
}

}  // namespace isg::slam
