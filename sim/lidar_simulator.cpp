#include "sim/lidar_simulator.hpp"

#include <algorithm>
#include <cmath>

#include "sim/vlp16.hpp"

namespace isg::sim {

namespace {

constexpr double kQuantum = 0.002;  // the VLP-16 reports ranges in 2 mm steps

}  // namespace

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
    const float* rgba =
        m.geom_matid[g] >= 0 ? m.mat_rgba + 4 * m.geom_matid[g] : m.geom_rgba + 4 * g;
    // Light surfaces return more light: the mean of the colour's channels.
    reflectivity_[g] = (rgba[0] + rgba[1] + rgba[2]) / 3.0f;
  }
}

Eigen::Vector3d LidarSimulator::surfaceNormal(int geom, const Eigen::Vector3d& point,
                                              const Eigen::Vector3d& direction) const {
  const mjModel& m = world_.model();
  const mjData& d = world_.data();
  const Eigen::Vector3d pos = Eigen::Map<const Eigen::Vector3d>(d.geom_xpos + 3 * geom);
  const Eigen::Matrix3d R =
      Eigen::Map<const Eigen::Matrix<double, 3, 3, Eigen::RowMajor>>(d.geom_xmat + 9 * geom);
  const Eigen::Vector3d local = R.transpose() * (point - pos);
  switch (m.geom_type[geom]) {
    case mjGEOM_BOX: {
      const Eigen::Vector3d half = Eigen::Map<const Eigen::Vector3d>(m.geom_size + 3 * geom);
      int axis = 0;
      (local.cwiseAbs().cwiseQuotient(half)).maxCoeff(&axis);
      return R.col(axis) * (local[axis] >= 0 ? 1.0 : -1.0);
    }
    case mjGEOM_SPHERE:
      return (point - pos).normalized();
    default:
      return -direction;  // unknown shape: as if hit head-on
  }
}

LidarScan LidarSimulator::scan(double stamp, const PoseAt& B_T_L, std::mt19937_64& rng) {
  LidarScan out;
  out.stamp = stamp;
  out.points.reserve(std::size_t(sequences_) * Vlp16::kLasers);
  // Sensor poses at every sequence boundary; each laser's pose is interpolated between them.
  std::vector<Eigen::Vector3d> positions(sequences_ + 1);
  std::vector<Eigen::Quaterniond> rotations(sequences_ + 1);
  Eigen::Vector2d lo = Eigen::Vector2d::Constant(1e300), hi = -lo;
  for (int s = 0; s <= sequences_; ++s) {
    const Eigen::Isometry3d T = B_T_L(stamp + s * kSequence);
    positions[s] = T.translation();
    rotations[s] = Eigen::Quaterniond(T.linear());
    lo = lo.cwiseMin(positions[s].head<2>());
    hi = hi.cwiseMax(positions[s].head<2>());
  }
  // Laser origins sit within millimetres of the sensor's axis.
  scan_caster_.prepare(0.5 * (lo + hi), 0.5 * (hi - lo).norm() + 0.02);

  std::normal_distribution<double> noise(0.0, 1.0);
  std::uniform_real_distribution<double> uniform(0.0, 1.0);
  for (int s = 0; s < sequences_; ++s) {
    for (int l = 0; l < Vlp16::kLasers; ++l) {
      const double t = Vlp16::firingTime(s, l);
      const double a = (t - s * kSequence) / kSequence;
      const Eigen::Vector3d position = positions[s] + a * (positions[s + 1] - positions[s]);
      const Eigen::Matrix3d R = rotations[s].slerp(a, rotations[s + 1]).toRotationMatrix();
      const Eigen::Vector3d origin_L = Vlp16::origin(l);
      const Eigen::Vector3d dir_L = Vlp16::direction(l, Vlp16::azimuth(t, config_.rate_hz));
      const Eigen::Vector3d origin = position + R * origin_L;
      const Eigen::Vector3d dir = R * dir_L;
      ++out.rays;
      const auto hit = scan_caster_.cast(origin, dir);
      // Every draw happens whether or not the ray hits, so that one ray's outcome never shifts
      // the noise of the next.
      const double n = noise(rng);
      const double u = uniform(rng);
      if (!hit) continue;
      double range = hit->distance + config_.range_noise_m * n;
      range = std::round(range / kQuantum) * kQuantum;
      if (range < config_.min_range_m || range > config_.max_range_m) continue;
      if (u < config_.dropout) continue;
      const Eigen::Vector3d normal = surfaceNormal(hit->geom, origin + hit->distance * dir, dir);
      const double incidence = std::abs(normal.dot(dir));
      const Eigen::Vector3d p = origin_L + range * dir_L;
      out.points.push_back({float(p.x()), float(p.y()), float(p.z()),
                            float(std::round(255.0 * reflectivity_[hit->geom] * incidence)),
                            std::uint16_t(Vlp16::ring(l)), float(t)});
    }
  }
  return out;
}

}  // namespace isg::sim
