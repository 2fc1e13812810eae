#include "slam/baselines/ndt_ukf_localizer.hpp"

#include <pcl/filters/voxel_grid.h>
#include <pcl/point_cloud.h>
#include <pcl/point_types.h>
#include <pcl/registration/ndt.h>

#include <cmath>
#include <numbers>
#include <stdexcept>

#include "bim/plan_geometry.hpp"
#include "slam/baselines/pose2.hpp"

namespace isg::slam {

namespace {

using Cloud = pcl::PointCloud<pcl::PointXYZ>;

Cloud::Ptr voxelise(const Cloud::Ptr& cloud, double leaf) {
  Cloud::Ptr out(new Cloud);
  pcl::VoxelGrid<pcl::PointXYZ> grid;
  grid.setLeafSize(float(leaf), float(leaf), float(leaf));
  grid.setInputCloud(cloud);
  grid.filter(*out);
  return out;
}

// The plan's exposed wall faces of one level as points on a `spacing` grid, floor to wall top,
// with the door and window openings left out. Each point stands ±relief off its face,
// in a checkerboard: a perfectly flat NDT cell has a smallest covariance eigenvalue of zero, which
// PCL computes as slightly negative for some cells and then drops the cell ("Invalid eigen
// value"); ±1 cm, a wall's finish tolerance, keeps every wall cell, and is far below PCL's own
// floor on that eigenvalue (1 % of the largest, about (3 cm)² for 1 m cells).
// The points are relative to `origin`: PCL's NDT works in float, whose steps are half a millimetre
// at 8 km from B's origin (docs/conventions.md, "Where B's origin is").
Cloud::Ptr planCloud(const bim::Plan& plan, const std::string& level_id, double spacing,
                     double relief, const Eigen::Vector2d& origin) {
  const bim::Level* level = plan.findLevel(level_id);
  if (level == nullptr) throw std::invalid_argument("the plan has no level \"" + level_id + "\"");
  const bim::LevelGeometry geometry = bim::computeLevelGeometry(*level);
  Cloud::Ptr cloud(new Cloud);
  for (const auto& wall : geometry.walls) {
    const std::vector<bim::WallOpening> holes = bim::wallOpenings(*level, wall.wall->id);
    const double base = level->elevation + wall.wall->base;
    for (int side : {+1, -1}) {
      const bim::WallFace& face = wall.face(side);
      const Eigen::Vector2d outward = side * wall.left_normal;
      for (const auto& piece : face.exposed) {
        int i = 0;
        for (double s = piece.lo; s <= piece.hi + 1e-9; s += spacing, ++i) {
          int j = 0;
          for (double z = face.z_min; z <= face.z_max + 1e-9; z += spacing, ++j) {
            const bool in_hole =
                std::any_of(holes.begin(), holes.end(), [&](const bim::WallOpening& h) {
                  return s > h.lo && s < h.hi && z >= base + h.bottom && z < base + h.top;
                });
            if (in_hole) continue;
            const Eigen::Vector2d xy = wall.facePointAt(side, s) - origin +
                                       ((i + j) % 2 == 0 ? relief : -relief) * outward;
            cloud->push_back(pcl::PointXYZ(float(xy.x()), float(xy.y()), float(z)));
          }
        }
      }
    }
  }
  // Round columns: points round their surface at the same spacing.
  for (const auto& column : level->columns) {
    if (!column.round()) continue;
    const int steps = std::max(8, int(std::ceil(2 * std::numbers::pi * column.radius() / spacing)));
    for (int k = 0; k < steps; ++k) {
      const double a = 2 * std::numbers::pi * k / steps;
      const Eigen::Vector2d xy =
          column.center + column.radius() * Eigen::Vector2d(std::cos(a), std::sin(a)) - origin;
      for (double z = level->elevation + column.base; z <= level->elevation + column.height + 1e-9;
           z += spacing) {
        cloud->push_back(pcl::PointXYZ(float(xy.x()), float(xy.y()), float(z)));
      }
    }
  }
  if (cloud->empty()) {
    throw std::invalid_argument("level \"" + level_id + "\" has no wall to register against");
  }
  return cloud;
}

// The middle of a level's walls to the metre: the origin of the NDT's map.
Eigen::Vector2d mapOrigin(const bim::Plan& plan, const std::string& level_id) {
  const bim::Level* level = plan.findLevel(level_id);
  Eigen::AlignedBox2d box;  // empty
  if (level != nullptr) {
    for (const auto& wall : level->walls) box.extend(wall.start).extend(wall.end);
  }
  return bim::localOriginOf(box);
}

// A translation in the plane as a transform.
Eigen::Isometry3d shiftBy(const Eigen::Vector2d& shift) {
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  T.translation() << shift, 0.0;
  return T;
}

// The state: x, y, z, yaw of the base in B, then its velocity vx, vy, vz, ω in B.
constexpr int kStateSize = 8;
constexpr int kYaw = 3;

Eigen::Isometry3d poseOf(const Eigen::VectorXd& state, const Eigen::Matrix3d& roll_pitch) {
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  T.linear() =
      Eigen::AngleAxisd(state[kYaw], Eigen::Vector3d::UnitZ()).toRotationMatrix() * roll_pitch;
  T.translation() = state.head<3>();
  return T;
}

// The rotation of T with its heading taken out: the tilt the odometry measures against gravity.
Eigen::Matrix3d tiltOf(const Eigen::Isometry3d& T) {
  return Eigen::AngleAxisd(-planarPose(T).yaw, Eigen::Vector3d::UnitZ()).toRotationMatrix() *
         T.linear();
}

}  // namespace

struct NdtUkfLocalizer::Registration {
  Eigen::Vector2d origin = Eigen::Vector2d::Zero();  // of the map, in B
  Cloud::Ptr map;
  pcl::NormalDistributionsTransform<pcl::PointXYZ, pcl::PointXYZ> ndt;
};

NdtUkfLocalizer::NdtUkfLocalizer(const bim::Plan& plan, const std::string& level,
                                 const Eigen::Isometry3d& R_T_L,
                                 const Eigen::Isometry3d& start_B_T_M, const NdtUkfOptions& options)
    : options_(options),
      R_T_L_(R_T_L),
      start_B_T_M_(start_B_T_M),
      registration_(std::make_unique<Registration>()) {
  registration_->origin = mapOrigin(plan, level);
  registration_->map =
      planCloud(plan, level, options.map_spacing, options.map_relief, registration_->origin);
  const bim::Level* plan_level = plan.findLevel(level);
  floor_ = plan_level->elevation;
  ceiling_ = plan_level->elevation + plan_level->height;
  auto& ndt = registration_->ndt;
  ndt.setResolution(float(options.ndt_resolution));
  ndt.setStepSize(options.ndt_step_size);
  ndt.setTransformationEpsilon(options.ndt_epsilon);
  ndt.setMaximumIterations(options.ndt_max_iterations);
  ndt.setInputTarget(registration_->map);
}

NdtUkfLocalizer::~NdtUkfLocalizer() = default;

std::size_t NdtUkfLocalizer::mapPoints() const { return registration_->map->size(); }

void NdtUkfLocalizer::pushOdometry(const sensors::Odometry& odometry) {
  odometry_.push(odometry);
  latest_ = odometry;
  if (filter_) return;
  // Before its first scan the tracker is where it was told it starts.
  B_T_M_ = start_B_T_M_;
  const Eigen::Isometry3d B_T_R = start_B_T_M_ * odometry.M_T_R;
  const Pose2 start = planarPose(B_T_R);
  Eigen::VectorXd state(kStateSize);
  state << start.x, start.y, B_T_R.translation().z(), start.yaw, 0, 0, 0, 0;
  filter_ = std::make_unique<UnscentedKalmanFilter>(
      state, options_.initial_covariance * Eigen::MatrixXd::Identity(kStateSize, kStateSize),
      std::vector<int>{kYaw});
}

void NdtUkfLocalizer::pushScan(const sensors::Scan& scan) {
  if (!latest_) return;
  // The scan stands at the middle of its turn (hdl_localization does not deskew either).
  double first = 0.0, last = 0.0;
  for (const auto& p : scan.points) {
    first = std::min(first, double(p.time));
    last = std::max(last, double(p.time));
  }
  const double t = scan.stamp + 0.5 * (first + last);
  sensors::Odometry odometry{t, odometry_.at(t).value_or(latest_->M_T_R)};
  if (last_scan_odometry_) {
    // Predict: the pose moves as the odometry moved since the last scan (in the base's frame),
    // the velocity is that move's rate.
    const double dt = std::max(1e-3, odometry.stamp - last_scan_odometry_->stamp);
    const Pose2 from = planarPose(last_scan_odometry_->M_T_R);
    const Pose2 to = planarPose(odometry.M_T_R);
    const Eigen::Vector2d step = Eigen::Rotation2Dd(-from.yaw) * (to.position() - from.position());
    const double dz =
        odometry.M_T_R.translation().z() - last_scan_odometry_->M_T_R.translation().z();
    const double turn = common::angleDifference(to.yaw, from.yaw);
    const auto f = [&](const Eigen::VectorXd& s) {
      Eigen::VectorXd next = s;
      const Eigen::Vector2d move = Eigen::Rotation2Dd(s[kYaw]) * step;
      next[0] += move.x();
      next[1] += move.y();
      next[2] += dz;
      next[kYaw] = common::angleDifference(s[kYaw] + turn, 0.0);
      next.segment<3>(4) = Eigen::Vector3d(move.x(), move.y(), dz) / dt;
      next[7] = turn / dt;
      return next;
    };
    Eigen::VectorXd q(kStateSize);
    q << options_.process_position, options_.process_position, options_.process_position,
        options_.process_yaw, options_.process_velocity, options_.process_velocity,
        options_.process_velocity, options_.process_yaw;
    filter_->predict(f, Eigen::MatrixXd(q.asDiagonal()) * dt);
  }
  last_scan_odometry_ = odometry;
  const Eigen::Matrix3d tilt = tiltOf(odometry.M_T_R);

  // The scan in the base frame, without the robot itself, downsampled.
  Cloud::Ptr cloud(new Cloud);
  const Eigen::Vector3d sensor = R_T_L_.translation();
  for (const auto& p : scan.points) {
    const Eigen::Vector3d q = R_T_L_ * Eigen::Vector3d(p.x, p.y, p.z);
    if ((q - sensor).norm() < options_.scan_min_range) continue;
    cloud->push_back(pcl::PointXYZ(float(q.x()), float(q.y()), float(q.z())));
  }
  ++scans_;
  const Eigen::Isometry3d guess_B_T_R = poseOf(filter_->mean(), tilt);
  if (options_.wall_band > 0.0) {
    // Only what the map can explain: the walls' height, less a band at the floor and ceiling
    // (at the predicted pose), which the walls-only map has no points for.
    Cloud::Ptr walls(new Cloud);
    for (const auto& p : *cloud) {
      const double z = (guess_B_T_R * Eigen::Vector3d(p.x, p.y, p.z)).z();
      if (z > floor_ + options_.wall_band && z < ceiling_ - options_.wall_band) walls->push_back(p);
    }
    cloud = walls;
  }
  if (cloud->size() >= 10) {
    const Cloud::Ptr filtered = voxelise(cloud, options_.scan_voxel);
    auto& ndt = registration_->ndt;
    ndt.setInputSource(filtered);
    Cloud aligned;
    // In the map's frame, and back: B_T_R = shift(origin) · map_T_R.
    const Eigen::Matrix4f guess =
        (shiftBy(-registration_->origin) * guess_B_T_R).matrix().cast<float>();
    ndt.align(aligned, guess);
    last_converged_ = ndt.hasConverged();
    last_fitness_ = ndt.getFitnessScore();
    iterations_ += ndt.getFinalNumIteration();
    ++registrations_;
    const Eigen::Isometry3d measured =
        shiftBy(registration_->origin) *
        Eigen::Isometry3d(ndt.getFinalTransformation().cast<double>());
    const Pose2 planar = planarPose(measured);
    Eigen::Vector4d z(planar.x, planar.y, measured.translation().z(), planar.yaw);
    const Eigen::Vector4d r(options_.measurement_position, options_.measurement_position,
                            options_.measurement_position, options_.measurement_yaw);
    filter_->update(z, [](const Eigen::VectorXd& s) { return Eigen::VectorXd(s.head<4>()); },
                    Eigen::MatrixXd(r.asDiagonal()), {kYaw});
  }
  B_T_M_ = poseOf(filter_->mean(), tilt) * odometry.M_T_R.inverse();
}

nlohmann::json NdtUkfLocalizer::graph() const {
  if (!filter_) return {{"method", name()}, {"scans", scans_}, {"map_points", mapPoints()}};
  const Eigen::VectorXd& s = filter_->mean();
  return {{"method", name()},
          {"scans", scans_},
          {"map_points", mapPoints()},
          {"state", {s[0], s[1], s[2], s[3], s[4], s[5], s[6], s[7]}},
          {"position_std", std::sqrt(filter_->covariance().topLeftCorner<2, 2>().trace())},
          {"last_ndt_converged", last_converged_},
          {"ndt_iterations_mean", registrations_ > 0 ? double(iterations_) / registrations_ : 0.0},
          {"last_ndt_fitness", last_fitness_}};
}

}  // namespace isg::slam
