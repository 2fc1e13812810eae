#include "sim/lidar_simulator.hpp"

#include <algorithm>
#include <array>
#include <boost/random/normal_distribution.hpp>
#include <chrono>
#include <cmath>
#include <numbers>
#include <string_view>

#include "sensors/mount_transform.hpp"
#include "sim/body_shadow.hpp"
#include "sim/fast_random.hpp"
#include "sim/robot_model.hpp"
#include "sim/vlp16.hpp"

namespace isg::sim {

namespace {

constexpr std::uint64_t kNoiseStream = 1;
constexpr std::uint64_t kJitterStream = 2;
// A beam diverges horizontally (the VLP-16's by 3.0 mrad, its manual; each model's in
// sensors/lidar_model.cpp): last and dual returns cast the beam's centre and its two horizontal
// edges, half the divergence either side, weighted 1/4, 1/2, 1/4 (a beam brighter at its centre).
// Vertical divergence is left out: edges across the beam's height (lintels, tops of clutter) are
// rarer indoors than wall ends and door jambs.
constexpr double kEdgeWeight = 0.25, kCentreWeight = 0.5;
// Two parts of a beam closer than this in range make one echo: the detector cannot separate
// pulses that overlap (an assumption of about the pulse's length; the manual gives no figure).
constexpr double kEchoSeparation = 1.0;

// std::round for x ≥ 0 without a library call (ties go up; they have probability zero here).
inline double roundHalfUp(double x) { return double(std::int64_t(x + 0.5)); }

// A range in the sensor's steps (the VLP-16's 2 mm).
inline double quantise(double range, double quantum) {
  if (range < 0) return std::round(range / quantum) * quantum;  // discarded by the range gate
  return roundHalfUp(range / quantum) * quantum;
}

const sensors::LidarModel& modelNamed(const std::string& name) {
  const sensors::LidarModel* model = sensors::findLidarModel(name);
  if (!model) {
    throw std::invalid_argument("unknown LiDAR model \"" + name +
                                "\" (known: " + sensors::lidarModelList() + ")");
  }
  return *model;
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
      model_(modelNamed(config.model)),
      lasers_(model_.lasers()),
      sequence_s_(model_.sequenceDuration(config.rate_hz)),
      quantum_(model_.range_resolution_m),
      half_divergence_(model_.half_divergence_rad),
      caster_(world.model(), world.data(), groups),
      scan_caster_(caster_),
      sequences_(model_.sequencesPerTurn(config.rate_hz)),
      period_(1.0 / config.rate_hz),
      stamp_offset_(0.0),
      body_(robotBodyBox(), sensors::mountTransform(config.mount)) {
  const int per_packet = sequencesPerPacket();
  if (config.cut == bim::LidarCut::kPackets) {
    // The ROS 1 driver publishes ceil(packet rate / rotation rate) packets per cloud.
    const double packet_rate = 1.0 / (per_packet * sequence_s_);
    sequences_ = int(std::ceil(packet_rate / config.rate_hz)) * per_packet;
    period_ = sequences_ * sequence_s_;
  }
  if (config.stamp == bim::LidarStamp::kLastPacket) {
    stamp_offset_ = ((sequences_ - 1) / per_packet) * per_packet * sequence_s_;
  }
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
    shape.upright = shape.type == mjGEOM_BOX && shape.R(2, 0) == 0.0 && shape.R(2, 1) == 0.0 &&
                    shape.R(0, 2) == 0.0 && shape.R(1, 2) == 0.0 && shape.R(2, 2) == 1.0;
  }
  laser_height_.resize(std::size_t(lasers_));
  for (int l = 0; l < lasers_; ++l) laser_height_[std::size_t(l)] = laserOrigin(l).z();
  firings_.reserve(std::size_t(sequences_) * lasers_);
  for (int s = 0; s < sequences_; ++s) {
    for (int l = 0; l < lasers_; ++l) {
      const sensors::LidarBeam& beam = model_.beams[std::size_t(l)];
      const double t = sequence_s_ * s + beam.firing_offset_s;
      const double head = Vlp16::azimuth(t, config.rate_hz);
      const double el = beam.elevation_deg * std::numbers::pi / 180.0;
      const double az = head + beam.azimuth_offset_deg * std::numbers::pi / 180.0;
      const Eigen::Vector3d direction(std::cos(el) * std::cos(az), std::cos(el) * std::sin(az),
                                      std::sin(el));
      // Ouster's beams leave from a circle about the axis, at the column's (the head's) azimuth.
      const double radius = model_.beam_origin_radius_mm * 1e-3;
      const Eigen::Vector3d radial =
          radius > 0.0 ? Eigen::Vector3d(radius * std::cos(head), radius * std::sin(head), 0.0)
                       : Eigen::Vector3d::Zero();
      const bool blocked =
          config.body_occlusion && body_.distance(laserOrigin(l) + radial, direction) >= 0;
      firings_.push_back({direction, t, blocked, radial});
    }
  }
}

Eigen::Vector3d LidarSimulator::laserOrigin(int laser) const {
  return {0.0, 0.0, model_.beams[std::size_t(laser)].vertical_offset_mm * 1e-3};
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
    case mjGEOM_CYLINDER: {
      // On a cap (within a hair of its height) the axis, else the radial direction.
      const Eigen::Vector3d local = shape.R.transpose() * (point - shape.pos);
      if (std::abs(local.z()) * shape.inverse_half.y() > 1.0 - 1e-9) {
        return local.z() >= 0 ? shape.R.col(2) : Eigen::Vector3d(-shape.R.col(2));
      }
      return (shape.R * Eigen::Vector3d(local.x(), local.y(), 0.0)).normalized();
    }
    default:
      return -direction;  // unknown shape: as if hit head-on
  }
}

double LidarSimulator::cosIncidence(int geom, const Eigen::Vector3d& point,
                                    const Eigen::Vector3d& direction) const {
  const GeomShape& shape = shapes_[geom];
  if (shape.type != mjGEOM_BOX)
    return std::abs(surfaceNormal(geom, point, direction).dot(direction));
  // surfaceNormal's face, chosen by selects rather than branches (which face a ray meets changes
  // from laser to laser: floor, wall, ceiling). The normal's sign drops out of |n · direction|.
  // An upright box's z row and column are zeros and a one, whose products add nothing: the local
  // point is the same bits from the 2-D rotation.
  const Eigen::Vector3d d = point - shape.pos;
  const Eigen::Matrix3d& R = shape.R;
  Eigen::Vector3d local;
  if (shape.upright) {
    local << R(0, 0) * d.x() + R(1, 0) * d.y(), R(0, 1) * d.x() + R(1, 1) * d.y(), d.z();
  } else {
    local = R.transpose() * d;
  }
  const Eigen::Vector3d out = local.cwiseAbs().cwiseProduct(shape.inverse_half);
  const bool x_over_y = out.x() >= out.y();
  const double larger = x_over_y ? out.x() : out.y();
  const int axis = larger >= out.z() ? (x_over_y ? 0 : 1) : 2;
  return std::abs(R.col(axis).dot(direction));
}

int LidarSimulator::blockCount() const {
  return (sequences_ + kBlockSequences - 1) / kBlockSequences;
}

int LidarSimulator::sequencesPerPacket() const {
  return config_.returns == bim::LidarReturns::kDual ? model_.sequences_per_packet_dual
                                                     : model_.sequences_per_packet_single;
}

double LidarSimulator::startAzimuth(double start) const {
  if (config_.cut == bim::LidarCut::kAngle) return -config_.cut_angle_deg * std::numbers::pi / 180;
  // The head turns at the rate on and on; at time 0 it was at azimuth 0.
  return -2.0 * std::numbers::pi * std::fmod(config_.rate_hz * start, 1.0);
}

LidarSimulator::SubHit LidarSimulator::subHit(const RayCaster::Hit& hit,
                                              const Eigen::Vector3d& origin,
                                              const Eigen::Vector3d& direction,
                                              double weight) const {
  SubHit out;
  if (hit.distance < 0) return out;
  out.distance = hit.distance;
  out.cos_incidence = cosIncidence(hit.geom, origin + hit.distance * direction, direction);
  out.lit = weight * reflectivity_[hit.geom] * out.cos_incidence;
  out.power = out.lit / (hit.distance * hit.distance);
  return out;
}

int LidarSimulator::echoes(const SubHit* sub, int count, Echo* out) const {
  std::array<SubHit, 3> sorted;
  int n = 0;
  for (int k = 0; k < count; ++k) {
    if (sub[k].distance >= 0) sorted[n++] = sub[k];
  }
  std::sort(sorted.begin(), sorted.begin() + n,
            [](const SubHit& a, const SubHit& b) { return a.distance < b.distance; });
  int echoes = 0;
  double strongest_part = 0.0;
  for (int k = 0; k < n; ++k) {
    const SubHit& h = sorted[k];
    if (echoes == 0 || h.distance - sorted[k - 1].distance >= kEchoSeparation) {
      out[echoes++] = Echo{};
      strongest_part = 0.0;
    }
    Echo& e = out[echoes - 1];
    e.power += h.power;
    e.lit += h.lit;
    if (h.power > strongest_part) {
      strongest_part = h.power;
      e.distance = h.distance;
      e.cos_incidence = h.cos_incidence;
    }
  }
  return echoes;
}

LidarScan LidarSimulator::scan(double start, const PoseAt& B_T_L, std::uint64_t seed) {
  return scanBlocks(start, B_T_L, seed, 0, blockCount());
}

void LidarSimulator::samplePoses(double start, const PoseAt& B_T_L, int first_sequence,
                                 int last_sequence, const Eigen::Matrix3d& L_R_table, bool turned) {
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
    const Eigen::Isometry3d T = B_T_L(start + s * sequence_s_);
    positions_[j] = T.translation();
    rotations_[j] = turned ? Eigen::Matrix3d(T.linear() * L_R_table) : T.linear();
    lo = lo.cwiseMin(positions_[j].head<2>());
    hi = hi.cwiseMax(positions_[j].head<2>());
  }
  // Laser origins sit within millimetres of the sensor's axis.
  scan_caster_.prepare(0.5 * (lo + hi), 0.5 * (hi - lo).norm() + 0.02);
}

void LidarSimulator::blockRays(int first, int last, const Eigen::Matrix3d& L_R_table, bool turned,
                               bool beam) {
  const bool radial = model_.beam_origin_radius_mm > 0.0;
  for (int s = first; s < last; ++s) {
    const int j = s / kPoseStride;
    const int from = j * kPoseStride, to = std::min(sequences_, from + kPoseStride);
    const Eigen::Matrix3d& R = rotations_[j];
    const Eigen::Matrix3d dR = rotations_[j + 1] - R;
    const Eigen::Vector3d dP = positions_[j + 1] - positions_[j];
    const double span = (to - from) * sequence_s_;
    for (int l = 0; l < lasers_; ++l) {
      const int i = (s - first) * lasers_ + l;
      const Firing& firing = firings_[std::size_t(s) * lasers_ + l];
      const double a = (firing.time - from * sequence_s_) / span;
      const Eigen::Vector3d v = R * firing.direction + a * (dR * firing.direction);
      // |v| departs from 1 by ~1e-8 (the rotations differ by < 1e-3 rad): one Newton step
      // for 1/|v| makes it unit to ~1e-16 without a square root or a division.
      directions_[i] = (1.5 - 0.5 * v.squaredNorm()) * v;
      const Eigen::Vector3d axis = R.col(2) + a * dR.col(2);
      origins_[i] = positions_[j] + a * dP + laser_height_[std::size_t(l)] * axis;
      if (radial) origins_[i] += R * firing.radial + a * (dR * firing.radial);
      // The body is rigid with the mount: only a turn off the table's azimuths asks anew.
      blocked_[i] = turned && config_.body_occlusion
                        ? body_.distance(laserOrigin(l) + L_R_table * firing.radial,
                                         L_R_table * firing.direction) >= 0
                        : firing.blocked;
      if (beam) {
        const Eigen::Vector3d side = half_divergence_ * axis.cross(directions_[i]).normalized();
        edge_directions_[0][i] = (directions_[i] + side).normalized();
        edge_directions_[1][i] = (directions_[i] - side).normalized();
      }
    }
  }
}

void LidarSimulator::castRays(int rays, bool beam) {
  for (int i = 0; i < rays; ++i) {
    // A ray the body stops never reaches the building.
    if (blocked_[i]) {
      hits_[i] = RayCaster::Hit{};
      for (int side = 0; side < 2 && beam; ++side) edge_hits_[side][i] = RayCaster::Hit{};
      continue;
    }
    const auto hit = scan_caster_.cast(origins_[i], directions_[i]);
    hits_[i] = hit ? *hit : RayCaster::Hit{};
    for (int side = 0; side < 2 && beam; ++side) {
      const auto edge = scan_caster_.cast(origins_[i], edge_directions_[side][i]);
      edge_hits_[side][i] = edge ? *edge : RayCaster::Hit{};
    }
  }
}

void LidarSimulator::BlockReport::point(const LidarSimulator& lidar, int s, int l, double range,
                                        double lit, std::vector<LidarPoint>& points) const {
  const Firing& firing = lidar.firings_[std::size_t(s) * lidar.lasers_ + l];
  Eigen::Vector3d direction = firing.direction;
  Eigen::Vector3d radial = firing.radial;
  if (reported_turn) {
    const int b = (s - first) / sequences_per_data_block;
    const auto turn = [&](const Eigen::Vector3d& v) {
      return Eigen::Vector2d(report_cos[b] * v.x() - report_sin[b] * v.y(),
                             report_sin[b] * v.x() + report_cos[b] * v.y());
    };
    direction.head<2>() = turn(firing.direction);
    radial.head<2>() = turn(firing.radial);
  }
  const Eigen::Vector3d p = lidar.laserOrigin(l) + radial + range * direction;
  // The VLP-16's calibrated reflectivity: 0–100 for diffuse surfaces (100: a perfect white one
  // met head-on); every model reports on that scale (docs/simulation.md, "LiDAR models").
  points.push_back({float(p.x()), float(p.y()), float(p.z()), float(roundHalfUp(100.0 * lit)),
                    std::uint16_t(lidar.model_.beams[std::size_t(l)].ring),
                    float(firing.time - lidar.stamp_offset_)});
}

double LidarSimulator::keptProbability(double cos_incidence) const {
  // Grazing returns fade: beyond the cutoff the beam's spot smears along the surface and the
  // echo's peak drops under the detector's threshold more and more often.
  const double kept_share = 1.0 - config_.dropout;
  return cos_incidence < full_return_cos_ ? kept_share * cos_incidence / full_return_cos_
                                          : kept_share;
}

void LidarSimulator::beamReturns(const BlockReport& block, int i, const double n[2],
                                 const double u[2], std::vector<LidarPoint>& points) const {
  const int s = block.first + i / lasers_, l = i % lasers_;
  if (hits_[i].distance < 0 && edge_hits_[0][i].distance < 0 && edge_hits_[1][i].distance < 0) {
    return;
  }
  const SubHit sub[3] = {
      subHit(edge_hits_[0][i], origins_[i], edge_directions_[0][i], kEdgeWeight),
      subHit(hits_[i], origins_[i], directions_[i], kCentreWeight),
      subHit(edge_hits_[1][i], origins_[i], edge_directions_[1][i], kEdgeWeight)};
  std::array<Echo, 3> found;
  const int count = echoes(sub, 3, found.data());
  // Too weak to detect: the LiDAR equation's power below the sensor's threshold.
  std::array<Echo, 3> detected;
  int kept = 0;
  for (int e = 0; e < count; ++e) {
    if (found[e].power >= min_signal_) detected[kept++] = found[e];
  }
  if (kept == 0) return;
  // Nearest first: the last echo is reported; in dual mode also the strongest of the others,
  // which is the strongest echo when the last is not, else the second strongest.
  int reported[2] = {kept - 1, -1};
  if (config_.returns == bim::LidarReturns::kDual && kept > 1) {
    reported[1] = 0;
    for (int e = 1; e < kept - 1; ++e) {
      if (detected[e].power > detected[reported[1]].power) reported[1] = e;
    }
  }
  for (int r = 0; r < 2 && reported[r] >= 0; ++r) {
    const Echo& e = detected[reported[r]];
    const double range = quantise(e.distance + config_.range_noise_m * n[r], quantum_);
    if (range < config_.min_range_m || range > config_.max_range_m) continue;
    if (u[r] >= keptProbability(e.cos_incidence)) continue;
    block.point(*this, s, l, range, e.lit, points);
  }
}

void LidarSimulator::blockReturns(const BlockReport& block, int rays, std::uint64_t seed, int index,
                                  bool beam, std::vector<LidarPoint>& points) {
  // Every ray draws its noise and whether its return is lost, whether or not it hit: the block's
  // draws first, in ray order, then the returns. Drawn ray by ray between the returns, each ray's
  // chain (draw, range, incidence, threshold) waited for the one before; apart, the returns of
  // neighbouring rays overlap in the processor. The same draws, so the same points.
  Xoshiro256 rng(deriveSeed(seed, kNoiseStream, std::uint64_t(index)));
  boost::random::normal_distribution<double> noise(0.0, 1.0);
  const int per_ray = beam ? 2 : 1;
  draws_normal_.resize(std::size_t(rays) * per_ray);
  draws_uniform_.resize(std::size_t(rays) * per_ray);
  for (int i = 0; i < rays; ++i) {
    for (int k = 0; k < per_ray; ++k) draws_normal_[std::size_t(i) * per_ray + k] = noise(rng);
    for (int k = 0; k < per_ray; ++k)
      draws_uniform_[std::size_t(i) * per_ray + k] = rng.uniform01();
  }
  for (int i = 0; i < rays; ++i) {
    if (beam) {
      // Last and dual returns: the beam's echoes, then the ones the mode reports.
      beamReturns(block, i, &draws_normal_[2 * std::size_t(i)], &draws_uniform_[2 * std::size_t(i)],
                  points);
      continue;
    }
    const RayCaster::Hit& hit = hits_[i];
    if (hit.distance < 0) continue;
    const int s = block.first + i / lasers_, l = i % lasers_;
    const double range =
        quantise(hit.distance + config_.range_noise_m * draws_normal_[i], quantum_);
    if (range < config_.min_range_m || range > config_.max_range_m) continue;
    const SubHit whole = subHit(hit, origins_[i], directions_[i], 1.0);
    // Too weak to detect: the LiDAR equation's power below the sensor's threshold.
    if (whole.power < min_signal_) continue;
    if (draws_uniform_[i] >= keptProbability(whole.cos_incidence)) continue;
    block.point(*this, s, l, range, whole.lit, points);
  }
}

LidarScan LidarSimulator::scanBlocks(double start, const PoseAt& B_T_L, std::uint64_t seed,
                                     int first_block, int last_block) {
  using Clock = std::chrono::steady_clock;
  auto seconds = [](Clock::time_point a, Clock::time_point b) {
    return std::chrono::duration<double>(b - a).count();
  };
  LidarScan out;
  out.stamp = start + stamp_offset_;
  const int first_sequence = first_block * kBlockSequences;
  const int last_sequence = std::min(sequences_, last_block * kBlockSequences);
  if (first_sequence >= last_sequence) return out;
  const bool beam = config_.returns != bim::LidarReturns::kStrongest;
  out.points.reserve(std::size_t(last_sequence - first_sequence) * lasers_ * (beam ? 2 : 1));
  auto mark = Clock::now();
  // The firing table starts at azimuth 0: a turn starting elsewhere turns it about L's z axis
  // (folded into the sensor's rotation, so it costs nothing per ray).
  const double start_azimuth = startAzimuth(start);
  const bool turned = start_azimuth != 0.0;
  const Eigen::Matrix3d L_R_table =
      Eigen::AngleAxisd(start_azimuth, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  samplePoses(start, B_T_L, first_sequence, last_sequence, L_R_table, turned);
  auto now = Clock::now();
  out.timing.poses_s += seconds(mark, now);
  mark = now;

  const int per_block = kBlockSequences * lasers_;
  origins_.resize(per_block);
  directions_.resize(per_block);
  hits_.resize(per_block);
  blocked_.resize(per_block);
  for (int side = 0; side < 2 && beam; ++side) {
    edge_directions_[side].resize(per_block);
    edge_hits_[side].resize(per_block);
  }
  // The azimuth each data block (two sequences) reports, as cos and sin of its turn from the
  // firing table's: the turn's start, and the block's jitter.
  const bool jitter = config_.azimuth_jitter_deg > 0.0;
  BlockReport report;
  report.reported_turn = turned || jitter;
  report.sequences_per_data_block = model_.sequences_per_data_block;
  report.data_blocks = kBlockSequences / model_.sequences_per_data_block;
  for (int block = first_block; block < last_block; ++block) {
    const int first = block * kBlockSequences;
    const int last = std::min(sequences_, first + kBlockSequences);
    blockRays(first, last, L_R_table, turned, beam);  // the block's rays in B
    const int rays = (last - first) * lasers_;
    now = Clock::now();
    out.timing.poses_s += seconds(mark, now);
    mark = now;
    castRays(rays, beam);
    out.rays += rays;
    now = Clock::now();
    out.timing.casting_s += seconds(mark, now);
    mark = now;
    report.first = first;
    if (report.reported_turn) {
      Xoshiro256 jitter_rng(deriveSeed(seed, kJitterStream, std::uint64_t(block)));
      boost::random::normal_distribution<double> jitter_noise(0.0, 1.0);
      const double sigma = config_.azimuth_jitter_deg * std::numbers::pi / 180.0;
      for (int b = 0; b < report.data_blocks; ++b) {
        const double angle = start_azimuth + (jitter ? sigma * jitter_noise(jitter_rng) : 0.0);
        report.report_cos[b] = std::cos(angle);
        report.report_sin[b] = std::sin(angle);
      }
    }
    blockReturns(report, rays, seed, block, beam, out.points);
    now = Clock::now();
    out.timing.noise_s += seconds(mark, now);
    mark = now;
  }
  return out;
}

}  // namespace isg::sim
