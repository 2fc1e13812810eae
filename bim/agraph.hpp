#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <string>
#include <vector>

#include "bim/plan.hpp"
#include "bim/plan_geometry.hpp"
#include "bim/plane.hpp"

namespace isg::bim {

// The architectural graph (paper §III, docs/agraph.md): the plan's wall surfaces, walls, rooms,
// doorways and floors as nodes in the plan frame B, joined by the edges their factors follow.

// Wall surfaces are classified as the paper does: |n_x| ≥ |n_y| → x-surface, else y-surface.
enum class SurfaceAxis { kX, kY };

struct WallSurfaceNode {
  std::string id;     // "<wall>:left" / "<wall>:right"; a flight's: "<stair>:stair-left" ...
  std::string wall;   // empty for a flight's face
  std::string stair;  // a face of this flight of stairs (its sides and its high end), not a wall's
  std::string level;
  int side = +1;  // +1 left face of the wall, -1 right face
  SurfaceAxis axis = SurfaceAxis::kX;
  Plane plane;  // normal away from the wall, into the space the face looks at
  // The exposed parts of the face as 2D segments (see WallFace::exposed) and its height range.
  std::vector<std::pair<Eigen::Vector2d, Eigen::Vector2d>> segments;
  double z_min = 0.0;
  double z_max = 0.0;
  double exposedLength() const;
};

struct WallNode {
  std::string id;  // the plan's wall id
  std::string level;
  int left_surface = -1;  // indices into AGraph::surfaces
  int right_surface = -1;
  // The point s of the paper's Eq. (1). The paper takes the wall's start; we take the middle of
  // its axis: Eq. (1) holds for any point of the axis, and so the node sits at the wall's centre.
  Eigen::Vector3d anchor = Eigen::Vector3d::Zero();
  Eigen::Vector3d centre = Eigen::Vector3d::Zero();  // ω = f(π_left, π_right, s)
  double thickness = 0.0;
  double length = 0.0;
  // A rectangular column taken as a wall (bim::columnWall): its faces bound space as walls do,
  // but the deviation report judges it as a column (docs/deviations.md, "Columns").
  bool column = false;
};

enum class RoomKind {
  kFourWall,  // a rectangle bounded by two opposed pairs of surfaces
  kTwoWall,   // a corridor: one opposed pair bounding a long narrow rectangle
  kPolygon,   // any other shape, kept with its N surfaces and no room factor
};

struct RoomNode {
  std::string id;
  std::string name;
  std::string level;
  RoomKind kind = RoomKind::kPolygon;
  Eigen::Vector2d centre = Eigen::Vector2d::Zero();  // ρ
  std::vector<Eigen::Vector2d> outline;
  std::vector<int> surfaces;  // one per bounded outline edge, in outline order (-1: open edge)
  // Four-wall rooms: pairs[0] and pairs[1] are the opposed surface pairs (x then y in the room's
  // own axes). Two-wall rooms: pairs[0] only. Widths are the distances between each pair's planes.
  std::vector<std::array<int, 2>> pairs;
  std::vector<double> widths;
  // Two-wall rooms: a point on the corridor's axis (the outline's centroid), the c of the factor.
  Eigen::Vector2d axis_point = Eigen::Vector2d::Zero();
  int floor = -1;
};

struct DoorwayNode {
  std::string id;  // the plan's door id
  std::string wall;
  std::string level;
  Eigen::Vector3d position = Eigen::Vector3d::Zero();  // door centre on the wall axis, at floor z
  double width = 0.0;
  double height = 0.0;     // of the opening, from the wall's base (position.z)
  std::vector<int> rooms;  // indices of the rooms it joins (one when it leads outside)
};

// A window of a wall: not a node of the paper's graph (nothing walks through it), but the sensor
// sees through it, which whoever judges a wall by what was seen past it must know.
struct WindowNode {
  std::string id;  // the plan's window id
  std::string wall;
  std::string level;
  Eigen::Vector3d position = Eigen::Vector3d::Zero();  // window centre on the wall axis, at floor z
  double width = 0.0;
  double sill = 0.0, height = 0.0;  // the opening from `sill` to `sill + height` above position.z
};

struct FloorNode {
  std::string id;  // the level id
  double elevation = 0.0;
  Eigen::Vector2d centre = Eigen::Vector2d::Zero();  // mean of its rooms' centres
  std::vector<int> rooms;
};

struct AGraph {
  std::string plan_name;
  std::vector<WallSurfaceNode> surfaces;
  std::vector<WallNode> walls;
  std::vector<RoomNode> rooms;
  std::vector<DoorwayNode> doorways;
  std::vector<WindowNode> windows;
  std::vector<FloorNode> floors;

  int findSurface(const std::string& id) const;
  int findRoom(const std::string& id) const;
  // The box of every wall surface segment in B (empty when there are none). Shared by whoever
  // needs "the building's extent", so that they all agree on it.
  Eigen::AlignedBox2d surfaceBounds() const;
  // The same graph moved by `shift` in the plane: every node, plane and outline; what a node is
  // and which it joins stay. Planes keep their normals and change their d (Plane::transformed).
  AGraph translated(const Eigen::Vector2d& shift) const;
  // The middle of surfaceBounds() to the metre (zero without surfaces): where an optimisation
  // over the graph puts its origin, so that no plane's d is measured from kilometres away
  // (docs/conventions.md, "Where B's origin is").
  Eigen::Vector2d localOrigin() const;
};

struct AGraphOptions {
  GeometryOptions geometry;
  // A four-sided room is a rectangle when its corners are within this of 90°.
  double rectangle_angle_tolerance_deg = 3.0;
  // A rectangle is a corridor (two-wall room) when long / short ≥ this and short ≤ corridor_width.
  double corridor_aspect = 3.0;
  double corridor_width = 3.0;
};

// Builds the A-Graph of every level of the plan. A flight of stairs, solid from the lower floor
// up to its steps, stands on its lower level like a wall the robot sees: its two sides and its
// high end become surfaces of that level (no wall node, no room edge), so that a map of the
// floor explains them.
AGraph buildAGraph(const Plan& plan, const AGraphOptions& options = {});

// The factor functions evaluated on the nodes' own values (the plan's): the wall centre of Eq.
// (1), the centre of a four-wall and of a two-wall room. Shared with the factors.
Eigen::Vector3d wallCentre(const Plane& a, const Plane& b, const Eigen::Vector3d& anchor);
Eigen::Vector2d fourWallRoomCentre(const Plane& x1, const Plane& x2, const Plane& y1,
                                   const Plane& y2);
Eigen::Vector2d twoWallRoomCentre(const Plane& a, const Plane& b,
                                  const Eigen::Vector2d& axis_point);

const char* toString(RoomKind kind);
const char* toString(SurfaceAxis axis);

}  // namespace isg::bim
