#pragma once

#include <Eigen/Geometry>
#include <optional>
#include <vector>

#include "bim/agraph.hpp"
#include "sensors/messages.hpp"

namespace isg::slam {

// The faces of the plan's door openings, across the wall's thickness: bounded surfaces whose
// normals run along the wall. The S-Graph's walls are unbounded planes, so along a corridor
// nothing the map holds says where it is; the jambs do (docs/matching.md, "Door jambs").
struct DoorJamb {
  int wall = -1;                                      // into AGraph::walls
  Eigen::Vector2d point = Eigen::Vector2d::Zero();    // on the wall's axis, in P
  Eigen::Vector2d normal = Eigen::Vector2d::UnitX();  // into the opening
  Eigen::Vector2d across = Eigen::Vector2d::UnitY();  // the wall's left normal
  double half_thickness = 0.0;
  double z_min = 0.0, z_max = 0.0;  // the opening's height range
  double opening = 0.0;             // the opening's width
};

// Thresholds of the jamb evidence (ISGraphOptions::jambs).
struct JambOptions {
  bool enabled = true;
  // A point belongs to a jamb only well inside the wall's thickness (this far from either
  // face: range noise spreads a face's points a few centimetres), and inside the opening's
  // height less this margin at the floor and at the lintel.
  double face_margin = 0.03;
  double height_margin = 0.3;
  // Kept at a keyframe: points within `gather` of the jamb's plane at the pose then; a window
  // then takes those within `cluster` of their median, if they form a jamb: at least
  // `min_points`, their spread (median absolute deviation) at most `max_spread`, and no more
  // than `max_open_share` of the gathered ones lying further into the opening (a closed door's
  // leaf or someone standing in it), counting those beyond `gather` up to the opening's middle
  // (JambSighting::filled).
  double gather = 0.3;
  double cluster = 0.06;
  int min_points = 8;
  double max_spread = 0.025;
  double max_open_share = 0.2;
  // At most this many points are kept of a sighting (evenly through the scan's order): enough
  // for the median and the spread, and a window's refit stays cheap.
  int max_points = 64;
  // A jamb seen from closer than `min_range` or further than `max_range` is not gathered: too
  // close, the sensor sees it edge-on; too far, with few points.
  double min_range = 0.5;
  double max_range = 12.0;
  // One point's error along the jamb's normal; the factor's σ is this over √points, never
  // below `min_sigma` (the plan's own accuracy).
  double sigma_point = 0.03;
  double min_sigma = 0.02;
};

// A jamb's points gathered from one keyframe's scan, in the sensor's frame L.
struct JambSighting {
  int jamb = -1;
  std::vector<Eigen::Vector3f> points_L;
  // The scan's points in the band further into the opening than `gather`, up to its middle, at
  // the pose of the gathering (scaled as points_L is thinned to max_points): what fills the
  // opening. A closed leaf seen beside its jamb lies partly within `gather` too, where it alone
  // would look like a jamb slid along the wall.
  int filled = 0;
};

// Both jambs of every doorway of a plan whose wall is known, with a grid over the plan that
// says which jambs lie near a point, so that a scan's points are sorted in one pass.
class DoorJambs {
 public:
  DoorJambs(const bim::AGraph& plan, const JambOptions& options);

  const std::vector<DoorJamb>& jambs() const { return jambs_; }

  // The points of a scan (in L) that may lie on a jamb, under P_T_L: those inside an opening's
  // thickness and height band within `gather` of its jamb's plane, for the jambs in front of the
  // sensor between min_range and max_range.
  std::vector<JambSighting> gather(const std::vector<sensors::ScanPoint>& points_L,
                                   const Eigen::Isometry3d& P_T_L) const;
  // The jamb as a sighting shows it under P_T_L: its points' centroid in L and how many, when
  // they form one (JambOptions).
  struct Fit {
    Eigen::Vector3d centroid_L = Eigen::Vector3d::Zero();
    int points = 0;
    double offset = 0.0;  // of the centroid from the jamb's plane along its normal, under P_T_L
  };
  std::optional<Fit> fit(const JambSighting& sighting, const Eigen::Isometry3d& P_T_L) const;

 private:
  // Where a point of P lies along the jamb's normal (u), and whether it is inside the band a
  // jamb's points occupy: across the wall's thickness and in height (inWallBand), and within
  // `gather` of the jamb's plane too (inBand).
  bool inWallBand(const DoorJamb& jamb, const Eigen::Vector3d& p, double* u) const;
  bool inBand(const DoorJamb& jamb, const Eigen::Vector3d& p, double* u) const;

  JambOptions options_;
  std::vector<DoorJamb> jambs_;
  Eigen::Vector2d origin_ = Eigen::Vector2d::Zero();
  double cell_ = 1.0;
  int columns_ = 0, rows_ = 0;
  std::vector<int> cell_start_;  // jambs of cell c: cell_jambs_[cell_start_[c] .. cell_start_[c+1])
  std::vector<int> cell_jambs_;
};

}  // namespace isg::slam
