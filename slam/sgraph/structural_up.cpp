#include "slam/sgraph/structural_up.hpp"

#include <Eigen/Eigenvalues>
#include <cmath>
#include <numbers>

#include "slam/sgraph/plane_normal.hpp"

namespace isg::slam {

namespace {

struct Patch {
  Eigen::Vector3d normal;
  double points;
};

std::vector<Patch> patchesOf(const std::vector<Eigen::Vector3f>& cloud,
                             const PlaneVoxelMapOptions& options) {
  const PlaneVoxelMap voxels(options);
  std::vector<Patch> patches;
  for (const auto& [key, m] : voxels.contributionOf(cloud, Eigen::Isometry3d::Identity()).voxels) {
    if (m.count < options.min_points) continue;
    const Eigen::Vector3d mean = m.sum / double(m.count);
    const Eigen::Matrix3d covariance = m.outer / double(m.count) - mean * mean.transpose();
    const Eigen::Vector3d normal =
        planeNormalOf(covariance, options.max_planarity, options.min_spread);
    if (!normal.isZero()) patches.push_back({normal, double(m.count)});
  }
  return patches;
}

}  // namespace

std::optional<Eigen::Vector3d> structuralUp(const std::vector<Eigen::Vector3f>& cloud,
                                            const Eigen::Vector3d& up_guess,
                                            const StructuralUpOptions& options) {
  const std::vector<Patch> patches = patchesOf(cloud, options.patches);
  constexpr double kDeg = std::numbers::pi / 180.0;
  const double wall_below = std::sin(options.class_angle_deg * kDeg);  // |n·up| of a wall
  const double level_above = std::cos(options.class_angle_deg * kDeg);
  Eigen::Vector3d up = up_guess.normalized();
  for (int pass = 0; pass < options.passes; ++pass) {
    Eigen::Matrix3d A = Eigen::Matrix3d::Zero();
    double points = 0.0;
    for (const Patch& patch : patches) {
      const double along = std::abs(patch.normal.dot(up));
      const Eigen::Matrix3d outer = patch.points * patch.normal * patch.normal.transpose();
      if (along <= wall_below) {
        A += outer;
      } else if (along >= level_above) {
        A -= outer;
      } else {
        continue;
      }
      points += patch.points;
    }
    if (points < options.min_points) return std::nullopt;
    const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> solver(A);
    if (solver.eigenvalues()(1) - solver.eigenvalues()(0) < options.min_gap_share * points) {
      return std::nullopt;
    }
    Eigen::Vector3d answer = solver.eigenvectors().col(0).normalized();
    if (answer.dot(up) < 0.0) answer = -answer;
    up = answer;
  }
  if (up.dot(up_guess.normalized()) < std::cos(options.max_tilt_deg * kDeg)) return std::nullopt;
  return up;
}

}  // namespace isg::slam
