#pragma once

// A world small enough to compute by hand, for the iS-Graph's parts: one room, 10 m × 6 m inside
// and 3 m high, whose inner wall faces stand at x = −2 and 8, y = −3 and 3 of the plan frame B;
// a robot whose LiDAR (at the base, R_T_L = identity) rides 1 m above the floor, walking along x
// from the origin; its S-Graph made from ring scans of the room's faces. The map frame M is the
// robot's start: B_T_M is the identity.

#include <Eigen/Geometry>
#include <cmath>
#include <nlohmann/json.hpp>
#include <numbers>

#include "bim/agraph.hpp"
#include "bim/plan_parser.hpp"
#include "common/json_reader.hpp"
#include "sensors/messages.hpp"
#include "slam/sgraph/sgraph.hpp"

namespace isg::testing {

// The plan: four walls 0.2 m thick whose inner faces bound the room, the room's outline.
inline bim::AGraph boxPlan() {
  const nlohmann::json plan = nlohmann::json::parse(R"({
    "format": "isg.plan", "version": 1, "name": "box",
    "levels": [{"id": "L0", "elevation": 0.0, "height": 3.0,
      "walls": [
        {"id": "S", "start": [-2.2, -3.1], "end": [8.2, -3.1], "thickness": 0.2},
        {"id": "E", "start": [8.1, -3.2], "end": [8.1, 3.2], "thickness": 0.2},
        {"id": "N", "start": [8.2, 3.1], "end": [-2.2, 3.1], "thickness": 0.2},
        {"id": "W", "start": [-2.1, 3.2], "end": [-2.1, -3.2], "thickness": 0.2}],
      "doors": [],
      "rooms": [{"id": "R", "name": "Box", "outline": [[-2, -3], [8, -3], [8, 3], [-2, 3]]}]}]})");
  const common::JsonSource source{"box.json", nullptr};
  return bim::buildAGraph(bim::parsePlan(common::JsonNode(plan, "", source)));
}

// A ring scan of the room's faces (16 rings from −15° to 15°) from a sensor at `M_T_L`, its points
// in L: `azimuths` a ring (1800: 0.2° apart, as a VLP-16 at 10 Hz).
inline sensors::Scan boxScan(const Eigen::Isometry3d& M_T_L, double stamp, int azimuths = 1800) {
  constexpr double kDeg = std::numbers::pi / 180.0;
  sensors::Scan scan;
  scan.stamp = stamp;
  const Eigen::Vector3d lo(-2, -3, -1), hi(8, 3, 2);
  for (int ring = 0; ring < 16; ++ring) {
    const double elevation = (-15.0 + 2.0 * ring) * kDeg;
    for (int a = 0; a < azimuths; ++a) {
      const double azimuth = 360.0 / azimuths * a * kDeg;
      const Eigen::Vector3d d_L(std::cos(elevation) * std::cos(azimuth),
                                std::cos(elevation) * std::sin(azimuth), std::sin(elevation));
      const Eigen::Vector3d o = M_T_L.translation(), d = M_T_L.linear() * d_L;
      double best = 1e9;
      for (int k = 0; k < 3; ++k) {
        if (std::abs(d[k]) < 1e-9) continue;
        for (double wall : {lo[k], hi[k]}) {
          const double s = (wall - o[k]) / d[k];
          if (s > 0 && s < best) best = s;
        }
      }
      const Eigen::Vector3d p = d_L * best;
      scan.points.push_back(
          {float(p.x()), float(p.y()), float(p.z()), 50.0f, std::uint16_t(ring), 0.0f});
    }
  }
  return scan;
}

// The S-Graph of a walk of `metres` along x from the origin at 0.5 m/s, scans at 10 Hz and
// odometry at 50 Hz, both exact.
inline slam::SGraph boxSGraph(double metres = 4.0) {
  slam::SGraph graph(Eigen::Isometry3d::Identity());
  const int steps = int(std::round(metres / 0.05));
  auto poseAt = [](double t) {
    Eigen::Isometry3d M_T_R = Eigen::Isometry3d::Identity();
    M_T_R.translation().x() = 0.5 * t;
    return M_T_R;
  };
  for (int k = 0; k <= steps; ++k) {
    const double t = 0.1 * k;
    for (int o = 0; o < 5; ++o) {
      const double to = t + 0.02 * o;
      graph.addOdometry({to, poseAt(to)});
    }
    graph.addScan(boxScan(poseAt(t), t));
  }
  return graph;
}

}  // namespace isg::testing
