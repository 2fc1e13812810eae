#include "raster/raster_plan.hpp"

#include <Eigen/Geometry>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <set>

#include "bim/free_space_rooms.hpp"
#include "bim/limits.hpp"
#include "bim/plan_geometry.hpp"
#include "bim/plan_json.hpp"
#include "bim/plan_parser.hpp"
#include "common/input_error.hpp"
#include "common/json_reader.hpp"

namespace isg::raster {
namespace {

using bim::Column;
using bim::Door;
using bim::Level;
using bim::Plan;
using bim::Room;
using bim::Wall;

}  // namespace

void checkImageExtent(long long width, long long height, const std::string& file,
                      const RasterPlanOptions& options) {
  if (!(options.resolution > 0.0) || options.resolution > 10.0) {
    throw common::InputError(file, "", "the resolution must be above 0 and at most 10 m a pixel");
  }
  const double width_m = double(width) * options.resolution,
               height_m = double(height) * options.resolution;
  if (std::max(width_m, height_m) > bim::limits::kMaxLevelExtent) {
    throw common::InputError(
        file, "",
        "the image (" + std::to_string(width) + " × " + std::to_string(height) +
            " pixels) covers " + std::to_string(std::llround(width_m)) + " m × " +
            std::to_string(std::llround(height_m)) +
            " m at this resolution; a level fits in 1000 m × 1000 m (docs/formats.md, Limits): "
            "is the resolution in metres a pixel?");
  }
  if (!(options.height > 0.0) || options.height > 100.0) {
    throw common::InputError(file, "", "the wall height must lie in (0, 100] m");
  }
}

namespace {

// Walls W1 …, columns C1 …, in the order traced.
std::vector<std::string> tracedIds(const RasterWalls& traced, int& walls, int& columns) {
  std::vector<std::string> id_of(traced.walls.size());
  walls = 0, columns = 0;
  for (std::size_t k = 0; k < traced.walls.size(); ++k) {
    id_of[k] = traced.walls[k].kind != RasterWall::Kind::kWall ? "C" + std::to_string(++columns)
                                                               : "W" + std::to_string(++walls);
  }
  return id_of;
}

// A compact blob: a column, rectangular along the traced axis or round (its diameter the traced
// thickness).
Column tracedColumn(const RasterWall& traced_wall, const std::string& id,
                    const Eigen::Vector2d& start, const Eigen::Vector2d& end, double thickness,
                    double height) {
  Column column;
  column.id = id;
  column.center = 0.5 * (start + end);
  column.height = height;
  if (traced_wall.kind == RasterWall::Kind::kRoundColumn) {
    column.shape = Column::Shape::kRound;
    column.size = {thickness, thickness};
  } else {
    const Eigen::Vector2d along = end - start;
    column.size = {std::clamp(along.norm(), 0.001, 10.0), thickness};
    column.yaw = std::atan2(along.y(), along.x());
  }
  return column;
}

// The traced walls and columns placed in the plan: the image's bottom-left corner at `origin`,
// turned by `yaw` about it.
void addWallsAndColumns(const RasterWalls& traced, const std::vector<std::string>& id_of,
                        const RasterPlanOptions& options, Level& level) {
  const Eigen::Rotation2Dd turn(options.yaw);
  const auto placed = [&](const Eigen::Vector2d& p) -> Eigen::Vector2d {
    return options.origin + turn * p;
  };
  for (std::size_t k = 0; k < traced.walls.size(); ++k) {
    const RasterWall& traced_wall = traced.walls[k];
    const Eigen::Vector2d start = placed(traced_wall.start), end = placed(traced_wall.end);
    // Clamped to what a plan holds; a wall clamped is said (rasterPlanFromImage).
    const double thickness = std::clamp(traced_wall.thickness, 0.001, bim::limits::kMaxThickness);
    if (traced_wall.kind != RasterWall::Kind::kWall) {
      level.columns.push_back(
          tracedColumn(traced_wall, id_of[k], start, end, thickness, options.height));
      continue;
    }
    Wall wall;
    wall.id = id_of[k];
    wall.start = start;
    wall.end = end;
    wall.thickness = thickness;
    wall.height = options.height;
    if ((wall.end - wall.start).norm() < 0.001) continue;
    level.walls.push_back(std::move(wall));
  }
}

// A level with nothing on it, or more walls than a plan may hold, is no plan.
void checkLevel(const Level& level, const RasterWalls& traced, const std::string& file) {
  if (level.walls.empty() && level.columns.empty()) {
    throw common::InputError(file, "",
                             "no wall or column found in the image (" +
                                 std::to_string(traced.regions) +
                                 " dark regions): is it a floor plan with dark walls on a light "
                                 "ground (or is negate needed)?");
  }
  if (level.walls.size() > bim::limits::kMaxWallsPerLevel) {
    throw common::InputError(file, "",
                             std::to_string(level.walls.size()) + " walls traced; at most " +
                                 std::to_string(bim::limits::kMaxWallsPerLevel) +
                                 " a level are supported (docs/formats.md, Limits)");
  }
}

// The traced doorways of walls (a column has none); the rooms either side are left to the parser.
int addDoors(const RasterWalls& traced, const std::vector<std::string>& id_of,
             const RasterPlanOptions& options, Level& level) {
  const double door_height = std::min(options.door_height, 0.9 * options.height);
  int doors = 0;
  for (const RasterDoor& traced_door : traced.doors) {
    if (traced.walls[traced_door.wall].kind != RasterWall::Kind::kWall) continue;  // no door
    Door door;
    door.id = "D" + std::to_string(++doors);
    door.wall = id_of[traced_door.wall];
    door.offset = traced_door.offset;
    door.width = traced_door.width;
    door.height = door_height;
    door.rooms_inferred = true;  // the image says none: the parser finds them from the outlines
    level.doors.push_back(std::move(door));
  }
  return doors;
}

// A doorway with no room on either side, or the same room on both (a gap in a façade of an open
// floor, in a wall standing free in a hall), joins nothing a plan's door could name: its wall is
// written in parts either side of it instead, the gap open to full height (the image cannot tell
// a lintel). Other doors of the wall move to the part they are in. Returns how many doorways
// became gaps; new parts are numbered on from `wall_count`, which counts them.
int doorwaysToGaps(Level& level, int& wall_count) {
  const bim::RoomLocator rooms(level);
  std::set<std::string> gap_ids;
  for (const Door& door : level.doors) {
    const auto sides = bim::inferDoorRooms(level, door, rooms);
    if (sides[0] == sides[1]) gap_ids.insert(door.id);
  }
  if (gap_ids.empty()) return 0;
  std::vector<Wall> walls;
  std::vector<Door> doors;
  for (const Wall& wall : level.walls) {
    std::vector<const Door*> on_wall;
    for (const Door& door : level.doors) {
      if (door.wall == wall.id) on_wall.push_back(&door);
    }
    std::sort(on_wall.begin(), on_wall.end(),
              [](const Door* a, const Door* b) { return a->offset < b->offset; });
    const Eigen::Vector2d axis = (wall.end - wall.start).normalized();
    const double length = (wall.end - wall.start).norm();
    Wall part = wall;
    double part_start = 0.0;
    for (const Door* door : on_wall) {
      if (gap_ids.count(door->id) == 0) {
        Door moved = *door;
        moved.wall = part.id;
        moved.offset -= part_start;
        doors.push_back(std::move(moved));
        continue;
      }
      const double lo = door->offset - 0.5 * door->width, hi = door->offset + 0.5 * door->width;
      if (lo - part_start >= 0.001) {
        part.end = wall.start + lo * axis;
        walls.push_back(part);
        part.id = "W" + std::to_string(++wall_count);
      }
      part.start = wall.start + hi * axis;
      part_start = hi;
    }
    if (length - part_start >= 0.001) {
      part.end = wall.end;
      walls.push_back(part);
    }
  }
  level.walls = std::move(walls);
  level.doors = std::move(doors);
  return int(gap_ids.size());
}

// What the trace and the rooms left out, one line each.
void logLeftOut(const RasterWalls& traced, const bim::FreeSpaceRooms& rooms,
                std::vector<std::string>& log) {
  for (const auto& line : traced.left_out) log.push_back(line);
  if (traced.specks > 0) {
    log.push_back(std::to_string(traced.specks) +
                  " specks (dark regions under 0.0025 m²): left out as noise");
  }
  if (rooms.pockets > 0) {
    log.push_back(std::to_string(rooms.pockets) +
                  " enclosed pockets under 1 m² (shafts drawn open, gaps): no rooms");
  }
}

// The level as a plan, written by the plan's one writer and read back by its own parser: what is
// written is a plan isg accepts.
void writeAndReadBack(Level level, const std::string& file, const RasterPlanOptions& options,
                      RasterPlanImport& result) {
  Plan plan;
  plan.name = std::filesystem::path(file).stem().string();
  bim::ImportedFrom& from = plan.imported_from.emplace();
  from.file = std::filesystem::path(file).filename().string();
  from.schema = options.source_kind;
  plan.levels.push_back(std::move(level));
  result.plan_json = bim::planToJson(
      plan, {.every_wall_height = false, .inferred_door_rooms = false, .names = true});
  const nlohmann::json document = nlohmann::json::parse(result.plan_json.dump());
  common::Warnings warnings;
  const common::JsonSource source{file, &warnings};
  try {
    result.plan = bim::parsePlan(common::JsonNode(document, "", source));
  } catch (const common::InputError& e) {
    throw common::InputError(file, "",
                             "the plan traced from it breaks a rule of the plan format at " +
                                 e.pointer() + ": " + e.reason());
  }
}

}  // namespace

RasterPlanImport rasterPlanFromImage(const OccupancyImage& image, const std::string& image_path,
                                     const RasterPlanOptions& options) {
  const std::string& file = options.from_file.empty() ? image_path : options.from_file;
  checkImageExtent(image.width, image.height, file, options);
  RasterWallOptions trace;
  trace.resolution = options.resolution;
  trace.origin = options.origin;
  trace.yaw = options.yaw;
  trace.check_interrupt = options.check_interrupt;
  const RasterWalls traced = traceRasterWalls(image, trace);

  RasterPlanImport result;
  result.width = image.width, result.height = image.height;
  result.specks = traced.specks;
  Level level;
  level.id = "L0";
  level.height = options.height;
  int walls = 0, columns = 0;
  const std::vector<std::string> id_of = tracedIds(traced, walls, columns);
  addWallsAndColumns(traced, id_of, options, level);
  checkLevel(level, traced, file);
  addDoors(traced, id_of, options, level);
  const bim::FreeSpaceRooms rooms = bim::enclosedFreeSpaces(level);
  for (std::size_t k = 0; k < rooms.outlines.size(); ++k) {
    Room room;
    room.id = "R" + std::to_string(k + 1);
    room.outline = rooms.outlines[k];
    level.rooms.push_back(std::move(room));
  }
  result.doorway_gaps = doorwaysToGaps(level, walls);
  logLeftOut(traced, rooms, result.log);
  for (std::size_t k = 0; k < traced.walls.size(); ++k) {
    if (traced.walls[k].thickness <= bim::limits::kMaxThickness) continue;
    char text[200];
    std::snprintf(text, sizeof text,
                  "%s is traced %.2f m thick: a plan's walls and columns are at most %.0f m, so it "
                  "is written %.0f m thick (a filled area drawn dark?)",
                  id_of[k].c_str(), traced.walls[k].thickness, bim::limits::kMaxThickness,
                  bim::limits::kMaxThickness);
    result.log.push_back(text);
  }
  result.walls = walls, result.columns = columns;
  result.doors = int(level.doors.size());
  result.rooms = int(level.rooms.size()), result.pockets = rooms.pockets;
  writeAndReadBack(std::move(level), file, options, result);
  return result;
}

}  // namespace isg::raster
