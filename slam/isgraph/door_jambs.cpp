#include "slam/isgraph/door_jambs.hpp"

#include <algorithm>
#include <cmath>
#include <unordered_map>

namespace isg::slam {

DoorJambs::DoorJambs(const bim::AGraph& plan, const JambOptions& options) : options_(options) {
  std::unordered_map<std::string, int> wall_index;
  for (int w = 0; w < int(plan.walls.size()); ++w) wall_index.emplace(plan.walls[w].id, w);
  for (int d = 0; d < int(plan.doorways.size()); ++d) {
    const bim::DoorwayNode& door = plan.doorways[d];
    const auto it = wall_index.find(door.wall);
    if (it == wall_index.end()) continue;
    const bim::WallNode& wall = plan.walls[it->second];
    if (wall.left_surface < 0 || door.width <= 0.0 || door.height <= 0.0) continue;
    const Eigen::Vector2d left =
        plan.surfaces[wall.left_surface].plane.normal.head<2>().normalized();
    const Eigen::Vector2d axis(left.y(), -left.x());  // start → end: left turned back by 90°
    for (int side : {-1, +1}) {
      DoorJamb jamb;
      jamb.wall = it->second;
      jamb.point = door.position.head<2>() + side * 0.5 * door.width * axis;
      jamb.normal = -side * axis;
      jamb.across = left;
      jamb.half_thickness = 0.5 * wall.thickness;
      jamb.z_min = door.position.z();
      jamb.z_max = door.position.z() + door.height;
      jamb.opening = door.width;
      // Too thin a wall leaves no band between its faces' points.
      if (jamb.half_thickness - options_.face_margin < 0.01) continue;
      jambs_.push_back(jamb);
    }
  }
  if (jambs_.empty()) return;
  // The grid: each jamb in every cell its gather box touches.
  Eigen::AlignedBox2d box;
  for (const auto& jamb : jambs_) box.extend(jamb.point);
  const double reach = options_.gather + 0.5;  // the half-thickness and more
  origin_ = box.min() - Eigen::Vector2d::Constant(reach);
  const Eigen::Vector2d extent = box.sizes() + Eigen::Vector2d::Constant(2.0 * reach);
  cell_ = std::max(1.0, std::sqrt(extent.x() * extent.y() / 4e6));
  columns_ = int(std::ceil(extent.x() / cell_)) + 1;
  rows_ = int(std::ceil(extent.y() / cell_)) + 1;
  std::vector<std::vector<int>> cells(std::size_t(columns_) * rows_);
  for (int j = 0; j < int(jambs_.size()); ++j) {
    const Eigen::Vector2d lo = jambs_[j].point - Eigen::Vector2d::Constant(reach) - origin_;
    const Eigen::Vector2d hi = jambs_[j].point + Eigen::Vector2d::Constant(reach) - origin_;
    for (int r = std::max(0, int(lo.y() / cell_)); r <= std::min(rows_ - 1, int(hi.y() / cell_));
         ++r) {
      for (int c = std::max(0, int(lo.x() / cell_));
           c <= std::min(columns_ - 1, int(hi.x() / cell_)); ++c) {
        cells[std::size_t(r) * columns_ + c].push_back(j);
      }
    }
  }
  cell_start_.assign(cells.size() + 1, 0);
  for (std::size_t c = 0; c < cells.size(); ++c) {
    cell_start_[c + 1] = cell_start_[c] + int(cells[c].size());
    cell_jambs_.insert(cell_jambs_.end(), cells[c].begin(), cells[c].end());
  }
}

bool DoorJambs::inWallBand(const DoorJamb& jamb, const Eigen::Vector3d& p, double* u) const {
  const Eigen::Vector2d d = p.head<2>() - jamb.point;
  *u = jamb.normal.dot(d);
  if (std::abs(jamb.across.dot(d)) > jamb.half_thickness - options_.face_margin) return false;
  return p.z() >= jamb.z_min + options_.height_margin &&
         p.z() <= jamb.z_max - options_.height_margin;
}

bool DoorJambs::inBand(const DoorJamb& jamb, const Eigen::Vector3d& p, double* u) const {
  return inWallBand(jamb, p, u) && std::abs(*u) <= options_.gather;
}

std::vector<JambSighting> DoorJambs::gather(const std::vector<sensors::ScanPoint>& points_L,
                                            const Eigen::Isometry3d& P_T_L) const {
  std::vector<JambSighting> sightings;
  if (jambs_.empty()) return sightings;
  // The jambs the sensor faces, within range: the others' points are never looked for.
  const Eigen::Vector2d sensor = P_T_L.translation().head<2>();
  std::vector<int> slot(jambs_.size(), -1);
  bool any = false;
  for (int j = 0; j < int(jambs_.size()); ++j) {
    const Eigen::Vector2d to_sensor = sensor - jambs_[j].point;
    const double range = to_sensor.norm();
    if (range < options_.min_range || range > options_.max_range) continue;
    if (jambs_[j].normal.dot(to_sensor) <= 0.0) continue;  // behind the face: it cannot be seen
    slot[j] = -2;  // wanted; a sighting once a point is found
    any = true;
  }
  if (!any) return sightings;
  std::vector<int> filled(jambs_.size(), 0);
  const Eigen::Matrix3d R = P_T_L.linear();
  const Eigen::Vector3d t = P_T_L.translation();
  for (const auto& point : points_L) {
    const Eigen::Vector3f q(point.x, point.y, point.z);
    const Eigen::Vector3d p = R * q.cast<double>() + t;
    const Eigen::Vector2d g = (p.head<2>() - origin_) / cell_;
    if (!(g.x() >= 0.0 && g.y() >= 0.0 && g.x() < columns_ && g.y() < rows_)) continue;
    const std::size_t c = std::size_t(g.y()) * columns_ + std::size_t(g.x());
    for (int i = cell_start_[c]; i < cell_start_[c + 1]; ++i) {
      const int j = cell_jambs_[i];
      double u = 0.0;
      if (slot[j] == -1 || !inWallBand(jambs_[j], p, &u)) continue;
      if (std::abs(u) > options_.gather) {
        // Deeper into the opening, short of its middle (the grid lists a jamb in the cells
        // within gather + 0.5 m of it: an opening up to 1.6 m wide is counted to its middle).
        if (u > 0.0 && u <= 0.5 * jambs_[j].opening) ++filled[j];
        continue;
      }
      if (slot[j] == -2) {
        slot[j] = int(sightings.size());
        sightings.push_back({j, {}});
      }
      sightings[slot[j]].points_L.push_back(q);
    }
  }
  for (JambSighting& sighting : sightings) {
    sighting.filled = filled[sighting.jamb];
    const std::size_t n = sighting.points_L.size(), keep = std::size_t(options_.max_points);
    if (n <= keep) continue;
    sighting.filled = int(std::size_t(sighting.filled) * keep / n);
    std::vector<Eigen::Vector3f> even(keep);
    for (std::size_t i = 0; i < keep; ++i) even[i] = sighting.points_L[i * n / keep];
    sighting.points_L = std::move(even);
  }
  return sightings;
}

std::optional<DoorJambs::Fit> DoorJambs::fit(const JambSighting& sighting,
                                             const Eigen::Isometry3d& P_T_L) const {
  const DoorJamb& jamb = jambs_[sighting.jamb];
  std::vector<double> offsets;
  std::vector<int> kept;
  offsets.reserve(sighting.points_L.size());
  for (int i = 0; i < int(sighting.points_L.size()); ++i) {
    double u = 0.0;
    if (!inBand(jamb, P_T_L * sighting.points_L[i].cast<double>(), &u)) continue;
    offsets.push_back(u);
    kept.push_back(i);
  }
  if (int(offsets.size()) < options_.min_points) return std::nullopt;
  std::vector<double> sorted = offsets;
  std::nth_element(sorted.begin(), sorted.begin() + sorted.size() / 2, sorted.end());
  const double median = sorted[sorted.size() / 2];
  Fit fit;
  std::vector<double> deviations;
  int open = 0;
  for (std::size_t i = 0; i < offsets.size(); ++i) {
    const double off = offsets[i] - median;
    if (off > options_.cluster) ++open;
    if (std::abs(off) > options_.cluster) continue;
    deviations.push_back(std::abs(off));
    fit.centroid_L += sighting.points_L[kept[i]].cast<double>();
    fit.offset += offsets[i];
    ++fit.points;
  }
  if (fit.points < options_.min_points) return std::nullopt;
  if (double(open + sighting.filled) >
      options_.max_open_share * double(offsets.size() + sighting.filled)) {
    return std::nullopt;
  }
  std::nth_element(deviations.begin(), deviations.begin() + deviations.size() / 2,
                   deviations.end());
  if (deviations[deviations.size() / 2] > options_.max_spread) return std::nullopt;
  fit.centroid_L /= fit.points;
  fit.offset /= fit.points;
  return fit;
}

}  // namespace isg::slam
