#pragma once

#include <Eigen/Core>
#include <array>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace isg::bim {

// The plan model of docs/formats.md ("isg.plan" v1): what the BIM says. All coordinates are in the
// plan frame B, in metres. Parsing fills every default, so nothing downstream sees a missing
// field.

// The room id used by doors that lead out of the building.
inline constexpr const char* kOutside = "outside";

struct Wall {
  std::string id;
  Eigen::Vector2d start = Eigen::Vector2d::Zero();
  Eigen::Vector2d end = Eigen::Vector2d::Zero();
  double thickness = 0.0;  // centred on the axis start → end
  double height = 0.0;     // top of the wall above the level's elevation
  double base = 0.0;       // bottom of the wall above the level's elevation
  std::string name;        // free text from the file (an imported element's name); "" when none
  std::string ifc_guid;    // the IFC GlobalId it was imported from (22 characters); "" when none
};

struct Door {
  std::string id;
  std::string wall;     // id of the wall the opening is in
  double offset = 0.0;  // centre of the opening, metres from the wall's start along its axis
  double width = 0.0;
  double height = 0.0;               // from the wall's base
  std::array<std::string, 2> rooms;  // the two rooms it joins (or kOutside)
  bool rooms_inferred = false;       // true when `rooms` came from the outlines, not the file
  std::string name;                  // free text from the file; "" when none
  std::string ifc_guid;  // the IFC GlobalId it was imported from (22 characters); "" when none
};

// A window: an opening in a wall from `sill` to `sill + height` above the wall's base, which the
// sensor sees through and nobody walks through (an optional extension of v1).
struct Window {
  std::string id;
  std::string wall;     // id of the wall the opening is in
  double offset = 0.0;  // centre of the opening, metres from the wall's start along its axis
  double width = 0.0;
  double sill = 0.0;     // bottom of the opening above the wall's base
  double height = 0.0;   // of the opening, sill to head
  std::string name;      // free text from the file; "" when none
  std::string ifc_guid;  // the IFC GlobalId it was imported from (22 characters); "" when none
};

// A straight flight of stairs (an optional extension of v1): its bottom edge is centred at
// `start` on the level that holds it, its top edge at `end` on level `to`, which may lie above or
// below. The steps are derived (bim/stairs.hpp); the floor of the upper level is open over the
// flight's upper part (StairGeometry::openingFootprint).
struct Stair {
  std::string id;
  Eigen::Vector2d start = Eigen::Vector2d::Zero();
  Eigen::Vector2d end = Eigen::Vector2d::Zero();
  double width = 0.0;
  std::string to;    // id of the level the flight leads to
  std::string name;  // free text from the file; "" when none
};

// A free-standing column (an optional extension of v1): rectangular, `size` = (width along its own
// x axis, depth across it) turned by `yaw` about its centre, or round, `size` = (diameter,
// diameter). Columns are solid from `base` to `height` above the level, as walls are; the geometry
// (bim/plan_geometry.hpp) treats a rectangular column's faces as wall faces.
struct Column {
  enum class Shape { kRectangle, kRound };
  std::string id;
  Shape shape = Shape::kRectangle;
  Eigen::Vector2d center = Eigen::Vector2d::Zero();
  Eigen::Vector2d size = Eigen::Vector2d::Zero();
  double yaw = 0.0;      // radians, counter-clockwise from the plan's x axis (rectangles only)
  double height = 0.0;   // top above the level's elevation
  double base = 0.0;     // bottom above the level's elevation
  std::string name;      // free text from the file; "" when none
  std::string ifc_guid;  // the IFC GlobalId it was imported from (22 characters); "" when none

  bool round() const { return shape == Shape::kRound; }
  double radius() const { return 0.5 * size.x(); }
};

struct Room {
  std::string id;
  std::string name;
  std::vector<Eigen::Vector2d> outline;  // simple polygon along the inner wall faces, CCW
  std::string ifc_guid;  // the IFC GlobalId it was imported from (22 characters); "" when none
};

struct Level {
  std::string id;
  std::string name;        // free text from the file (an imported storey's name); "" when none
  double elevation = 0.0;  // top of the floor
  double height = 0.0;     // default wall height, floor to ceiling
  std::string ifc_guid;    // the IFC GlobalId it was imported from (22 characters); "" when none
  std::vector<Wall> walls;
  std::vector<Door> doors;
  std::vector<Window> windows;
  std::vector<Room> rooms;
  std::vector<Stair> stairs;
  std::vector<Column> columns;

  const Wall* findWall(const std::string& wall_id) const;
  const Door* findDoor(const std::string& door_id) const;
  const Window* findWindow(const std::string& window_id) const;
  const Room* findRoom(const std::string& room_id) const;
  const Stair* findStair(const std::string& stair_id) const;
  const Column* findColumn(const std::string& column_id) const;
};

// An IFC GlobalId as IFC writes one (IfcGloballyUniqueId): a 128-bit GUID in 22 characters of
// 0-9, A-Z, a-z, _ and $, the first 0-3 (it carries the top 2 bits). What `ifc_guid` holds.
bool isIfcGlobalId(std::string_view text);

// Where an imported plan came from (isg import): free text for the reader, "" where not given.
struct ImportedFrom {
  std::string file;         // the model's file name
  std::string schema;       // IFC2X3, IFC4, ...
  std::string application;  // the authoring tool, as the model's header names it
};

struct Plan {
  std::string name;
  std::string source;  // file it was read from, for messages
  std::optional<ImportedFrom> imported_from;
  std::vector<Level> levels;

  const Level* findLevel(const std::string& level_id) const;
  // The level that holds a wall / door / room with this id, or nullptr.
  const Level* levelOfWall(const std::string& wall_id) const;
  const Level* levelOfDoor(const std::string& door_id) const;
  const Level* levelOfRoom(const std::string& room_id) const;
};

}  // namespace isg::bim
