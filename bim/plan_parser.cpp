#include "bim/plan_parser.hpp"

#include <algorithm>
#include <filesystem>
#include <map>
#include <sstream>

#include "bim/plan_geometry.hpp"
#include "bim/polygon.hpp"

namespace isg::bim {

namespace {

std::string formatPoint(const Eigen::Vector2d& p) {
  return "[" + formatNumber(p.x()) + ", " + formatNumber(p.y()) + "]";
}

// Ids are unique within the whole file, whatever they name.
class IdRegistry {
 public:
  void add(const JsonNode& id_node, const std::string& id) {
    auto [it, inserted] = first_use_.emplace(id, id_node.pointer());
    if (!inserted)
      id_node.fail("duplicate id " + inQuotes(id) + " (first used at " + it->second + ")");
  }

 private:
  std::map<std::string, std::string> first_use_;
};

Wall parseWall(const JsonNode& node, const Level& level, IdRegistry& ids) {
  node.expectObject({"id", "start", "end", "thickness", "height", "base", "name"});
  Wall wall;
  const JsonNode id = node.field("id");
  wall.id = id.nonEmptyString();
  ids.add(id, wall.id);
  wall.start = node.field("start").point2();
  wall.end = node.field("end").point2();
  if ((wall.end - wall.start).norm() < 1e-6) {
    node.field("end").fail("zero-length wall: end equals start " + formatPoint(wall.start));
  }
  wall.thickness = node.field("thickness").positiveNumber();
  wall.height = level.height;
  if (auto h = node.optionalField("height")) wall.height = h->positiveNumber();
  if (auto b = node.optionalField("base")) {
    wall.base = b->nonNegativeNumber();
    if (wall.base >= wall.height) {
      b->fail("base " + formatNumber(wall.base) + " is not below the wall's top at " +
              formatNumber(wall.height));
    }
  }
  return wall;
}

Room parseRoom(const JsonNode& node, IdRegistry& ids) {
  node.expectObject({"id", "name", "outline"});
  Room room;
  const JsonNode id = node.field("id");
  room.id = id.nonEmptyString();
  if (room.id == kOutside)
    id.fail(inQuotes(kOutside) + " is reserved for the outside of the building");
  ids.add(id, room.id);
  room.name = room.id;
  if (auto name = node.optionalField("name")) room.name = name->string();
  const JsonNode outline = node.field("outline");
  const auto vertices = outline.elements();
  if (vertices.size() < 3) {
    outline.fail("an outline needs at least 3 vertices, got " + std::to_string(vertices.size()));
  }
  for (const auto& v : vertices) room.outline.push_back(v.point2());
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

// Doors are parsed after walls and rooms, whose ids they reference.
Door parseDoor(const JsonNode& node, const Level& level, IdRegistry& ids) {
  node.expectObject({"id", "wall", "offset", "width", "height", "rooms", "name"});
  Door door;
  const JsonNode id = node.field("id");
  door.id = id.nonEmptyString();
  ids.add(id, door.id);
  const JsonNode wall_node = node.field("wall");
  door.wall = wall_node.nonEmptyString();
  const Wall* wall = level.findWall(door.wall);
  if (wall == nullptr) {
    wall_node.fail("no wall " + inQuotes(door.wall) + " on level " + inQuotes(level.id));
  }
  const JsonNode offset = node.field("offset");
  door.offset = offset.number();
  door.width = node.field("width").positiveNumber();
  const JsonNode height = node.field("height");
  door.height = height.positiveNumber();

  const double length = (wall->end - wall->start).norm();
  const double lo = door.offset - 0.5 * door.width;
  const double hi = door.offset + 0.5 * door.width;
  constexpr double kEps = 1e-9;
  if (lo < -kEps || hi > length + kEps) {
    offset.fail("opening from " + formatNumber(lo) + " to " + formatNumber(hi) +
                " m along the wall does not fit inside wall " + inQuotes(wall->id) + " (length " +
                formatNumber(length) + " m)");
  }
  const double room_above_base = wall->height - wall->base;
  if (door.height > room_above_base + kEps) {
    height.fail("door is " + formatNumber(door.height) + " m high, taller than wall " +
                inQuotes(wall->id) + " (" + formatNumber(room_above_base) + " m above its base)");
  }

  if (auto rooms = node.optionalField("rooms")) {
    const auto items = rooms->elements();
    if (items.size() != 2) {
      rooms->fail("a door joins exactly 2 rooms, got " + std::to_string(items.size()));
    }
    for (std::size_t k = 0; k < 2; ++k) {
      door.rooms[k] = items[k].nonEmptyString();
      if (door.rooms[k] != kOutside && level.findRoom(door.rooms[k]) == nullptr) {
        items[k].fail("no room " + inQuotes(door.rooms[k]) + " on level " + inQuotes(level.id) +
                      " (use " + inQuotes(kOutside) + " for the outside)");
      }
    }
    if (door.rooms[0] == door.rooms[1]) {
      rooms->fail("a door joins two different rooms, got " + inQuotes(door.rooms[0]) + " twice");
    }
  }
  return door;
}

void checkDoorOverlaps(const std::vector<JsonNode>& door_nodes, const Level& level) {
  for (std::size_t i = 0; i < level.doors.size(); ++i) {
    for (std::size_t j = 0; j < i; ++j) {
      const Door& a = level.doors[i];
      const Door& b = level.doors[j];
      if (a.wall != b.wall) continue;
      const double gap = std::abs(a.offset - b.offset) - 0.5 * (a.width + b.width);
      if (gap < -1e-9) {
        door_nodes[i].field("offset").fail("opening overlaps door " + inQuotes(b.id) + " on wall " +
                                           inQuotes(a.wall));
      }
    }
  }
}

Level parseLevel(const JsonNode& node, IdRegistry& ids) {
  node.expectObject({"id", "name", "elevation", "height", "walls", "doors", "rooms"});
  Level level;
  const JsonNode id = node.field("id");
  level.id = id.nonEmptyString();
  ids.add(id, level.id);
  if (auto e = node.optionalField("elevation")) level.elevation = e->number();
  level.height = node.field("height").positiveNumber();
  for (const auto& w : node.field("walls").elements(1))
    level.walls.push_back(parseWall(w, level, ids));
  if (auto rooms = node.optionalField("rooms")) {
    for (const auto& r : rooms->elements()) level.rooms.push_back(parseRoom(r, ids));
  }
  std::vector<JsonNode> door_nodes;
  if (auto doors = node.optionalField("doors")) door_nodes = doors->elements();
  for (const auto& d : door_nodes) level.doors.push_back(parseDoor(d, level, ids));
  checkDoorOverlaps(door_nodes, level);

  for (std::size_t i = 0; i < level.doors.size(); ++i) {
    Door& door = level.doors[i];
    if (!door.rooms[0].empty()) continue;
    door.rooms = inferDoorRooms(level, door);
    door.rooms_inferred = true;
    if (door.rooms[0] == door.rooms[1]) {
      door_nodes[i].warn("cannot infer the rooms this door joins: " + inQuotes(door.rooms[0]) +
                         " on both sides (give \"rooms\")");
    }
  }
  return level;
}

}  // namespace

Plan parsePlan(const JsonNode& root) {
  root.expectObject({"$schema", "format", "version", "name", "levels"});
  checkFormatAndVersion(root, kPlanFormat, kPlanVersion);
  Plan plan;
  plan.source = root.source().file;
  plan.name = std::filesystem::path(plan.source).stem().string();
  if (auto name = root.optionalField("name")) plan.name = name->string();
  IdRegistry ids;
  for (const auto& level : root.field("levels").elements(1)) {
    plan.levels.push_back(parseLevel(level, ids));
  }
  return plan;
}

Plan loadPlan(const std::string& path, Warnings* warnings) {
  const nlohmann::json document = readJsonFile(path);
  const JsonSource source{path, warnings};
  return parsePlan(JsonNode(document, "", source));
}

}  // namespace isg::bim
