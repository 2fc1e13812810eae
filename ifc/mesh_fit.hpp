#pragma once

#include <Eigen/Core>
#include <optional>
#include <string>
#include <vector>

namespace isg::ifc {

// The geometry the import reads from an IFC element: its body as planar polygons (faces) in the
// plan frame B, metres. Everything here is plain geometry, independent of IFC and of IFC++, so
// that it is tested against hand calculations (docs/formats.md, "Importing IFC", says how each
// number is taken).
using Face = std::vector<Eigen::Vector3d>;
using Mesh = std::vector<Face>;

// A wall's body read as the plan's straight, prismatic wall.
struct WallFit {
  Eigen::Vector2d start = Eigen::Vector2d::Zero();  // axis, at mid thickness
  Eigen::Vector2d end = Eigen::Vector2d::Zero();
  double thickness = 0.0;
  double bottom = 0.0;         // median of the body's bottom along the axis (z in B)
  double top = 0.0;            // lowest top along the axis: never wall where there is none
  double lowest_bottom = 0.0;  // the extremes, to say what was simplified
  double highest_top = 0.0;
  // Footprint area of the body over the area of its rectangle: 1 for a straight wall with square
  // ends, a little less with mitred ends, well below for an L-shaped or curved one.
  double rectangle_fill = 1.0;
  // How well the body is one straight wall, 1 at best. For a wall longer than three
  // thicknesses: the narrowest it is across its axis over the part of its length farther than
  // one thickness from either end (where a mitred or angled joint cannot reach), as a fraction of
  // its thickness — an L-shaped or curved body's rectangle is wider than the wall. For a shorter
  // one: its rectangle_fill over the least fill of a wall mitred at 45° at both ends,
  // 1 − thickness / length (capped at 1).
  double straightness = 1.0;
};

// The smallest rectangle around the body seen from above, with its long side as the axis; the
// element's own x direction (`preferred_axis`, from its placement) is kept when its rectangle is
// within 2 % of the smallest, so that a short, thick wall keeps the axis its tool gave it.
// nullopt for a body without faces.
std::optional<WallFit> fitWall(const Mesh& body, const Eigen::Vector2d& preferred_axis);

// A stair flight's body read as the plan's straight flight: the smallest rectangle around it seen
// from above, walked along the side over which its top rises most (the steps'), from the end
// where its top is low to the end where it is high.
struct FlightFit {
  Eigen::Vector2d low_edge = Eigen::Vector2d::Zero();   // centre of the rectangle's low side
  Eigen::Vector2d high_edge = Eigen::Vector2d::Zero();  // ... and of its high side
  double width = 0.0;                                   // across the walking direction
  double bottom = 0.0;                                  // lowest point of the body (z in B)
  double top = 0.0;                                     // highest
};
std::optional<FlightFit> fitFlight(const Mesh& body);

// Where a body lies along a wall's axis: [along_min, along_max] in metres from the wall's start,
// [z_min, z_max] in B.
struct AxisExtent {
  double along_min = 0.0, along_max = 0.0;
  double z_min = 0.0, z_max = 0.0;
};
std::optional<AxisExtent> extentAlong(const Mesh& body, const Eigen::Vector2d& start,
                                      const Eigen::Vector2d& end);

// The outline of a body seen from below: the boundary of its downward faces at its lowest level
// (within 2 cm), vertices welded to the millimetre, collinear vertices removed, counter-clockwise.
// The largest loop when there are several (holes such as column cut-outs are dropped, and
// `loops` says how many there were). nullopt when the faces do not close a loop.
struct Footprint {
  std::vector<Eigen::Vector2d> outline;
  double z = 0.0;  // the bottom's height in B
  int loops = 0;
};
std::optional<Footprint> footprintOf(const Mesh& body);

// Axis-aligned bounds of a body (for the summary and the oracle test).
struct Bounds {
  Eigen::Vector3d min = Eigen::Vector3d::Zero(), max = Eigen::Vector3d::Zero();
};
std::optional<Bounds> boundsOf(const Mesh& body);

}  // namespace isg::ifc
