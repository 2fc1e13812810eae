#include "sim/scan_caster.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "bim/polygon.hpp"

namespace isg::sim {

namespace {

constexpr double kPi = 3.14159265358979323846;

// A monotonic stand-in for atan2 on [0, 4): cheaper, and only its order matters for sectors.
inline double diamondAngle(double x, double y) {
  if (y >= 0) return x >= 0 ? y / (x + y) : 1 - x / (-x + y);
  return x < 0 ? 2 - y / (-x - y) : 3 + x / (x - y);
}

}  // namespace

ScanCaster::ScanCaster(const RayCaster& caster, int sectors) : caster_(caster), sectors_(sectors) {}

int ScanCaster::sectorOf(double x, double y) const {
  const int k = int(diamondAngle(x, y) * (sectors_ / 4.0));
  return std::min(k, sectors_ - 1);
}

void ScanCaster::prepare(const Eigen::Vector2d& centre, double radius) {
  centre_ = centre;
  radius_ = radius;
  candidates_.clear();
  everywhere_.clear();
  std::vector<std::vector<Candidate>> per_sector(sectors_);
  const auto& boxes = caster_.boxes_;
  for (int b = 0; b < int(boxes.size()); ++b) {
    const auto& box = boxes[b];
    // The box's footprint: exact for boxes standing upright, else its bounding rectangle.
    std::vector<Eigen::Vector2d> corners;
    if (std::abs(box.mat(2, 2)) > 1.0 - 1e-12) {
      const Eigen::Vector2d c = box.pos.head<2>();
      const Eigen::Vector2d u = box.mat.col(0).head<2>() * box.half.x();
      const Eigen::Vector2d v = box.mat.col(1).head<2>() * box.half.y();
      corners = {c - u - v, c + u - v, c + u + v, c - u + v};
    } else {
      const Eigen::Vector3d e = box.mat.cwiseAbs() * box.half;
      const Eigen::Vector2d lo = box.pos.head<2>() - e.head<2>(),
                            hi = box.pos.head<2>() + e.head<2>();
      corners = {lo, {hi.x(), lo.y()}, hi, {lo.x(), hi.y()}};
    }
    // Least distance from the disc to the footprint (0 when they touch).
    double distance =
        bim::containsPoint(corners, centre) ? 0.0 : std::numeric_limits<double>::infinity();
    for (int i = 0; i < 4; ++i) {
      distance =
          std::min(distance, bim::distanceToSegment(centre, corners[i], corners[(i + 1) % 4]));
    }
    const double pad = 1e-6;  // rounding margin, metres
    const double min_distance = std::max(0.0, distance - radius - pad);
    if (distance <= radius + 1e-3) {
      everywhere_.push_back({min_distance, b});
      continue;
    }
    // Angular interval of (footprint ⊕ disc) seen from the centre, relative to the direction of
    // the footprint's centre; it is less than π wide because the disc does not reach the box.
    const Eigen::Vector2d mid = 0.25 * (corners[0] + corners[1] + corners[2] + corners[3]) - centre;
    const double base = std::atan2(mid.y(), mid.x());
    double lo = std::numeric_limits<double>::infinity(), hi = -lo;
    for (const auto& q : corners) {
      const Eigen::Vector2d d = q - centre;
      double a = std::atan2(d.y(), d.x()) - base;
      a = std::remainder(a, 2 * kPi);
      const double widen =
          std::asin(std::min(1.0, (radius + pad) / std::max(d.norm(), 1e-9))) + 1e-9;
      lo = std::min(lo, a - widen);
      hi = std::max(hi, a + widen);
    }
    // Walk the sectors from lo to hi (through the wrap at ±π).
    const int first = sectorOf(std::cos(base + lo), std::sin(base + lo));
    const int last = sectorOf(std::cos(base + hi), std::sin(base + hi));
    for (int k = first;; k = (k + 1) % sectors_) {
      per_sector[k].push_back({min_distance, b});
      if (k == last) break;
    }
  }
  sector_begin_.assign(sectors_ + 1, 0);
  for (int k = 0; k < sectors_; ++k) {
    auto& list = per_sector[k];
    std::sort(list.begin(), list.end(), [](const Candidate& a, const Candidate& b) {
      return a.min_distance < b.min_distance;
    });
    sector_begin_[k] = int(candidates_.size());
    candidates_.insert(candidates_.end(), list.begin(), list.end());
  }
  sector_begin_[sectors_] = int(candidates_.size());
}

std::optional<RayCaster::Hit> ScanCaster::cast(const Eigen::Vector3d& origin,
                                               const Eigen::Vector3d& direction) const {
  const double horizontal = direction.x() * direction.x() + direction.y() * direction.y();
  if (radius_ < 0 || horizontal < 1e-12 ||
      (origin.head<2>() - centre_).squaredNorm() > radius_ * radius_) {
    return caster_.cast(origin, direction);
  }
  RayCaster::Hit best;
  auto consider = [&best](double x, int geom) {
    if (x >= 0 &&
        (best.distance < 0 || x < best.distance || (x == best.distance && geom < best.geom))) {
      best = {x, geom};
    }
  };
  for (const auto& box : caster_.large_) {
    consider(caster_.intersectSlab(box, origin, direction), box.geom);
  }
  for (int g : caster_.others_) consider(caster_.intersectOther(g, origin, direction), g);
  for (int g : caster_.moving_) consider(caster_.intersectOther(g, origin, direction), g);
  for (const auto& c : everywhere_) {
    const auto& box = caster_.boxes_[c.box];
    consider(caster_.intersectBox(box, origin, direction), box.geom);
  }
  const int k = sectorOf(direction.x(), direction.y());
  for (int i = sector_begin_[k]; i < sector_begin_[k + 1]; ++i) {
    const Candidate& c = candidates_[i];
    if (best.distance >= 0 && c.min_distance > best.distance) break;
    const auto& box = caster_.boxes_[c.box];
    consider(caster_.intersectBox(box, origin, direction), box.geom);
  }
  if (best.distance < 0) return std::nullopt;
  return best;
}

}  // namespace isg::sim
