#pragma once

#include <Eigen/Core>
#include <array>
#include <optional>
#include <vector>

#include "bim/agraph.hpp"

namespace isg::slam {

// The plan's exposed wall segments, bucketed on a grid of 1 m cells: a segment is listed in every
// cell within the cutoff of its box, so that one cell's list holds every segment near its points.
// A segment counts for points in its surface's height band, `margin` clear of the surface's
// bottom and top (floor and ceiling are not walls).
class PlanSegmentGrid {
 public:
  struct Segment {
    Eigen::Vector2d a, b;
    double z_lo, z_hi;  // the band a point must lie in
    int surface;        // index into AGraph::surfaces
  };
  struct Nearest {
    double distance = 0.0;  // in the plane
    int segment = -1;       // index into segments()
  };

  PlanSegmentGrid(const bim::AGraph& plan, double cutoff, double margin);

  // Whether `z` lies in some surface's band.
  bool inBand(double z) const;

  // The nearest segment in the plane whose band holds `p`'s height, if any lies in `p`'s cell
  // (every segment within the cutoff does).
  std::optional<Nearest> nearest(const Eigen::Vector3d& p) const;

  const std::vector<Segment>& segments() const { return segments_; }

 private:
  static constexpr double kCell = 1.0;
  Eigen::Vector2d origin_ = Eigen::Vector2d::Zero();
  int columns_ = 0, rows_ = 0;
  std::vector<Segment> segments_;
  std::vector<std::array<double, 2>> bands_;
  std::vector<std::vector<int>> cells_;
};

}  // namespace isg::slam
