#include "slam/isgraph/wall_release.hpp"

#include <Eigen/Dense>
#include <Eigen/Geometry>
#include <array>
#include <cmath>
#include <map>
#include <optional>

#include "common/angles.hpp"

namespace isg::slam {
namespace {

// A weak prior on the correction, so that the fit stays defined where the others do not fix a
// direction (those walls are then not judged: see below).
constexpr double kPriorTranslation = 0.5;           // m
constexpr double kPriorYaw = common::radians(5.0);  // rad
// The others fix both directions of the translation: the smaller eigenvalue of the sum of their
// normals' outer products is at least half a wall's worth.
constexpr double kMinCrossEvidence = 0.5;

// One wall's two rows of the linearised fit: its residuals (distance, angle), scaled by their
// sigmas, are b + J δ for the correction δ = (x, y, yaw about `centre`).
struct Rows {
  std::array<Eigen::Vector3d, 2> jacobian;
  std::array<double, 2> residual;
};

Rows rowsOf(const HeldWall& wall, const Eigen::Vector2d& centre, double sigma_distance,
            double sigma_angle) {
  const Eigen::Vector2d arm = wall.middle - centre;
  const Eigen::Vector2d turned(-arm.y(), arm.x());  // d(middle)/d(yaw)
  Rows rows;
  rows.jacobian[0] =
      Eigen::Vector3d(wall.normal.x(), wall.normal.y(), wall.normal.dot(turned)) / sigma_distance;
  rows.residual[0] = wall.offset / sigma_distance;
  rows.jacobian[1] = Eigen::Vector3d(0.0, 0.0, 1.0 / sigma_angle);
  rows.residual[1] = wall.angle / sigma_angle;
  return rows;
}

// Reweighting: Huber's first (convex, so the start does not matter), then Cauchy's, under which a
// wall built 4 sigmas off pulls the correction that judges the others with 1/17 of its weight
// instead of Huber's 1/4.
double huberWeight(double scaled) {
  const double a = std::abs(scaled);
  return a <= 1.0 ? 1.0 : 1.0 / a;
}
double cauchyWeight(double scaled) { return 1.0 / (1.0 + scaled * scaled); }

double smallerEigenvalue(const Eigen::Matrix2d& m) {
  const double half_trace = 0.5 * m.trace();
  const double det = m.determinant();
  return half_trace - std::sqrt(std::max(0.0, half_trace * half_trace - det));
}

}  // namespace

bool WallResidual::beyond(const WallReleaseOptions& options) const {
  return judged && (std::abs(offset) > options.distance ||
                    std::abs(angle) > common::radians(options.angle_deg));
}

namespace {

// Normal equations of some walls' rows, and their evidence across directions.
struct NormalEquations {
  Eigen::Matrix3d H = Eigen::Matrix3d::Zero();
  Eigen::Vector3d g = Eigen::Vector3d::Zero();
  Eigen::Matrix2d cross = Eigen::Matrix2d::Zero();
};

// One robust fit of the correction over every wall seen over min_length (reweighted rounds, Huber
// then Cauchy), each plan wall counted once however many S-planes it was seen as: its normal
// equations at the final weights, in all and per plan wall.
struct FloorFit {
  std::vector<int> counted;  // walls that count, as judges and as judged
  Eigen::Vector2d centre = Eigen::Vector2d::Zero();
  std::vector<Rows> rows;  // of each counted wall, about `centre`
  NormalEquations all;
  std::map<int, NormalEquations> of_wall;  // plan wall → its rows' share of `all`
  Eigen::Matrix3d prior = Eigen::Matrix3d::Zero();
};

FloorFit fitFloor(const std::vector<HeldWall>& walls, const WallReleaseOptions& options) {
  FloorFit fit;
  std::map<int, int> pieces;  // plan wall → its pieces among the counted
  for (int j = 0; j < int(walls.size()); ++j) {
    if (walls[j].length < options.min_length) continue;
    fit.counted.push_back(j);
    ++pieces[walls[j].wall];
    fit.centre += walls[j].middle;
  }
  if (fit.counted.empty()) return fit;
  // Yaw about the walls' centroid: there it is least tied to the translation.
  fit.centre /= double(fit.counted.size());
  const double sigma_angle = common::radians(options.sigma_angle_deg);
  std::vector<double> share;
  for (int j : fit.counted) {
    fit.rows.push_back(rowsOf(walls[j], fit.centre, options.sigma_distance, sigma_angle));
    share.push_back(1.0 / pieces[walls[j].wall]);
  }
  fit.prior =
      Eigen::Vector3d(1.0 / (kPriorTranslation * kPriorTranslation),
                      1.0 / (kPriorTranslation * kPriorTranslation), 1.0 / (kPriorYaw * kPriorYaw))
          .asDiagonal();
  std::vector<std::array<double, 2>> weights(fit.rows.size(), {1.0, 1.0});
  const auto add = [&](NormalEquations& to, std::size_t k) {
    for (int r = 0; r < 2; ++r) {
      const double w = share[k] * weights[k][r];
      to.H += w * fit.rows[k].jacobian[r] * fit.rows[k].jacobian[r].transpose();
      to.g += w * fit.rows[k].jacobian[r] * fit.rows[k].residual[r];
    }
    const Eigen::Vector2d& normal = walls[fit.counted[k]].normal;
    to.cross += share[k] * normal * normal.transpose();
  };
  constexpr int kHuberRounds = 3, kRounds = 6;
  for (int round = 0; round < kRounds; ++round) {
    NormalEquations all;
    for (std::size_t k = 0; k < fit.rows.size(); ++k) add(all, k);
    const Eigen::Vector3d delta = -(fit.prior + all.H).ldlt().solve(all.g);
    for (std::size_t k = 0; k < fit.rows.size(); ++k) {
      for (int r = 0; r < 2; ++r) {
        const double scaled = fit.rows[k].residual[r] + fit.rows[k].jacobian[r].dot(delta);
        weights[k][r] = round < kHuberRounds ? huberWeight(scaled) : cauchyWeight(scaled);
      }
    }
  }
  for (std::size_t k = 0; k < fit.rows.size(); ++k) {
    add(fit.all, k);
    add(fit.of_wall[walls[fit.counted[k]].wall], k);
  }
  return fit;
}

// The correction these normal equations give, if they fix it.
std::optional<Eigen::Vector3d> solve(const FloorFit& fit, const NormalEquations& equations,
                                     int plan_walls, const WallReleaseOptions& options) {
  if (plan_walls < options.min_others || smallerEigenvalue(equations.cross) < kMinCrossEvidence) {
    return std::nullopt;
  }
  return Eigen::Vector3d(-(fit.prior + equations.H).ldlt().solve(equations.g));
}

}  // namespace

std::vector<WallResidual> residualsAgainstOthers(const std::vector<HeldWall>& walls,
                                                 const WallReleaseOptions& options) {
  std::vector<WallResidual> out(walls.size());
  // A wall built off gets little weight in the robust fit over all, so leaving it out afterwards
  // changes the others' weights little. Each wall is judged by the fit without its own plan wall
  // (its pieces and its other face, which moved with it): their rows taken out of the normal
  // equations, O(walls) for the floor instead of a robust fit per wall.
  const FloorFit fit = fitFloor(walls, options);
  const double sigma_angle = common::radians(options.sigma_angle_deg);
  for (std::size_t k = 0; k < fit.rows.size(); ++k) {
    const NormalEquations& own = fit.of_wall.at(walls[fit.counted[k]].wall);
    NormalEquations others = fit.all;
    others.H -= own.H;
    others.g -= own.g;
    others.cross -= own.cross;
    const auto delta = solve(fit, others, int(fit.of_wall.size()) - 1, options);
    if (!delta) continue;
    const Rows& rows = fit.rows[k];
    WallResidual& residual = out[fit.counted[k]];
    residual.judged = true;
    residual.offset = options.sigma_distance * (rows.residual[0] + rows.jacobian[0].dot(*delta));
    residual.angle = sigma_angle * (rows.residual[1] + rows.jacobian[1].dot(*delta));
  }
  return out;
}

std::optional<Eigen::Vector3d> correctionOfAll(const std::vector<HeldWall>& walls,
                                               const WallReleaseOptions& options) {
  const FloorFit fit = fitFloor(walls, options);
  const auto delta = solve(fit, fit.all, int(fit.of_wall.size()), options);
  if (!delta) return std::nullopt;
  // About the centroid, the correction is R(yaw) (p − c) + c + t: about the origin, the same
  // turn and R(yaw) (−c) + c + t.
  const Eigen::Vector2d moved =
      Eigen::Rotation2Dd(delta->z()) * (-fit.centre) + fit.centre + delta->head<2>();
  return Eigen::Vector3d(moved.x(), moved.y(), delta->z());
}

}  // namespace isg::slam
