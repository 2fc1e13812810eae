#pragma once

#include <Eigen/Core>
#include <cstddef>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "bim/agraph.hpp"
#include "bim/plan.hpp"
#include "slam/deviations/viewpoint.hpp"

namespace isg::slam {

// Columns as built against as planned (docs/deviations.md, "Columns"). A column's faces are
// shorter than the half metre a map plane needs to be a wall, so a column is judged from the
// map's points around it: where they lie on its outline, moved as a whole, the column stands
// there; where none do and the sensor saw past where it stands, it is not built.
enum class ColumnStatus { kAsPlanned, kMoved, kMissing, kNotSeen };
const char* toString(ColumnStatus status);

struct ColumnOptions {
  // A point within `search_m` of a column's planned outline, and `band_margin_m` clear of its
  // bottom and top, is its evidence, unless it lies within `wall_clearance_m` of another element
  // of the plan (a wall it stands against, another column).
  double search_m = 0.35;
  double band_margin_m = 0.2;
  double wall_clearance_m = 0.1;
  // Its outline moved (a translation, its shape and turn as planned) to fit them; points within
  // `inlier_m` of the fitted outline are on it. Built: at least `min_points` on it.
  double inlier_m = 0.05;
  std::size_t min_points = 30;
  // The offset is measured along the directions the points on it constrain: a direction whose
  // Σ(n·e)² over their outline normals n reaches `min_direction_weight` (a face seen from one
  // side constrains only its normal).
  double min_direction_weight = 15.0;
  // Moved: the offset measured at or beyond this (the walls' shift threshold, 6 cm).
  double moved_m = 0.06;
  // Not built: too few points on it, and at least `min_views` viewpoints within `view_range_m`
  // saw past where it stands, their farthest return toward its centre beyond its far side by
  // `see_past_margin_m`.
  double view_range_m = 8.0;
  double see_past_margin_m = 0.2;
  int min_views = 3;
};

struct ColumnDeviation {
  std::string column;
  std::string level;
  std::string ifc_guid;  // the plan column's IFC GlobalId (bim::Column::ifc_guid); "" when none
  bool round = false;
  Eigen::Vector2d planned_centre = Eigen::Vector2d::Zero();  // in B
  std::vector<Eigen::Vector2d>
      planned_outline;  // its footprint (bim::columnFootprint), for pictures
  ColumnStatus status = ColumnStatus::kNotSeen;
  std::size_t points = 0;  // the map's points on its fitted outline
  // Where it stands against where it is planned (B, metres), along the directions measured; none
  // for a column too little seen to fit.
  std::optional<Eigen::Vector2d> offset_m;
  int directions_measured = 0;  // 0, 1 (one side seen) or 2
  int seen_past = 0;            // viewpoints that saw past where it stands
};

// Gathers the map's points near the columns of the levels walked, then judges every column.
class ColumnEvidence {
 public:
  ColumnEvidence(const bim::Plan& plan, const std::vector<std::string>& levels,
                 const ColumnOptions& options = {});
  // Whether any column stands on the levels given.
  bool any() const { return !candidates_.empty(); }
  // A point of the map in B: kept when it is some column's evidence.
  void add(const Eigen::Vector3d& point_B);
  // `viewpoints`: where the sensor stood on each level (keyed by the A-Graph's floor index, as
  // viewpointsOnLevels gives them); a level without any judges its columns by points alone.
  std::vector<ColumnDeviation> judge(const bim::AGraph& graph,
                                     const std::map<int, std::vector<Viewpoint>>& viewpoints) const;

 private:
  struct Candidate {
    const bim::Column* column = nullptr;
    std::string level;
    double z_min = 0.0, z_max = 0.0;  // the band its evidence is taken in, in B
    Eigen::Vector2d lo, hi;           // the box around its outline grown by search_m
    std::vector<std::vector<Eigen::Vector2d>> others;  // the footprints of what stands near it
    std::vector<Eigen::Vector2d> points;
  };
  ColumnOptions options_;
  std::vector<Candidate> candidates_;
};

// The signed distance of `p` from the column's outline (negative inside) and the outline's
// outward normal there: its centre moved by `offset`.
double columnDistance(const bim::Column& column, const Eigen::Vector2d& offset,
                      const Eigen::Vector2d& p, Eigen::Vector2d* normal = nullptr);

}  // namespace isg::slam
