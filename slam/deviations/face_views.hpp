#pragma once

#include <Eigen/Core>
#include <optional>
#include <vector>

#include "bim/agraph.hpp"
#include "slam/deviations/built_line.hpp"
#include "slam/deviations/plan_deviations.hpp"
#include "slam/deviations/viewpoint.hpp"

namespace isg::slam {

// Whether the sensor saw where a point of a plan wall's face stands (docs/deviations.md, "In
// view"): at least `min_views` keyframes stand in front of it within `view_range`, at most
// `max_incidence_deg` off the face's normal, and each saw past it — its farthest return toward
// the point lies beyond the wall's far face, as built there, by `see_through_margin`
// (SightProfile): along the sight line, (max(0, thickness − o) + margin) / cos(incidence) past the
// point, o how far the built line stands toward the keyframe's side at the point's place along
// the wall (negative: away from it; 0 where the wall is taken as planned). A
// keyframe that did not record how far it saw counts when no other plan wall's face lies between it
// and the point. Either way the wall's own faces do not hide it: what is asked is whether it stands
// there.
class FaceViews {
 public:
  // `built`: where the wall stands off its planned axis (its fitted line, the turn's swing
  // included), so that a sight line stopped by a wall built 0.3 m off does not read as past the
  // planned one, and one that passes where a turned wall would stand does.
  FaceViews(const bim::AGraph& plan, const bim::WallNode& wall,
            const std::vector<Viewpoint>& viewpoints, const DeviationOptions& options,
            const BuiltLine& built = {});
  // `point` on the face, `normal` its outward normal (unit, in the plane).
  bool inView(const Eigen::Vector2d& point, const Eigen::Vector2d& normal) const;
  // Whether any keyframe stood in front of the point within view_range and max_incidence_deg:
  // whether it could have been in view at all (the outer face of an outer wall never is).
  bool faced(const Eigen::Vector2d& point, const Eigen::Vector2d& normal) const;

 private:
  struct Occluder {
    Eigen::Vector2d a, b;
  };
  std::vector<Occluder> occluders_;
  const std::vector<Viewpoint>& viewpoints_;
  const DeviationOptions& options_;
  BuiltLine built_;
  double thickness_ = 0.0;
  double min_cos_ = 0.0;

  // How far past the face at `point` (outward `normal`), along the normal, a sight line must reach
  // to have passed the wall as built there.
  double through(const Eigen::Vector2d& point, const Eigen::Vector2d& normal) const;

  // The line from the point p (just off the face) to keyframe `k`, when `k` stands in front of p
  // within range and incidence.
  struct Sightline {
    Eigen::Vector2d ray;  // p → k
    double range = 0.0;   // its length
  };
  std::optional<Sightline> inFront(const Viewpoint& k, const Eigen::Vector2d& p,
                                   const Eigen::Vector2d& normal) const;
};

// The stretches along a wall's axis (metres from `start` along `axis`) of its windows, widened by
// `margin` each side: the sensor sees through them, so what is seen past there says nothing of
// whether the wall is built.
std::vector<std::pair<double, double>> windowSpans(const bim::AGraph& plan,
                                                   const bim::WallNode& wall,
                                                   const Eigen::Vector2d& start,
                                                   const Eigen::Vector2d& axis, double margin);

}  // namespace isg::slam
