#include "sim/scan_caster.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <numbers>

#include "bim/polygon.hpp"

namespace isg::sim {

namespace {

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

int ScanCaster::sectorOfDiamond(double d) const {
  if (d < 0) d += 4;
  if (d >= 4) d -= 4;
  return std::clamp(int(d * (sectors_ / 4.0)), 0, sectors_ - 1);
}

void ScanCaster::prepare(const Eigen::Vector2d& centre, double radius) {
  centre_ = centre;
  radius_ = radius;
  everywhere_.clear();
  // First pass: each box's least distance and the sectors [first, last] it may occupy.
  spans_.clear();
  const auto& boxes = caster_.boxes_;
  for (int b = 0; b < int(boxes.size()); ++b) {
    const auto& box = boxes[b];
    // The box's footprint: exact for boxes standing upright, else its bounding rectangle.
    std::array<Eigen::Vector2d, 4> corners;
    if (box.upright) {
      const Eigen::Vector2d c = box.pos.head<2>();
      const Eigen::Vector2d u = box.mat.col(0).head<2>() * box.half.x();
      const Eigen::Vector2d v = box.mat.col(1).head<2>() * box.half.y();
      corners = {c - u - v, c + u - v, c + u + v, c - u + v};
    } else {
      const Eigen::Vector3d e = box.mat.cwiseAbs() * box.half;
      const Eigen::Vector2d lo = box.pos.head<2>() - e.head<2>(),
                            hi = box.pos.head<2>() + e.head<2>();
      corners = {lo, Eigen::Vector2d(hi.x(), lo.y()), hi, Eigen::Vector2d(lo.x(), hi.y())};
    }
    // Least distance from the disc to the footprint (0 when they touch). The footprint is a
    // convex quadrilateral: the centre is inside when it lies on the same side of every edge (on
    // an edge the distance below is 0 anyway, and so is the bound).
    int left = 0, right = 0;
    for (int i = 0; i < 4; ++i) {
      const Eigen::Vector2d e = corners[(i + 1) % 4] - corners[i];
      const Eigen::Vector2d q = centre - corners[i];
      const double side = e.x() * q.y() - e.y() * q.x();
      left += side > 0;
      right += side < 0;
    }
    double distance = left == 0 || right == 0 ? 0.0 : std::numeric_limits<double>::infinity();
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
    // Measured in diamondAngle's units (monotonic in the angle, a half-turn is 2), without a
    // trigonometric function: each corner's disc seen from the centre lies between the two
    // tangents to it, the corner's direction turned by ±asin(r / |d|), whose cosine and sine are
    // √(1 − s²) and s for s = r / |d|. One sector more at either end covers rounding.
    const Eigen::Vector2d mid = 0.25 * (corners[0] + corners[1] + corners[2] + corners[3]) - centre;
    const double base = diamondAngle(mid.x(), mid.y());
    double lo = std::numeric_limits<double>::infinity(), hi = -lo;
    for (const auto& q : corners) {
      const Eigen::Vector2d d = q - centre;
      const double length = d.norm();  // > radius: the disc does not reach the box
      const double sine = std::min(1.0, (radius + pad) / length);
      const double cosine = std::sqrt(1.0 - sine * sine);
      const Eigen::Vector2d along = d / length, across(-along.y(), along.x());
      for (const double turn : {-sine, sine}) {
        const Eigen::Vector2d tangent = cosine * along + turn * across;
        double relative = diamondAngle(tangent.x(), tangent.y()) - base;
        if (relative >= 2) relative -= 4;
        if (relative < -2) relative += 4;
        lo = std::min(lo, relative);
        hi = std::max(hi, relative);
      }
    }
    spans_.push_back({min_distance, b, (sectorOfDiamond(base + lo) + sectors_ - 1) % sectors_,
                      (sectorOfDiamond(base + hi) + 1) % sectors_});
  }
  // Second pass: count, then fill in order of distance, so every sector comes out sorted.
  std::sort(spans_.begin(), spans_.end(),
            [](const Span& a, const Span& b) { return a.min_distance < b.min_distance; });
  sector_begin_.assign(sectors_ + 1, 0);
  auto for_each_sector = [this](const Span& span, auto&& f) {
    for (int k = span.first;; k = (k + 1) % sectors_) {
      f(k);
      if (k == span.last) break;
    }
  };
  for (const auto& span : spans_) for_each_sector(span, [&](int k) { ++sector_begin_[k + 1]; });
  for (int k = 0; k < sectors_; ++k) sector_begin_[k + 1] += sector_begin_[k];
  candidates_.resize(sector_begin_[sectors_]);
  fill_.assign(sector_begin_.begin(), sector_begin_.end() - 1);
  for (const auto& span : spans_) {
    for_each_sector(span, [&](int k) { candidates_[fill_[k]++] = {span.min_distance, span.box}; });
  }
}

std::optional<RayCaster::Hit> ScanCaster::cast(const Eigen::Vector3d& origin,
                                               const Eigen::Vector3d& direction) const {
  const double horizontal = direction.x() * direction.x() + direction.y() * direction.y();
  if (radius_ < 0 || horizontal < 1e-12 ||
      (origin.head<2>() - centre_).squaredNorm() > radius_ * radius_) {
    return caster_.cast(origin, direction);
  }
  RayCaster::Hit best;
  caster_.castAlwaysTested(origin, direction, best);
  for (const auto& c : everywhere_) {
    const auto& box = caster_.boxes_[c.box];
    best.consider(caster_.intersectSolid(box, origin, direction), box.geom);
  }
  const int k = sectorOf(direction.x(), direction.y());
  for (int i = sector_begin_[k]; i < sector_begin_[k + 1]; ++i) {
    const Candidate& c = candidates_[i];
    if (best.distance >= 0 && c.min_distance > best.distance) break;
    const auto& box = caster_.boxes_[c.box];
    best.consider(caster_.intersectSolid(box, origin, direction), box.geom);
  }
  if (best.distance < 0) return std::nullopt;
  return best;
}

}  // namespace isg::sim
