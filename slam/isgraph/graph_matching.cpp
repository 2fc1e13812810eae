#include "slam/isgraph/graph_matching.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <map>
#include <numbers>
#include <optional>
#include <set>
#include <unordered_map>

#include "common/angles.hpp"

namespace isg::slam {

namespace {

// Difference of two axes (directions modulo π).
double axisDifference(double a, double b) {
  return std::abs(common::remainderOf(a - b, std::numbers::pi));
}

Eigen::Matrix2d rotation(double yaw) { return Eigen::Rotation2Dd(yaw).toRotationMatrix(); }

Eigen::Vector2d apply(const Eigen::Vector3d& x_y_yaw, const Eigen::Vector2d& p) {
  return rotation(x_y_yaw.z()) * p + x_y_yaw.head<2>();
}

double yawOfNormal(const bim::Plane& plane) {
  return std::atan2(plane.normal.y(), plane.normal.x());
}

// Surfaces in line with one another — on one plane, facing the same way, within kInLineAngle and
// kInLineOffset: a façade's bays between its columns, a wall's pieces either side of an opening
// the plan draws as a gap. An S-plane may span the gaps between them.
constexpr double kInLineAngle = common::radians(1.0);
constexpr double kInLineOffset = 0.03;  // m
template <typename Surfaces>
std::vector<std::vector<int>> surfacesInLine(const Surfaces& surfaces) {
  struct Key {
    double yaw, offset;
    int index;
  };
  std::vector<Key> keys;
  for (int i = 0; i < int(surfaces.size()); ++i) {
    const bim::Plane& plane = surfaces[i].plane;
    const double n = plane.normal.head<2>().norm();
    if (n < 0.5) continue;  // not a vertical surface
    keys.push_back({yawOfNormal(plane), -plane.d / n, i});
  }
  std::sort(keys.begin(), keys.end(), [](const Key& a, const Key& b) {
    return a.yaw < b.yaw || (a.yaw == b.yaw && a.index < b.index);
  });
  std::vector<std::vector<int>> out(surfaces.size());
  const std::size_t n = keys.size();
  for (std::size_t a = 0; a < n; ++a) {
    // Forward in yaw, wrapping once past π.
    for (std::size_t step = 1; step < n; ++step) {
      const Key& k = keys[a];
      const Key& m = keys[(a + step) % n];
      const double gap = m.yaw - k.yaw + (a + step >= n ? 2.0 * std::numbers::pi : 0.0);
      if (gap > kInLineAngle) break;
      if (std::abs(m.offset - k.offset) > kInLineOffset) continue;
      out[std::size_t(k.index)].push_back(m.index);
      out[std::size_t(m.index)].push_back(k.index);
    }
  }
  return out;
}

bool pointInPolygon(const std::vector<Eigen::Vector2d>& polygon, const Eigen::Vector2d& p) {
  bool inside = false;
  for (std::size_t i = 0, j = polygon.size() - 1; i < polygon.size(); j = i++) {
    const Eigen::Vector2d& a = polygon[i];
    const Eigen::Vector2d& b = polygon[j];
    if ((a.y() > p.y()) != (b.y() > p.y()) &&
        p.x() < (b.x() - a.x()) * (p.y() - a.y()) / (b.y() - a.y()) + a.x()) {
      inside = !inside;
    }
  }
  return inside;
}

}  // namespace

double Verification::unexplainedShare() const {
  const double total = explained_length + unexplained_length;
  return total > 0.0 ? (unexplained_length - built_off_length) / total : 0.0;
}

Eigen::Isometry3d MatchResult::B_T_M() const {
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  T.linear() = Eigen::AngleAxisd(best.x_y_yaw.z(), Eigen::Vector3d::UnitZ()).toRotationMatrix();
  T.translation() = Eigen::Vector3d(best.x_y_yaw.x(), best.x_y_yaw.y(), 0.0);
  return T;
}

MatchResult MatchResult::translated(const Eigen::Vector2d& shift) const {
  MatchResult moved = *this;
  moved.best.x_y_yaw.head<2>() += shift;
  moved.second.x_y_yaw.head<2>() += shift;
  for (auto& candidate : moved.candidates) candidate.answer.x_y_yaw.head<2>() += shift;
  return moved;
}

nlohmann::json MatchResult::toJson() const {
  nlohmann::json rooms = nlohmann::json::array(), planes = nlohmann::json::array();
  for (const auto& [s, a] : best.rooms) rooms.push_back({s, a});
  for (const auto& [s, a] : best.planes) planes.push_back({s, a});
  return {{"status", toString(status)},
          {"reason", reason},
          {"x_y_yaw", {best.x_y_yaw.x(), best.x_y_yaw.y(), best.x_y_yaw.z()}},
          {"score", best.score},
          {"second_score", second_score},
          {"hypotheses", hypotheses},
          {"clusters", clusters},
          {"rooms", rooms},
          {"planes", planes},
          {"doors_passed", best.doors_passed},
          {"doors_missing", best.doors_missing},
          {"rooms_contradicted", best.rooms_contradicted},
          {"plane_rms", best.plane_rms},
          {"explained_length", best.explained_length},
          {"unexplained_length", best.unexplained_length},
          {"built_off_length", best.built_off_length},
          {"candidates", candidatesJson()},
          {"seconds", seconds}};
}

nlohmann::json MatchResult::candidatesJson() const {
  // The best answer first, then the others with what separates each from it.
  auto answer = [](const Verification& v) {
    return nlohmann::json{
        {"B_T_M", {{"x", v.x_y_yaw.x()}, {"y", v.x_y_yaw.y()}, {"yaw", v.x_y_yaw.z()}}},
        {"score", v.score},
        {"rooms", v.rooms.size()},
        {"planes", v.planes.size()},
        {"explained_length", v.explained_length},
        {"unexplained_length", v.unexplained_length},
        {"built_off_length", v.built_off_length}};
  };
  nlohmann::json out = nlohmann::json::array();
  if (hypotheses == 0) return out;
  out.push_back(answer(best));
  out.back()["best"] = true;
  for (const Candidate& c : candidates) {
    nlohmann::json j = answer(c.answer);
    const Distinction& d = c.from_best;
    j["evidence_for_best"] = d.evidence;
    j["disagreement"] = d.disagreement;
    j["walls_for_best"] = d.walls_for;
    j["walls_for_this"] = d.walls_against;
    j["rooms_for_best"] = d.rooms_for;
    j["rooms_for_this"] = d.rooms_against;
    j["doorways_for_best"] = d.doors_for;
    j["doorways_for_this"] = d.doors_against;
    j["would_separate"] = d.separating_rooms;
    out.push_back(j);
  }
  return out;
}

GraphMatcher::GraphMatcher(const bim::AGraph& graph, const MatchingOptions& options)
    : graph_(&graph), options_(options) {
  layGrid();
  if (options_.plane_angle_deg < 90.0) {
    plane_angle_screen_ = std::cos(common::radians(options_.plane_angle_deg)) - 1e-9;
  }
  indexSurfaces();
  indexRoomsAndDoors();
  findCorners();
}

// The grid's extent: every surface segment and room outline, with a margin.
void GraphMatcher::layGrid() {
  const bim::AGraph& graph = *graph_;
  Eigen::AlignedBox2d bounds = graph.surfaceBounds();
  for (const auto& r : graph.rooms) {
    for (const auto& p : r.outline) bounds.extend(p);
  }
  if (bounds.isEmpty())
    bounds = Eigen::AlignedBox2d(Eigen::Vector2d::Zero(), Eigen::Vector2d::Zero());
  const Eigen::Vector2d lo = bounds.min(), hi = bounds.max();
  const double margin = 2.0;
  origin_ = lo - Eigen::Vector2d::Constant(margin);
  columns_ = int(std::ceil((hi.x() - lo.x() + 2 * margin) / cell_)) + 1;
  rows_ = int(std::ceil((hi.y() - lo.y() + 2 * margin) / cell_)) + 1;
  cells_.resize(std::size_t(columns_) * rows_);
}

std::vector<GraphMatcher::Cell*> GraphMatcher::cellsNear(const Eigen::Vector2d& a,
                                                         const Eigen::Vector2d& b, double pad) {
  const Eigen::Vector2d box_lo = a.cwiseMin(b) - Eigen::Vector2d::Constant(pad);
  const Eigen::Vector2d box_hi = a.cwiseMax(b) + Eigen::Vector2d::Constant(pad);
  const int c0 = std::max(0, int((box_lo.x() - origin_.x()) / cell_));
  const int c1 = std::min(columns_ - 1, int((box_hi.x() - origin_.x()) / cell_));
  const int r0 = std::max(0, int((box_lo.y() - origin_.y()) / cell_));
  const int r1 = std::min(rows_ - 1, int((box_hi.y() - origin_.y()) / cell_));
  std::vector<Cell*> out;
  for (int r = r0; r <= r1; ++r) {
    for (int c = c0; c <= c1; ++c) out.push_back(&cells_[std::size_t(r) * columns_ + c]);
  }
  return out;
}

// Each surface's normal and wall, entered in every cell from which an S-plane's middle could lie
// within the tolerances of it.
void GraphMatcher::indexSurfaces() {
  const bim::AGraph& graph = *graph_;
  const double surface_pad = options_.plane_distance + options_.plane_gap + 0.5;
  for (int i = 0; i < int(graph.surfaces.size()); ++i) {
    const auto& s = graph.surfaces[i];
    surface_yaw_.push_back(yawOfNormal(s.plane));
    surface_direction_.emplace_back(std::cos(surface_yaw_.back()), std::sin(surface_yaw_.back()));
    int first_face = i;
    for (int j = 0; j < i && !s.wall.empty(); ++j) {
      if (graph.surfaces[j].wall == s.wall) {
        first_face = j;
        break;
      }
    }
    wall_of_surface_.push_back(first_face);
    for (const auto& [a, b] : s.segments) {
      for (Cell* cell : cellsNear(a, b, surface_pad)) {
        if (cell->surfaces.empty() || cell->surfaces.back() != i) cell->surfaces.push_back(i);
      }
    }
  }
}

// Each room's yaw and outline's box in the grid; each room's doorways.
void GraphMatcher::indexRoomsAndDoors() {
  const bim::AGraph& graph = *graph_;
  for (int i = 0; i < int(graph.rooms.size()); ++i) {
    const auto& r = graph.rooms[i];
    room_yaw_.push_back(r.pairs.empty() ? 0.0 : yawOfNormal(graph.surfaces[r.pairs[0][0]].plane));
    if (r.outline.empty()) continue;
    Eigen::Vector2d a = r.outline[0], b = r.outline[0];
    for (const auto& p : r.outline) a = a.cwiseMin(p), b = b.cwiseMax(p);
    for (Cell* cell : cellsNear(a, b, options_.centre_tolerance)) cell->rooms.push_back(i);
  }
  doors_of_room_.resize(graph.rooms.size());
  for (int d = 0; d < int(graph.doorways.size()); ++d) {
    for (int r : graph.doorways[d].rooms) {
      if (r >= 0 && r < int(graph.rooms.size())) doors_of_room_[r].push_back(d);
    }
  }
}

// The plan's wall corners (seeds, slam/isgraph/match_seeds.cpp): segment ends that meet. Each arm
// is as long as its surface, and the surfaces in line with it, reach from the corner, across
// doorways and gaps: an S-plane spans them.
void GraphMatcher::findCorners() {
  const bim::AGraph& graph = *graph_;
  const std::vector<std::vector<int>> in_line = surfacesInLine(graph.surfaces);
  std::set<std::array<int, 4>> paired;
  for (int i = 0; i < int(graph.surfaces.size()); ++i) {
    const auto& si = graph.surfaces[i];
    for (int a = 0; a < int(si.segments.size()); ++a) {
      for (const Eigen::Vector2d& end : {si.segments[a].first, si.segments[a].second}) {
        const Cell* cell = cellAt(end);
        if (!cell) continue;
        for (int j : cell->surfaces) {
          if (j <= i) continue;
          const auto& sj = graph.surfaces[j];
          for (int b = 0; b < int(sj.segments.size()); ++b) {
            if (!paired.insert({i, a, j, b}).second) continue;
            auto corner = cornerOf(si.plane, si.segments[a].first, si.segments[a].second, sj.plane,
                                   sj.segments[b].first, sj.segments[b].second, options_.corner_gap,
                                   options_.minCornerSine());
            if (!corner) continue;
            for (int k = 0; k < 2; ++k) {
              const int surface = k == 0 ? i : j;
              const auto reach = [&](int t) {
                for (const auto& [p, q] : graph.surfaces[std::size_t(t)].segments) {
                  for (const Eigen::Vector2d& x : {p, q}) {
                    corner->arm[k] =
                        std::max(corner->arm[k], corner->arm_direction[k].dot(x - corner->point));
                  }
                }
              };
              reach(surface);
              for (int t : in_line[std::size_t(surface)]) reach(t);
            }
            corners_.push_back(*corner);
          }
        }
      }
    }
  }
}

const GraphMatcher::Cell* GraphMatcher::cellAt(const Eigen::Vector2d& p) const {
  const int c = int(std::floor((p.x() - origin_.x()) / cell_));
  const int r = int(std::floor((p.y() - origin_.y()) / cell_));
  if (c < 0 || r < 0 || c >= columns_ || r >= rows_) return nullptr;
  return &cells_[std::size_t(r) * columns_ + c];
}

bool GraphMatcher::joinedByDoor(int a, int b) const {
  for (int d : doors_of_room_[a]) {
    const auto& rooms = graph_->doorways[d].rooms;
    if (std::find(rooms.begin(), rooms.end(), b) != rooms.end()) return true;
  }
  return false;
}

int GraphMatcher::matchRoom(const MatchRoom& room, const Placement& placed,
                            double* distance_out) const {
  const double width_tolerance = options_.width_tolerance;
  const double centre_tolerance = options_.centre_tolerance;
  const Eigen::Vector2d centre = placed(room.centre);
  const Cell* cell = cellAt(centre);
  if (!cell) return -1;
  const double axis = room.axis_yaw + placed.yaw();
  const double axis_tolerance = common::radians(20.0);
  int best = -1;
  double best_distance = 1e300;
  for (int i : cell->rooms) {
    const auto& a = graph_->rooms[i];
    double distance = 0.0;
    if (room.four_wall) {
      if (a.kind != bim::RoomKind::kFourWall) continue;
      distance = (a.centre - centre).norm();
      if (distance > centre_tolerance) continue;
      const double d0 = axisDifference(axis, room_yaw_[i]);
      const bool same_order = d0 < axis_tolerance;
      const bool swapped = std::abs(d0 - std::numbers::pi / 2) < axis_tolerance;
      if (!same_order && !swapped) continue;
      const double w0 = same_order ? a.widths[0] : a.widths[1];
      const double w1 = same_order ? a.widths[1] : a.widths[0];
      if (std::abs(w0 - room.widths[0]) > width_tolerance ||
          std::abs(w1 - room.widths[1]) > width_tolerance) {
        continue;
      }
    } else {
      if (a.kind != bim::RoomKind::kTwoWall) continue;
      if (axisDifference(axis, room_yaw_[i]) > axis_tolerance) continue;
      if (std::abs(a.widths[0] - room.widths[0]) > width_tolerance) continue;
      // Across the corridor the centre is known; along it, only that it is inside.
      const Eigen::Vector2d n = graph_->surfaces[a.pairs[0][0]].plane.normal.head<2>().normalized();
      distance = std::abs(n.dot(centre - a.centre));
      if (distance > centre_tolerance) continue;
      const Eigen::Vector2d along(-n.y(), n.x());
      double lo = 1e300, hi = -1e300;
      for (const auto& p : a.outline) {
        lo = std::min(lo, along.dot(p));
        hi = std::max(hi, along.dot(p));
      }
      const double s = along.dot(centre);
      if (s < lo - centre_tolerance || s > hi + centre_tolerance) continue;
    }
    if (distance < best_distance) {
      best_distance = distance;
      best = i;
    }
  }
  *distance_out = best_distance;
  return best;
}

int GraphMatcher::matchPlane(const MatchPlane& plane, const Placement& placed, double* overlap,
                             double* distance) const {
  const Eigen::Vector2d a = placed(plane.start);
  const Eigen::Vector2d b = placed(plane.end);
  const Eigen::Vector2d middle = 0.5 * (a + b);
  const Cell* cell = cellAt(middle);
  if (!cell) return -1;
  const double yaw = plane.normalYaw() + placed.yaw();
  const double angle_tolerance = common::radians(options_.plane_angle_deg);
  // The S-plane's normal in B as a unit vector: a dot product screens out the surfaces facing
  // clearly elsewhere (most of a cell's) before the exact test, which decides.
  const Eigen::Vector2d direction(std::cos(yaw), std::sin(yaw));
  int best = -1;
  double best_distance = 1e300;
  for (int i : cell->surfaces) {
    if (direction.dot(surface_direction_[i]) < plane_angle_screen_) continue;
    const auto& s = graph_->surfaces[i];
    if (std::abs(common::wrapAngle(yaw - surface_yaw_[i])) > angle_tolerance) continue;
    const double offset = std::abs(s.plane.signedDistance({middle.x(), middle.y(), 0.0}));
    if (offset > options_.plane_distance || offset >= best_distance) continue;
    const Reach reach = reachOf(i, a, b);
    if (!reach.reaches) continue;
    best = i;
    best_distance = offset;
    *overlap = reach.shared;
  }
  *distance = best_distance;
  return best;
}

bool GraphMatcher::nearAsBuiltOff(const MatchPlane& plane, const Placement& placed) const {
  const Eigen::Vector2d a = placed(plane.start);
  const Eigen::Vector2d b = placed(plane.end);
  // Surfaces are listed in the cells around them out to the tolerances' reach plus half a metre:
  // a wall turned about one end has its middle furthest off, and may leave its cell's list when
  // long; then it counts as unexplained, as before.
  const Cell* cell = cellAt(0.5 * (a + b));
  if (!cell) return false;
  const double yaw = plane.normalYaw() + placed.yaw();
  const double angle_tolerance = common::radians(options_.deviation_angle_deg);
  for (int i : cell->surfaces) {
    const auto& s = graph_->surfaces[i];
    if (std::abs(common::wrapAngle(yaw - surface_yaw_[i])) > angle_tolerance) continue;
    // The segment's closest approach to the surface's line: 0 when it crosses it (a wall turned
    // about a point on its planned line).
    const double da = s.plane.signedDistance({a.x(), a.y(), 0.0});
    const double db = s.plane.signedDistance({b.x(), b.y(), 0.0});
    const double closest = da * db <= 0.0 ? 0.0 : std::min(std::abs(da), std::abs(db));
    if (closest > options_.deviation_distance) continue;
    if (reachOf(i, a, b).reaches) return true;
  }
  return false;
}

GraphMatcher::Reach GraphMatcher::reachOf(int surface, const Eigen::Vector2d& a,
                                          const Eigen::Vector2d& b) const {
  const auto& s = graph_->surfaces[surface];
  const Eigen::Vector2d along(-s.plane.normal.y(), s.plane.normal.x());
  const double lo = std::min(along.dot(a), along.dot(b));
  const double hi = std::max(along.dot(a), along.dot(b));
  Reach reach;
  for (const auto& [p, q] : s.segments) {
    const double o = std::min(hi, std::max(along.dot(p), along.dot(q))) -
                     std::max(lo, std::min(along.dot(p), along.dot(q)));
    reach.shared += std::max(0.0, o);
    reach.reaches = reach.reaches || o > 0.0 || -o <= options_.plane_gap;
  }
  return reach;
}

bool GraphMatcher::planeAgrees(const MatchPlane& plane, int surface, const Placement& placed,
                               double angle_deg, double distance) const {
  const auto& s = graph_->surfaces[surface];
  const double yaw = plane.normalYaw() + placed.yaw();
  if (std::abs(common::wrapAngle(yaw - surface_yaw_[surface])) > common::radians(angle_deg)) {
    return false;
  }
  const Eigen::Vector2d middle = placed(0.5 * (plane.start + plane.end));
  return std::abs(s.plane.signedDistance({middle.x(), middle.y(), 0.0})) <= distance;
}

Verification GraphMatcher::verify(const MatchInput& input, const Eigen::Vector3d& x_y_yaw) const {
  return verify(input, x_y_yaw, true);
}

Verification GraphMatcher::verify(const MatchInput& input, const Eigen::Vector3d& x_y_yaw,
                                  bool built_off) const {
  Verification v;
  v.x_y_yaw = x_y_yaw;
  const Placement placed(x_y_yaw);
  std::vector<int> room_match(input.rooms.size(), -1);
  std::map<int, double> a_rooms;  // matched A-rooms and their best fit weight
  auto fit = [](double error, double sigma) {
    return std::exp(-0.5 * (error / sigma) * (error / sigma));
  };
  double shared_total = 0.0, squared = 0.0;
  for (const MatchPlane& plane : input.planes) {
    if (plane.length() < options_.min_plane_length) continue;
    double overlap = 0.0, distance = 0.0;
    const int s = matchPlane(plane, placed, &overlap, &distance);
    if (s < 0) {
      v.unexplained_length += plane.length();
      if (built_off && nearAsBuiltOff(plane, placed)) v.built_off_length += plane.length();
      continue;
    }
    v.planes.emplace_back(plane.id, s);
    v.explained_length += plane.length();
    shared_total += std::min(overlap, plane.length()) * fit(distance, options_.plane_sigma);
    squared += distance * distance;
  }
  for (std::size_t i = 0; i < input.rooms.size(); ++i) {
    const MatchRoom& room = input.rooms[i];
    double distance = 0.0;
    room_match[i] = matchRoom(room, placed, &distance);
    if (room_match[i] >= 0) {
      v.rooms.emplace_back(room.id, room_match[i]);
      double& weight = a_rooms[room_match[i]];
      weight = std::max(weight, fit(distance, options_.room_sigma));
      continue;
    }
    if (!room.four_wall) continue;
    // An unmatched four-wall room standing inside a four-wall room of the plan that it does not
    // fit is evidence against this transform — unless each of its walls lies on a plan surface:
    // then it is the plan's walls around a space the building has and the plan divides (as
    // built, a wall is missing), not a contradiction.
    const bool walls_explained =
        !room.planes.empty() && std::all_of(room.planes.begin(), room.planes.end(), [&](int p) {
          return std::any_of(v.planes.begin(), v.planes.end(),
                             [&](const auto& m) { return m.first == p; });
        });
    if (walls_explained) continue;
    const Eigen::Vector2d centre = placed(room.centre);
    if (const Cell* cell = cellAt(centre)) {
      for (int r : cell->rooms) {
        const auto& a = graph_->rooms[r];
        if (a.kind == bim::RoomKind::kFourWall && pointInPolygon(a.outline, centre)) {
          ++v.rooms_contradicted;
          v.contradicted.push_back(room.id);
          break;
        }
      }
    }
  }
  if (!v.planes.empty()) v.plane_rms = std::sqrt(squared / double(v.planes.size()));
  v.transition_doors.assign(input.transitions.size(), 0);
  for (std::size_t t = 0; t < input.transitions.size(); ++t) {
    const int a = room_match[input.transitions[t].first];
    const int b = room_match[input.transitions[t].second];
    if (a < 0 || b < 0 || a == b) continue;
    if (joinedByDoor(a, b)) {
      ++v.doors_passed;
      v.transition_doors[t] = 1;
    } else {
      ++v.doors_missing;
      v.transition_doors[t] = -1;
    }
  }
  double rooms_total = 0.0;
  for (const auto& [a, weight] : a_rooms) rooms_total += weight;
  v.score = shared_total - options_.unexplained_penalty * v.unexplained_length +
            options_.room_score * rooms_total +
            options_.door_score * double(v.doors_passed - v.doors_missing) -
            options_.room_score * double(v.rooms_contradicted);
  return v;
}

Eigen::Vector3d GraphMatcher::refine(const MatchInput& input,
                                     const Verification& verification) const {
  std::vector<const MatchPlane*> planes_by_id;
  for (const auto& p : input.planes) {
    if (p.id >= int(planes_by_id.size())) planes_by_id.resize(p.id + 1, nullptr);
    planes_by_id[p.id] = &p;
  }
  std::vector<const MatchRoom*> rooms_by_id;
  for (const auto& r : input.rooms) {
    if (r.id >= int(rooms_by_id.size())) rooms_by_id.resize(r.id + 1, nullptr);
    rooms_by_id[r.id] = &r;
  }
  // Gauss-Newton on (x, y, yaw): point-to-plane distances of each matched S-plane's two ends to
  // its surface, and four-wall room centres. Residuals beyond 0.3 m are left out (outliers).
  Eigen::Vector3d x = verification.x_y_yaw;
  for (int iteration = 0; iteration < 5; ++iteration) {
    Eigen::Matrix3d H = Eigen::Matrix3d::Zero();
    Eigen::Vector3d g = Eigen::Vector3d::Zero();
    const Eigen::Matrix2d R = rotation(x.z());
    auto add = [&](double r, const Eigen::Vector3d& J) {
      if (std::abs(r) > 0.3) return;
      H += J * J.transpose();
      g += J * r;
    };
    for (const auto& [s, a] : verification.planes) {
      const MatchPlane& p = *planes_by_id[s];
      const Eigen::Vector2d n = graph_->surfaces[a].plane.normal.head<2>();
      const double d = graph_->surfaces[a].plane.d;
      for (const Eigen::Vector2d& point : {p.start, p.end}) {
        const Eigen::Vector2d q = R * point + x.head<2>();
        const Eigen::Vector2d dq_dyaw = R * Eigen::Vector2d(-point.y(), point.x());
        add(n.dot(q) + d, Eigen::Vector3d(n.x(), n.y(), n.dot(dq_dyaw)));
      }
    }
    for (const auto& [s, a] : verification.rooms) {
      const MatchRoom& room = *rooms_by_id[s];
      if (!room.four_wall) continue;
      const Eigen::Vector2d q = R * room.centre + x.head<2>();
      const Eigen::Vector2d dq_dyaw = R * Eigen::Vector2d(-room.centre.y(), room.centre.x());
      const Eigen::Vector2d r = q - graph_->rooms[a].centre;
      add(r.x(), Eigen::Vector3d(1.0, 0.0, dq_dyaw.x()));
      add(r.y(), Eigen::Vector3d(0.0, 1.0, dq_dyaw.y()));
    }
    if (std::abs(H.determinant()) < 1e-9) break;
    const Eigen::Vector3d step = -H.ldlt().solve(g);
    x += step;
    if (step.norm() < 1e-6) break;
  }
  x.z() = common::wrapAngle(x.z());
  return x;
}

Eigen::Vector2d GraphMatcher::middleOf(const MatchInput& input) {
  Eigen::Vector2d middle = Eigen::Vector2d::Zero();
  for (const auto& r : input.rooms) middle += r.centre / double(input.rooms.size());
  if (!input.rooms.empty()) return middle;
  // No room yet: the middle of the walls.
  for (const auto& p : input.planes)
    middle += 0.5 * (p.start + p.end) / double(input.planes.size());
  return middle;
}

bool GraphMatcher::sameAnswer(const Eigen::Vector3d& a, const Eigen::Vector3d& b,
                              const Eigen::Vector2d& middle, double scale) const {
  return (apply(a, middle) - apply(b, middle)).norm() < scale * options_.cluster_distance &&
         std::abs(common::wrapAngle(a.z() - b.z())) <
             common::radians(scale * options_.cluster_yaw_deg);
}

MatchResult GraphMatcher::match(const MatchInput& input, ThreadPool* pool) const {
  const auto start = std::chrono::steady_clock::now();
  // 1. Hypotheses from four-wall rooms, corridors and corners of long walls: corners propose the
  // right answer in a building of halls, and the one that a room missing from the plan (as built,
  // a wall is missing) hides from the room seeds, so that it is always among the answers compared.
  std::vector<Eigen::Vector3d> hypotheses;
  seedFromFourWallRooms(input, hypotheses);
  seedFromCorridors(input, hypotheses);
  seedFromCorners(input, hypotheses);
  MatchResult result = evaluate(input, hypotheses, pool);
  if (result.hypotheses == 0) {
    result.reason = input.rooms.empty() && input.planes.empty()
                        ? "no room in the S-Graph yet"
                        : "no S-Graph room or corner fits the plan in kind and size";
  }
  result.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return result;
}

MatchResult GraphMatcher::evaluate(const MatchInput& input,
                                   const std::vector<Eigen::Vector3d>& hypotheses,
                                   ThreadPool* pool) const {
  MatchResult result;
  result.hypotheses = int(hypotheses.size());
  if (hypotheses.empty()) return result;
  // 2. Each checked against the whole S-Graph.
  // Items of 64 hypotheses, on the pool's threads when given: each verification is its own.
  std::vector<Verification> verified(hypotheses.size());
  constexpr int kItem = 64;
  const int n = int(hypotheses.size());
  const auto verify_item = [&](int item) {
    for (int i = item * kItem; i < std::min(n, (item + 1) * kItem); ++i) {
      verified[std::size_t(i)] = verify(input, hypotheses[std::size_t(i)], false);
    }
  };
  if (pool != nullptr && pool->threads() > 1) {
    pool->run(itemCount(n, kItem), verify_item);
  } else {
    for (int item = 0; item < itemCount(n, kItem); ++item) verify_item(item);
  }
  std::sort(verified.begin(), verified.end(),
            [](const Verification& a, const Verification& b) { return a.score > b.score; });
  // 3. Clusters: the same answer proposed by several seeds. Two transforms are the same answer
  // when they put the S-Graph in the same place (sameAnswer; its images computed once each).
  const Eigen::Vector2d middle = middleOf(input);
  const double yaw_tolerance = common::radians(options_.cluster_yaw_deg);
  std::vector<const Verification*> representatives;
  std::vector<Eigen::Vector2d> placed;  // where each representative puts the middle
  // The representatives by the cluster_distance cell their image falls in: a hypothesis can only
  // join one in its own cell or the eight around it. Without this, clustering was quadratic in the
  // hypotheses, which grow with the building.
  std::unordered_map<std::uint64_t, std::vector<int>> by_cell;
  const auto cell_of = [&](const Eigen::Vector2d& p) {
    return Eigen::Vector2i(int(std::floor(p.x() / options_.cluster_distance)),
                           int(std::floor(p.y() / options_.cluster_distance)));
  };
  const auto key_of = [](const Eigen::Vector2i& c) {
    return (std::uint64_t(std::uint32_t(c.x())) << 32) | std::uint32_t(c.y());
  };
  for (const auto& v : verified) {
    const Eigen::Vector2d image = apply(v.x_y_yaw, middle);
    const Eigen::Vector2i cell = cell_of(image);
    bool joined = false;
    for (int dx = -1; dx <= 1 && !joined; ++dx) {
      for (int dy = -1; dy <= 1 && !joined; ++dy) {
        const auto it = by_cell.find(key_of(cell + Eigen::Vector2i(dx, dy)));
        if (it == by_cell.end()) continue;
        for (int r : it->second) {
          joined = (image - placed[r]).norm() < options_.cluster_distance &&
                   std::abs(common::wrapAngle(v.x_y_yaw.z() - representatives[r]->x_y_yaw.z())) <
                       yaw_tolerance;
          if (joined) break;
        }
      }
    }
    if (joined) continue;
    by_cell[key_of(cell)].push_back(int(representatives.size()));
    representatives.push_back(&v);
    placed.push_back(image);
  }
  result.clusters = int(representatives.size());
  // 4. The best few answers, each refined over its correspondences and checked again, so that
  // they are compared at their best.
  std::vector<Verification> finalists;
  for (std::size_t i = 0; i < representatives.size() && int(i) < options_.finalists; ++i) {
    Verification refined = verify(input, refine(input, *representatives[i]));
    finalists.push_back(consensus(input, refined.score >= representatives[i]->score
                                             ? refined
                                             : verify(input, representatives[i]->x_y_yaw)));
  }
  std::sort(finalists.begin(), finalists.end(),
            [](const Verification& a, const Verification& b) { return a.score > b.score; });
  result.best = finalists[0];
  // Refinement may bring two clusters to the same answer: the others must be distinct. If all
  // finalists came together, the next cluster is the other answer.
  for (std::size_t i = 1; i < finalists.size(); ++i) {
    if (sameAnswer(finalists[i].x_y_yaw, result.best.x_y_yaw, middle)) continue;
    result.candidates.push_back({finalists[i], {}});
  }
  if (result.candidates.empty() && representatives.size() > finalists.size()) {
    result.candidates.push_back({verify(input, representatives[finalists.size()]->x_y_yaw), {}});
  }
  decide(input, result);
  return result;
}

}  // namespace isg::slam
