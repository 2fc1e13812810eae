#include "slam/deviations/map_against_plan.hpp"

#include <algorithm>
#include <cmath>
#include <map>

#include "bim/floor_at.hpp"
#include "slam/deviations/plan_segment_grid.hpp"

namespace isg::slam {

namespace {

// A level's near distances in millimetre bins up to the cutoff: its median and 95th percentile
// to the millimetre, without holding a long run's points.
struct DistanceHistogram {
  std::vector<std::size_t> bins;
  std::size_t count = 0;
  double quantile(double q) const {
    const std::size_t rank = std::size_t(std::ceil(q * double(count)));
    std::size_t seen = 0;
    for (std::size_t i = 0; i < bins.size(); ++i) {
      seen += bins[i];
      if (seen >= std::max<std::size_t>(rank, 1)) return (double(i) + 0.5) * 1e-3;
    }
    return 0.0;
  }
};

struct StretchSums {
  std::size_t points = 0;
  double sum = 0.0, sum_squares = 0.0;
};

}  // namespace

std::vector<LevelAgainstPlan> measureMapAgainstPlan(const bim::AGraph& plan,
                                                    const std::vector<std::string>& levels,
                                                    const MapPointSource& map_points,
                                                    const MapAgainstPlanOptions& options) {
  if (levels.empty()) return {};
  const PlanSegmentGrid grid(plan, options.cutoff_m, options.margin_m);
  const auto& segments = grid.segments();
  // Each segment cut into equal stretches of at most stretch_m.
  std::vector<std::size_t> first_stretch(segments.size() + 1, 0);
  for (std::size_t i = 0; i < segments.size(); ++i) {
    const double length = (segments[i].b - segments[i].a).norm();
    first_stretch[i + 1] =
        first_stretch[i] +
        std::max<std::size_t>(1, std::size_t(std::ceil(length / options.stretch_m)));
  }
  std::vector<StretchSums> sums(first_stretch.back());
  std::map<std::string, std::size_t> index_of;
  for (std::size_t l = 0; l < levels.size(); ++l) index_of[levels[l]] = l;
  std::vector<LevelAgainstPlan> out(levels.size());
  std::vector<DistanceHistogram> histograms(levels.size());
  const std::size_t bins = std::size_t(std::ceil(options.cutoff_m * 1e3)) + 1;
  for (std::size_t l = 0; l < levels.size(); ++l) {
    out[l].level = levels[l];
    out[l].cutoff_m = options.cutoff_m;
    histograms[l].bins.assign(bins, 0);
  }
  std::size_t placed = 0;
  map_points([&](const Eigen::Vector3d& p) {
    ++placed;
    if (!grid.inBand(p.z())) return;
    const auto nearest = grid.nearest(p);
    const bool near = nearest && nearest->distance <= options.cutoff_m;
    const int floor = near ? -1 : bim::floorAt(plan, p.z());
    if (!near && floor < 0) return;
    const std::string& level =
        near ? plan.surfaces[segments[nearest->segment].surface].level : plan.floors[floor].id;
    const auto it = index_of.find(level);
    if (it == index_of.end()) return;
    LevelAgainstPlan& on = out[it->second];
    ++on.points;
    if (!near) return;
    DistanceHistogram& histogram = histograms[it->second];
    ++histogram.count;
    ++histogram.bins[std::min(bins - 1, std::size_t(nearest->distance * 1e3))];
    const PlanSegmentGrid::Segment& s = segments[nearest->segment];
    const Eigen::Vector2d along = s.b - s.a;
    const double length = along.norm();
    const std::size_t count = first_stretch[nearest->segment + 1] - first_stretch[nearest->segment];
    const double t = length > 0.0 ? (p.head<2>() - s.a).dot(along) / (length * length) : 0.0;
    const std::size_t k = std::min(count - 1, std::size_t(std::clamp(t, 0.0, 1.0) * double(count)));
    const Eigen::Vector2d normal = plan.surfaces[s.surface].plane.normal.head<2>().normalized();
    const double signed_distance = normal.dot(p.head<2>() - s.a);
    StretchSums& stretch = sums[first_stretch[nearest->segment] + k];
    ++stretch.points;
    stretch.sum += signed_distance;
    stretch.sum_squares += signed_distance * signed_distance;
  });
  if (placed == 0) return {};
  for (std::size_t l = 0; l < levels.size(); ++l) {
    LevelAgainstPlan& on = out[l];
    if (on.points > 0) on.near_share = double(histograms[l].count) / double(on.points);
    if (histograms[l].count > 0) {
      on.median_m = histograms[l].quantile(0.5);
      on.p95_m = histograms[l].quantile(0.95);
    }
  }
  for (std::size_t i = 0; i < segments.size(); ++i) {
    const PlanSegmentGrid::Segment& s = segments[i];
    const bim::WallSurfaceNode& surface = plan.surfaces[s.surface];
    const auto it = index_of.find(surface.level);
    if (it == index_of.end()) continue;
    const std::size_t count = first_stretch[i + 1] - first_stretch[i];
    for (std::size_t k = 0; k < count; ++k) {
      const StretchSums& stretch = sums[first_stretch[i] + k];
      if (stretch.points < options.min_points) continue;
      FaceStretch face;
      face.surface = surface.id;
      face.start = s.a + (s.b - s.a) * (double(k) / double(count));
      face.end = s.a + (s.b - s.a) * (double(k + 1) / double(count));
      face.points = stretch.points;
      face.mean_m = stretch.sum / double(stretch.points);
      face.rms_m = std::sqrt(stretch.sum_squares / double(stretch.points));
      out[it->second].stretches.push_back(face);
    }
  }
  return out;
}

}  // namespace isg::slam
