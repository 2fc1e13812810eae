#include "sim/lidar_simulator.hpp"

#include <algorithm>
#include <array>
#include <boost/random/normal_distribution.hpp>
#include <chrono>
#include <cmath>
#include <numbers>
#include <string_view>

#include "sim/body_shadow.hpp"
#include "sim/fast_random.hpp"
#include "sim/mount_transform.hpp"
#include "sim/robot_model.hpp"
#include "sim/vlp16.hpp"

namespace isg::sim {

namespace {

constexpr double kQuantum = 0.002;  // the VLP-16 reports ranges in 2 mm steps
constexpr std::uint64_t kNoiseStream = 1;

// std::round for x ≥ 0 without a library call (ties go up; they have probability zero here).
inline double roundHalfUp(double x) { return double(std::int64_t(x + 0.5)); }

// A range in the sensor's 2 mm steps.
inline double quantise(double range) {
  if (range < 0) return std::round(range / kQuantum) * kQuantum;  // discarded by the range gate
  return roundHalfUp(range / kQuantum) * kQuantum;
}

}  // namespace

double surfaceReflectivity(const bim::SurfaceReflectivity& reflectivity,
                           std::string_view material) {
  if (material == "wall" || material == "extra_wall") return reflectivity.wall;
  if (material == "floor") return reflectivity.floor;
  if (material == "ceiling") return reflectivity.ceiling;
  if (material == "door") return reflectivity.door;
  if (material == "stair") return reflectivity.stair;
  return reflectivity.clutter;  // clutter, and anything else a world holds
}

LidarSimulator::LidarSimulator(const MujocoWorld& world, const bim::LidarConfig& config,
                               unsigned groups)
    : world_(world),
      config_(config),
      caster_(world.model(), world.data(), groups),
      scan_caster_(caster_),
      sequences_(Vlp16::sequencesPerTurn(config.rate_hz)) {
  const mjModel& m = world.model();
  reflectivity_.resize(m.ngeom);
  for (int g = 0; g < m.ngeom; ++g) {
    const int material = m.geom_matid[g];
    const char* name = material >= 0 ? mj_id2name(&m, mjOBJ_MATERIAL, material) : nullptr;
    reflectivity_[g] = float(surfaceReflectivity(config.reflectivity, name ? name : ""));
  }
  // The LiDAR equation for a surface filling the beam: the returned power goes as
  // reflectivity × cos(incidence) / range². The weakest the sensor detects is a 10 % surface met
  // head-on at detection_range_m.
  min_signal_ = 0.1 / (config.detection_range_m * config.detection_range_m);
  full_return_cos_ = std::cos(config.grazing_cutoff_deg * std::numbers::pi / 180.0);
  // Geoms' poses as the sensor sees them (the building does not move during a run).
  const mjData& d = world.data();
  shapes_.resize(m.ngeom);
  for (int g = 0; g < m.ngeom; ++g) {
    GeomShape& shape = shapes_[g];
    shape.type = m.geom_type[g];
    shape.pos = Eigen::Map<const Eigen::Vector3d>(d.geom_xpos + 3 * g);
    shape.R = Eigen::Map<const Eigen::Matrix<double, 3, 3, Eigen::RowMajor>>(d.geom_xmat + 9 * g);
    shape.inverse_half = Eigen::Map<const Eigen::Vector3d>(m.geom_size + 3 * g).cwiseInverse();
  }
  const BodyShadow body(robotBodyBox(), mountTransform(config.mount));
  firings_.reserve(std::size_t(sequences_) * Vlp16::kLasers);
  for (int s = 0; s < sequences_; ++s) {
    for (int l = 0; l < Vlp16::kLasers; ++l) {
      const double t = Vlp16::firingTime(s, l);
      const Eigen::Vector3d direction = Vlp16::direction(l, Vlp16::azimuth(t, config.rate_hz));
      const bool blocked = config.body_occlusion && body.distance(Vlp16::origin(l), direction) >= 0;
      firings_.push_back({direction, t, blocked});
    }
  }
}

Eigen::Vector3d LidarSimulator::surfaceNormal(int geom, const Eigen::Vector3d& point,
                                              const Eigen::Vector3d& direction) const {
  const GeomShape& shape = shapes_[geom];
  switch (shape.type) {
    case mjGEOM_BOX: {
      const Eigen::Vector3d local = shape.R.transpose() * (point - shape.pos);
      // The face the point lies on: the axis along which it is furthest out, in half-sizes.
      const Eigen::Vector3d out = local.cwiseAbs().cwiseProduct(shape.inverse_half);
      const int axis =
          out.x() >= out.y() ? (out.x() >= out.z() ? 0 : 2) : (out.y() >= out.z() ? 1 : 2);
      return local[axis] >= 0 ? shape.R.col(axis) : Eigen::Vector3d(-shape.R.col(axis));
    }
    case mjGEOM_SPHERE:
      return (point - shape.pos).normalized();
    default:
      return -direction;  // unknown shape: as if hit head-on
  }
}

int LidarSimulator::blockCount() const {
  return (sequences_ + kBlockSequences - 1) / kBlockSequences;
}

LidarScan LidarSimulator::scan(double stamp, const PoseAt& B_T_L, std::uint64_t seed) {
  return scanBlocks(stamp, B_T_L, seed, 0, blockCount());
}

LidarScan LidarSimulator::scanBlocks(double stamp, const PoseAt& B_T_L, std::uint64_t seed,
                                     int first_block, int last_block) {
  using Clock = std::chrono::steady_clock;
  auto seconds = [](Clock::time_point a, Clock::time_point b) {
    return std::chrono::duration<double>(b - a).count();
  };
  LidarScan out;
  out.stamp = stamp;
  const int first_sequence = first_block * kBlockSequences;
  const int last_sequence = std::min(sequences_, last_block * kBlockSequences);
  if (first_sequence >= last_sequence) return out;
  out.points.reserve(std::size_t(last_sequence - first_sequence) * Vlp16::kLasers);
  auto mark = Clock::now();
  // Sensor poses every kPoseStride sequences (0.44 ms) and at the turn's end; each laser's pose
  // is interpolated linearly between them. The gait sways the sensor at about 2 Hz: over 0.44 ms
  // its path departs from a straight line by under 0.1 µm and its rotation from slerp by under
  // 1e-7 rad, far below the sensor's 2 mm range steps.
  // Samples j cover sequences [j·stride, (j+1)·stride); those of the blocks asked for only, so
  // that a turn made in parts is the very same as one made whole.
  const int first_sample = first_sequence / kPoseStride;
  const int last_sample = (last_sequence + kPoseStride - 1) / kPoseStride;
  positions_.resize(last_sample + 1);
  rotations_.resize(last_sample + 1);
  Eigen::Vector2d lo = Eigen::Vector2d::Constant(1e300), hi = -lo;
  for (int j = first_sample; j <= last_sample; ++j) {
    const int s = std::min(sequences_, j * kPoseStride);
    const Eigen::Isometry3d T = B_T_L(stamp + s * kSequence);
    positions_[j] = T.translation();
    rotations_[j] = T.linear();
    lo = lo.cwiseMin(positions_[j].head<2>());
    hi = hi.cwiseMax(positions_[j].head<2>());
  }
  // Laser origins sit within millimetres of the sensor's axis.
  scan_caster_.prepare(0.5 * (lo + hi), 0.5 * (hi - lo).norm() + 0.02);
  std::array<double, Vlp16::kLasers> offset{};
  for (int l = 0; l < Vlp16::kLasers; ++l) offset[l] = Vlp16::origin(l).z();
  auto now = Clock::now();
  out.timing.poses_s += seconds(mark, now);
  mark = now;

  const int per_block = kBlockSequences * Vlp16::kLasers;
  origins_.resize(per_block);
  directions_.resize(per_block);
  hits_.resize(per_block);
  for (int block = first_block; block < last_block; ++block) {
    const int first = block * kBlockSequences;
    const int last = std::min(sequences_, first + kBlockSequences);
    // The block's rays in B.
    for (int s = first; s < last; ++s) {
      const int j = s / kPoseStride;
      const int from = j * kPoseStride, to = std::min(sequences_, from + kPoseStride);
      const Eigen::Matrix3d& R = rotations_[j];
      const Eigen::Matrix3d dR = rotations_[j + 1] - R;
      const Eigen::Vector3d dP = positions_[j + 1] - positions_[j];
      const double span = (to - from) * kSequence;
      for (int l = 0; l < Vlp16::kLasers; ++l) {
        const int i = (s - first) * Vlp16::kLasers + l;
        const Firing& firing = firings_[s * Vlp16::kLasers + l];
        const double a = (firing.time - from * kSequence) / span;
        const Eigen::Vector3d v = R * firing.direction + a * (dR * firing.direction);
        // |v| departs from 1 by ~1e-8 (the rotations differ by < 1e-3 rad): one Newton step
        // for 1/|v| makes it unit to ~1e-16 without a square root or a division.
        directions_[i] = (1.5 - 0.5 * v.squaredNorm()) * v;
        origins_[i] = positions_[j] + a * dP + offset[l] * (R.col(2) + a * dR.col(2));
      }
    }
    const int rays = (last - first) * Vlp16::kLasers;
    now = Clock::now();
    out.timing.poses_s += seconds(mark, now);
    mark = now;
    for (int i = 0; i < rays; ++i) {
      // A ray the body stops never reaches the building.
      if (firings_[first * Vlp16::kLasers + i].blocked) {
        hits_[i] = RayCaster::Hit{};
        continue;
      }
      const auto hit = scan_caster_.cast(origins_[i], directions_[i]);
      hits_[i] = hit ? *hit : RayCaster::Hit{};
    }
    out.rays += rays;
    now = Clock::now();
    out.timing.casting_s += seconds(mark, now);
    mark = now;
    // Every ray draws its noise and whether its return is lost, whether or not it hit.
    Xoshiro256 rng(deriveSeed(seed, kNoiseStream, std::uint64_t(block)));
    boost::random::normal_distribution<double> noise(0.0, 1.0);
    const double kept_share = 1.0 - config_.dropout;
    for (int i = 0; i < rays; ++i) {
      const double n = noise(rng);
      const double u = rng.uniform01();
      const RayCaster::Hit& hit = hits_[i];
      if (hit.distance < 0) continue;
      const double range = quantise(hit.distance + config_.range_noise_m * n);
      if (range < config_.min_range_m || range > config_.max_range_m) continue;
      const Eigen::Vector3d& dir = directions_[i];
      const Eigen::Vector3d normal = surfaceNormal(hit.geom, origins_[i] + hit.distance * dir, dir);
      const double cos_incidence = std::abs(normal.dot(dir));
      const double reflectivity = reflectivity_[hit.geom];
      // Too weak to detect: the LiDAR equation's power below the sensor's threshold.
      if (reflectivity * cos_incidence < min_signal_ * hit.distance * hit.distance) continue;
      // Grazing returns fade: beyond the cutoff the beam's spot smears along the surface and the
      // echo's peak drops under the detector's threshold more and more often.
      const double kept = cos_incidence < full_return_cos_
                              ? kept_share * cos_incidence / full_return_cos_
                              : kept_share;
      if (u >= kept) continue;
      const int s = first + i / Vlp16::kLasers, l = i % Vlp16::kLasers;
      const Firing& firing = firings_[s * Vlp16::kLasers + l];
      const Eigen::Vector3d p = Vlp16::origin(l) + range * firing.direction;
      // The VLP-16's calibrated reflectivity: 0–100 for diffuse surfaces (100: a perfect white
      // one met head-on).
      out.points.push_back({float(p.x()), float(p.y()), float(p.z()),
                            float(roundHalfUp(100.0 * reflectivity * cos_incidence)),
                            std::uint16_t(Vlp16::ring(l)), float(firing.time)});
    }
    now = Clock::now();
    out.timing.noise_s += seconds(mark, now);
    mark = now;
  }
  return out;
}

}  // namespace isg::sim
