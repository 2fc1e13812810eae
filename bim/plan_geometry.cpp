#include "bim/plan_geometry.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <unordered_map>

#include "bim/box_grid.hpp"
#include "bim/column.hpp"
#include "bim/polygon.hpp"

namespace isg::bim {

namespace {

// Walls whose axes are closer to parallel than this do not close each other's ends.
constexpr double kParallelCosine = 0.1;
// How far outside a wall's solid an endpoint may lie and still be taken as meeting it.
constexpr double kJunctionTolerance = 1e-3;
// A face that lies on another wall's side (collinear walls in a row) only touches that wall and
// is not cut by it; exposed pieces shorter than this are dropped.
constexpr double kTouchEpsilon = 1e-6;
constexpr double kMinExposed = 1e-3;

Eigen::Vector2d perpendicular(const Eigen::Vector2d& v) { return {-v.y(), v.x()}; }

// How far the end of `wall` at `point`, leaving in direction `outward`, must continue to reach
// the far side of `other`; nullopt when the end does not meet `other`.
std::optional<double> extensionInto(const Eigen::Vector2d& point, const Eigen::Vector2d& outward,
                                    const WallGeometry& other) {
  const Eigen::Vector2d& m = other.left_normal;
  const double cosine = m.dot(outward);
  if (std::abs(cosine) < kParallelCosine) return std::nullopt;
  const double half = 0.5 * other.wall->thickness;
  const double distance = distanceToSegment(point, other.wall->start, other.wall->end);
  if (distance > half + kJunctionTolerance) return std::nullopt;
  const double far_face = m.dot(other.wall->start) + (cosine > 0 ? half : -half);
  const double e = (far_face - m.dot(point)) / cosine;
  if (e <= 0.0) return std::nullopt;
  return e;
}

// The part [lo, hi] of the line origin + s·direction (s in [s0, s1]) inside a convex CCW polygon
// (Cyrus–Beck clipping); nullopt when they do not overlap.
std::optional<AxisInterval> clipLineToConvex(const Eigen::Vector2d& origin,
                                             const Eigen::Vector2d& direction, double s0, double s1,
                                             const std::vector<Eigen::Vector2d>& poly) {
  double lo = s0;
  double hi = s1;
  for (std::size_t i = 0; i < poly.size(); ++i) {
    const Eigen::Vector2d& a = poly[i];
    const Eigen::Vector2d& b = poly[(i + 1) % poly.size()];
    const Eigen::Vector2d inward = perpendicular(b - a);  // CCW: interior on the left
    const double num = inward.dot(origin - a);            // >= 0 inside
    const double den = inward.dot(direction);
    if (std::abs(den) < 1e-12) {
      // Parallel to this side: outside it, or lying on it (touching), the line is not cut.
      if (num < kTouchEpsilon * (b - a).norm()) return std::nullopt;
      continue;
    }
    const double t = -num / den;
    if (den > 0) {
      lo = std::max(lo, t);
    } else {
      hi = std::min(hi, t);
    }
    if (lo >= hi) return std::nullopt;
  }
  return AxisInterval{lo, hi};
}

// Removes `cut` from a sorted list of disjoint intervals.
void subtractInterval(std::vector<AxisInterval>& intervals, const AxisInterval& cut) {
  std::vector<AxisInterval> out;
  for (const auto& piece : intervals) {
    if (cut.hi <= piece.lo || cut.lo >= piece.hi) {
      out.push_back(piece);
      continue;
    }
    if (cut.lo - piece.lo >= kMinExposed) out.push_back({piece.lo, cut.lo});
    if (piece.hi - cut.hi >= kMinExposed) out.push_back({cut.hi, piece.hi});
  }
  intervals = std::move(out);
}

}  // namespace

std::vector<Eigen::Vector2d> WallGeometry::footprint() const {
  const double half = 0.5 * wall->thickness;
  const Eigen::Vector2d a = pointAt(-extend_start);
  const Eigen::Vector2d b = pointAt(length + extend_end);
  return {a - half * left_normal, b - half * left_normal, b + half * left_normal,
          a + half * left_normal};
}

std::vector<std::vector<Eigen::Vector2d>> WallGeometry::footprintPieces() const {
  std::vector<AxisInterval> openings = left.openings;
  openings.insert(openings.end(), right.openings.begin(), right.openings.end());
  std::sort(openings.begin(), openings.end(),
            [](const AxisInterval& a, const AxisInterval& b) { return a.lo < b.lo; });
  const double half = 0.5 * wall->thickness;
  std::vector<std::vector<Eigen::Vector2d>> pieces;
  auto piece = [&](double from, double to) {
    if (to - from < 1e-9) return;
    const Eigen::Vector2d a = pointAt(from), b = pointAt(to);
    pieces.push_back({a - half * left_normal, b - half * left_normal, b + half * left_normal,
                      a + half * left_normal});
  };
  double at = -extend_start;
  for (const AxisInterval& o : openings) {
    piece(at, o.lo);
    at = std::max(at, o.hi);
  }
  piece(at, length + extend_end);
  return pieces;
}

const WallGeometry* LevelGeometry::findWall(const std::string& wall_id) const {
  for (const auto& w : walls) {
    if (w.wall->id == wall_id) return &w;
  }
  return nullptr;
}

std::vector<RoomBoundary> LevelGeometry::boundariesOf(const std::string& room_id) const {
  std::vector<RoomBoundary> out;
  for (const auto& b : boundaries) {
    if (b.room == room_id) out.push_back(b);
  }
  return out;
}

namespace {

// Close the joints: an end that meets another wall continues to that wall's far side. Pairs of
// walls come from grids over their boxes, so that plans with thousands of walls stay
// near-linear; an end meets a wall only within half its thickness (plus the tolerance) of it.
void closeJoints(std::vector<WallGeometry>& walls) {
  std::vector<Box2> reach_boxes;
  reach_boxes.reserve(walls.size());
  for (const auto& g : walls) {
    reach_boxes.push_back(Box2::around(g.wall->start, g.wall->end)
                              .grown(0.5 * g.wall->thickness + 2 * kJunctionTolerance));
  }
  const BoxGrid reach_grid(std::move(reach_boxes));
  for (auto& g : walls) {
    const Box2 ends = Box2::around(g.wall->start, g.wall->end);
    for (int j : reach_grid.candidates(ends)) {
      const WallGeometry& other = walls[std::size_t(j)];
      if (&other == &g) continue;
      if (auto e = extensionInto(g.wall->start, -g.axis, other)) {
        g.extend_start = std::max(g.extend_start, *e);
      }
      if (auto e = extensionInto(g.wall->end, g.axis, other)) {
        g.extend_end = std::max(g.extend_end, *e);
      }
    }
  }
}

// A wall's face on `side`: its plane, its heights, the parts of it other walls' footprints do
// not cover, its doors' openings.
void buildFace(const Level& level, WallGeometry& g, int side, std::size_t i,
               const std::vector<std::vector<Eigen::Vector2d>>& cutters,
               const std::vector<Box2>& cutter_boxes, const BoxGrid& cutter_grid,
               const std::vector<const Door*>& doors) {
  WallFace& face = side > 0 ? g.left : g.right;
  face.side = side;
  const Eigen::Vector2d n2 = side * g.left_normal;
  const Eigen::Vector2d on_face = g.facePointAt(side, 0.0);
  face.plane = Plane::throughPoint({n2.x(), n2.y(), 0.0}, {on_face.x(), on_face.y(), 0.0});
  face.z_min = level.elevation + g.wall->base;
  face.z_max = level.elevation + g.wall->height;
  face.exposed = {{-g.extend_start, g.length + g.extend_end}};
  for (int j : cutter_grid.candidates(cutter_boxes[i])) {
    if (std::size_t(j) == i) continue;
    if (auto cut = clipLineToConvex(on_face, g.axis, -g.extend_start, g.length + g.extend_end,
                                    cutters[std::size_t(j)])) {
      subtractInterval(face.exposed, *cut);
    }
  }
  for (const Door* door : doors) {
    face.openings.push_back({door->offset - 0.5 * door->width, door->offset + 0.5 * door->width});
  }
  std::sort(face.openings.begin(), face.openings.end(),
            [](const AxisInterval& a, const AxisInterval& b) { return a.lo < b.lo; });
}

// The wall faces a room's outline runs along: facing into the room, near both ends of an edge,
// over enough of their exposed parts.
void roomBoundaries(const Room& room, const BoxGrid& cutter_grid, const GeometryOptions& options,
                    LevelGeometry& geometry) {
  const double min_cosine = std::cos(options.boundary_angle_deg * std::numbers::pi / 180.0);
  const auto& outline = room.outline;
  for (std::size_t e = 0; e < outline.size(); ++e) {
    const Eigen::Vector2d& a = outline[e];
    const Eigen::Vector2d& b = outline[(e + 1) % outline.size()];
    const Eigen::Vector2d inward = perpendicular((b - a).normalized());
    for (int j : cutter_grid.candidates(Box2::around(a, b).grown(options.boundary_distance))) {
      if (std::size_t(j) >= geometry.walls.size()) continue;  // a round column: no face
      const WallGeometry& g = geometry.walls[std::size_t(j)];
      for (const WallFace* face : {&g.left, &g.right}) {
        const Eigen::Vector2d n2 = face->plane.normal.head<2>();
        if (n2.dot(inward) < min_cosine) continue;
        const double da = std::abs(face->plane.signedDistance({a.x(), a.y(), 0.0}));
        const double db = std::abs(face->plane.signedDistance({b.x(), b.y(), 0.0}));
        if (da > options.boundary_distance || db > options.boundary_distance) continue;
        const double sa = (a - g.wall->start).dot(g.axis);
        const double sb = (b - g.wall->start).dot(g.axis);
        const double lo = std::min(sa, sb);
        const double hi = std::max(sa, sb);
        double overlap = 0.0;
        for (const auto& piece : face->exposed) {
          overlap += std::max(0.0, std::min(hi, piece.hi) - std::max(lo, piece.lo));
        }
        if (overlap < options.boundary_min_overlap) continue;
        geometry.boundaries.push_back(
            {room.id, int(e), g.wall->id, face->side, overlap, 0.5 * (da + db)});
      }
    }
  }
}

}  // namespace

LevelGeometry computeLevelGeometry(const Level& level, const GeometryOptions& options) {
  LevelGeometry geometry;
  auto column_walls = std::make_shared<std::vector<Wall>>();
  for (const auto& column : level.columns) {
    if (!column.round()) column_walls->push_back(columnWall(column));
  }
  geometry.column_walls = column_walls;
  geometry.walls.reserve(level.walls.size() + column_walls->size());
  std::vector<const Wall*> solids;
  for (const auto& wall : level.walls) solids.push_back(&wall);
  for (const auto& wall : *column_walls) solids.push_back(&wall);
  for (const Wall* solid : solids) {
    const Wall& wall = *solid;
    WallGeometry g;
    g.wall = &wall;
    g.column = geometry.walls.size() >= level.walls.size();
    const Eigen::Vector2d along = wall.end - wall.start;
    g.length = along.norm();
    g.axis = along / g.length;
    g.left_normal = perpendicular(g.axis);
    geometry.walls.push_back(g);
  }
  closeJoints(geometry.walls);
  std::vector<std::vector<Eigen::Vector2d>> cutters;
  std::vector<Box2> cutter_boxes;
  cutters.reserve(geometry.walls.size());
  for (const auto& g : geometry.walls) {
    cutters.push_back(g.footprint());
    cutter_boxes.push_back(Box2::around(cutters.back()).grown(kJunctionTolerance));
  }
  // Round columns hide what is behind them too; they come after every wall in the grid.
  for (const auto& column : level.columns) {
    if (!column.round()) continue;
    cutters.push_back(columnFootprint(column));
    cutter_boxes.push_back(Box2::around(cutters.back()).grown(kJunctionTolerance));
  }
  const BoxGrid cutter_grid(cutter_boxes);
  std::unordered_map<std::string, std::vector<const Door*>> doors_by_wall;
  for (const auto& door : level.doors) doors_by_wall[door.wall].push_back(&door);
  for (std::size_t i = 0; i < geometry.walls.size(); ++i) {
    auto& g = geometry.walls[i];
    for (int side : {+1, -1}) {
      buildFace(level, g, side, i, cutters, cutter_boxes, cutter_grid, doors_by_wall[g.wall->id]);
    }
  }
  for (const auto& room : level.rooms) roomBoundaries(room, cutter_grid, options, geometry);
  return geometry;
}

std::optional<std::string> roomAt(const Level& level, const Eigen::Vector2d& point) {
  for (const auto& room : level.rooms) {
    if (containsPoint(room.outline, point)) return room.id;
  }
  return std::nullopt;
}

Eigen::Vector2d doorCentre(const Level& level, const Door& door) {
  const Wall* wall = level.findWall(door.wall);
  const Eigen::Vector2d axis = (wall->end - wall->start).normalized();
  return wall->start + door.offset * axis;
}

namespace {

std::vector<Box2> roomBoxes(const Level& level) {
  std::vector<Box2> boxes;
  boxes.reserve(level.rooms.size());
  for (const auto& room : level.rooms) boxes.push_back(Box2::around(room.outline).grown(1e-9));
  return boxes;
}

}  // namespace

RoomLocator::RoomLocator(const Level& level) : level_(&level), grid_(roomBoxes(level)) {}

std::optional<std::string> RoomLocator::roomAt(const Eigen::Vector2d& point) const {
  for (int i : grid_.candidates(Box2{point, point})) {
    const Room& room = level_->rooms[std::size_t(i)];
    if (containsPoint(room.outline, point)) return room.id;
  }
  return std::nullopt;
}

std::array<std::string, 2> inferDoorRooms(const Level& level, const Door& door) {
  return inferDoorRooms(level, door, RoomLocator(level));
}

std::array<std::string, 2> inferDoorRooms(const Level& level, const Door& door,
                                          const RoomLocator& locator) {
  return inferDoorRooms(*level.findWall(door.wall), door, locator);
}

std::array<std::string, 2> inferDoorRooms(const Wall& wall, const Door& door,
                                          const RoomLocator& locator) {
  const Eigen::Vector2d axis = (wall.end - wall.start).normalized();
  const Eigen::Vector2d left = perpendicular(axis);
  const Eigen::Vector2d centre = wall.start + door.offset * axis;
  // Just beyond each face: outlines follow the inner faces, so 10 cm past a face is in the room.
  const double reach = 0.5 * wall.thickness + 0.1;
  std::array<std::string, 2> rooms;
  rooms[0] = locator.roomAt(centre + reach * left).value_or(kOutside);
  rooms[1] = locator.roomAt(centre - reach * left).value_or(kOutside);
  return rooms;
}

std::vector<WallOpening> wallOpenings(const Level& level, const std::string& wall_id) {
  std::vector<WallOpening> openings;
  for (const auto& door : level.doors) {
    if (door.wall != wall_id) continue;
    openings.push_back({door.id, &door, door.offset - 0.5 * door.width,
                        door.offset + 0.5 * door.width, 0.0, door.height});
  }
  for (const auto& window : level.windows) {
    if (window.wall != wall_id) continue;
    openings.push_back({window.id, nullptr, window.offset - 0.5 * window.width,
                        window.offset + 0.5 * window.width, window.sill,
                        window.sill + window.height});
  }
  // The parser keeps openings of one wall apart, so their starts order them.
  std::sort(openings.begin(), openings.end(),
            [](const WallOpening& a, const WallOpening& b) { return a.lo < b.lo; });
  return openings;
}

Eigen::Vector2d localOriginOf(const Eigen::AlignedBox2d& box) {
  if (box.isEmpty()) return Eigen::Vector2d::Zero();
  const Eigen::Vector2d middle = box.center();
  return {std::round(middle.x()), std::round(middle.y())};
}

}  // namespace isg::bim
