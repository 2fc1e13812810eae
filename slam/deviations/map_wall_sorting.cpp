#include "slam/deviations/map_wall_sorting.hpp"

#include <algorithm>
#include <cmath>

#include "common/angles.hpp"

namespace isg::slam {

SortedMapWall sortMapWall(const bim::AGraph& plan, const std::string& level, const WallInB& m,
                          const DeviationOptions& options) {
  SortedMapWall out;
  const int best = surfaceOf(plan, level, m, options);
  auto along = piecesAlongFaces(plan, level, m, options);
  // Along several faces in line, its own among them: evidence for each, by the piece along it
  // (a façade's bays between columns, seen as one plane, are each judged on that plane).
  const bool along_its_own =
      std::any_of(along.begin(), along.end(), [&](const auto& p) { return p.first == best; });
  if (best >= 0 && !(along.size() >= 2 && along_its_own)) {
    out.role = MapWallRole::kEvidence;
    out.surface = best;
  } else if (!along.empty()) {
    out.role = MapWallRole::kAlongFacesInLine;
    out.pieces = std::move(along);
  } else if (onColumn(plan, level, m, options)) {
    out.role = MapWallRole::kOnColumn;
  } else if (isStray(m, options)) {
    out.role = MapWallRole::kStray;
  }
  return out;
}

bool isStray(const WallInB& m, const DeviationOptions& options) {
  return m.observations < options.min_deviation_observations &&
         (m.lean_deg > options.max_stray_lean_deg || m.behind_walls);
}

// The plan surface of `level` a map wall is evidence for: turned within the search angle, within
// the search distance, over a third of its length along the surface's extent; the nearest on
// average. -1 for none.
int surfaceOf(const bim::AGraph& plan, const std::string& level, const WallInB& m,
              const DeviationOptions& options) {
  const double min_cos = std::cos(common::radians(options.search_angle_deg));
  int best = -1;
  double best_distance = 0.0;
  for (int s = 0; s < int(plan.surfaces.size()); ++s) {
    const bim::WallSurfaceNode& surface = plan.surfaces[s];
    if (surface.level != level) continue;
    const Eigen::Vector2d n = surface.plane.normal.head<2>().normalized();
    if (n.dot(m.normal) < min_cos) continue;
    const double d = surface.plane.d;
    auto distance = [&](const Eigen::Vector2d& p) { return std::abs(n.dot(p) + d); };
    const double nearest = std::min({distance(m.start), distance(m.middle()), distance(m.end)});
    if (nearest > options.search_distance) continue;
    // A third of it along the surface's extent (its segments' span).
    const Eigen::Vector2d along(n.y(), -n.x());
    double lo = INFINITY, hi = -INFINITY;
    for (const auto& [a, b] : surface.segments) {
      lo = std::min({lo, a.dot(along), b.dot(along)});
      hi = std::max({hi, a.dot(along), b.dot(along)});
    }
    const double t0 = std::min(m.start.dot(along), m.end.dot(along));
    const double t1 = std::max(m.start.dot(along), m.end.dot(along));
    if (std::min(hi, t1) - std::max(lo, t0) < m.length() / 3.0) continue;
    const double mean = (distance(m.start) + distance(m.middle()) + distance(m.end)) / 3.0;
    if (best < 0 || mean < best_distance) best = s, best_distance = mean;
  }
  return best;
}

// A map wall lying all along a rectangular column of the plan (its ends and middle within
// column_margin of the column's outline): a face of the column, judged with the column
// (column_deviations.hpp), not an extra wall. The A-Graph holds a column's two long faces as
// surfaces, not its ends, and a column 0.5 m or more across has ends as long as a map wall.
bool onColumn(const bim::AGraph& plan, const std::string& level, const WallInB& m,
              const DeviationOptions& options) {
  for (const auto& node : plan.walls) {
    if (!node.column || node.level != level) continue;
    const Eigen::Vector2d left =
        plan.surfaces[node.left_surface].plane.normal.head<2>().normalized();
    const Eigen::Vector2d axis(left.y(), -left.x());
    const Eigen::Vector2d centre = node.anchor.head<2>();
    auto outside = [&](const Eigen::Vector2d& p) {
      return Eigen::Vector2d(std::abs((p - centre).dot(axis)) - 0.5 * node.length,
                             std::abs((p - centre).dot(left)) - 0.5 * node.thickness)
          .cwiseMax(0.0)
          .norm();
    };
    if (std::max({outside(m.start), outside(m.middle()), outside(m.end)}) <=
        options.column_margin) {
      return true;
    }
  }
  return false;
}

// A map wall along several plan faces in line (a façade of bays between columns, a corridor's
// wall broken by a junction), whether or not it is a third along one of them (surfaceOf), is
// evidence for each it runs along over at least half the face's extent: the piece of it along that
// face, when that is at least min_wall_length long. Together the pieces must cover two thirds of
// it, or it is not along the plan but past it (an extra wall in line with a face). None: it is
// unexplained.
std::vector<std::pair<int, WallInB>> piecesAlongFaces(const bim::AGraph& plan,
                                                      const std::string& level, const WallInB& m,
                                                      const DeviationOptions& options) {
  const double min_cos = std::cos(common::radians(options.search_angle_deg));
  const Eigen::Vector2d direction = (m.end - m.start) / std::max(m.length(), 1e-9);
  std::vector<std::pair<int, WallInB>> pieces;
  double covered = 0.0;
  for (int s = 0; s < int(plan.surfaces.size()); ++s) {
    const bim::WallSurfaceNode& surface = plan.surfaces[s];
    if (surface.level != level || surface.segments.empty()) continue;
    const Eigen::Vector2d n = surface.plane.normal.head<2>().normalized();
    if (n.dot(m.normal) < min_cos) continue;
    auto distance = [&](const Eigen::Vector2d& p) { return std::abs(n.dot(p) + surface.plane.d); };
    // Along its whole length within the search distance: in line with the face, not crossing it.
    if (std::max({distance(m.start), distance(m.middle()), distance(m.end)}) >
        options.search_distance) {
      continue;
    }
    double lo = INFINITY, hi = -INFINITY;
    for (const auto& [a, b] : surface.segments) {
      lo = std::min({lo, (a - m.start).dot(direction), (b - m.start).dot(direction)});
      hi = std::max({hi, (a - m.start).dot(direction), (b - m.start).dot(direction)});
    }
    const double from = std::max(lo, 0.0), to = std::min(hi, m.length());
    if (to - from < std::max(0.5 * (hi - lo), options.min_wall_length)) continue;
    WallInB piece = m;
    piece.start = m.start + from * direction;
    piece.end = m.start + to * direction;
    // Its confirmed parts, as shares of the piece.
    const double share_from = from / m.length(), share_to = to / m.length();
    piece.confirmed.clear();
    const auto whole =
        m.confirmed.empty() ? std::vector<std::pair<double, double>>{{0.0, 1.0}} : m.confirmed;
    for (const auto& [a, b] : whole) {
      const double x = std::max(a, share_from), y = std::min(b, share_to);
      if (y > x) {
        piece.confirmed.push_back({(x - share_from) / (share_to - share_from),
                                   (y - share_from) / (share_to - share_from)});
      }
    }
    covered += to - from;
    pieces.push_back({s, piece});
  }
  if (covered < 2.0 / 3.0 * m.length()) return {};
  return pieces;
}

}  // namespace isg::slam
