// The consensus of the walls (docs/matching.md): an answer refined over the walls within the
// matching tolerances may sit on the walls that were built off the plan by about the same amount,
// leaving the ones built as planned just outside. Each direction's walls vote for how far the
// answer should move along it (one vote per plan wall); the few strongest votes are tried, and the
// move that puts the most plan walls on their surfaces is taken if it adds enough of them.
#include <algorithm>
#include <cmath>
#include <map>
#include <numbers>

#include "common/angles.hpp"
#include "slam/isgraph/graph_matching.hpp"

namespace isg::slam {

namespace {

struct Vote {
  double shift = 0.0;   // m along the direction's normal
  double weight = 1.0;  // the plan wall's one vote, shared by its S-planes
  int wall = -1;        // the plan wall (index of its first surface)
};

// The walls facing one way (or the opposite way: both fix the answer along that normal) and, per
// wall, how far along the normal the answer would have to move to put it on its surface.
struct DirectionVotes {
  Eigen::Vector2d normal;
  double length = 0.0;
  std::vector<Vote> shifts;
};

// Up to `count` shifts, each the centre of the most plan walls' votes within `sigma` of it
// (Gaussian-weighted), at least `separation` apart: the modes of the vote.
std::vector<double> strongestShifts(const DirectionVotes& votes, double sigma, double separation,
                                    int count) {
  std::vector<std::pair<double, double>> weighted;  // (support, shift)
  for (const Vote& vote : votes.shifts) {
    double support = 0.0;
    for (const Vote& other : votes.shifts) {
      const double z = (vote.shift - other.shift) / sigma;
      support += other.weight * std::exp(-0.5 * z * z);
    }
    weighted.emplace_back(support, vote.shift);
  }
  std::sort(weighted.begin(), weighted.end(),
            [](const auto& a, const auto& b) { return a.first > b.first; });
  std::vector<double> out;
  for (const auto& candidate : weighted) {
    if (int(out.size()) == count) break;
    const double shift = candidate.second;
    const bool distinct = std::all_of(out.begin(), out.end(),
                                      [&](double s) { return std::abs(s - shift) >= separation; });
    if (distinct) out.push_back(shift);
  }
  return out;
}

}  // namespace

Verification GraphMatcher::consensus(const MatchInput& input, const Verification& answer) const {
  const Eigen::Vector3d& x = answer.x_y_yaw;
  const Eigen::Matrix2d R = Eigen::Rotation2Dd(x.z()).toRotationMatrix();
  const double same_direction = std::sin(options_.plane_angle_deg * std::numbers::pi / 180.0);
  std::vector<DirectionVotes> directions;
  for (const MatchPlane& plane : input.planes) {
    if (plane.length() < options_.min_plane_length) continue;
    const Eigen::Vector2d a = R * plane.start + x.head<2>();
    const Eigen::Vector2d b = R * plane.end + x.head<2>();
    const Eigen::Vector2d middle = 0.5 * (a + b);
    const Cell* cell = cellAt(middle);
    if (!cell) continue;
    const double yaw = plane.normalYaw() + x.z();
    // The nearest surface facing the same way within the deviation distance whose exposed parts
    // the plane's extent reaches: the wall it would be, built as planned or built off.
    double vote = 0.0, nearest = options_.deviation_distance;
    int wall = -1;
    Eigen::Vector2d normal = Eigen::Vector2d::Zero();
    for (int i : cell->surfaces) {
      const auto& s = graph_->surfaces[i];
      if (std::abs(common::wrapAngle(yaw - surface_yaw_[i])) >
          options_.plane_angle_deg * std::numbers::pi / 180.0) {
        continue;
      }
      const double offset = s.plane.signedDistance({middle.x(), middle.y(), 0.0});
      if (std::abs(offset) > nearest) continue;
      if (!reachOf(i, a, b).reaches) continue;
      nearest = std::abs(offset);
      // Moving the answer by t moves the plane's offset by n·t: n·t = −offset puts it on.
      vote = -offset;
      normal = s.plane.normal.head<2>().normalized();
      wall = wall_of_surface_[i];
    }
    if (normal.isZero()) continue;
    if (normal.x() < 0.0 || (normal.x() == 0.0 && normal.y() < 0.0)) {
      normal = -normal;
      vote = -vote;
    }
    auto group = std::find_if(directions.begin(), directions.end(), [&](const auto& d) {
      return d.normal.dot(normal) > 0.0 &&
             std::abs(d.normal.x() * normal.y() - d.normal.y() * normal.x()) < same_direction;
    });
    if (group == directions.end()) {
      directions.push_back({normal, 0.0, {}});
      group = directions.end() - 1;
    }
    group->length += plane.length();
    group->shifts.push_back({vote, 1.0, wall});
  }
  // One vote per plan wall: its S-planes (pieces, both faces) share it.
  for (DirectionVotes& d : directions) {
    std::map<int, int> pieces;
    for (const Vote& v : d.shifts) ++pieces[v.wall];
    for (Vote& v : d.shifts) v.weight = 1.0 / pieces[v.wall];
  }
  if (directions.empty()) return answer;
  std::sort(directions.begin(), directions.end(),
            [](const auto& p, const auto& q) { return p.length > q.length; });
  // The two most walled directions at least 30° apart fix the answer's position.
  const DirectionVotes& first = directions[0];
  const DirectionVotes* second = nullptr;
  for (std::size_t k = 1; k < directions.size() && !second; ++k) {
    const Eigen::Vector2d& n = directions[k].normal;
    if (std::abs(first.normal.x() * n.y() - first.normal.y() * n.x()) >= 0.5) {
      second = &directions[k];
    }
  }
  const double sigma = options_.plane_sigma;
  const int modes = options_.consensus_modes;
  std::vector<double> first_shifts = strongestShifts(first, sigma, 2.0 * sigma, modes);
  std::vector<double> second_shifts{0.0};
  if (second) second_shifts = strongestShifts(*second, sigma, 2.0 * sigma, modes);
  first_shifts.push_back(0.0);
  second_shifts.push_back(0.0);
  const double held = wallsAgreeing(input, x);
  Eigen::Vector3d best = x;
  double most = held;
  for (double along_first : first_shifts) {
    for (double along_second : second_shifts) {
      if (std::abs(along_first) < 0.01 && std::abs(along_second) < 0.01) continue;
      Eigen::Vector2d t = along_first * first.normal;
      if (second) {
        Eigen::Matrix2d N;
        N.row(0) = first.normal.transpose();
        N.row(1) = second->normal.transpose();
        t = N.inverse() * Eigen::Vector2d(along_first, along_second);
      }
      const Eigen::Vector3d moved(x.x() + t.x(), x.y() + t.y(), x.z());
      const double agreeing = wallsAgreeing(input, moved);
      if (agreeing > most) {
        most = agreeing;
        best = moved;
      }
    }
  }
  if (most < held + options_.consensus_min_walls) return answer;
  // Not refined here: a refinement over the walls it now explains may turn it, and the vote says
  // nothing about yaw (the localizer refits a moved answer robustly, ISGraphLocalizer).
  return verify(input, best);
}

double GraphMatcher::wallsAgreeing(const MatchInput& input, const Eigen::Vector3d& x_y_yaw) const {
  std::map<int, double> fit_of_wall;
  const Placement placed(x_y_yaw);
  for (const MatchPlane& plane : input.planes) {
    if (plane.length() < options_.min_plane_length) continue;
    double overlap = 0.0, distance = 0.0;
    const int s = matchPlane(plane, placed, &overlap, &distance);
    if (s < 0) continue;
    const double z = distance / options_.plane_sigma;
    double& fit = fit_of_wall[wall_of_surface_[s]];
    fit = std::max(fit, std::exp(-0.5 * z * z));
  }
  double total = 0.0;
  for (const auto& [wall, fit] : fit_of_wall) total += fit;
  return total;
}

}  // namespace isg::slam
