#include "bim/facade.hpp"

#include <algorithm>

#include "bim/column.hpp"
#include "bim/plan_geometry.hpp"
#include "bim/polygon.hpp"

namespace isg::bim {

Polygon2 facadeOutline(const Level& level) {
  std::vector<Eigen::Vector2d> points;
  for (const auto& wall : computeLevelGeometry(level).walls) {
    for (const auto& p : wall.footprint()) points.push_back(p);
  }
  for (const auto& column : level.columns) {  // rectangular ones are among the walls already
    if (!column.round()) continue;
    for (const auto& p : columnFootprint(column)) points.push_back(p);
  }
  std::sort(points.begin(), points.end(), [](const Eigen::Vector2d& a, const Eigen::Vector2d& b) {
    return a.x() < b.x() || (a.x() == b.x() && a.y() < b.y());
  });
  points.erase(std::unique(points.begin(), points.end()), points.end());
  if (points.size() < 3) return {};
  // Andrew's monotone chain: the lower hull left to right, then the upper one back.
  const auto turn = [](const Eigen::Vector2d& o, const Eigen::Vector2d& a,
                       const Eigen::Vector2d& b) {
    return (a.x() - o.x()) * (b.y() - o.y()) - (a.y() - o.y()) * (b.x() - o.x());
  };
  Polygon2 hull(2 * points.size());
  std::size_t k = 0;
  for (std::size_t i = 0; i < points.size(); ++i) {
    while (k >= 2 && turn(hull[k - 2], hull[k - 1], points[i]) <= 0) --k;
    hull[k++] = points[i];
  }
  for (std::size_t i = points.size() - 1, lower = k + 1; i > 0; --i) {
    while (k >= lower && turn(hull[k - 2], hull[k - 1], points[i - 1]) <= 0) --k;
    hull[k++] = points[i - 1];
  }
  hull.resize(k - 1);
  return hull;
}

bool isOpenFloor(const Level& level) {
  if (level.rooms.empty()) return true;
  double rooms = 0.0;
  for (const auto& room : level.rooms) rooms += std::abs(signedArea(room.outline));
  // The hull lies within the walls' box: rooms covering a quarter of the box cover a quarter of
  // the hull, without computing it (a roomed building, the usual case, stops here).
  Eigen::Vector2d lo = level.walls.empty() ? Eigen::Vector2d::Zero() : level.walls[0].start;
  if (level.walls.empty() && !level.columns.empty()) lo = level.columns[0].center;
  Eigen::Vector2d hi = lo;
  for (const auto& w : level.walls) {
    const double t = 0.5 * w.thickness;
    lo = lo.cwiseMin(w.start.cwiseMin(w.end) - Eigen::Vector2d::Constant(t));
    hi = hi.cwiseMax(w.start.cwiseMax(w.end) + Eigen::Vector2d::Constant(t));
  }
  for (const auto& c : level.columns) {
    const Eigen::Vector2d reach = Eigen::Vector2d::Constant(0.5 * c.size.norm());
    lo = lo.cwiseMin(c.center - reach);
    hi = hi.cwiseMax(c.center + reach);
  }
  const Eigen::Vector2d box = hi - lo;
  if (rooms >= kOpenFloorRoomShare * box.x() * box.y()) return false;
  const Polygon2 outline = facadeOutline(level);
  if (outline.size() < 3) return false;
  return rooms < kOpenFloorRoomShare * std::abs(signedArea(outline));
}

}  // namespace isg::bim
