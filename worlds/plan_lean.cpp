#include "worlds/plan_lean.hpp"

#include <Eigen/Geometry>
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <map>
#include <string>
#include <vector>

#include "common/angles.hpp"
#include "worlds/millimetres.hpp"
#include "worlds/segment_distance.hpp"

namespace isg::worlds {

namespace {

using nlohmann::json;

double tenthMm(double v) { return std::round(v * 10000.0) / 10000.0; }
// The millimetre just below `length`: a part of a wall may not run past its rounded end.
double below(double length) { return std::floor(length * 1000.0 - 1e-6) / 1000.0; }

Eigen::Vector2d point2(const json& p) { return {p[0].get<double>(), p[1].get<double>()}; }

// A plan wall as the lean found it, and what the lean makes of it.
struct LeanedWall {
  Eigen::Vector2d start, end;  // after the lean, in B
  double stretch = 1.0;        // how much longer the lean made it
  double half_thickness = 0.0;
};

bool boxMeetsWall(const Eigen::Vector2d& centre, const Eigen::Vector2d& size, double yaw,
                  const LeanedWall& wall, double clearance) {
  const Eigen::Rotation2Dd turn(yaw);
  std::array<Eigen::Vector2d, 4> corners;
  const double hx = 0.5 * size.x(), hy = 0.5 * size.y();
  corners[0] = centre + turn * Eigen::Vector2d(-hx, -hy);
  corners[1] = centre + turn * Eigen::Vector2d(hx, -hy);
  corners[2] = centre + turn * Eigen::Vector2d(hx, hy);
  corners[3] = centre + turn * Eigen::Vector2d(-hx, hy);
  for (int k = 0; k < 4; ++k) {
    const Eigen::Vector2d& a = corners[k];
    const Eigen::Vector2d& b = corners[(k + 1) % 4];
    if (crosses(a, b, wall.start, wall.end)) return true;
    if (segmentDistance(a, b, wall.start, wall.end) < wall.half_thickness + clearance) return true;
  }
  // A wall whose axis lies wholly inside the box crosses none of its sides.
  const Eigen::Vector2d local = turn.inverse() * (wall.start - centre);
  return std::abs(local.x()) <= hx && std::abs(local.y()) <= hy;
}

// The lean as a map of the plan: sheared, then turned about the origin.
struct Lean {
  Eigen::Matrix2d A;
  double turn = 0.0;
  Eigen::Vector2d map(const Eigen::Vector2d& p) const {
    const Eigen::Vector2d q = A * p;
    return {mm(q.x()), mm(q.y())};
  }
  json map(const json& p) const {
    const Eigen::Vector2d q = map(point2(p));
    return json::array({q.x(), q.y()});
  }
};

// The plan's walls, doors and rooms leaned; returns each wall as leaned, by id.
std::map<std::string, LeanedWall> leanPlan(json& plan, const Lean& lean) {
  std::map<std::string, LeanedWall> walls;
  for (json& level : plan["levels"]) {
    for (json& wall : level["walls"]) {
      const Eigen::Vector2d start = point2(wall["start"]), end = point2(wall["end"]);
      LeanedWall leaned;
      leaned.stretch = (lean.A * (end - start)).norm() / (end - start).norm();
      wall["start"] = lean.map(wall["start"]);
      wall["end"] = lean.map(wall["end"]);
      leaned.start = point2(wall["start"]);
      leaned.end = point2(wall["end"]);
      // A shear keeps areas: a wall's length times its thickness stays.
      const double thickness = tenthMm(wall["thickness"].get<double>() / leaned.stretch);
      wall["thickness"] = thickness;
      leaned.half_thickness = 0.5 * thickness;
      walls[wall["id"].get<std::string>()] = leaned;
    }
    if (level.contains("doors")) {
      for (json& door : level["doors"]) {
        const double stretch = walls.at(door["wall"].get<std::string>()).stretch;
        door["offset"] = mm(door["offset"].get<double>() * stretch);
        door["width"] = mm(door["width"].get<double>() * stretch);
      }
    }
    if (level.contains("rooms")) {
      for (json& room : level["rooms"]) {
        for (json& vertex : room["outline"]) vertex = lean.map(vertex);
      }
    }
  }
  return walls;
}

// Places along walls (a rotation's pivot, a shortened wall's built parts) stretched with them,
// never past the leaned wall's end.
void leanAlongWalls(bim::AsBuilt& as_built, const std::map<std::string, LeanedWall>& walls) {
  const auto length = [&](const std::string& id) {
    const LeanedWall& w = walls.at(id);
    return (w.end - w.start).norm();
  };
  for (bim::WallRotation& rotation : as_built.wall_rotations) {
    // About its start, centre or end, a wall turns about where it did.
    if (rotation.about != bim::WallRotation::About::kAlong) continue;
    rotation.along_m = std::min(mm(rotation.along_m * walls.at(rotation.wall).stretch),
                                below(length(rotation.wall)));
  }
  for (bim::ShortenedWall& shortened : as_built.shortened_walls) {
    const double stretch = walls.at(shortened.wall).stretch;
    for (auto& [from, to] : shortened.built) {
      from = mm(from * stretch);
      to = std::min(mm(to * stretch), below(length(shortened.wall)));
    }
  }
}

// Extra walls leaned; clutter leaned and turned, a box that now meets a wall left out.
void leanExtraWallsAndClutter(bim::AsBuilt& as_built, const Lean& lean,
                              const std::map<std::string, LeanedWall>& walls) {
  std::vector<LeanedWall> obstacles;
  for (const auto& [id, wall] : walls) obstacles.push_back(wall);
  for (bim::ExtraWall& extra : as_built.extra_walls) {
    extra.start = lean.map(extra.start);
    extra.end = lean.map(extra.end);
    LeanedWall leaned;
    leaned.start = extra.start;
    leaned.end = extra.end;
    leaned.half_thickness = 0.5 * extra.thickness;
    obstacles.push_back(leaned);
  }
  std::vector<bim::Clutter> kept;
  for (bim::Clutter box : as_built.clutter) {
    box.center.head<2>() = lean.map(Eigen::Vector2d(box.center.head<2>()));
    box.yaw = mm(box.yaw + lean.turn);
    const Eigen::Vector2d centre = box.center.head<2>(), size = box.size.head<2>();
    const bool in_wall = std::any_of(obstacles.begin(), obstacles.end(), [&](const auto& w) {
      return boxMeetsWall(centre, size, box.yaw, w, 0.05);
    });
    if (!in_wall) kept.push_back(std::move(box));
  }
  as_built.clutter = std::move(kept);
}

}  // namespace

void leanBuilding(nlohmann::json& plan, bim::AsBuilt& as_built, double shear_deg, double turn_deg) {
  if (shear_deg == 0.0 && turn_deg == 0.0) return;
  const double shear = common::radians(shear_deg);
  Lean lean;
  lean.turn = common::radians(turn_deg);
  Eigen::Matrix2d shear_matrix;
  shear_matrix << 1.0, std::tan(shear), 0.0, 1.0;
  lean.A = Eigen::Rotation2Dd(lean.turn).toRotationMatrix() * shear_matrix;
  const std::map<std::string, LeanedWall> walls = leanPlan(plan, lean);
  char title[96];
  std::snprintf(title, sizeof title, ", sheared %g°, turned %g°", shear_deg, turn_deg);
  plan["name"] = plan["name"].get<std::string>() + title;
  leanAlongWalls(as_built, walls);
  leanExtraWallsAndClutter(as_built, lean, walls);
}

}  // namespace isg::worlds
