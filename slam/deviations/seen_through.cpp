#include "slam/deviations/seen_through.hpp"

#include <Eigen/Geometry>
#include <utility>
#include <vector>

#include "bim/polygon.hpp"

namespace isg::slam {
namespace {

using bim::cross;

// Whether the sight line from `eye` to `target` crosses `occluder` at a confirmed part, `margin`
// inside it and more than `margin` short of the target.
bool blocks(const MapWall& occluder, const Eigen::Vector2d& eye, const Eigen::Vector2d& target,
            double margin) {
  const Eigen::Vector2d along = occluder.end - occluder.start;
  const double length = along.norm();
  const Eigen::Vector2d sight = target - eye;
  const double denominator = cross(sight, along);
  if (length <= 0.0 || std::abs(denominator) < 1e-12) return false;
  // eye + t·sight = start + s·along
  const double t = cross(occluder.start - eye, along) / denominator;
  const double s = cross(occluder.start - eye, sight) / denominator * length;  // metres along
  if (t <= 0.0 || (1.0 - t) * sight.norm() <= margin) return false;
  const std::vector<std::pair<double, double>> whole{{0.0, length}};
  for (const auto& [from, to] : occluder.confirmed.empty() ? whole : occluder.confirmed) {
    if (s >= from + margin && s <= to - margin) return true;
  }
  return false;
}

}  // namespace

bool seenOnlyThroughWalls(const MapDiagnostics& map, const MapWall& wall,
                          int min_occluder_observations, double margin) {
  const Eigen::Vector2d targets[3] = {wall.start, 0.5 * (wall.start + wall.end), wall.end};
  int keyframes = 0;
  for (int k : wall.keyframes) {
    if (k < 0 || k >= int(map.keyframes.size())) continue;
    ++keyframes;
    const MapKeyframe& keyframe = map.keyframes[k];
    const Eigen::Vector2d eye = (keyframe.estimate * keyframe.sight.sensor_R).head<2>();
    for (const Eigen::Vector2d& target : targets) {
      bool blocked = false;
      for (const MapWall& occluder : map.walls) {
        if (occluder.id == wall.id || occluder.observations < min_occluder_observations ||
            occluder.z_min > wall.z_min + margin || occluder.z_max < wall.z_max - margin) {
          continue;
        }
        if (blocks(occluder, eye, target, margin)) {
          blocked = true;
          break;
        }
      }
      if (!blocked) return false;
    }
  }
  return keyframes > 0;
}

}  // namespace isg::slam
