#include "slam/deviations/face_views.hpp"

#include <algorithm>
#include <cmath>

#include "bim/polygon.hpp"
#include "common/angles.hpp"

namespace isg::slam {

namespace {

using bim::cross;

// Whether the open segments cross (bim::segmentsIntersect takes closed ones): a sight line that
// only grazes the end of a face, where faces meet at a corner, is not blocked by it.
bool segmentsCross(const Eigen::Vector2d& p, const Eigen::Vector2d& q, const Eigen::Vector2d& a,
                   const Eigen::Vector2d& b) {
  const double d1 = cross(q - p, a - p), d2 = cross(q - p, b - p);
  const double d3 = cross(b - a, p - a), d4 = cross(b - a, q - a);
  return ((d1 > 0) != (d2 > 0)) && ((d3 > 0) != (d4 > 0));
}

}  // namespace

FaceViews::FaceViews(const bim::AGraph& plan, const bim::WallNode& wall,
                     const std::vector<Viewpoint>& viewpoints, const DeviationOptions& options,
                     const BuiltLine& built)
    : viewpoints_(viewpoints),
      options_(options),
      built_(built),
      thickness_(wall.thickness),
      min_cos_(std::cos(common::radians(options.max_incidence_deg))) {
  for (const auto& s : plan.surfaces) {
    if (s.level != wall.level || s.wall == wall.id) continue;
    for (const auto& [a, b] : s.segments) occluders_.push_back({a, b});
  }
}

double FaceViews::through(const Eigen::Vector2d& point, const Eigen::Vector2d& normal) const {
  // The built wall's far face from this side lies thickness − o past the planned face, o how far
  // the built line stands toward this side; moved toward the keyframe by more than the
  // thickness, the whole built wall stands before the point, and any return past it says so.
  const double toward = built_.offsetAt(point) * built_.left().dot(normal);
  return std::max(0.0, thickness_ - toward) + options_.see_through_margin;
}

std::optional<FaceViews::Sightline> FaceViews::inFront(const Viewpoint& k, const Eigen::Vector2d& p,
                                                       const Eigen::Vector2d& normal) const {
  const Eigen::Vector2d ray = k.position - p;
  const double range = ray.norm();
  if (range > options_.view_range || range < 1e-6 || normal.dot(ray) < min_cos_ * range) {
    return std::nullopt;
  }
  return Sightline{ray, range};
}

bool FaceViews::faced(const Eigen::Vector2d& point, const Eigen::Vector2d& normal) const {
  const Eigen::Vector2d p = point + 0.01 * normal;
  return std::any_of(viewpoints_.begin(), viewpoints_.end(),
                     [&](const Viewpoint& k) { return inFront(k, p, normal).has_value(); });
}

bool FaceViews::inView(const Eigen::Vector2d& point, const Eigen::Vector2d& normal) const {
  // Just in front of the face, so that the face itself is not met.
  const Eigen::Vector2d p = point + 0.01 * normal;
  const double past = through(point, normal);
  int views = 0;
  for (const auto& k : viewpoints_) {
    const auto line = inFront(k, p, normal);
    if (!line) continue;
    const auto& [ray, range] = *line;
    bool seen = false;
    if (k.hasSight()) {
      // The azimuth from the sensor toward the point, in the base's frame.
      const double azimuth = std::atan2(-ray.y(), -ray.x()) - k.yaw;
      const double incidence_cos = normal.dot(ray) / range;
      seen = k.sight->rangeToward(azimuth) > range + past / incidence_cos;
    } else {
      seen = std::none_of(occluders_.begin(), occluders_.end(),
                          [&](const auto& o) { return segmentsCross(p, k.position, o.a, o.b); });
    }
    if (seen && ++views >= options_.min_views) return true;
  }
  return false;
}

std::vector<std::pair<double, double>> windowSpans(const bim::AGraph& plan,
                                                   const bim::WallNode& wall,
                                                   const Eigen::Vector2d& start,
                                                   const Eigen::Vector2d& axis, double margin) {
  std::vector<std::pair<double, double>> spans;
  for (const auto& window : plan.windows) {
    if (window.wall != wall.id || window.level != wall.level) continue;
    const double c = (window.position.head<2>() - start).dot(axis);
    spans.push_back({c - 0.5 * window.width - margin, c + 0.5 * window.width + margin});
  }
  std::sort(spans.begin(), spans.end());
  return spans;
}

}  // namespace isg::slam
