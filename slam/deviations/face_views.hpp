#pragma once

#include <Eigen/Core>
#include <vector>

#include "bim/agraph.hpp"
#include "slam/deviations/plan_deviations.hpp"

namespace isg::slam {

// Whether the sensor had a point of a plan wall's face in view (docs/deviations.md, "In view"):
// at least `min_views` keyframes stand in front of it within `view_range`, at most
// `max_incidence_deg` off the face's normal, with no other plan wall's face between them. The
// wall's own faces do not hide it: a part of a wall not built is seen through.
class FaceViews {
 public:
  FaceViews(const bim::AGraph& plan, const bim::WallNode& wall,
            const std::vector<Eigen::Vector2d>& keyframes, const DeviationOptions& options);
  // `point` on the face, `normal` its outward normal (unit, in the plane).
  bool inView(const Eigen::Vector2d& point, const Eigen::Vector2d& normal) const;

 private:
  struct Occluder {
    Eigen::Vector2d a, b;
  };
  std::vector<Occluder> occluders_;
  const std::vector<Eigen::Vector2d>& keyframes_;
  const DeviationOptions& options_;
  double min_cos_ = 0.0;
};

}  // namespace isg::slam
