#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "bim/box_grid.hpp"
#include "bim/plan.hpp"
#include "bim/plane.hpp"

namespace isg::bim {

// Geometry derived from a plan level: wall axes and faces, where walls meet, which faces bound
// which room, which rooms a door joins. Everything is in the plan frame B.

// A closed interval [lo, hi] along a wall's axis, measured from the wall's start.
struct AxisInterval {
  double lo = 0.0;
  double hi = 0.0;
  double length() const { return hi - lo; }
};

// One face of a wall: a vertical plane with the parts of it that are really exposed.
struct WallFace {
  int side = +1;  // +1: the face on the left of start → end, -1: the right one
  Plane plane;    // normal points away from the wall, into the space the face looks at
  // Exposed parts along the wall axis (0 = wall start). Where another wall abuts the face, the
  // face is interrupted: a T-junction splits one face into two exposed pieces.
  std::vector<AxisInterval> exposed;
  std::vector<AxisInterval> openings;  // door openings (holes in the face, not interruptions)
  double z_min = 0.0;                  // absolute z in B (level elevation + wall base)
  double z_max = 0.0;
};

struct WallGeometry {
  const Wall* wall = nullptr;
  bool column = false;  // a rectangular column taken as a wall (LevelGeometry::column_walls)
  Eigen::Vector2d axis = Eigen::Vector2d::UnitX();         // unit, start → end
  Eigen::Vector2d left_normal = Eigen::Vector2d::UnitY();  // axis turned +90°
  double length = 0.0;
  // How far the wall's solid continues past its start / end so that it closes the joint with
  // the walls it meets there (0 for a free end). The solid spans [-extend_start, length +
  // extend_end] along the axis.
  double extend_start = 0.0;
  double extend_end = 0.0;
  WallFace left;
  WallFace right;

  const WallFace& face(int side) const { return side > 0 ? left : right; }
  // A point of the wall's axis, or of one of its faces, at axis coordinate s (0 = start).
  Eigen::Vector2d pointAt(double s) const { return wall->start + s * axis; }
  Eigen::Vector2d facePointAt(int side, double s) const {
    return pointAt(s) + side * 0.5 * wall->thickness * left_normal;
  }
  // The wall's footprint (including the end extensions) as a CCW rectangle.
  std::vector<Eigen::Vector2d> footprint() const;
  // The footprint with its door openings cut out, as a plan is drawn: one CCW rectangle per solid
  // piece, in order along the axis.
  std::vector<std::vector<Eigen::Vector2d>> footprintPieces() const;
};

// A room edge that lies on a wall face looking into the room.
struct RoomBoundary {
  std::string room;
  int edge = 0;  // outline edge from vertex `edge` to `edge + 1`
  std::string wall;
  int side = +1;          // which face of the wall
  double overlap = 0.0;   // metres of the edge covered by the face's exposed parts
  double distance = 0.0;  // mean distance of the edge's endpoints from the face plane
};

struct LevelGeometry {
  // The level's walls in the order of Level::walls, then its rectangular columns as walls
  // (columnWall, in the order of Level::columns; their WallGeometry::wall points into
  // column_walls, which every copy shares). Round columns have no faces: they only cut the faces
  // they hide.
  std::vector<WallGeometry> walls;
  std::shared_ptr<const std::vector<Wall>> column_walls;
  std::vector<RoomBoundary> boundaries;

  const WallGeometry* findWall(const std::string& wall_id) const;
  std::vector<RoomBoundary> boundariesOf(const std::string& room_id) const;
};

struct GeometryOptions {
  double boundary_distance = 0.05;  // an outline edge this close to a face lies on it
  double boundary_angle_deg = 5.0;  // ... and this close in direction
  double boundary_min_overlap = 0.05;
};

// Axes, normals, end extensions and exposed faces of every wall of a level, and which faces
// bound which room.
LevelGeometry computeLevelGeometry(const Level& level, const GeometryOptions& options = {});

// The room whose outline contains `point` (the first one, in file order), or nullopt.
std::optional<std::string> roomAt(const Level& level, const Eigen::Vector2d& point);

// roomAt for many points: a grid over the rooms' boxes, so each look-up tests only the rooms
// whose box holds the point. The level must outlive it.
class RoomLocator {
 public:
  explicit RoomLocator(const Level& level);
  std::optional<std::string> roomAt(const Eigen::Vector2d& point) const;

 private:
  const Level* level_;
  BoxGrid grid_;
};

// The rooms on either side of a door (left side first), inferred from the outlines: the point
// just beyond each face of the wall at the door's centre. kOutside where no room contains it.
std::array<std::string, 2> inferDoorRooms(const Level& level, const Door& door);
std::array<std::string, 2> inferDoorRooms(const Level& level, const Door& door,
                                          const RoomLocator& rooms);
std::array<std::string, 2> inferDoorRooms(const Wall& wall, const Door& door,
                                          const RoomLocator& rooms);

// The centre of a door's opening on its wall's axis, in B (2D).
Eigen::Vector2d doorCentre(const Level& level, const Door& door);

// One opening of a wall: a door (from the wall's base) or a window (from its sill), along the
// wall's axis [lo, hi] and in z [bottom, top] above the wall's base.
struct WallOpening {
  std::string id;
  const Door* door = nullptr;  // null for a window
  double lo = 0.0, hi = 0.0;
  double bottom = 0.0, top = 0.0;
};
// The doors and windows of `wall_id` on the level, by where they start along the wall.
std::vector<WallOpening> wallOpenings(const Level& level, const std::string& wall_id);

// The middle of a box to the metre (zero for an empty box): the origin of a frame local to a
// building, so that nothing is measured from kilometres away (docs/conventions.md, "Where B's
// origin is").
Eigen::Vector2d localOriginOf(const Eigen::AlignedBox2d& box);

}  // namespace isg::bim
