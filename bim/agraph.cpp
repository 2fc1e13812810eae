#include "bim/agraph.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "bim/polygon.hpp"
#include "bim/stairs.hpp"

namespace isg::bim {

namespace {

bool isRectangle(const std::vector<Eigen::Vector2d>& outline, double tolerance_deg) {
  if (outline.size() != 4) return false;
  const double max_cos = std::sin(tolerance_deg * std::numbers::pi / 180.0);
  for (std::size_t i = 0; i < 4; ++i) {
    const Eigen::Vector2d a = (outline[(i + 1) % 4] - outline[i]).normalized();
    const Eigen::Vector2d b = (outline[(i + 2) % 4] - outline[(i + 1) % 4]).normalized();
    if (std::abs(a.dot(b)) > max_cos) return false;
  }
  return true;
}

// A quadrilateral whose opposite edges are parallel within `tolerance_deg` (a rectangle is one):
// a room of a sheared, non-Manhattan plan.
bool isParallelogram(const std::vector<Eigen::Vector2d>& outline, double tolerance_deg) {
  if (outline.size() != 4) return false;
  const double max_sin = std::sin(tolerance_deg * std::numbers::pi / 180.0);
  for (std::size_t i = 0; i < 2; ++i) {
    const Eigen::Vector2d a = (outline[i + 1] - outline[i]).normalized();
    const Eigen::Vector2d b = (outline[(i + 3) % 4] - outline[i + 2]).normalized();
    if (std::abs(a.x() * b.y() - a.y() * b.x()) > max_sin || a.dot(b) > 0.0) return false;
  }
  return true;
}

double pairWidth(const Plane& a, const Plane& b) {
  return std::abs(a.signedDistance(b.closestPoint()));
}

// For each outline edge the surface that covers most of it, or -1.
std::vector<int> edgeSurfaces(const Room& room, const LevelGeometry& geometry,
                              const AGraph& graph) {
  std::vector<int> out(room.outline.size(), -1);
  std::vector<double> best(room.outline.size(), 0.0);
  for (const auto& b : geometry.boundariesOf(room.id)) {
    if (b.overlap <= best[b.edge]) continue;
    best[b.edge] = b.overlap;
    out[b.edge] = graph.findSurface(b.wall + (b.side > 0 ? ":left" : ":right"));
  }
  return out;
}

// A parallelogram that is not a rectangle (a corridor of a sheared plan) is a two-wall room when
// one pair of opposite edges bounds a long narrow band: the distance between them at most
// corridor_width, their length at least corridor_aspect times it. Its ends lean, so it cannot be
// the rectangle of a four-wall room; other parallelograms stay polygons.
void classifySlantedCorridor(RoomNode& node, const AGraph& graph, const AGraphOptions& options) {
  if (!isParallelogram(node.outline, options.rectangle_angle_tolerance_deg)) return;
  const auto& s = node.surfaces;
  for (int first : {0, 1}) {
    if (s[first] < 0 || s[first + 2] < 0) continue;
    const Plane& a = graph.surfaces[s[first]].plane;
    const Plane& b = graph.surfaces[s[first + 2]].plane;
    const double width = pairWidth(a, b);
    const double length =
        std::min((node.outline[first + 1] - node.outline[first]).norm(),
                 (node.outline[(first + 3) % 4] - node.outline[first + 2]).norm());
    if (width > options.corridor_width || length < options.corridor_aspect * width) continue;
    node.kind = RoomKind::kTwoWall;
    node.pairs = {{s[first], s[first + 2]}};
    node.widths = {width};
    node.centre = twoWallRoomCentre(a, b, node.axis_point);
    return;
  }
}

void classifyRoom(RoomNode& node, const AGraph& graph, const AGraphOptions& options) {
  const auto& s = node.surfaces;
  node.kind = RoomKind::kPolygon;
  node.centre = centroid(node.outline);
  node.axis_point = node.centre;
  if (!isRectangle(node.outline, options.rectangle_angle_tolerance_deg)) {
    classifySlantedCorridor(node, graph, options);
    return;
  }
  const double length0 = (node.outline[1] - node.outline[0]).norm();
  const double length1 = (node.outline[2] - node.outline[1]).norm();
  const bool pair0 = s[0] >= 0 && s[2] >= 0;  // edges 0 and 2 face each other
  const bool pair1 = s[1] >= 0 && s[3] >= 0;
  const double shorter = std::min(length0, length1);
  const bool narrow = std::max(length0, length1) >= options.corridor_aspect * shorter &&
                      shorter <= options.corridor_width;
  // The pair across the short side bounds a corridor: its long walls.
  const bool long_pair_is_0 = length0 > length1;
  auto plane = [&](int surface) -> const Plane& { return graph.surfaces[surface].plane; };

  if (pair0 && pair1 && !narrow) {
    node.kind = RoomKind::kFourWall;
    std::array<int, 2> a{s[0], s[2]};
    std::array<int, 2> b{s[1], s[3]};
    // x-pair first: the pair whose normal is closer to B's x axis.
    if (std::abs(plane(a[0]).normal.x()) < std::abs(plane(b[0]).normal.x())) std::swap(a, b);
    node.pairs = {a, b};
    node.widths = {pairWidth(plane(a[0]), plane(a[1])), pairWidth(plane(b[0]), plane(b[1]))};
    node.centre = fourWallRoomCentre(plane(a[0]), plane(a[1]), plane(b[0]), plane(b[1]));
    return;
  }
  std::array<int, 2> corridor{-1, -1};
  if (narrow && (long_pair_is_0 ? pair0 : pair1)) {
    corridor = long_pair_is_0 ? std::array<int, 2>{s[0], s[2]} : std::array<int, 2>{s[1], s[3]};
  } else if (pair0 != pair1) {
    corridor = pair0 ? std::array<int, 2>{s[0], s[2]} : std::array<int, 2>{s[1], s[3]};
  }
  if (corridor[0] < 0) return;
  node.kind = RoomKind::kTwoWall;
  node.pairs = {corridor};
  node.widths = {pairWidth(plane(corridor[0]), plane(corridor[1]))};
  node.centre = twoWallRoomCentre(plane(corridor[0]), plane(corridor[1]), node.axis_point);
}

}  // namespace

double WallSurfaceNode::exposedLength() const {
  double total = 0.0;
  for (const auto& [a, b] : segments) total += (b - a).norm();
  return total;
}

Eigen::AlignedBox2d AGraph::surfaceBounds() const {
  Eigen::AlignedBox2d box;  // default-constructed: empty
  for (const auto& surface : surfaces) {
    for (const auto& [a, b] : surface.segments) box.extend(a).extend(b);
  }
  return box;
}

AGraph AGraph::translated(const Eigen::Vector2d& shift) const {
  AGraph moved = *this;
  const Eigen::Vector3d shift3(shift.x(), shift.y(), 0.0);
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  T.translation() = shift3;
  for (auto& surface : moved.surfaces) {
    surface.plane = surface.plane.transformed(T);
    for (auto& [a, b] : surface.segments) a += shift, b += shift;
  }
  for (auto& wall : moved.walls) {
    wall.anchor += shift3;
    wall.centre += shift3;
  }
  for (auto& room : moved.rooms) {
    room.centre += shift;
    room.axis_point += shift;
    for (auto& vertex : room.outline) vertex += shift;
  }
  for (auto& doorway : moved.doorways) doorway.position += shift3;
  for (auto& window : moved.windows) window.position += shift3;
  for (auto& floor : moved.floors) floor.centre += shift;
  return moved;
}

Eigen::Vector2d AGraph::localOrigin() const { return localOriginOf(surfaceBounds()); }

int AGraph::findSurface(const std::string& id) const {
  for (std::size_t i = 0; i < surfaces.size(); ++i) {
    if (surfaces[i].id == id) return int(i);
  }
  return -1;
}

int AGraph::findRoom(const std::string& id) const {
  for (std::size_t i = 0; i < rooms.size(); ++i) {
    if (rooms[i].id == id) return int(i);
  }
  return -1;
}

Eigen::Vector3d wallCentre(const Plane& a, const Plane& b, const Eigen::Vector3d& anchor) {
  const Eigen::Vector3d mid = 0.5 * (a.closestPoint() + b.closestPoint());
  return mid + anchor - a.normal * a.normal.dot(anchor);
}

Eigen::Vector2d fourWallRoomCentre(const Plane& x1, const Plane& x2, const Plane& y1,
                                   const Plane& y2) {
  const Eigen::Vector3d c =
      0.5 * (x1.closestPoint() + x2.closestPoint()) + 0.5 * (y1.closestPoint() + y2.closestPoint());
  return c.head<2>();
}

Eigen::Vector2d twoWallRoomCentre(const Plane& a, const Plane& b,
                                  const Eigen::Vector2d& axis_point) {
  return wallCentre(a, b, {axis_point.x(), axis_point.y(), 0.0}).head<2>();
}

// The faces of each flight that starts or ends on `level` and rises from it: its sides, from
// the bottom edge to the top, and its high end, across the flight (docs/agraph.md).
void addFlightFaces(const Plan& plan, const Level& level, AGraph& graph) {
  for (const auto& from : plan.levels) {
    for (const auto& stair : from.stairs) {
      const Level* to = plan.findLevel(stair.to);
      if (to == nullptr || (&from != &level && to != &level)) continue;
      const StairGeometry g = computeStairGeometry(stair, from, *to);
      const double floor = std::min(g.z_start, g.z_end);
      if (std::abs(floor - level.elevation) > 1e-9) continue;  // it rises from the other level
      const Eigen::Vector2d start = stair.start, end = stair.start + g.run * g.axis;
      const Eigen::Vector2d high = g.z_end > g.z_start ? end : start;
      const Eigen::Vector2d outwards = g.z_end > g.z_start ? g.axis : Eigen::Vector2d(-g.axis);
      const Eigen::Vector2d half = 0.5 * stair.width * g.left_normal;
      auto add = [&](const std::string& name, const Eigen::Vector2d& normal,
                     const Eigen::Vector2d& a, const Eigen::Vector2d& b) {
        WallSurfaceNode surface;
        surface.id = stair.id + ":" + name;
        surface.stair = stair.id;
        surface.level = level.id;
        surface.side = name == "stair-right" ? -1 : +1;
        surface.plane = Plane::throughPoint({normal.x(), normal.y(), 0.0}, {a.x(), a.y(), floor});
        surface.axis =
            std::abs(normal.x()) >= std::abs(normal.y()) ? SurfaceAxis::kX : SurfaceAxis::kY;
        surface.segments.emplace_back(a, b);
        surface.z_min = floor;
        surface.z_max = floor + g.rise();
        graph.surfaces.push_back(std::move(surface));
      };
      add("stair-left", g.left_normal, start + half, end + half);
      add("stair-right", -g.left_normal, start - half, end - half);
      add("stair-end", outwards, high - half, high + half);
    }
  }
}

AGraph buildAGraph(const Plan& plan, const AGraphOptions& options) {
  AGraph graph;
  graph.plan_name = plan.name;
  for (const auto& level : plan.levels) {
    const LevelGeometry geometry = computeLevelGeometry(level, options.geometry);
    FloorNode floor;
    floor.id = level.id;
    floor.elevation = level.elevation;

    for (const auto& g : geometry.walls) {
      WallNode wall;
      wall.id = g.wall->id;
      wall.level = level.id;
      wall.thickness = g.wall->thickness;
      wall.length = g.length;
      wall.column = g.column;
      for (int side : {+1, -1}) {
        const WallFace& face = g.face(side);
        WallSurfaceNode surface;
        surface.id = g.wall->id + (side > 0 ? ":left" : ":right");
        surface.wall = g.wall->id;
        surface.level = level.id;
        surface.side = side;
        surface.plane = face.plane;
        surface.axis = std::abs(face.plane.normal.x()) >= std::abs(face.plane.normal.y())
                           ? SurfaceAxis::kX
                           : SurfaceAxis::kY;
        for (const auto& piece : face.exposed) {
          surface.segments.emplace_back(g.facePointAt(side, piece.lo),
                                        g.facePointAt(side, piece.hi));
        }
        surface.z_min = face.z_min;
        surface.z_max = face.z_max;
        (side > 0 ? wall.left_surface : wall.right_surface) = int(graph.surfaces.size());
        graph.surfaces.push_back(std::move(surface));
      }
      const Eigen::Vector2d middle = g.pointAt(0.5 * g.length);
      wall.anchor = {middle.x(), middle.y(),
                     level.elevation + 0.5 * (g.wall->base + g.wall->height)};
      wall.centre = wallCentre(graph.surfaces[wall.left_surface].plane,
                               graph.surfaces[wall.right_surface].plane, wall.anchor);
      graph.walls.push_back(wall);
    }

    const int floor_index = int(graph.floors.size());
    for (const auto& room : level.rooms) {
      RoomNode node;
      node.id = room.id;
      node.name = room.name;
      node.level = level.id;
      node.outline = room.outline;
      node.surfaces = edgeSurfaces(room, geometry, graph);
      node.floor = floor_index;
      classifyRoom(node, graph, options);
      floor.rooms.push_back(int(graph.rooms.size()));
      floor.centre += node.centre;
      graph.rooms.push_back(std::move(node));
    }
    if (!floor.rooms.empty()) floor.centre /= double(floor.rooms.size());

    for (const auto& door : level.doors) {
      DoorwayNode node;
      node.id = door.id;
      node.wall = door.wall;
      node.level = level.id;
      node.width = door.width;
      node.height = door.height;
      const Eigen::Vector2d c = doorCentre(level, door);
      node.position = {c.x(), c.y(), level.elevation + level.findWall(door.wall)->base};
      for (const auto& room_id : door.rooms) {
        const int index = graph.findRoom(room_id);
        if (index >= 0 &&
            std::find(node.rooms.begin(), node.rooms.end(), index) == node.rooms.end()) {
          node.rooms.push_back(index);
        }
      }
      graph.doorways.push_back(std::move(node));
    }
    for (const auto& window : level.windows) {
      const Wall* wall = level.findWall(window.wall);
      const Eigen::Vector2d c =
          wall->start + window.offset * (wall->end - wall->start).normalized();
      graph.windows.push_back({window.id, window.wall, level.id,
                               Eigen::Vector3d(c.x(), c.y(), level.elevation + wall->base),
                               window.width, window.sill, window.height});
    }
    addFlightFaces(plan, level, graph);
    graph.floors.push_back(std::move(floor));
  }
  return graph;
}

const char* toString(RoomKind kind) {
  switch (kind) {
    case RoomKind::kFourWall:
      return "four_wall";
    case RoomKind::kTwoWall:
      return "two_wall";
    case RoomKind::kPolygon:
      return "polygon";
  }
  return "?";
}

const char* toString(SurfaceAxis axis) { return axis == SurfaceAxis::kX ? "x" : "y"; }

}  // namespace isg::bim
