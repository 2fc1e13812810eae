#include "slam/isgraph/wall_release.hpp"

#include <Eigen/Dense>
#include <array>
#include <cmath>
#include <map>

#include "bim/angles.hpp"

namespace isg::slam {
namespace {

// A weak prior on the correction, so that the fit stays defined where the others do not fix a
// direction (those walls are then not judged: see below).
constexpr double kPriorTranslation = 0.5;        // m
constexpr double kPriorYaw = bim::radians(5.0);  // rad
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
  return judged &&
         (std::abs(offset) > options.distance || std::abs(angle) > bim::radians(options.angle_deg));
}

std::vector<WallResidual> residualsAgainstOthers(const std::vector<HeldWall>& walls,
                                                 const WallReleaseOptions& options) {
  const int n = int(walls.size());
  std::vector<WallResidual> out(n);
  const double sigma_angle = bim::radians(options.sigma_angle_deg);
  const Eigen::Matrix3d prior =
      Eigen::Vector3d(1.0 / (kPriorTranslation * kPriorTranslation),
                      1.0 / (kPriorTranslation * kPriorTranslation), 1.0 / (kPriorYaw * kPriorYaw))
          .asDiagonal();
  for (int i = 0; i < n; ++i) {
    const HeldWall& wall = walls[i];
    if (wall.length < options.min_length) continue;
    // Its neighbours: a map that has bent since it was merged is bent alike around the wall.
    // Not the other pieces or the other face of the same plan wall: they moved with it.
    std::vector<int> others;
    std::map<int, int> pieces;  // plan wall → its pieces among the others
    for (int j = 0; j < n; ++j) {
      const HeldWall& other = walls[j];
      if (other.wall == wall.wall || other.length < options.min_length ||
          (other.middle - wall.middle).norm() > options.neighbourhood) {
        continue;
      }
      others.push_back(j);
      ++pieces[other.wall];
    }
    // Each plan wall counts once, however many S-planes it was seen as.
    std::vector<Rows> rows;
    std::vector<double> share;
    Eigen::Matrix2d cross = Eigen::Matrix2d::Zero();
    for (int j : others) {
      // About the judged wall's middle: there the correction's yaw moves nothing along its
      // normal, and its offset is the translation's alone.
      rows.push_back(rowsOf(walls[j], wall.middle, options.sigma_distance, sigma_angle));
      share.push_back(1.0 / pieces[walls[j].wall]);
      cross += share.back() * walls[j].normal * walls[j].normal.transpose();
    }
    if (int(pieces.size()) < options.min_others || smallerEigenvalue(cross) < kMinCrossEvidence) {
      continue;
    }
    // Robust fit of the correction over the neighbours: reweighted rounds, Huber then Cauchy.
    std::vector<std::array<double, 2>> weights(rows.size(), {1.0, 1.0});
    Eigen::Vector3d delta = Eigen::Vector3d::Zero();
    constexpr int kHuberRounds = 3, kRounds = 6;
    for (int round = 0; round < kRounds; ++round) {
      Eigen::Matrix3d H = prior;
      Eigen::Vector3d g = Eigen::Vector3d::Zero();
      for (std::size_t k = 0; k < rows.size(); ++k) {
        for (int r = 0; r < 2; ++r) {
          const double w = share[k] * weights[k][r];
          H += w * rows[k].jacobian[r] * rows[k].jacobian[r].transpose();
          g += w * rows[k].jacobian[r] * rows[k].residual[r];
        }
      }
      delta = -H.ldlt().solve(g);
      for (std::size_t k = 0; k < rows.size(); ++k) {
        for (int r = 0; r < 2; ++r) {
          const double scaled = rows[k].residual[r] + rows[k].jacobian[r].dot(delta);
          weights[k][r] = round + 1 < kHuberRounds ? huberWeight(scaled) : cauchyWeight(scaled);
        }
      }
    }
    const Rows own = rowsOf(wall, wall.middle, options.sigma_distance, sigma_angle);
    out[i].judged = true;
    out[i].offset = options.sigma_distance * (own.residual[0] + own.jacobian[0].dot(delta));
    out[i].angle = sigma_angle * (own.residual[1] + own.jacobian[1].dot(delta));
  }
  return out;
}

}  // namespace isg::slam
