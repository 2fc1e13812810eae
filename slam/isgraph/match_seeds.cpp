// The seeds of graph matching (docs/matching.md): which B_T_M the local structures of the
// S-Graph propose. Four-wall rooms fix the whole transform up to their symmetry; a corridor fixes
// it up to a slide along its axis, which a wall across it settles; a corner of two long walls
// fixes it once, which is how halls and L-shaped rooms, which no room detector reports, seed.
#include <algorithm>
#include <cmath>
#include <numbers>
#include <set>

#include "common/angles.hpp"
#include "slam/isgraph/graph_matching.hpp"
#include "slam/isgraph/slide_support.hpp"

namespace isg::slam {

namespace {

Eigen::Vector2d normal2(const bim::Plane& plane) { return plane.normal.head<2>().normalized(); }

Eigen::Matrix2d yawRotation(double yaw) { return Eigen::Rotation2Dd(yaw).toRotationMatrix(); }

// Collects transforms, skipping one equal (within 2 cm and 0.2°, on a grid of those) to one already
// there: the same room pair or corner pair seen through two of its walls proposes it twice.
class UniqueTransforms {
 public:
  explicit UniqueTransforms(std::vector<Eigen::Vector3d>& out) : out_(out) {}
  // Whether `h` was new (and so added).
  bool add(const Eigen::Vector3d& h) {
    const std::array<long, 3> key{std::lround(h.x() / 0.02), std::lround(h.y() / 0.02),
                                  std::lround(common::wrapAngle(h.z()) / common::radians(0.2))};
    if (!seen_.insert(key).second) return false;
    out_.push_back(h);
    return true;
  }

 private:
  std::vector<Eigen::Vector3d>& out_;
  std::set<std::array<long, 3>> seen_;
};

}  // namespace

std::optional<GraphMatcher::Corner> GraphMatcher::cornerOf(
    const bim::Plane& p, Eigen::Vector2d p_start, Eigen::Vector2d p_end, const bim::Plane& q,
    Eigen::Vector2d q_start, Eigen::Vector2d q_end, double gap, double min_sine) {
  const Eigen::Vector2d np = normal2(p), nq = normal2(q);
  const double det = np.x() * nq.y() - np.y() * nq.x();
  if (std::abs(det) < min_sine) return std::nullopt;
  Eigen::Matrix2d A;
  A << np.x(), np.y(), nq.x(), nq.y();
  const double dp = p.d / p.normal.head<2>().norm(), dq = q.d / q.normal.head<2>().norm();
  const Eigen::Vector2d point = A.inverse() * Eigen::Vector2d(-dp, -dq);
  Corner corner;
  corner.point = point;
  const std::array<std::pair<Eigen::Vector2d, Eigen::Vector2d>, 2> arms{std::pair{p_start, p_end},
                                                                        std::pair{q_start, q_end}};
  const std::array<Eigen::Vector2d, 2> normals{np, nq};
  for (int k = 0; k < 2; ++k) {
    const auto& [a, b] = arms[k];
    const bool a_near = (a - point).norm() <= (b - point).norm();
    const Eigen::Vector2d near = a_near ? a : b, far = a_near ? b : a;
    if ((near - point).norm() > gap) return std::nullopt;
    const Eigen::Vector2d along = far - point;
    if (along.norm() < 1e-6) return std::nullopt;
    corner.arm_direction[k] = along.normalized();
    corner.arm[k] = along.norm();
    corner.normal_yaw[k] = common::headingOf(normals[k]);
  }
  return corner;
}

void GraphMatcher::seedFromFourWallRooms(const MatchInput& input,
                                         std::vector<Eigen::Vector3d>& out) const {
  // Every compatible (S four-wall room, A four-wall room) pair: 2 yaws for a rectangle, 4 for a
  // square, the translation from the centres.
  for (const MatchRoom& s : input.rooms) {
    if (!s.four_wall) continue;
    for (int i = 0; i < int(graph_->rooms.size()); ++i) {
      const auto& a = graph_->rooms[i];
      if (a.kind != bim::RoomKind::kFourWall) continue;
      for (int k = 0; k < 4; ++k) {
        const bool swapped = k % 2 == 1;
        const double w0 = swapped ? a.widths[1] : a.widths[0];
        const double w1 = swapped ? a.widths[0] : a.widths[1];
        if (std::abs(w0 - s.widths[0]) > options_.width_tolerance ||
            std::abs(w1 - s.widths[1]) > options_.width_tolerance) {
          continue;
        }
        const double yaw = common::wrapAngle(room_yaw_[i] + k * std::numbers::pi / 2 - s.axis_yaw);
        const Eigen::Vector2d t = a.centre - yawRotation(yaw) * s.centre;
        out.emplace_back(t.x(), t.y(), yaw);
      }
    }
  }
}

void GraphMatcher::seedFromCorridors(const MatchInput& input,
                                     std::vector<Eigen::Vector3d>& out) const {
  // An S-corridor on an A-corridor of its width: yaw (two ways round) and the offset across are
  // fixed; along the axis, each S-plane across the corridor (its normal along the axis) put on an
  // A-surface facing the same way that spans the same band across the axis gives one slide.
  const double angle = common::radians(options_.plane_angle_deg);
  for (const MatchRoom& s : input.rooms) {
    if (s.four_wall) continue;
    for (int i = 0; i < int(graph_->rooms.size()); ++i) {
      const auto& a = graph_->rooms[i];
      if (a.kind != bim::RoomKind::kTwoWall) continue;
      if (std::abs(a.widths[0] - s.widths[0]) > options_.width_tolerance) continue;
      const Eigen::Vector2d a_normal = normal2(graph_->surfaces[a.pairs[0][0]].plane);
      const Eigen::Vector2d a_along(-a_normal.y(), a_normal.x());
      std::vector<Eigen::Vector3d> group;  // this pair's slides, each once, in the order found
      std::vector<std::pair<int, double>> slides;  // their turn and slide
      std::vector<SlideProposal> proposals;        // every (S-plane, A-surface) pair's
      UniqueTransforms unique(group);
      for (int turn = 0; turn < 2; ++turn) {
        const double yaw = common::wrapAngle(room_yaw_[i] + turn * std::numbers::pi - s.axis_yaw);
        const Eigen::Matrix2d R = yawRotation(yaw);
        // Across the axis: the S-centre on the A-centre's line.
        const Eigen::Vector2d centre = R * s.centre;
        const double across = a_normal.dot(a.centre - centre);
        for (const MatchPlane& plane : input.planes) {
          if (plane.length() < options_.min_plane_length) continue;
          const Eigen::Vector2d n = R * normal2(plane.plane);
          if (std::abs(std::abs(n.dot(a_along)) - 1.0) > 1.0 - std::cos(angle)) continue;
          const Eigen::Vector2d p0 = R * plane.start + across * a_normal;
          const Eigen::Vector2d p1 = R * plane.end + across * a_normal;
          // The S-plane's band across the axis, relative to the A-corridor's centre line.
          const double lo = std::min(a_normal.dot(p0 - a.centre), a_normal.dot(p1 - a.centre));
          const double hi = std::max(a_normal.dot(p0 - a.centre), a_normal.dot(p1 - a.centre));
          const double s_along = a_along.dot(0.5 * (p0 + p1));
          const double yaw_n = common::headingOf(n);
          for (int k = 0; k < int(graph_->surfaces.size()); ++k) {
            if (std::abs(common::wrapAngle(yaw_n - surface_yaw_[k])) > angle) continue;
            const auto& surface = graph_->surfaces[k];
            bool spans = false;
            for (const auto& [u, v] : surface.segments) {
              const double ulo = std::min(a_normal.dot(u - a.centre), a_normal.dot(v - a.centre));
              const double uhi = std::max(a_normal.dot(u - a.centre), a_normal.dot(v - a.centre));
              spans = spans || (std::min(hi, uhi) - std::max(lo, ulo) > -options_.plane_gap);
            }
            if (!spans) continue;
            const double a_along_at = a_along.dot(surface.segments.front().first);
            const double slide = a_along_at - s_along;
            const Eigen::Vector2d t = across * a_normal + slide * a_along;
            proposals.push_back({turn, slide, plane.length()});
            if (unique.add(Eigen::Vector3d(t.x(), t.y(), yaw))) slides.emplace_back(turn, slide);
          }
        }
      }
      keepBestSupported(group, slides, std::move(proposals),
                        std::size_t(std::max(0, options_.max_corridor_slides)),
                        options_.cluster_distance);
      out.insert(out.end(), group.begin(), group.end());
    }
  }
}

void GraphMatcher::seedFromCorners(const MatchInput& input,
                                   std::vector<Eigen::Vector3d>& out) const {
  // The S-Graph's corners of two long walls, longest arms first. A corner of a four-wall S-room
  // proposes nothing its room did not: only corners whose walls are not both of one such room.
  std::set<std::pair<int, int>> room_corners;
  for (const MatchRoom& room : input.rooms) {
    if (!room.four_wall) continue;
    for (int a : room.planes) {
      for (int b : room.planes) room_corners.insert({a, b});
    }
  }
  std::vector<Corner> s_corners;
  for (std::size_t i = 0; i < input.planes.size(); ++i) {
    const MatchPlane& p = input.planes[i];
    if (p.length() < options_.min_corner_arm) continue;
    for (std::size_t j = i + 1; j < input.planes.size(); ++j) {
      const MatchPlane& q = input.planes[j];
      if (q.length() < options_.min_corner_arm || room_corners.count({p.id, q.id})) continue;
      const auto corner = cornerOf(p.plane, p.start, p.end, q.plane, q.start, q.end,
                                   options_.corner_gap, options_.minCornerSine());
      if (corner && std::min(corner->arm[0], corner->arm[1]) >= options_.min_corner_arm) {
        s_corners.push_back(*corner);
      }
    }
  }
  std::sort(s_corners.begin(), s_corners.end(), [](const Corner& a, const Corner& b) {
    return std::min(a.arm[0], a.arm[1]) > std::min(b.arm[0], b.arm[1]);
  });
  if (int(s_corners.size()) > options_.max_corners) s_corners.resize(options_.max_corners);
  // A cheap screen before the full verification: the longest S-planes must mostly be explained.
  std::vector<const MatchPlane*> screen;
  for (const auto& p : input.planes) {
    if (p.length() >= options_.min_plane_length) screen.push_back(&p);
  }
  std::sort(screen.begin(), screen.end(),
            [](const MatchPlane* a, const MatchPlane* b) { return a->length() > b->length(); });
  if (screen.size() > 6) screen.resize(6);
  double screen_length = 0.0;
  for (const auto* p : screen) screen_length += p->length();
  const double angle = common::radians(options_.plane_angle_deg);
  UniqueTransforms unique(out);
  for (const Corner& s : s_corners) {
    for (const Corner& a : corners_) {
      for (int order = 0; order < 2; ++order) {
        // S's first wall on A's wall `order`, the second on the other.
        const int k0 = order, k1 = 1 - order;
        const double yaw = common::wrapAngle(a.normal_yaw[k0] - s.normal_yaw[0]);
        if (std::abs(common::wrapAngle(s.normal_yaw[1] + yaw - a.normal_yaw[k1])) > angle) continue;
        const Eigen::Matrix2d R = yawRotation(yaw);
        if ((R * s.arm_direction[0]).dot(a.arm_direction[k0]) < 0.9 ||
            (R * s.arm_direction[1]).dot(a.arm_direction[k1]) < 0.9) {
          continue;
        }
        // The S-Graph sees no more wall than the plan has along the arm.
        if (s.arm[0] > a.arm[k0] + options_.plane_gap ||
            s.arm[1] > a.arm[k1] + options_.plane_gap) {
          continue;
        }
        const Eigen::Vector2d t = a.point - R * s.point;
        const Eigen::Vector3d h(t.x(), t.y(), yaw);
        double unexplained = 0.0;
        const Placement placed(h);
        for (const MatchPlane* p : screen) {
          double overlap = 0.0, distance = 0.0;
          if (matchPlane(*p, placed, &overlap, &distance) < 0) unexplained += p->length();
          if (unexplained > 0.5 * screen_length) break;
        }
        if (unexplained > 0.5 * screen_length) continue;
        unique.add(h);
      }
    }
  }
}

}  // namespace isg::slam
