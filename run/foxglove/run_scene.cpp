#include "run/foxglove/run_scene.hpp"

#include <cmath>
#include <cstdio>
#include <map>
#include <string>

#include "formats/foxglove_json.hpp"
#include "run/off_class_colours.hpp"
#include "slam/deviations/map_against_plan.hpp"

namespace isg::run {

namespace {

namespace fx = formats::foxglove;
using Json = nlohmann::json;
using Eigen::Vector3d;

// Colours: the plan in greys, the A-Graph warm, the S-Graph cool; deviations as in
// deviations.svg.
constexpr fx::Rgba kWallFace{0.62, 0.62, 0.66, 1.0};
constexpr fx::Rgba kDoorway{0.18, 0.70, 0.35, 1.0};
constexpr fx::Rgba kRoomOutline{0.25, 0.45, 0.85, 1.0};
constexpr fx::Rgba kLabel{0.95, 0.95, 0.95, 1.0};
constexpr fx::Rgba kAWall{0.95, 0.55, 0.15, 1.0};
constexpr fx::Rgba kASurface{0.95, 0.75, 0.35, 1.0};
constexpr fx::Rgba kARoom{0.85, 0.25, 0.20, 1.0};
constexpr fx::Rgba kAFloor{0.55, 0.20, 0.15, 1.0};
constexpr fx::Rgba kAEdge{0.95, 0.65, 0.40, 0.8};
constexpr fx::Rgba kKeyframe{0.95, 0.90, 0.25, 1.0};
constexpr fx::Rgba kPlane{0.20, 0.75, 0.90, 0.45};
constexpr fx::Rgba kSRoom{0.75, 0.30, 0.90, 1.0};
constexpr fx::Rgba kSFloor{0.35, 0.20, 0.75, 1.0};
constexpr fx::Rgba kSEdge{0.45, 0.80, 0.95, 0.8};
constexpr fx::Rgba kAsBuilt{1.0, 1.0, 1.0, 1.0};
constexpr fx::Rgba kExtraWall{0.10, 0.10, 0.10, 1.0};

constexpr double kNodeSize = 0.35;      // m: a graph node's sphere
constexpr double kKeyframeSize = 0.15;  // m
constexpr double kEdgeThickness = 0.03;
constexpr double kFontSize = 14.0;  // px

Vector3d at(const Json& xy, double z) {
  return {xy.at(0).get<double>(), xy.at(1).get<double>(), z};
}

Vector3d xyz(const Json& p) {
  return {p.at(0).get<double>(), p.at(1).get<double>(), p.at(2).get<double>()};
}

// Each level's floor elevation, from agraph.json's floors.
std::map<std::string, double> elevations(const Json& agraph) {
  std::map<std::string, double> by_level;
  for (const Json& floor : agraph.at("nodes").at("floors")) {
    by_level[floor.at("id").get<std::string>()] = floor.at("elevation").get<double>();
  }
  return by_level;
}

double elevationOf(const std::map<std::string, double>& by_level, const Json& node) {
  const auto it = by_level.find(node.value("level", std::string()));
  return it == by_level.end() ? 0.0 : it->second;
}

// The four corners of a vertical face over a segment, as two triangles.
void face(const Vector3d& a, const Vector3d& b, double z0, double z1,
          std::vector<Vector3d>& triangles) {
  const Vector3d a0(a.x(), a.y(), z0), a1(a.x(), a.y(), z1);
  const Vector3d b0(b.x(), b.y(), z0), b1(b.x(), b.y(), z1);
  triangles.insert(triangles.end(), {a0, b0, b1, a0, b1, a1});
}

// The point of a wall surface its A-Graph node is drawn at: the middle of its longest segment at
// the top of the surface.
Vector3d surfaceNode(const Json& surface) {
  double longest = -1.0;
  Vector3d node = Vector3d::Zero();
  const double top = surface.at("z").at(1).get<double>();
  for (const Json& segment : surface.at("segments")) {
    const Vector3d a = at(segment.at(0), top), b = at(segment.at(1), top);
    if ((b - a).norm() > longest) {
      longest = (b - a).norm();
      node = (a + b) / 2.0;
    }
  }
  return node;
}

std::string fixed(double value, int decimals) {
  char buffer[32];
  std::snprintf(buffer, sizeof buffer, "%.*f", decimals, value);
  return buffer;
}

fx::Rgba statusColour(const std::string& status) {
  if (status == "as_planned") return {0.18, 0.55, 0.34, 1.0};
  if (status == "shifted" || status == "moved") return {0.90, 0.49, 0.0, 1.0};
  if (status == "rotated") return {0.61, 0.19, 0.78, 1.0};
  if (status == "missing") return {0.82, 0.01, 0.11, 1.0};
  return {0.6, 0.6, 0.6, 1.0};  // not seen
}

}  // namespace

std::vector<Json> planEntities(const Json& agraph, formats::RosTime stamp) {
  const auto by_level = elevations(agraph);
  const Json& nodes = agraph.at("nodes");
  std::map<std::string, double> wall_thickness;
  std::map<std::string, Vector3d> wall_normal;
  for (const Json& wall : nodes.at("walls")) {
    wall_thickness[wall.at("id").get<std::string>()] = wall.at("thickness").get<double>();
  }
  std::vector<Vector3d> faces;
  for (const Json& surface : nodes.at("wall_surfaces")) {
    const double z0 = surface.at("z").at(0).get<double>(), z1 = surface.at("z").at(1).get<double>();
    for (const Json& segment : surface.at("segments")) {
      face(at(segment.at(0), 0.0), at(segment.at(1), 0.0), z0, z1, faces);
    }
    // A flight of stairs' surfaces name their flight ("stair"), not a wall.
    if (!surface.contains("wall")) continue;
    const Json& n = surface.at("plane").at("n");
    wall_normal[surface.at("wall").get<std::string>()] = {n.at(0).get<double>(),
                                                          n.at(1).get<double>(), 0.0};
  }
  Json walls = fx::sceneEntity(stamp, "plan", "plan/walls");
  if (!faces.empty()) walls["triangles"].push_back(fx::triangles(faces, kWallFace));

  Json doorways = fx::sceneEntity(stamp, "plan", "plan/doorways");
  for (const Json& doorway : nodes.at("doorways")) {
    const std::string wall = doorway.at("wall").get<std::string>();
    const Json& p = doorway.at("position");
    const double z = elevationOf(by_level, doorway) + 0.01;
    Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
    pose.translation() = Vector3d(p.at(0).get<double>(), p.at(1).get<double>(), z);
    const Vector3d n = wall_normal.count(wall) ? wall_normal[wall] : Vector3d::UnitX();
    pose.linear() = Eigen::AngleAxisd(std::atan2(n.y(), n.x()), Vector3d::UnitZ()).matrix();
    // x across the wall (its thickness and a little), y along it (the doorway's width).
    const double across = (wall_thickness.count(wall) ? wall_thickness[wall] : 0.2) + 0.2;
    doorways["cubes"].push_back(
        fx::cube(pose, {across, doorway.at("width").get<double>(), 0.02}, kDoorway));
  }

  Json rooms = fx::sceneEntity(stamp, "plan", "plan/rooms");
  for (const Json& room : nodes.at("rooms")) {
    const double z = elevationOf(by_level, room) + 0.02;
    std::vector<Vector3d> outline;
    for (const Json& corner : room.at("outline")) outline.push_back(at(corner, z));
    if (!outline.empty()) rooms["lines"].push_back(fx::lineLoop(outline, 0.05, kRoomOutline));
    const std::string name = room.value("name", std::string());
    rooms["texts"].push_back(fx::text(
        at(room.at("centre"), z + 0.3),
        room.at("id").get<std::string>() + (name.empty() ? "" : " " + name), kFontSize, kLabel));
  }
  return {walls, doorways, rooms};
}

std::vector<Json> agraphEntities(const Json& agraph, formats::RosTime stamp) {
  const auto by_level = elevations(agraph);
  const Json& nodes = agraph.at("nodes");
  std::map<std::string, Vector3d> where;
  Json entity = fx::sceneEntity(stamp, "plan", "agraph/nodes");
  auto node = [&](const std::string& id, const Vector3d& p, const fx::Rgba& colour) {
    where[id] = p;
    entity["spheres"].push_back(fx::sphere(p, kNodeSize, colour));
  };
  for (const Json& surface : nodes.at("wall_surfaces")) {
    node(surface.at("id").get<std::string>(), surfaceNode(surface), kASurface);
  }
  for (const Json& wall : nodes.at("walls")) {
    const Json& centre = wall.at("centre");
    node(wall.at("id").get<std::string>(),
         at(centre, elevationOf(by_level, wall) + kWallLayerHeight), kAWall);
  }
  for (const Json& room : nodes.at("rooms")) {
    node(room.at("id").get<std::string>(),
         at(room.at("centre"), elevationOf(by_level, room) + kRoomLayerHeight), kARoom);
  }
  for (const Json& doorway : nodes.at("doorways")) {
    node(doorway.at("id").get<std::string>(),
         at(doorway.at("position"), elevationOf(by_level, doorway) + kRoomLayerHeight), kDoorway);
  }
  for (const Json& floor : nodes.at("floors")) {
    node(floor.at("id").get<std::string>(),
         at(floor.at("centre"), floor.at("elevation").get<double>() + kFloorLayerHeight), kAFloor);
  }
  std::vector<Vector3d> segments;
  for (const Json& edge : agraph.at("edges")) {
    const auto from = where.find(edge.at("from").get<std::string>());
    const auto to = where.find(edge.at("to").get<std::string>());
    if (from == where.end() || to == where.end()) continue;
    segments.push_back(from->second);
    segments.push_back(to->second);
  }
  Json edges = fx::sceneEntity(stamp, "plan", "agraph/edges");
  if (!segments.empty()) edges["lines"].push_back(fx::lineList(segments, kEdgeThickness, kAEdge));
  return {entity, edges};
}

std::vector<Json> sgraphEntities(const Json& sgraph, formats::RosTime stamp) {
  Json keyframes = fx::sceneEntity(stamp, "map", "sgraph/keyframes");
  Json planes = fx::sceneEntity(stamp, "map", "sgraph/planes");
  Json rooms = fx::sceneEntity(stamp, "map", "sgraph/rooms");
  Json floors = fx::sceneEntity(stamp, "map", "sgraph/floors");
  Json edges = fx::sceneEntity(stamp, "map", "sgraph/edges");
  const Json empty = Json::array();
  auto list = [&](const char* key) -> const Json& {
    const auto it = sgraph.find(key);
    return it != sgraph.end() && it->is_array() ? *it : empty;
  };
  // Each floor's height in M (the floor under the robot), by its index.
  std::map<int, double> floor_z;
  std::map<int, Vector3d> floor_node;
  for (const Json& floor : list("floors")) {
    const int id = floor.at("id").get<int>();
    // The floor's height in M once estimated; until then the robot's.
    floor_z[id] = floor.value("height", floor.value("robot_z", 0.0));
    if (!floor.contains("centre")) continue;  // no rooms yet: nothing to centre it on
    floor_node[id] = at(floor.at("centre"), floor_z[id] + kFloorLayerHeight);
    floors["cubes"].push_back(fx::cube(Eigen::Isometry3d(Eigen::Translation3d(floor_node[id])),
                                       Vector3d::Constant(kNodeSize * 1.5), kSFloor));
  }
  auto floorOf = [&](const Json& node) {
    const auto it = floor_z.find(node.value("floor", 0));
    return it == floor_z.end() ? 0.0 : it->second;
  };
  for (const Json& keyframe : list("keyframes")) {
    const Json& p = keyframe.at("position");
    keyframes["spheres"].push_back(fx::sphere(xyz(p), kKeyframeSize, kKeyframe));
  }
  std::map<int, Vector3d> plane_top;
  std::vector<Vector3d> plane_faces;
  for (const Json& plane : list("planes")) {
    const double z0 = floorOf(plane), z1 = z0 + kPlaneDrawHeight;
    const Vector3d a = at(plane.at("start"), 0.0), b = at(plane.at("end"), 0.0);
    face(a, b, z0, z1, plane_faces);
    plane_top[plane.at("id").get<int>()] = Vector3d((a.x() + b.x()) / 2, (a.y() + b.y()) / 2, z1);
  }
  if (!plane_faces.empty()) planes["triangles"].push_back(fx::triangles(plane_faces, kPlane));
  std::vector<Vector3d> segments;
  // Keyframe–plane: each plane a keyframe observed (sgraph.json's plane_ids), to its middle.
  for (const Json& keyframe : list("keyframes")) {
    const Json& p = keyframe.at("position");
    const Vector3d from = xyz(p);
    for (const Json& id : keyframe.value("plane_ids", empty)) {
      const auto it = plane_top.find(id.get<int>());
      if (it == plane_top.end()) continue;
      segments.push_back(from);
      segments.push_back(it->second - Vector3d(0, 0, kPlaneDrawHeight / 2));
    }
  }
  for (const Json& room : list("rooms")) {
    const Vector3d centre = at(room.at("centre"), floorOf(room) + kRoomLayerHeight);
    rooms["spheres"].push_back(fx::sphere(centre, kNodeSize, kSRoom));
    for (const Json& pair : room.value("plane_pairs", empty)) {
      for (const Json& id : pair) {
        const auto it = plane_top.find(id.get<int>());
        if (it == plane_top.end()) continue;
        segments.push_back(it->second);
        segments.push_back(centre);
      }
    }
    const auto floor = floor_node.find(room.value("floor", 0));
    if (floor != floor_node.end()) {
      segments.push_back(centre);
      segments.push_back(floor->second);
    }
  }
  if (!segments.empty()) edges["lines"].push_back(fx::lineList(segments, kEdgeThickness, kSEdge));
  return {keyframes, planes, rooms, floors, edges};
}

std::vector<Json> candidateEntities(const Json& sgraph, const Json& agraph,
                                    formats::RosTime stamp) {
  Json entity = fx::sceneEntity(stamp, "plan", "matching/candidates");
  const auto matching = sgraph.find("matching");
  if (matching == sgraph.end() || !matching->is_object()) return {entity};
  const Json* last = matching->contains("last_match") ? &matching->at("last_match") : nullptr;
  if (!last || !last->is_object() || !last->contains("candidates")) return {entity};
  const std::string level = matching->value("level", std::string());
  const auto by_level = elevations(agraph);
  const auto elevation = by_level.find(level);
  const double z = (elevation == by_level.end() ? 0.0 : elevation->second) + 0.1;
  // The S-Graph's floors on the matched level (all of them when the graph does not say).
  const Json floor_levels = matching->value("floor_levels", Json::object());
  auto onLevel = [&](const Json& plane) {
    const auto it = floor_levels.find(std::to_string(plane.value("floor", 0)));
    return floor_levels.empty() || (it != floor_levels.end() && *it == level);
  };
  constexpr fx::Rgba kBest{0.20, 0.85, 0.35, 1.0}, kOther{0.95, 0.55, 0.10, 0.7};
  for (const Json& candidate : last->at("candidates")) {
    const Json& pose = candidate.at("B_T_M");
    const Eigen::Rotation2Dd rotation(pose.at("yaw").get<double>());
    const Eigen::Vector2d shift(pose.at("x").get<double>(), pose.at("y").get<double>());
    auto placed = [&](const Json& xy) {
      const Eigen::Vector2d p =
          rotation * Eigen::Vector2d(xy.at(0).get<double>(), xy.at(1).get<double>()) + shift;
      return Vector3d(p.x(), p.y(), z);
    };
    std::vector<Vector3d> segments;
    Vector3d sum = Vector3d::Zero();
    for (const Json& plane : sgraph.value("planes", Json::array())) {
      if (!onLevel(plane)) continue;
      segments.push_back(placed(plane.at("start")));
      segments.push_back(placed(plane.at("end")));
      sum += segments[segments.size() - 2] + segments.back();
    }
    if (segments.empty()) continue;
    const bool best = candidate.value("best", false);
    entity["lines"].push_back(fx::lineList(segments, best ? 0.08 : 0.04, best ? kBest : kOther));
    entity["texts"].push_back(
        fx::text(sum / double(segments.size()) + Vector3d(0, 0, 0.5),
                 (best ? "best, score " : "score ") + fixed(candidate.value("score", 0.0), 1),
                 kFontSize, best ? kBest : kOther));
  }
  return {entity};
}

namespace {

// A point of the report (B, metres) at height z.
Vector3d at(const Eigen::Vector2d& xy, double z) { return {xy.x(), xy.y(), z}; }

double elevationOf(const std::map<std::string, double>& by_level, const std::string& level) {
  const auto it = by_level.find(level);
  return it == by_level.end() ? 0.0 : it->second;
}

// Where the map lies off the plan (deviations.json's map_against_plan): each face's stretches at
// a metre above its floor, one line list per class of slam::offClass, the farther ones labelled
// with their mean offset.
Json againstPlanEntity(const std::vector<slam::LevelAgainstPlan>& levels,
                       const std::map<std::string, double>& by_level, formats::RosTime stamp) {
  Json entity = fx::sceneEntity(stamp, "plan", "deviations/map-against-plan");
  fx::Rgba colour[4];
  for (int c = 0; c < 4; ++c) {
    const auto& rgb = kOffClassRgb[std::size_t(c)];
    colour[c] = {rgb[0] / 255.0, rgb[1] / 255.0, rgb[2] / 255.0, 1.0};
  }
  std::vector<Vector3d> lines[4];
  for (const slam::LevelAgainstPlan& level : levels) {
    const double z = elevationOf(by_level, level.level) + 1.0;
    for (const slam::FaceStretch& stretch : level.stretches) {
      const double mean = stretch.mean_m;
      const int c = slam::offClass(mean);
      const Vector3d a = at(stretch.start, z), b = at(stretch.end, z);
      lines[c].push_back(a);
      lines[c].push_back(b);
      if (c >= 2) {
        entity["texts"].push_back(fx::text((a + b) / 2.0 + Vector3d(0, 0, 0.2),
                                           fixed(mean, 2) + " m", kFontSize, colour[c]));
      }
    }
  }
  for (int c = 0; c < 4; ++c) {
    if (!lines[c].empty()) entity["lines"].push_back(fx::lineList(lines[c], 0.06, colour[c]));
  }
  return entity;
}

// The columns judged (deviations.json `columns`): a square mark at each planned centre coloured by
// its status (the column's own outline is among the plan's walls, drawn under it); a moved one
// also a line to where the map found it, and the moved and missing ones labelled.
Json columnEntity(const std::vector<slam::ColumnDeviation>& columns,
                  const std::map<std::string, double>& by_level, formats::RosTime stamp) {
  Json entity = fx::sceneEntity(stamp, "plan", "deviations/columns");
  entity["lines"] = Json::array();
  entity["texts"] = Json::array();
  constexpr double kLift = 0.07;  // m above the floor, over the walls' layer
  constexpr double kHalf = 0.25;  // m: half the mark's side
  for (const slam::ColumnDeviation& column : columns) {
    const double z = elevationOf(by_level, column.level) + kLift;
    const std::string status = slam::toString(column.status);
    const Vector3d c = at(column.planned_centre, z);
    entity["lines"].push_back(
        fx::lineLoop({c + Vector3d(-kHalf, -kHalf, 0), c + Vector3d(kHalf, -kHalf, 0),
                      c + Vector3d(kHalf, kHalf, 0), c + Vector3d(-kHalf, kHalf, 0)},
                     0.06, statusColour(status)));
    std::string label = column.column + " " + status;
    if (status == "moved" && column.offset_m) {
      const Vector3d offset(column.offset_m->x(), column.offset_m->y(), 0.0);
      entity["lines"].push_back(fx::lineList({c, c + offset}, 0.04, statusColour(status)));
      label += " " + fixed(offset.norm(), 2) + " m";
    }
    if (status == "moved" || status == "missing") {
      entity["texts"].push_back(
          fx::text(c + Vector3d(0, 0, 0.4), label, kFontSize, statusColour(status)));
    }
  }
  return entity;
}

// Each judged wall at its planned place, coloured by status, with the map's evidence along it;
// the deviating ones labelled with their offset and angle; the extra walls.
Json wallEntity(const slam::DeviationReport& report, const std::map<std::string, double>& by_level,
                formats::RosTime stamp) {
  Json entity = fx::sceneEntity(stamp, "plan", "deviations/walls");
  constexpr double kLift = 0.05;  // m above the floor, over the room outlines
  for (const slam::WallDeviation& wall : report.walls) {
    const double z = elevationOf(by_level, wall.level) + kLift;
    const std::string status = slam::toString(wall.status);
    const Vector3d a = at(wall.planned_start, z);
    const Vector3d b = at(wall.planned_end, z);
    entity["lines"].push_back(fx::lineList({a, b}, 0.12, statusColour(status)));
    std::vector<Vector3d> built;
    for (const slam::WallEvidence& evidence : wall.evidence) {
      built.push_back(at(evidence.start_B, z + 0.02));
      built.push_back(at(evidence.end_B, z + 0.02));
    }
    if (!built.empty()) entity["lines"].push_back(fx::lineList(built, 0.04, kAsBuilt));
    if (status == "as_planned" || status == "not_seen") continue;
    std::string label = wall.wall + " " + status;
    if (wall.offset_m) label += " " + fixed(*wall.offset_m, 2) + " m";
    if (wall.angle_deg) label += " " + fixed(*wall.angle_deg, 1) + " deg";
    entity["texts"].push_back(
        fx::text((a + b) / 2.0 + Vector3d(0, 0, 0.4), label, kFontSize, statusColour(status)));
  }
  for (const slam::ExtraWall& extra : report.extra_walls) {
    const double z = elevationOf(by_level, extra.level) + kLift;
    entity["lines"].push_back(
        fx::lineList({at(extra.start, z), at(extra.end, z)}, 0.12, kExtraWall));
  }
  return entity;
}

}  // namespace

std::vector<Json> deviationEntities(const slam::DeviationReport& report, const Json& agraph,
                                    formats::RosTime stamp) {
  const auto by_level = elevations(agraph);
  std::vector<Json> entities = {wallEntity(report, by_level, stamp)};
  if (!report.columns.empty()) entities.push_back(columnEntity(report.columns, by_level, stamp));
  if (!report.against_plan.empty()) {
    entities.push_back(againstPlanEntity(report.against_plan, by_level, stamp));
  }
  return entities;
}

}  // namespace isg::run
