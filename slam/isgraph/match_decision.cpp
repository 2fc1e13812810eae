// The decision of graph matching (docs/matching.md): an answer is accepted when it explains the
// S-Graph well on its own and when, against every other answer, the evidence on which the two
// disagree favours it decisively. Totals are not compared: the more of a symmetric building the
// robot has seen, the more evidence both answers share, and a ratio of totals would then refuse
// however decisive the part where they differ.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numbers>
#include <set>

#include "bim/polygon.hpp"
#include "common/angles.hpp"
#include "common/plural.hpp"
#include "slam/isgraph/graph_matching.hpp"

namespace isg::slam {

namespace {

Eigen::Vector2d applyPlanar(const Eigen::Vector3d& x_y_yaw, const Eigen::Vector2d& p) {
  return Eigen::Rotation2Dd(x_y_yaw.z()) * p + x_y_yaw.head<2>();
}

// a ∘ b⁻¹ for planar transforms (x, y, yaw).
Eigen::Vector3d relative(const Eigen::Vector3d& a, const Eigen::Vector3d& b) {
  const double yaw = common::wrapAngle(a.z() - b.z());
  const Eigen::Vector2d t = a.head<2>() - Eigen::Rotation2Dd(yaw) * b.head<2>();
  return {t.x(), t.y(), yaw};
}

double polygonArea(const std::vector<Eigen::Vector2d>& outline) {
  return std::abs(bim::signedArea(outline));
}

}  // namespace

std::string Distinction::describe() const {
  char text[256];
  std::snprintf(text, sizeof text,
                "%.1f m of evidence (walls %.1f m for, %.1f m against; rooms %d for, %d against; "
                "doorways %d for, %d against; %.1f m of disagreement)",
                evidence, walls_for, walls_against, rooms_for, rooms_against, doors_for,
                doors_against, disagreement);
  return text;
}

Distinction GraphMatcher::distinguish(const MatchInput& input, const Verification& best,
                                      const Verification& other,
                                      const GraphMatcher* other_matcher) const {
  const GraphMatcher& under_other = other_matcher != nullptr ? *other_matcher : *this;
  // The score is a sum over the S-Graph's elements, so the evidence both answers share cancels
  // and what is left is the part on which they disagree: each wall, room and walked doorway
  // scored under both answers as verify() scores it, and the differences summed. Elements whose
  // scores differ by less than 5 % of a wall's length agree.
  Distinction d;
  auto fit = [](double error, double sigma) {
    return std::exp(-0.5 * (error / sigma) * (error / sigma));
  };
  const Placement best_placed(best.x_y_yaw), other_placed(other.x_y_yaw);
  auto wall_score = [&](const MatchPlane& plane, const Placement& placed,
                        const GraphMatcher& matcher) {
    double overlap = 0.0, distance = 0.0;
    if (matcher.matchPlane(plane, placed, &overlap, &distance) < 0) {
      return -options_.unexplained_penalty * plane.length();
    }
    return std::min(overlap, plane.length()) * fit(distance, options_.plane_sigma);
  };
  double evidence = 0.0;
  for (const MatchPlane& plane : input.planes) {
    if (plane.length() < options_.min_plane_length) continue;
    const double delta =
        wall_score(plane, best_placed, *this) - wall_score(plane, other_placed, under_other);
    evidence += delta;
    d.disagreement += std::abs(delta);
    if (delta > 0.05 * plane.length()) d.walls_for += delta;
    if (delta < -0.05 * plane.length()) d.walls_against -= delta;
  }
  const std::set<int> best_contradicted(best.contradicted.begin(), best.contradicted.end());
  const std::set<int> other_contradicted(other.contradicted.begin(), other.contradicted.end());
  auto room_score = [&](const MatchRoom& room, const Placement& placed,
                        const std::set<int>& contradicted, const GraphMatcher& matcher) {
    double distance = 0.0;
    if (matcher.matchRoom(room, placed, &distance) >= 0) return fit(distance, options_.room_sigma);
    return contradicted.count(room.id) ? -1.0 : 0.0;
  };
  for (const MatchRoom& room : input.rooms) {
    const double delta =
        options_.room_score * (room_score(room, best_placed, best_contradicted, *this) -
                               room_score(room, other_placed, other_contradicted, under_other));
    evidence += delta;
    if (delta > 0.5 * options_.room_score) ++d.rooms_for;
    if (delta < -0.5 * options_.room_score) ++d.rooms_against;
  }
  for (std::size_t t = 0; t < input.transitions.size(); ++t) {
    const int b = t < best.transition_doors.size() ? best.transition_doors[t] : 0;
    const int o = t < other.transition_doors.size() ? other.transition_doors[t] : 0;
    evidence += options_.door_score * double(b - o);
    d.disagreement += options_.door_score * std::abs(double(b - o));
    if (b > o) ++d.doors_for;
    if (b < o) ++d.doors_against;
  }
  d.evidence = evidence;
  return d;
}

bool GraphMatcher::decisive(const Distinction& d, double* needed) const {
  const double need = std::max(options_.min_decisive_evidence,
                               options_.decisive_sigmas * std::sqrt(d.disagreement));
  if (needed != nullptr) *needed = need;
  return d.evidence >= need;
}

std::vector<std::string> GraphMatcher::separatingRooms(const Eigen::Vector3d& best,
                                                       const Eigen::Vector3d& other) const {
  // If the best answer is right, the robot standing in plan room r is, for the other answer, in
  // T(r) with T = other ∘ best⁻¹; if nothing alike is there, a visit to r tells them apart. And
  // the other way round for T⁻¹.
  std::vector<std::string> out;
  const std::array<Eigen::Vector3d, 2> turns{relative(other, best), relative(best, other)};
  for (int i = 0; i < int(graph_->rooms.size()); ++i) {
    const auto& a = graph_->rooms[i];
    if (a.outline.empty()) continue;
    bool separates = false;
    for (const Eigen::Vector3d& T : turns) {
      if (a.kind == bim::RoomKind::kPolygon) {
        // No room factor: alike is a polygon room of the same area and corners at the image of
        // its centroid.
        const Eigen::Vector2d image = applyPlanar(T, a.centre);
        const double area = polygonArea(a.outline);
        bool alike = false;
        for (const auto& b : graph_->rooms) {
          alike =
              alike || (b.kind == bim::RoomKind::kPolygon && b.outline.size() == a.outline.size() &&
                        (b.centre - image).norm() < options_.centre_tolerance &&
                        std::abs(polygonArea(b.outline) - area) < 0.1 * area);
        }
        separates = separates || !alike;
        continue;
      }
      MatchRoom as_seen;
      as_seen.four_wall = a.kind == bim::RoomKind::kFourWall;
      as_seen.centre = a.centre;
      as_seen.axis_yaw = room_yaw_[i];
      for (std::size_t k = 0; k < 2 && k < a.widths.size(); ++k) as_seen.widths[k] = a.widths[k];
      double distance = 0.0;
      separates = separates || matchRoom(as_seen, T, &distance) < 0;
    }
    if (separates) out.push_back(a.id);
  }
  return out;
}

namespace {

// How much of the best answer's own evidence there is: the plan rooms it matches, its planes
// outside them, whether its surfaces' normals span two directions.
struct Support {
  std::set<int> a_rooms;
  int planes_outside = 0;
  bool supported = false;
};

Support supportOf(const MatchInput& input, const Verification& best, const bim::AGraph& graph,
                  const MatchingOptions& options) {
  Support s;
  for (const auto& [sr, a] : best.rooms) s.a_rooms.insert(a);
  std::set<int> own_planes;
  for (const auto& r : input.rooms) {
    for (const auto& [sr, a] : best.rooms) {
      if (sr == r.id) own_planes.insert(r.planes.begin(), r.planes.end());
    }
  }
  std::vector<Eigen::Vector2d> normals;
  for (const auto& [sp, a] : best.planes) {
    s.planes_outside += own_planes.count(sp) ? 0 : 1;
    normals.push_back(graph.surfaces[a].plane.normal.head<2>().normalized());
  }
  bool two_directions = false;
  const double spread = std::sin(30.0 * std::numbers::pi / 180.0);
  for (std::size_t i = 0; i < normals.size() && !two_directions; ++i) {
    for (std::size_t j = i + 1; j < normals.size() && !two_directions; ++j) {
      two_directions =
          std::abs(normals[i].x() * normals[j].y() - normals[i].y() * normals[j].x()) >= spread;
    }
  }
  s.supported = int(s.a_rooms.size()) >= options.min_rooms ||
                (s.a_rooms.size() == 1 && s.planes_outside >= options.min_planes_outside) ||
                (int(best.planes.size()) >= options.min_planes_without_rooms && two_directions);
  return s;
}

// The S-rooms explained: matched to an A-room, or each of their walls on an A-surface (a room the
// plan draws as two, as built a wall missing, is still explained).
int roomsExplained(const MatchInput& input, const Verification& best) {
  std::set<int> explained_planes, matched_rooms;
  for (const auto& [s, a] : best.planes) explained_planes.insert(s);
  for (const auto& [s, a] : best.rooms) matched_rooms.insert(s);
  int rooms_explained = 0;
  for (const MatchRoom& room : input.rooms) {
    const bool walls =
        !room.planes.empty() && std::all_of(room.planes.begin(), room.planes.end(),
                                            [&](int p) { return explained_planes.count(p) > 0; });
    rooms_explained += matched_rooms.count(room.id) || walls ? 1 : 0;
  }
  return rooms_explained;
}

}  // namespace

std::string GraphMatcher::evidenceText(const MatchInput& input, const MatchResult& result,
                                       const std::set<int>& a_rooms, int planes_outside,
                                       int rooms_explained) const {
  const Verification& best = result.best;
  auto plural = [](std::size_t n) { return n == 1 ? "" : "s"; };
  char text[384];
  std::snprintf(text, sizeof text,
                "best: %zu room%s (%d of %zu explained), %zu plane%s (%d outside its rooms), %d "
                "door%s, %.1f of "
                "%.1f m of wall explained (%.1f m more as if built off), score %.1f; second "
                "answer %.1f",
                a_rooms.size(), plural(a_rooms.size()), rooms_explained, input.rooms.size(),
                best.planes.size(), plural(best.planes.size()), planes_outside, best.doors_passed,
                plural(std::size_t(best.doors_passed)), best.explained_length,
                best.explained_length + best.unexplained_length, best.built_off_length, best.score,
                result.second_score);
  return text;
}

void GraphMatcher::decide(const MatchInput& input, MatchResult& result) const {
  const Verification& best = result.best;
  // What separates each other answer from the best; the least decisively separated first.
  for (Candidate& c : result.candidates) c.from_best = distinguish(input, best, c.answer);
  auto margin = [&](const Distinction& d) {
    double needed = 0.0;
    decisive(d, &needed);
    return d.evidence - needed;
  };
  std::sort(result.candidates.begin(), result.candidates.end(),
            [&](const Candidate& a, const Candidate& b) {
              return margin(a.from_best) < margin(b.from_best);
            });
  if (!result.candidates.empty()) {
    result.second = result.candidates.front().answer;
    result.second_score = result.second.score;
  }
  const Support support = supportOf(input, best, *graph_, options_);
  const int rooms_explained = roomsExplained(input, best);
  const double room_share =
      input.rooms.empty() ? 1.0 : double(rooms_explained) / double(input.rooms.size());
  const std::string text =
      evidenceText(input, result, support.a_rooms, support.planes_outside, rooms_explained);
  std::string evidence;
  if (!result.candidates.empty()) {
    double needed = 0.0;
    const Distinction& closest = result.candidates.front().from_best;
    decisive(closest, &needed);
    char need[64];
    std::snprintf(need, sizeof need, ", %.1f m needed", needed);
    evidence = ", leads it by " + closest.describe() + need;
  }
  if (!support.supported || best.score <= 0.0) {
    result.status = MatchStatus::kNotYet;
    result.reason = "too little evidence: " + text;
  } else if (best.unexplainedShare() > options_.max_unexplained_share) {
    result.status = MatchStatus::kNotYet;
    result.reason = "the plan leaves too much of the mapped wall unexplained: " + text;
  } else if (room_share < options_.min_room_share) {
    result.status = MatchStatus::kNotYet;
    result.reason = "the plan leaves too many of the mapped rooms unexplained: " + text;
  } else if (!result.candidates.empty() && !decisive(result.candidates.front().from_best)) {
    result.status = MatchStatus::kAmbiguous;
    // Where to look: the plan rooms that would separate the answers not yet separated.
    // In the plan's order, the first ten named: on a floor of a thousand alike offices every
    // room may separate them, and the reason is a line a person reads.
    std::set<std::string> named;
    for (Candidate& c : result.candidates) {
      if (decisive(c.from_best)) continue;
      c.from_best.separating_rooms = separatingRooms(best.x_y_yaw, c.answer.x_y_yaw);
      named.insert(c.from_best.separating_rooms.begin(), c.from_best.separating_rooms.end());
    }
    std::vector<std::string> where;
    for (const auto& room : graph_->rooms) {
      if (named.count(room.id)) where.push_back(room.id);
    }
    const std::string look = common::namedList(where);
    result.reason = "two answers explain the map alike: " + text + evidence +
                    (look.empty() ? "; nothing in the plan separates them"
                                  : "; seeing " + look + " would separate them");
  } else {
    result.status = MatchStatus::kMatched;
    result.reason = text + evidence;
  }
}

}  // namespace isg::slam
