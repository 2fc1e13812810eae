#include "run/map_plan_error.hpp"

#include <algorithm>
#include <cmath>
#include <functional>
#include <utility>

#include "bim/polygon.hpp"
#include "common/pose_interpolation.hpp"

namespace isg::run {

namespace {

// The plan's exposed wall segments, bucketed on a grid of 1 m cells: a segment is listed in every
// cell within the cutoff of its box, so that one cell's list holds every segment near its points.
class SegmentGrid {
 public:
  struct Segment {
    Eigen::Vector2d a, b;
    double z_lo, z_hi;  // the band a point must lie in
  };

  SegmentGrid(const bim::AGraph& plan, double cutoff, double margin) {
    const Eigen::AlignedBox2d bounds = plan.surfaceBounds();
    if (bounds.isEmpty()) return;
    origin_ = bounds.min() - Eigen::Vector2d::Constant(cutoff + kCell);
    columns_ = int(std::ceil((bounds.sizes().x() + 2 * (cutoff + kCell)) / kCell)) + 1;
    rows_ = int(std::ceil((bounds.sizes().y() + 2 * (cutoff + kCell)) / kCell)) + 1;
    cells_.resize(std::size_t(columns_) * rows_);
    for (const auto& surface : plan.surfaces) {
      const double lo = surface.z_min + margin, hi = surface.z_max - margin;
      if (!(lo < hi)) continue;
      bands_.push_back({lo, hi});
      for (const auto& [a, b] : surface.segments) {
        const int index = int(segments_.size());
        segments_.push_back({a, b, lo, hi});
        const Eigen::Vector2d box_lo = a.cwiseMin(b) - Eigen::Vector2d::Constant(cutoff) - origin_;
        const Eigen::Vector2d box_hi = a.cwiseMax(b) + Eigen::Vector2d::Constant(cutoff) - origin_;
        for (int r = int(box_lo.y() / kCell); r <= int(box_hi.y() / kCell); ++r) {
          for (int c = int(box_lo.x() / kCell); c <= int(box_hi.x() / kCell); ++c) {
            cells_[std::size_t(r) * columns_ + c].push_back(index);
          }
        }
      }
    }
  }

  // Whether `z` lies in some surface's band.
  bool inBand(double z) const {
    return std::any_of(bands_.begin(), bands_.end(),
                       [&](const auto& band) { return z >= band[0] && z <= band[1]; });
  }

  // The distance in the plane to the nearest segment whose band holds `p`'s height, if any lies
  // in `p`'s cell (every segment within the cutoff does).
  std::optional<double> nearest(const Eigen::Vector3d& p) const {
    const Eigen::Vector2d q = (p.head<2>() - origin_) / kCell;
    if (!(q.x() >= 0 && q.y() >= 0 && q.x() < columns_ && q.y() < rows_)) return std::nullopt;
    std::optional<double> best;
    for (int index : cells_[std::size_t(q.y()) * columns_ + std::size_t(q.x())]) {
      const Segment& s = segments_[std::size_t(index)];
      if (p.z() < s.z_lo || p.z() > s.z_hi) continue;
      const double d = bim::distanceToSegment(p.head<2>(), s.a, s.b);
      if (!best || d < *best) best = d;
    }
    return best;
  }

 private:
  static constexpr double kCell = 1.0;
  Eigen::Vector2d origin_ = Eigen::Vector2d::Zero();
  int columns_ = 0, rows_ = 0;
  std::vector<Segment> segments_;
  std::vector<std::array<double, 2>> bands_;
  std::vector<std::vector<int>> cells_;
};

// The run's final M_T_R at any time: from the keyframe at or before it (the first for earlier
// times), carried by odometry; without keyframes or without an odometry stream (the method made
// its own from the scans), the online estimate.
class FinalTrajectory {
 public:
  explicit FinalTrajectory(const RunRecord& run) : run_(run) {}

  std::optional<Eigen::Isometry3d> at(double t) const {
    if (!run_.map || run_.map->keyframes.empty() || run_.streams.odometry.empty()) {
      return common::interpolatePose(run_.estimate_map, t);
    }
    const auto& keyframes = run_.map->keyframes;
    auto after =
        std::upper_bound(keyframes.begin(), keyframes.end(), t,
                         [](double time, const slam::MapKeyframe& k) { return time < k.stamp; });
    const slam::MapKeyframe& k = after == keyframes.begin() ? *after : *(after - 1);
    const auto odometry = common::interpolatePose(run_.streams.odometry, t);
    if (!odometry) return std::nullopt;
    return k.estimate * k.odometry.inverse() * *odometry;
  }

 private:
  const RunRecord& run_;
};

}  // namespace

void forEachPlacedMapPoint(const RunRecord& run,
                           const std::function<void(const Eigen::Vector3d&)>& visit) {
  if (!run.final_B_T_M) return;
  const FinalTrajectory trajectory(run);
  const Eigen::Isometry3d& B_T_M = *run.final_B_T_M;
  const Eigen::Isometry3d& R_T_L = run.streams.R_T_L;
  // Poses every 10 ms across a turn: a point moves under 1 cm between them at walking speed.
  constexpr double kStep = 0.01;
  for (const auto& scan : run.map_samples) {
    if (scan.points.empty()) continue;
    float first = scan.points.front()[3], last = first;
    for (const auto& p : scan.points) first = std::min(first, p[3]), last = std::max(last, p[3]);
    std::vector<std::optional<Eigen::Isometry3d>> B_T_L;
    for (int i = 0; i <= int(std::ceil((last - first) / kStep)); ++i) {
      const auto M_T_R = trajectory.at(scan.stamp + first + i * kStep);
      B_T_L.push_back(M_T_R ? std::optional(B_T_M * *M_T_R * R_T_L) : std::nullopt);
    }
    for (const auto& p : scan.points) {
      const auto& pose = B_T_L[std::size_t(std::lround((p[3] - first) / kStep))];
      if (pose) visit(*pose * Eigen::Vector3d(p[0], p[1], p[2]));
    }
  }
}

void forEachWallBandMapPoint(const RunRecord& run, const MapPlanErrorOptions& options,
                             const std::function<void(const Eigen::Vector3d&)>& visit) {
  if (!run.setup.agraph) return;
  const SegmentGrid grid(*run.setup.agraph, options.cutoff, options.margin);
  forEachPlacedMapPoint(run, [&](const Eigen::Vector3d& p) {
    if (grid.inBand(p.z())) visit(p);
  });
}

std::optional<MapPlanError> mapPlanError(const RunRecord& run, const MapPlanErrorOptions& options) {
  if (!run.setup.agraph) return std::nullopt;
  const SegmentGrid grid(*run.setup.agraph, options.cutoff, options.margin);
  MapPlanError out;
  // Two passes, the first counting: the distances are the evaluation's largest array (1.8 M at
  // two hours), and a vector grown by doubling would hold up to three times their size while it
  // moves.
  std::size_t near = 0;
  forEachPlacedMapPoint(run, [&](const Eigen::Vector3d& in_B) {
    if (!grid.inBand(in_B.z())) return;
    const auto d = grid.nearest(in_B);
    if (d && *d <= options.cutoff) ++near;
  });
  std::vector<double> distances;
  distances.reserve(near);
  forEachPlacedMapPoint(run, [&](const Eigen::Vector3d& in_B) {
    if (!grid.inBand(in_B.z())) return;
    ++out.points;
    const auto d = grid.nearest(in_B);
    if (d && *d <= options.cutoff) distances.push_back(*d);
  });
  if (out.points == 0) return std::nullopt;
  out.near_share = double(distances.size()) / double(out.points);
  if (!distances.empty()) out.distance = eval::statistics(std::move(distances));
  return out;
}

}  // namespace isg::run
