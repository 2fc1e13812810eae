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
  // The walls that count, as judges and as judged: seen over min_length. Each plan wall counts
  // once, however many S-planes it was seen as.
  std::vector<int> counted;
  std::map<int, int> pieces;  // plan wall → its pieces among the counted
  Eigen::Vector2d centre = Eigen::Vector2d::Zero();
  for (int j = 0; j < n; ++j) {
    if (walls[j].length < options.min_length) continue;
    counted.push_back(j);
    ++pieces[walls[j].wall];
    centre += walls[j].middle;
  }
  if (counted.empty()) return out;
  // Yaw about the walls' centroid: there it is least tied to the translation.
  centre /= double(counted.size());
  const double sigma_angle = bim::radians(options.sigma_angle_deg);
  std::vector<Rows> rows;
  std::vector<double> share;
  for (int j : counted) {
    rows.push_back(rowsOf(walls[j], centre, options.sigma_distance, sigma_angle));
    share.push_back(1.0 / pieces[walls[j].wall]);
  }
  // One robust fit over every counted wall gives the weights (reweighted rounds, Huber then
  // Cauchy); a wall built off gets little weight in it, so leaving it out afterwards changes the
  // others' weights little. Each wall is then judged by the fit without its own plan wall: its
  // rows subtracted from the normal equations, which costs O(walls) for the floor instead of a
  // robust fit per wall.
  std::vector<std::array<double, 2>> weights(rows.size(), {1.0, 1.0});
  const Eigen::Matrix3d prior =
      Eigen::Vector3d(1.0 / (kPriorTranslation * kPriorTranslation),
                      1.0 / (kPriorTranslation * kPriorTranslation), 1.0 / (kPriorYaw * kPriorYaw))
          .asDiagonal();
  struct Normal {  // normal equations, and the evidence across directions, of some rows
    Eigen::Matrix3d H = Eigen::Matrix3d::Zero();
    Eigen::Vector3d g = Eigen::Vector3d::Zero();
    Eigen::Matrix2d cross = Eigen::Matrix2d::Zero();
  };
  const auto add = [&](Normal& to, std::size_t k) {
    for (int r = 0; r < 2; ++r) {
      const double w = share[k] * weights[k][r];
      to.H += w * rows[k].jacobian[r] * rows[k].jacobian[r].transpose();
      to.g += w * rows[k].jacobian[r] * rows[k].residual[r];
    }
    const Eigen::Vector2d& normal = walls[counted[k]].normal;
    to.cross += share[k] * normal * normal.transpose();
  };
  constexpr int kHuberRounds = 3, kRounds = 6;
  for (int round = 0; round < kRounds; ++round) {
    Normal all;
    for (std::size_t k = 0; k < rows.size(); ++k) add(all, k);
    const Eigen::Vector3d delta = -(prior + all.H).ldlt().solve(all.g);
    for (std::size_t k = 0; k < rows.size(); ++k) {
      for (int r = 0; r < 2; ++r) {
        const double scaled = rows[k].residual[r] + rows[k].jacobian[r].dot(delta);
        weights[k][r] = round < kHuberRounds ? huberWeight(scaled) : cauchyWeight(scaled);
      }
    }
  }
  Normal all;
  std::map<int, Normal> own_rows;  // plan wall → its rows' share of `all`
  for (std::size_t k = 0; k < rows.size(); ++k) {
    add(all, k);
    add(own_rows[walls[counted[k]].wall], k);
  }
  for (std::size_t k = 0; k < rows.size(); ++k) {
    const Normal& own = own_rows[walls[counted[k]].wall];
    if (int(pieces.size()) - 1 < options.min_others ||
        smallerEigenvalue(all.cross - own.cross) < kMinCrossEvidence) {
      continue;
    }
    const Eigen::Vector3d delta = -(prior + all.H - own.H).ldlt().solve(all.g - own.g);
    WallResidual& residual = out[counted[k]];
    residual.judged = true;
    residual.offset =
        options.sigma_distance * (rows[k].residual[0] + rows[k].jacobian[0].dot(delta));
    residual.angle = sigma_angle * (rows[k].residual[1] + rows[k].jacobian[1].dot(delta));
  }
  return out;
}

}  // namespace isg::slam
