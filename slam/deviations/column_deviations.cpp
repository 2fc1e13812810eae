#include "slam/deviations/column_deviations.hpp"

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>

#include "bim/column.hpp"
#include "bim/plan_geometry.hpp"
#include "bim/polygon.hpp"

namespace isg::slam {

const char* toString(ColumnStatus status) {
  switch (status) {
    case ColumnStatus::kAsPlanned:
      return "as_planned";
    case ColumnStatus::kMoved:
      return "moved";
    case ColumnStatus::kMissing:
      return "missing";
    case ColumnStatus::kNotSeen:
      return "not_seen";
  }
  return "not_seen";
}

double columnDistance(const bim::Column& column, const Eigen::Vector2d& offset,
                      const Eigen::Vector2d& p, Eigen::Vector2d* normal) {
  const Eigen::Vector2d from_centre = p - (column.center + offset);
  if (column.round()) {
    const double r = from_centre.norm();
    if (normal != nullptr)
      *normal = r > 1e-9 ? Eigen::Vector2d(from_centre / r) : Eigen::Vector2d::UnitX();
    return r - column.radius();
  }
  // In the column's own frame: x along its width, y along its depth.
  const Eigen::Rotation2Dd turn(column.yaw);
  const Eigen::Vector2d q = turn.inverse() * from_centre;
  const Eigen::Vector2d half = 0.5 * column.size;
  const Eigen::Vector2d beyond = q.cwiseAbs() - half;
  Eigen::Vector2d n_local;
  double distance;
  if (beyond.x() > 0.0 || beyond.y() > 0.0) {
    const Eigen::Vector2d outside = beyond.cwiseMax(0.0);
    distance = outside.norm();
    n_local = Eigen::Vector2d(outside.x() * (q.x() < 0 ? -1.0 : 1.0),
                              outside.y() * (q.y() < 0 ? -1.0 : 1.0)) /
              distance;
  } else if (beyond.x() > beyond.y()) {
    distance = beyond.x();
    n_local = Eigen::Vector2d(q.x() < 0 ? -1.0 : 1.0, 0.0);
  } else {
    distance = beyond.y();
    n_local = Eigen::Vector2d(0.0, q.y() < 0 ? -1.0 : 1.0);
  }
  if (normal != nullptr) *normal = turn * n_local;
  return distance;
}

namespace {

double polygonDistance(const std::vector<Eigen::Vector2d>& polygon, const Eigen::Vector2d& p) {
  if (bim::containsPoint(polygon, p)) return 0.0;
  double nearest = INFINITY;
  for (std::size_t i = 0; i < polygon.size(); ++i) {
    nearest =
        std::min(nearest, bim::distanceToSegment(p, polygon[i], polygon[(i + 1) % polygon.size()]));
  }
  return nearest;
}

struct Box {
  Eigen::Vector2d lo, hi;
  bool overlaps(const Box& other) const {
    return (lo.array() <= other.hi.array()).all() && (other.lo.array() <= hi.array()).all();
  }
};

Box boxAround(const std::vector<Eigen::Vector2d>& points, double grown) {
  Box box{Eigen::Vector2d::Constant(INFINITY), Eigen::Vector2d::Constant(-INFINITY)};
  for (const auto& p : points) {
    box.lo = box.lo.cwiseMin(p);
    box.hi = box.hi.cwiseMax(p);
  }
  box.lo.array() -= grown;
  box.hi.array() += grown;
  return box;
}

// The outline moved to fit the points (Gauss–Newton on the translation, along the directions the
// points constrain): its offset, the points on it and the directions measured.
struct ColumnFit {
  Eigen::Vector2d offset = Eigen::Vector2d::Zero();
  std::size_t on = 0;
  int directions = 0;
};

ColumnFit fitColumn(const bim::Column& column, const std::vector<Eigen::Vector2d>& points,
                    const ColumnOptions& options) {
  ColumnFit fit;
  // The first steps weigh every point (a column moved a few decimetres has its points that far
  // from the planned outline), damped beyond 0.1 m; the later ones take only those near the
  // outline as it stands then.
  constexpr double kNear = 0.1;
  for (int iteration = 0; iteration < 12; ++iteration) {
    Eigen::Matrix2d H = Eigen::Matrix2d::Zero();
    Eigen::Vector2d g = Eigen::Vector2d::Zero();
    for (const auto& p : points) {
      Eigen::Vector2d n;
      const double r = columnDistance(column, fit.offset, p, &n);
      double w = 1.0;
      if (std::abs(r) > kNear) {
        if (iteration >= 3) continue;
        w = kNear / std::abs(r);
      }
      H += w * n * n.transpose();
      g += w * r * n;
    }
    const Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d> eigen(H);
    Eigen::Vector2d step = Eigen::Vector2d::Zero();
    for (int k = 0; k < 2; ++k) {
      if (eigen.eigenvalues()(k) < options.min_direction_weight) continue;
      const Eigen::Vector2d e = eigen.eigenvectors().col(k);
      step += e * (e.dot(g) / eigen.eigenvalues()(k));
    }
    // A step at most 0.1 m: the points beyond the outline must not throw it across the column.
    if (step.norm() > kNear) step *= kNear / step.norm();
    fit.offset += step;
    if (step.norm() < 1e-5) break;
  }
  // What the points on the fitted outline measure.
  Eigen::Matrix2d H = Eigen::Matrix2d::Zero();
  for (const auto& p : points) {
    Eigen::Vector2d n;
    if (std::abs(columnDistance(column, fit.offset, p, &n)) > options.inlier_m) continue;
    ++fit.on;
    H += n * n.transpose();
  }
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d> eigen(H);
  Eigen::Vector2d measured = Eigen::Vector2d::Zero();
  for (int k = 0; k < 2; ++k) {
    if (eigen.eigenvalues()(k) < options.min_direction_weight) continue;
    const Eigen::Vector2d e = eigen.eigenvectors().col(k);
    measured += e * e.dot(fit.offset);
    ++fit.directions;
  }
  fit.offset = measured;
  return fit;
}

}  // namespace

ColumnEvidence::ColumnEvidence(const bim::Plan& plan, const std::vector<std::string>& levels,
                               const ColumnOptions& options)
    : options_(options) {
  for (const auto& level : plan.levels) {
    if (std::find(levels.begin(), levels.end(), level.id) == levels.end()) continue;
    if (level.columns.empty()) continue;
    // What else stands on the level: walls (not the rectangular columns among them) and the
    // round columns.
    std::vector<std::vector<Eigen::Vector2d>> footprints;
    std::vector<const bim::Column*> footprint_column;
    for (const auto& g : bim::computeLevelGeometry(level).walls) {
      if (g.column) continue;
      footprints.push_back(g.footprint());
      footprint_column.push_back(nullptr);
    }
    for (const auto& column : level.columns) {
      footprints.push_back(bim::columnFootprint(column));
      footprint_column.push_back(&column);
    }
    for (const auto& column : level.columns) {
      Candidate candidate;
      candidate.column = &column;
      candidate.level = level.id;
      candidate.z_min = level.elevation + column.base + options.band_margin_m;
      candidate.z_max = level.elevation + column.height - options.band_margin_m;
      const Box box = boxAround(bim::columnFootprint(column), options.search_m);
      candidate.lo = box.lo;
      candidate.hi = box.hi;
      for (std::size_t f = 0; f < footprints.size(); ++f) {
        if (footprint_column[f] == &column) continue;
        if (box.overlaps(boxAround(footprints[f], options.wall_clearance_m))) {
          candidate.others.push_back(footprints[f]);
        }
      }
      if (candidate.z_max > candidate.z_min) candidates_.push_back(std::move(candidate));
    }
  }
}

void ColumnEvidence::add(const Eigen::Vector3d& point_B) {
  const Eigen::Vector2d p = point_B.head<2>();
  for (auto& candidate : candidates_) {
    if (point_B.z() < candidate.z_min || point_B.z() > candidate.z_max) continue;
    if ((p.array() < candidate.lo.array()).any() || (p.array() > candidate.hi.array()).any()) {
      continue;
    }
    if (std::abs(columnDistance(*candidate.column, Eigen::Vector2d::Zero(), p)) >
        options_.search_m) {
      continue;
    }
    const bool by_another =
        std::any_of(candidate.others.begin(), candidate.others.end(), [&](const auto& footprint) {
          return polygonDistance(footprint, p) <= options_.wall_clearance_m;
        });
    if (!by_another) candidate.points.push_back(p);
  }
}

std::vector<ColumnDeviation> ColumnEvidence::judge(
    const bim::AGraph& graph, const std::map<int, std::vector<Viewpoint>>& viewpoints) const {
  std::vector<ColumnDeviation> out;
  for (const auto& candidate : candidates_) {
    const bim::Column& column = *candidate.column;
    ColumnDeviation judged;
    judged.column = column.id;
    judged.level = candidate.level;
    judged.round = column.round();
    judged.planned_centre = column.center;
    judged.planned_outline = bim::columnFootprint(column);
    const ColumnFit fit = fitColumn(column, candidate.points, options_);
    judged.points = fit.on;
    if (fit.on >= options_.min_points) {
      judged.offset_m = fit.offset;
      judged.directions_measured = fit.directions;
      judged.status =
          fit.offset.norm() >= options_.moved_m ? ColumnStatus::kMoved : ColumnStatus::kAsPlanned;
      out.push_back(judged);
      continue;
    }
    // Too little of it in the map: did the sensor see past where it stands?
    int floor = -1;
    for (int f = 0; f < int(graph.floors.size()); ++f) {
      if (graph.floors[f].id == candidate.level) floor = f;
    }
    const double across = column.round() ? column.radius() : 0.5 * column.size.norm();
    if (const auto it = viewpoints.find(floor); it != viewpoints.end()) {
      for (const Viewpoint& v : it->second) {
        if (!v.hasSight()) continue;
        const Eigen::Vector2d ray = column.center - v.position;
        const double range = ray.norm();
        if (range > options_.view_range_m || range <= across) continue;
        const double azimuth = std::atan2(ray.y(), ray.x()) - v.yaw;
        if (v.sight->rangeToward(azimuth) > range + across + options_.see_past_margin_m) {
          ++judged.seen_past;
        }
      }
    }
    judged.status =
        judged.seen_past >= options_.min_views ? ColumnStatus::kMissing : ColumnStatus::kNotSeen;
    out.push_back(judged);
  }
  return out;
}

}  // namespace isg::slam
