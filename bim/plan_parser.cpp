#include "bim/plan_parser.hpp"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <map>
#include <numbers>
#include <optional>
#include <sstream>
#include <unordered_map>

#include "bim/box_grid.hpp"
#include "bim/limits.hpp"
#include "bim/plan_geometry.hpp"
#include "bim/plan_point.hpp"
#include "bim/polygon.hpp"
#include "bim/stairs.hpp"

namespace isg::bim {

namespace {

std::string formatPoint(const Eigen::Vector2d& p) {
  return "[" + common::formatNumber(p.x()) + ", " + common::formatNumber(p.y()) + "]";
}

// Ids are unique within the whole file, whatever they name.
class IdRegistry {
 public:
  void add(const common::JsonNode& id_node, const std::string& id) {
    auto [it, inserted] = first_use_.emplace(id, id_node.pointer());
    if (!inserted)
      id_node.fail("duplicate id " + common::inQuotes(id) + " (first used at " + it->second + ")");
  }

 private:
  std::map<std::string, std::string> first_use_;
};

// The vertical extent of a wall or column: `height` (the level's height when absent) and `base`,
// the base below the top. `what` names the element in the error ("wall", "column").
struct VerticalExtent {
  double height = 0.0;
  double base = 0.0;
};
VerticalExtent parseVerticalExtent(const common::JsonNode& node, const Level& level,
                                   const std::string& what) {
  VerticalExtent extent;
  extent.height = level.height;
  if (auto h = node.optionalField("height")) {
    extent.height = h->numberInRange(limits::kMinSize, limits::kMaxHeight);
  }
  if (auto b = node.optionalField("base")) {
    extent.base = b->numberInRange(0.0, limits::kMaxHeight);
    if (extent.base >= extent.height) {
      b->fail("base " + common::formatNumber(extent.base) + " is not below the " + what +
              "'s top at " + common::formatNumber(extent.height));
    }
  }
  return extent;
}

// An element's "ifc_guid": the IFC GlobalId it was imported from, as IFC writes one
// (IfcGloballyUniqueId: a 128-bit GUID in 22 characters of 0-9, A-Z, a-z, _ and $, the first 0-3);
// "" when not given.
std::string ifcGuidOf(const common::JsonNode& node) {
  const std::optional<common::JsonNode> field = node.optionalField("ifc_guid");
  if (!field) return "";
  const std::string guid = field->string();
  if (!isIfcGlobalId(guid)) {
    field->fail(
        "expected an IFC GlobalId: 22 characters of 0-9, A-Z, a-z, _ and $, the first "
        "0-3, not " +
        common::inQuotes(guid.substr(0, 40)));
  }
  return guid;
}

Wall parseWall(const common::JsonNode& node, const Level& level, IdRegistry& ids) {
  node.expectObject({"id", "start", "end", "thickness", "height", "base", "name", "ifc_guid"});
  Wall wall;
  const common::JsonNode id = node.field("id");
  wall.id = id.identifier();
  ids.add(id, wall.id);
  wall.start = planPoint(node.field("start"));
  wall.end = planPoint(node.field("end"));
  if ((wall.end - wall.start).norm() < limits::kMinSize) {
    node.field("end").fail("zero-length wall: end equals start " + formatPoint(wall.start));
  }
  wall.thickness = node.field("thickness").numberInRange(limits::kMinSize, limits::kMaxThickness);
  if (auto name = node.optionalField("name")) wall.name = name->text();
  wall.ifc_guid = ifcGuidOf(node);
  const VerticalExtent extent = parseVerticalExtent(node, level, "wall");
  wall.height = extent.height;
  wall.base = extent.base;
  return wall;
}

Room parseRoom(const common::JsonNode& node, IdRegistry& ids) {
  node.expectObject({"id", "name", "outline", "ifc_guid"});
  Room room;
  const common::JsonNode id = node.field("id");
  room.id = id.identifier();
  if (room.id == kOutside)
    id.fail(common::inQuotes(kOutside) + " is reserved for the outside of the building");
  ids.add(id, room.id);
  room.name = room.id;
  if (auto name = node.optionalField("name")) room.name = name->text();
  room.ifc_guid = ifcGuidOf(node);
  const common::JsonNode outline = node.field("outline");
  const auto vertices = outline.elements(0, limits::kMaxOutlineVertices, "vertices");
  if (vertices.size() < 3) {
    outline.fail("an outline needs at least 3 vertices, got " + std::to_string(vertices.size()));
  }
  for (const auto& v : vertices) room.outline.push_back(planPoint(v));
  for (std::size_t i = 0; i < room.outline.size(); ++i) {
    const auto& a = room.outline[i];
    const auto& b = room.outline[(i + 1) % room.outline.size()];
    if ((b - a).norm() < 1e-6) {
      outline.fail("zero-length edge " + std::to_string(i) + ": vertex " + std::to_string(i) +
                   " repeats at " + formatPoint(a));
    }
  }
  if (auto crossing = findSelfIntersection(room.outline)) {
    const auto [i, j] = *crossing;
    const auto n = room.outline.size();
    outline.fail("self-intersecting outline: edge " + std::to_string(i) + " " +
                 formatPoint(room.outline[i]) + "→" + formatPoint(room.outline[(i + 1) % n]) +
                 " meets edge " + std::to_string(j) + " " + formatPoint(room.outline[j]) + "→" +
                 formatPoint(room.outline[(j + 1) % n]));
  }
  const double area = signedArea(room.outline);
  if (std::abs(area) < 1e-6) outline.fail("degenerate outline: zero area");
  if (area < 0) {
    outline.warn("outline is clockwise; taken in counter-clockwise order");
    std::reverse(room.outline.begin(), room.outline.end());
  }
  return room;
}

// A column: `size` [width, depth] (a rectangle turned by `yaw`) or `diameter` (round), exactly
// one of them.
Column parseColumn(const common::JsonNode& node, const Level& level, IdRegistry& ids) {
  node.expectObject(
      {"id", "center", "size", "diameter", "yaw", "height", "base", "name", "ifc_guid"});
  Column column;
  const common::JsonNode id = node.field("id");
  column.id = id.identifier();
  ids.add(id, column.id);
  column.center = planPoint(node.field("center"));
  const auto size = node.optionalField("size");
  const auto diameter = node.optionalField("diameter");
  if (size && diameter) diameter->fail("a column has a size or a diameter, not both");
  if (!size && !diameter) {
    node.fail("a column needs \"size\": [width, depth] (rectangular) or \"diameter\" (round)");
  }
  if (size) {
    const auto extents = size->elements(2, 2, "extents");
    column.size = {extents[0].numberInRange(limits::kMinSize, limits::kMaxThickness),
                   extents[1].numberInRange(limits::kMinSize, limits::kMaxThickness)};
    if (auto yaw = node.optionalField("yaw")) column.yaw = yaw->numberInRange(-100.0, 100.0);
  } else {
    column.shape = Column::Shape::kRound;
    const double d = diameter->numberInRange(limits::kMinSize, limits::kMaxThickness);
    column.size = {d, d};
    if (auto yaw = node.optionalField("yaw")) yaw->fail("a round column has no yaw");
  }
  if (auto name = node.optionalField("name")) column.name = name->text();
  column.ifc_guid = ifcGuidOf(node);
  const VerticalExtent extent = parseVerticalExtent(node, level, "column");
  column.height = extent.height;
  column.base = extent.base;
  return column;
}

// Doors are parsed after walls and rooms, whose ids they reference.
// Walls and rooms of a level by id, so that checking thousands of doors stays linear.
struct LevelIndex {
  std::unordered_map<std::string, const Wall*> walls;
  std::unordered_map<std::string, const Room*> rooms;

  explicit LevelIndex(const Level& level) {
    for (const auto& w : level.walls) walls.emplace(w.id, &w);
    for (const auto& r : level.rooms) rooms.emplace(r.id, &r);
  }
};

// The wall an opening names, or an error at `wall_node`.
const Wall& openingWall(const common::JsonNode& wall_node, const std::string& wall_id,
                        const Level& level, const LevelIndex& index) {
  const auto found = index.walls.find(wall_id);
  if (found == index.walls.end()) {
    wall_node.fail("no wall " + common::inQuotes(wall_id) + " on level " +
                   common::inQuotes(level.id));
  }
  return *found->second;
}

// An opening [offset − width/2, offset + width/2] must lie within its wall's axis.
void checkOpeningFits(const common::JsonNode& offset_node, double offset, double width,
                      const Wall& wall) {
  const double length = (wall.end - wall.start).norm();
  const double lo = offset - 0.5 * width;
  const double hi = offset + 0.5 * width;
  constexpr double kEps = 1e-9;
  if (lo < -kEps || hi > length + kEps) {
    offset_node.fail("opening from " + common::formatNumber(lo) + " to " +
                     common::formatNumber(hi) + " m along the wall does not fit inside wall " +
                     common::inQuotes(wall.id) + " (length " + common::formatNumber(length) +
                     " m)");
  }
}

Window parseWindow(const common::JsonNode& node, const Level& level, const LevelIndex& index,
                   IdRegistry& ids) {
  node.expectObject({"id", "wall", "offset", "width", "sill", "height", "name", "ifc_guid"});
  Window window;
  const common::JsonNode id = node.field("id");
  window.id = id.identifier();
  ids.add(id, window.id);
  if (auto name = node.optionalField("name")) window.name = name->text();
  window.ifc_guid = ifcGuidOf(node);
  const common::JsonNode wall_node = node.field("wall");
  window.wall = wall_node.nonEmptyString();
  const Wall& wall = openingWall(wall_node, window.wall, level, index);
  const common::JsonNode offset = node.field("offset");
  window.offset = offset.number();
  window.width = node.field("width").numberInRange(limits::kMinSize, limits::kMaxLevelExtent);
  window.sill = node.field("sill").numberInRange(0.0, limits::kMaxHeight);
  const common::JsonNode height = node.field("height");
  window.height = height.numberInRange(limits::kMinSize, limits::kMaxHeight);
  checkOpeningFits(offset, window.offset, window.width, wall);
  const double room_above_base = wall.height - wall.base;
  if (window.sill + window.height > room_above_base + 1e-9) {
    height.fail("window reaches " + common::formatNumber(window.sill + window.height) +
                " m above the wall's base, above the top of wall " + common::inQuotes(wall.id) +
                " (" + common::formatNumber(room_above_base) + " m above its base)");
  }
  return window;
}

Door parseDoor(const common::JsonNode& node, const Level& level, const LevelIndex& index,
               IdRegistry& ids) {
  node.expectObject({"id", "wall", "offset", "width", "height", "rooms", "name", "ifc_guid"});
  Door door;
  const common::JsonNode id = node.field("id");
  door.id = id.identifier();
  ids.add(id, door.id);
  if (auto name = node.optionalField("name")) door.name = name->text();
  door.ifc_guid = ifcGuidOf(node);
  const common::JsonNode wall_node = node.field("wall");
  door.wall = wall_node.nonEmptyString();
  const Wall& wall = openingWall(wall_node, door.wall, level, index);
  const common::JsonNode offset = node.field("offset");
  door.offset = offset.number();
  door.width = node.field("width").numberInRange(limits::kMinSize, limits::kMaxLevelExtent);
  const common::JsonNode height = node.field("height");
  door.height = height.numberInRange(limits::kMinSize, limits::kMaxHeight);

  checkOpeningFits(offset, door.offset, door.width, wall);
  constexpr double kEps = 1e-9;
  const double room_above_base = wall.height - wall.base;
  if (door.height > room_above_base + kEps) {
    height.fail("door is " + common::formatNumber(door.height) + " m high, taller than wall " +
                common::inQuotes(wall.id) + " (" + common::formatNumber(room_above_base) +
                " m above its base)");
  }

  if (auto rooms = node.optionalField("rooms")) {
    const auto items = rooms->elements();
    if (items.size() != 2) {
      rooms->fail("a door joins exactly 2 rooms, got " + std::to_string(items.size()));
    }
    for (std::size_t k = 0; k < 2; ++k) {
      door.rooms[k] = items[k].identifier();
      if (door.rooms[k] != kOutside && !index.rooms.contains(door.rooms[k])) {
        items[k].fail("no room " + common::inQuotes(door.rooms[k]) + " on level " +
                      common::inQuotes(level.id) + " (use " + common::inQuotes(kOutside) +
                      " for the outside)");
      }
    }
    if (door.rooms[0] == door.rooms[1]) {
      rooms->fail("a door joins two different rooms, got " + common::inQuotes(door.rooms[0]) +
                  " twice");
    }
  }
  return door;
}

// A flight's own fields; what it means across levels is checked once every level is read
// (checkStairs).
Stair parseStair(const common::JsonNode& node, IdRegistry& ids) {
  node.expectObject({"id", "start", "end", "width", "to", "name"});
  Stair stair;
  const common::JsonNode id = node.field("id");
  stair.id = id.identifier();
  ids.add(id, stair.id);
  if (auto name = node.optionalField("name")) stair.name = name->text();
  stair.start = planPoint(node.field("start"));
  stair.end = planPoint(node.field("end"));
  if ((stair.end - stair.start).norm() < limits::kMinSize) {
    node.field("end").fail("zero-length flight: end equals start " + formatPoint(stair.start));
  }
  const common::JsonNode width = node.field("width");
  stair.width = width.numberInRange(limits::kMinSize, limits::kMaxLevelExtent);
  if (stair.width < kMinStairWidth) {
    width.fail("a flight " + common::formatNumber(stair.width) +
               " m wide is too narrow for a legged robot (at least " +
               common::formatNumber(kMinStairWidth) + " m; docs/formats.md, Stairs)");
  }
  stair.to = node.field("to").identifier();
  return stair;
}

// Openings (doors, then windows) are compared with the earlier openings of their own wall only;
// a wall's openings sorted by where they start make the check O(n log n) however many a level
// has. Two openings of one wall may not overlap along it, whatever their heights: a transom over a
// door is part of the door's opening.
struct Opening {
  const common::JsonNode* node;
  std::string kind;  // "door" or "window"
  std::string id;
  std::string wall;
  double lo = 0.0, hi = 0.0;
};

void checkOpeningOverlaps(const std::vector<Opening>& openings) {
  std::map<std::string, std::vector<std::size_t>> by_wall;
  for (std::size_t i = 0; i < openings.size(); ++i) by_wall[openings[i].wall].push_back(i);
  std::optional<std::pair<std::size_t, std::size_t>> first;  // (later opening, earlier opening)
  for (auto& [wall, indices] : by_wall) {
    auto lo = [&](std::size_t i) { return openings[i].lo; };
    auto hi = [&](std::size_t i) { return openings[i].hi; };
    std::sort(indices.begin(), indices.end(), [&](std::size_t a, std::size_t b) {
      return lo(a) < lo(b) || (lo(a) == lo(b) && a < b);
    });
    // Sweep: every earlier-starting opening still open when this one starts overlaps it.
    std::vector<std::size_t> open;
    // The sweep stops at a wall's first overlap, so it stays linear even when every opening of a
    // wall overlaps every other; the message names the earliest such pair in file order.
    bool found = false;
    for (std::size_t i : indices) {
      std::erase_if(open, [&](std::size_t j) { return hi(j) - lo(i) <= 1e-9; });
      for (std::size_t j : open) {
        const auto pair = std::make_pair(std::max(i, j), std::min(i, j));
        if (!first || pair < *first) first = pair;
        found = true;
      }
      if (found) break;
      open.push_back(i);
    }
  }
  if (first) {
    const Opening& a = openings[first->first];
    const Opening& b = openings[first->second];
    a.node->field("offset").fail("opening overlaps " + b.kind + " " + common::inQuotes(b.id) +
                                 " on wall " + common::inQuotes(a.wall));
  }
}

// The walls and outlines of a level must fit in a square of limits::kMaxLevelExtent: the route
// grid and the world are built over that square.
void checkLevelExtent(const common::JsonNode& node, const Level& level) {
  std::vector<Eigen::Vector2d> points;
  for (const auto& w : level.walls) {
    points.push_back(w.start);
    points.push_back(w.end);
  }
  for (const auto& r : level.rooms) points.insert(points.end(), r.outline.begin(), r.outline.end());
  for (const auto& c : level.columns) points.push_back(c.center);
  const Box2 box = Box2::around(points);
  const Eigen::Vector2d size = box.hi - box.lo;
  if (size.maxCoeff() > limits::kMaxLevelExtent) {
    node.fail("level " + common::inQuotes(level.id) + " spans " + common::formatNumber(size.x()) +
              " m × " + common::formatNumber(size.y()) + " m; at most " +
              common::formatNumber(limits::kMaxLevelExtent) +
              " m on a side is supported (docs/formats.md, Limits)");
  }
}

Level parseLevel(const common::JsonNode& node, IdRegistry& ids) {
  node.expectObject({"id", "name", "ifc_guid", "elevation", "height", "walls", "doors", "windows",
                     "rooms", "stairs", "columns"});
  Level level;
  const common::JsonNode id = node.field("id");
  level.id = id.identifier();
  ids.add(id, level.id);
  if (auto name = node.optionalField("name")) level.name = name->text();
  level.ifc_guid = ifcGuidOf(node);
  if (auto e = node.optionalField("elevation")) {
    level.elevation = e->numberInRange(-limits::kMaxCoordinate, limits::kMaxCoordinate);
  }
  level.height = node.field("height").numberInRange(limits::kMinSize, limits::kMaxHeight);
  // A level of columns alone (an open floor's shell) needs no wall.
  const auto columns = node.optionalField("columns");
  std::vector<common::JsonNode> column_nodes;
  if (columns) column_nodes = columns->elements(0, limits::kMaxWallsPerLevel, "columns");
  const std::size_t min_walls = column_nodes.empty() ? 1 : 0;
  for (const auto& w :
       node.field("walls").elements(min_walls, limits::kMaxWallsPerLevel, "walls")) {
    level.walls.push_back(parseWall(w, level, ids));
  }
  for (const auto& c : column_nodes) level.columns.push_back(parseColumn(c, level, ids));
  if (auto rooms = node.optionalField("rooms")) {
    std::size_t vertices = 0;
    for (const auto& r : rooms->elements(0, limits::kMaxRoomsPerLevel, "rooms")) {
      level.rooms.push_back(parseRoom(r, ids));
      vertices += level.rooms.back().outline.size();
      if (vertices > limits::kMaxVerticesPerLevel) {
        r.field("outline").fail("the level's outlines have " + std::to_string(vertices) +
                                " vertices so far; at most " +
                                std::to_string(limits::kMaxVerticesPerLevel) +
                                " per level are supported (docs/formats.md, Limits)");
      }
    }
  }
  checkLevelExtent(node, level);

  std::vector<common::JsonNode> door_nodes;
  if (auto doors = node.optionalField("doors")) {
    door_nodes = doors->elements(0, limits::kMaxDoorsPerLevel, "doors");
  }
  const LevelIndex index(level);
  for (const auto& d : door_nodes) level.doors.push_back(parseDoor(d, level, index, ids));
  std::vector<common::JsonNode> window_nodes;
  if (auto windows = node.optionalField("windows")) {
    window_nodes = windows->elements(0, limits::kMaxDoorsPerLevel, "windows");
  }
  for (const auto& w : window_nodes) level.windows.push_back(parseWindow(w, level, index, ids));
  std::vector<Opening> openings;
  for (std::size_t i = 0; i < level.doors.size(); ++i) {
    const Door& d = level.doors[i];
    openings.push_back(
        {&door_nodes[i], "door", d.id, d.wall, d.offset - 0.5 * d.width, d.offset + 0.5 * d.width});
  }
  for (std::size_t i = 0; i < level.windows.size(); ++i) {
    const Window& w = level.windows[i];
    openings.push_back({&window_nodes[i], "window", w.id, w.wall, w.offset - 0.5 * w.width,
                        w.offset + 0.5 * w.width});
  }
  checkOpeningOverlaps(openings);
  if (auto stairs = node.optionalField("stairs")) {
    for (const auto& st : stairs->elements(0, limits::kMaxStairsPerLevel, "stairs")) {
      level.stairs.push_back(parseStair(st, ids));
    }
  }

  const RoomLocator rooms(level);
  for (std::size_t i = 0; i < level.doors.size(); ++i) {
    Door& door = level.doors[i];
    if (!door.rooms[0].empty()) continue;
    door.rooms = inferDoorRooms(*index.walls.at(door.wall), door, rooms);
    door.rooms_inferred = true;
    if (door.rooms[0] == door.rooms[1]) {
      door_nodes[i].warn("cannot infer the rooms this door joins: " +
                         common::inQuotes(door.rooms[0]) + " on both sides (give \"rooms\")");
    }
  }
  return level;
}

// Whether `point` lies on a level: in (or within 5 cm of) one of its rooms, or, on a level without
// rooms, within the box of its walls.
bool onLevel(const Level& level, const Eigen::Vector2d& point) {
  constexpr double kTolerance = 0.05;
  if (level.rooms.empty()) {
    std::vector<Eigen::Vector2d> corners;
    for (const auto& w : level.walls) {
      corners.push_back(w.start);
      corners.push_back(w.end);
    }
    return Box2::around(corners).grown(kTolerance).contains(point);
  }
  for (const auto& room : level.rooms) {
    if (containsPoint(room.outline, point)) return true;
    for (std::size_t i = 0; i < room.outline.size(); ++i) {
      const auto& a = room.outline[i];
      const auto& b = room.outline[(i + 1) % room.outline.size()];
      if (distanceToSegment(point, a, b) <= kTolerance) return true;
    }
  }
  return false;
}

std::string slopeText(double slope) {
  return common::formatNumber(std::round(std::atan(slope) * 1800.0 / std::numbers::pi) / 10.0) +
         "°";
}

// The flights of a plan whose `to` names another level at another elevation, each with its
// levels and geometry, and per level the flights that start or end there (in file order): each
// flight is compared with the walls (through a grid of their boxes) and the flights of its own
// two levels only, so that checking stays near-linear however many flights and walls a plan has.
// A flight whose `to` is wrong is left out here and reported at its own pointer.
class FlightIndex {
 public:
  struct Flight {
    const Stair* stair;
    const Level* from;
    const Level* to;
    StairGeometry geometry;
    // Its footprint on `level`: the steps on its lower level, the stairwell on its upper one.
    std::vector<Eigen::Vector2d> footprintOn(const Level& level) const {
      return std::min(from->elevation, to->elevation) == level.elevation
                 ? geometry.footprint()
                 : geometry.openingFootprint();
    }
  };

  explicit FlightIndex(const Plan& plan) {
    for (std::size_t i = 0; i < plan.levels.size(); ++i) level_index_[&plan.levels[i]] = i;
    by_level_.resize(plan.levels.size());
    for (const auto& from : plan.levels) {
      for (const auto& stair : from.stairs) {
        const Level* to = plan.findLevel(stair.to);
        if (to == nullptr || to == &from ||
            std::abs(to->elevation - from.elevation) < limits::kMinSize) {
          continue;
        }
        flights_.push_back({&stair, &from, to, computeStairGeometry(stair, from, *to)});
      }
    }
    for (const auto& flight : flights_) {
      by_level_[level_index_.at(flight.from)].push_back(&flight);
      by_level_[level_index_.at(flight.to)].push_back(&flight);
    }
  }

  const std::vector<const Flight*>& on(const Level& level) const {
    return by_level_[level_index_.at(&level)];
  }

  // A grid over the boxes of the level's walls, built the first time it is asked for.
  const BoxGrid& wallsOf(const Level& level) {
    const std::size_t i = level_index_.at(&level);
    auto found = wall_grids_.find(i);
    if (found != wall_grids_.end()) return found->second;
    std::vector<Box2> boxes;
    for (const auto& wall : level.walls) boxes.push_back(Box2::around(wallRectangle(wall)));
    return wall_grids_.emplace(i, BoxGrid(std::move(boxes))).first->second;
  }

 private:
  std::vector<Flight> flights_;  // never resized after construction: by_level_ points into it
  std::map<const Level*, std::size_t> level_index_;
  std::vector<std::vector<const Flight*>> by_level_;
  std::map<std::size_t, BoxGrid> wall_grids_;
};

// A flight joins two neighbouring levels at different elevations, within the slope and clear of
// the walls and the other flights of both.
void checkStair(const common::JsonNode& node, const Plan& plan, const Level& from,
                const Stair& stair, FlightIndex& flights) {
  const common::JsonNode to_node = node.field("to");
  const Level* to = plan.findLevel(stair.to);
  if (to == nullptr) to_node.fail("no level " + common::inQuotes(stair.to));
  if (to == &from) to_node.fail("a flight leads to another level, not to its own");
  const double lo = std::min(from.elevation, to->elevation);
  const double hi = std::max(from.elevation, to->elevation);
  if (hi - lo < limits::kMinSize) {
    to_node.fail("level " + common::inQuotes(to->id) + " is at the same elevation as level " +
                 common::inQuotes(from.id) + " (" + common::formatNumber(from.elevation) +
                 " m): a flight joins levels at different heights");
  }
  for (const auto& other : plan.levels) {
    if (other.elevation > lo + 1e-9 && other.elevation < hi - 1e-9) {
      to_node.fail("level " + common::inQuotes(other.id) + " lies between " +
                   common::inQuotes(from.id) + " and " + common::inQuotes(to->id) +
                   ": a flight joins neighbouring levels");
    }
  }
  const StairGeometry g = computeStairGeometry(stair, from, *to);
  if (g.slope() > kMaxStairSlope + 1e-9) {
    const double needed = g.rise() / kMaxStairSlope;
    node.field("end").fail(
        "the flight rises " + common::formatNumber(g.rise()) + " m over " +
        common::formatNumber(g.run) + " m (" + slopeText(g.slope()) +
        "), steeper than a legged robot climbs (at most " + slopeText(kMaxStairSlope) +
        ": a rise of " + common::formatNumber(kMaxStepRise) + " m per " +
        common::formatNumber(kMaxStepRise / kMaxStairSlope) +
        " m going); it needs a run of at least " + common::formatNumber(needed) + " m");
  }
  const Level& bottom = from.elevation < to->elevation ? from : *to;
  const Level& top = from.elevation < to->elevation ? *to : from;
  const Eigen::Vector2d bottom_edge = &bottom == &from ? stair.start : stair.end;
  const Eigen::Vector2d top_edge = &top == &from ? stair.start : stair.end;
  if (!onLevel(bottom, bottom_edge)) {
    node.field(&bottom == &from ? "start" : "end")
        .fail("the flight's bottom edge " + formatPoint(bottom_edge) + " is in no room of level " +
              common::inQuotes(bottom.id));
  }
  if (!onLevel(top, top_edge)) {
    node.field(&top == &from ? "start" : "end")
        .fail("the flight's top edge " + formatPoint(top_edge) + " is in no room of level " +
              common::inQuotes(top.id));
  }
  // On the lower level the steps stand on the whole footprint; on the upper one the stairwell
  // is open over its upper part. Walls and other flights must keep clear of both.
  constexpr double kTouch = 1e-3;  // flights may touch walls and each other, not overlap them
  for (const Level* level : {&from, to}) {
    const auto footprint = level == &bottom ? g.footprint() : g.openingFootprint();
    const Box2 box = Box2::around(footprint);
    const BoxGrid& walls = flights.wallsOf(*level);
    for (const int w : walls.candidates(box)) {
      const Wall& wall = level->walls[std::size_t(w)];
      if (convexPolygonsOverlap(footprint, wallRectangle(wall), kTouch)) {
        node.fail("the flight runs into wall " + common::inQuotes(wall.id) + " of level " +
                  common::inQuotes(level->id) + (level == &bottom ? "" : ", over its stairwell") +
                  ": it must be clear of the walls of both its levels");
      }
    }
    for (const auto* other : flights.on(*level)) {
      if (other->stair == &stair) continue;
      if (convexPolygonsOverlap(footprint, other->footprintOn(*level), kTouch)) {
        node.fail("the flight overlaps flight " + common::inQuotes(other->stair->id) +
                  " on level " + common::inQuotes(level->id) +
                  " (one flight is declared once, on either of its levels)");
      }
    }
  }
}

// Stairs name other levels, so they are checked once all levels are read.
void checkStairs(const common::JsonNode& root, const Plan& plan) {
  FlightIndex flights(plan);
  const auto level_nodes = root.field("levels").elements();
  for (std::size_t i = 0; i < plan.levels.size(); ++i) {
    const Level& level = plan.levels[i];
    if (level.stairs.empty()) continue;
    const auto stair_nodes = level_nodes[i].field("stairs").elements();
    for (std::size_t k = 0; k < level.stairs.size(); ++k) {
      checkStair(stair_nodes[k], plan, level, level.stairs[k], flights);
    }
  }
}

}  // namespace

Plan parsePlan(const common::JsonNode& root) {
  root.expectObject({"$schema", "format", "version", "name", "imported_from", "levels"});
  common::checkFormatAndVersion(root, kPlanFormat, kPlanVersion);
  Plan plan;
  plan.source = root.source().file;
  plan.name = std::filesystem::path(plan.source).stem().string();
  if (auto name = root.optionalField("name")) plan.name = name->text();
  // Where an imported plan came from (isg import): text only, for the reader.
  if (auto imported = root.optionalField("imported_from")) {
    imported->expectObject({"file", "schema", "application"});
    ImportedFrom& from = plan.imported_from.emplace();
    if (auto file = imported->optionalField("file")) from.file = file->text();
    if (auto schema = imported->optionalField("schema")) from.schema = schema->text();
    if (auto application = imported->optionalField("application"))
      from.application = application->text();
  }
  IdRegistry ids;
  for (const auto& level : root.field("levels").elements(1, limits::kMaxLevels, "levels")) {
    plan.levels.push_back(parseLevel(level, ids));
  }
  checkStairs(root, plan);
  return plan;
}

Plan loadPlan(const std::string& path, common::Warnings* warnings) {
  const nlohmann::json document = common::readJsonFile(path);
  const common::JsonSource source{path, warnings};
  return parsePlan(common::JsonNode(document, "", source));
}

}  // namespace isg::bim
