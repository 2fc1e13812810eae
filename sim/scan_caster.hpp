#pragma once

#include <Eigen/Core>
#include <optional>
#include <vector>

#include "sim/ray_caster.hpp"

namespace isg::sim {

// The fast path for one LiDAR turn. During a turn (0.1 s) the sensor stays within a few
// centimetres, so the walls it can see in each direction hardly change: `prepare` sorts the
// static boxes into azimuth sectors as seen from anywhere in a small disc around the sensor
// (conservatively: a box is in every sector it could occupy from any point of the disc), each
// sector ordered by the box's least possible distance. A ray then tests only its sector's boxes,
// nearest first, and stops as soon as the next box cannot be nearer than what it hit.
// Results are exactly RayCaster's (and so mj_ray's): the same exact box test and tie-break, on
// a superset of the boxes that can be hit. Rays from outside the disc, or straight up or down,
// fall back to RayCaster::cast.
class ScanCaster {
 public:
  explicit ScanCaster(const RayCaster& caster, int sectors = 1024);

  // Prepares for ray origins whose xy lie within `radius` of `centre`.
  void prepare(const Eigen::Vector2d& centre, double radius);

  std::optional<RayCaster::Hit> cast(const Eigen::Vector3d& origin,
                                     const Eigen::Vector3d& direction) const;

 private:
  struct Candidate {
    double min_distance;
    int box;
  };
  int sectorOf(double x, double y) const;
  // The sector of a diamondAngle value, any in [−4, 8).
  int sectorOfDiamond(double d) const;

  const RayCaster& caster_;
  int sectors_;
  Eigen::Vector2d centre_ = Eigen::Vector2d::Zero();
  double radius_ = -1.0;
  std::vector<int> sector_begin_;  // CSR: candidates of sector k are [begin[k], begin[k+1])
  std::vector<Candidate> candidates_;
  std::vector<Candidate> everywhere_;  // boxes within reach of the disc: in every sector
  // Scratch space of prepare(), kept to avoid allocating every turn.
  struct Span {
    double min_distance;
    int box, first, last;
  };
  std::vector<Span> spans_;
  std::vector<int> fill_;
};

}  // namespace isg::sim
