#pragma once

// Synthetic S-Graphs for matching tests and benchmarks: the part of a plan's A-Graph a robot
// would have mapped after walking through some rooms, expressed in a map frame M placed anywhere
// in the plan, with measurement noise.

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <numbers>
#include <random>
#include <set>
#include <vector>

#include "bim/agraph.hpp"
#include "slam/isgraph/graph_matching.hpp"

namespace isg::testing {

struct CutSGraph {
  slam::MatchInput input;
  std::vector<int> a_room_of_s_room;  // truth: the A-room of each input room
  std::vector<int> a_surface_of_s_plane;
};

inline Eigen::Vector3d randomPlanarTransform(std::mt19937_64& rng, double extent = 50.0) {
  std::uniform_real_distribution<double> position(-extent, extent),
      yaw(-std::numbers::pi, std::numbers::pi);
  return {position(rng), position(rng), yaw(rng)};
}

// A walk of up to `count` rooms through the plan's doorways from `start`, in visiting order.
inline std::vector<int> walkRooms(const bim::AGraph& graph, int start, int count,
                                  std::mt19937_64& rng) {
  std::vector<int> walked{start};
  while (int(walked.size()) < count) {
    std::vector<int> next;
    for (int from : walked) {
      for (const auto& d : graph.doorways) {
        if (d.rooms.size() != 2) continue;
        for (int side = 0; side < 2; ++side) {
          const int a = d.rooms[side], b = d.rooms[1 - side];
          if (a == from && std::find(walked.begin(), walked.end(), b) == walked.end())
            next.push_back(b);
        }
      }
    }
    if (next.empty()) break;
    walked.push_back(next[std::uniform_int_distribution<std::size_t>(0, next.size() - 1)(rng)]);
  }
  return walked;
}

// The S-Graph of the walked rooms, in M where B_T_M = (x, y, yaw): each room (four- and
// two-wall; others only give planes), each of its surfaces clipped to the room, noise on all.
inline CutSGraph cutSGraph(const bim::AGraph& graph, const std::vector<int>& rooms,
                           const Eigen::Vector3d& B_T_M, std::mt19937_64& rng,
                           double noise = 0.02) {
  std::normal_distribution<double> gauss(0.0, 1.0);
  const Eigen::Rotation2Dd R_MB(-B_T_M.z());
  auto to_M = [&](const Eigen::Vector2d& p) {
    return Eigen::Vector2d(R_MB * (p - B_T_M.head<2>()));
  };
  CutSGraph cut;
  std::vector<int> walked_index;  // input index of each walked room, or -1
  for (int r : rooms) {
    const auto& a = graph.rooms[r];
    std::vector<int> plane_ids;
    Eigen::Vector2d lo = a.outline[0], hi = a.outline[0];
    for (const auto& p : a.outline) lo = lo.cwiseMin(p), hi = hi.cwiseMax(p);
    for (int s : a.surfaces) {
      if (s < 0) continue;
      const auto& surface = graph.surfaces[s];
      const Eigen::Vector2d along(-surface.plane.normal.y(), surface.plane.normal.x());
      double room_lo = 1e300, room_hi = -1e300;
      for (const auto& p : a.outline) {
        room_lo = std::min(room_lo, along.dot(p));
        room_hi = std::max(room_hi, along.dot(p));
      }
      for (const auto& [p, q] : surface.segments) {
        const double sp = along.dot(p), sq = along.dot(q);
        const double lo_s = std::max(std::min(sp, sq), room_lo);
        const double hi_s = std::min(std::max(sp, sq), room_hi);
        if (hi_s - lo_s < 0.3) continue;
        const Eigen::Vector2d base = p - along.dot(p) * along;
        const double yaw_noise = noise * 0.5 * gauss(rng);  // 0.01 rad for 2 cm
        const Eigen::Rotation2Dd tilt(yaw_noise);
        slam::MatchPlane plane;
        plane.id = int(cut.input.planes.size());
        const Eigen::Vector2d start = base + lo_s * along, end = base + hi_s * along;
        const Eigen::Vector2d middle = 0.5 * (start + end);
        const Eigen::Vector2d n = tilt * surface.plane.normal.head<2>();
        const Eigen::Vector2d offset = noise * gauss(rng) * n;
        plane.start = to_M(middle + offset + tilt * (start - middle));
        plane.end = to_M(middle + offset + tilt * (end - middle));
        const Eigen::Vector2d n_M = R_MB * n;
        plane.plane = bim::Plane::throughPoint({n_M.x(), n_M.y(), 0.0},
                                               {plane.start.x(), plane.start.y(), 1.0});
        cut.input.planes.push_back(plane);
        cut.a_surface_of_s_plane.push_back(s);
        plane_ids.push_back(plane.id);
      }
    }
    if (a.kind == bim::RoomKind::kPolygon) {
      walked_index.push_back(-1);
      continue;
    }
    slam::MatchRoom room;
    room.id = int(cut.input.rooms.size());
    room.four_wall = a.kind == bim::RoomKind::kFourWall;
    room.centre = to_M(a.centre + noise * Eigen::Vector2d(gauss(rng), gauss(rng)));
    if (!room.four_wall) {
      // A corridor's centre is wherever the robot saw it from: somewhere along its axis.
      const Eigen::Vector2d n = graph.surfaces[a.pairs[0][0]].plane.normal.head<2>();
      const Eigen::Vector2d along(-n.y(), n.x());
      room.centre = to_M(a.centre + std::uniform_real_distribution<double>(-2, 2)(rng) * along);
    }
    const Eigen::Vector3d n0 = graph.surfaces[a.pairs[0][0]].plane.normal;
    room.axis_yaw = std::atan2(n0.y(), n0.x()) - B_T_M.z();
    for (std::size_t i = 0; i < a.widths.size() && i < 2; ++i) {
      room.widths[i] = a.widths[i] + noise * gauss(rng);
    }
    room.planes = plane_ids;
    walked_index.push_back(room.id);
    cut.input.rooms.push_back(room);
    cut.a_room_of_s_room.push_back(r);
  }
  // Consecutive rooms of the walk that share a doorway were walked between directly.
  for (std::size_t i = 1; i < rooms.size(); ++i) {
    if (walked_index[i - 1] < 0 || walked_index[i] < 0) continue;
    for (const auto& d : graph.doorways) {
      const std::set<int> joined(d.rooms.begin(), d.rooms.end());
      if (joined.count(rooms[i - 1]) && joined.count(rooms[i])) {
        cut.input.transitions.emplace_back(walked_index[i - 1], walked_index[i]);
        break;
      }
    }
  }
  return cut;
}

}  // namespace isg::testing
