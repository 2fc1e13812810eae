#include "slam/deviations/plan_deviations.hpp"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <deque>
#include <map>
#include <numbers>
#include <stdexcept>
#include <tuple>

#include "bim/floor_at.hpp"
#include "bim/polygon.hpp"
#include "common/angles.hpp"
#include "slam/deviations/deviation_threshold.hpp"
#include "slam/deviations/face_views.hpp"
#include "slam/deviations/line_uncertainty.hpp"
#include "slam/deviations/map_wall_sorting.hpp"
#include "slam/deviations/seen_through.hpp"

namespace isg::slam {

namespace {

using bim::cross;

// A plan wall's axis, from its node: the anchor is the axis's middle, the left face's normal its
// left normal.
struct PlannedWall {
  int index = -1;
  Eigen::Vector2d start, end, axis, left;
  double length = 0.0, thickness = 0.0;
  // The face on `side` as a line: a point of it and the planned centre's foot on it.
  Eigen::Vector2d faceCentre(int side) const {
    return 0.5 * (start + end) + side * 0.5 * thickness * left;
  }
};

PlannedWall plannedWall(const bim::AGraph& plan, int w) {
  const bim::WallNode& node = plan.walls[w];
  PlannedWall p;
  p.index = w;
  p.left = plan.surfaces[node.left_surface].plane.normal.head<2>().normalized();
  p.axis = Eigen::Vector2d(p.left.y(), -p.left.x());
  p.length = node.length;
  p.thickness = node.thickness;
  p.start = node.anchor.head<2>() - 0.5 * node.length * p.axis;
  p.end = node.anchor.head<2>() + 0.5 * node.length * p.axis;
  return p;
}

WallInB toB(const MapWall& wall, const Eigen::Isometry3d& B_T_M) {
  WallInB out;
  out.plane = wall.id;
  out.normal = (B_T_M.linear() * wall.normal).head<2>().normalized();
  auto point = [&](const Eigen::Vector2d& p) {
    return (B_T_M * Eigen::Vector3d(p.x(), p.y(), 0.0)).head<2>().eval();
  };
  out.start = point(wall.start);
  out.end = point(wall.end);
  out.z_min = wall.z_min + B_T_M.translation().z();
  out.z_max = wall.z_max + B_T_M.translation().z();
  out.observations = wall.observations;
  out.lean_deg = common::degrees(std::asin(std::min(1.0, std::abs(wall.normal.normalized().z()))));
  const double length = (wall.end - wall.start).norm();
  if (length > 0.0) {
    for (const auto& [a, b] : wall.confirmed) out.confirmed.push_back({a / length, b / length});
  }
  return out;
}

// The level a height in B stands on: the highest floor at or below it (the lowest, below all),
// a micrometre's rounding allowed (a wall's bottom is its floor's elevation).
int levelAt(const bim::AGraph& plan, double z) { return bim::floorAt(plan, z + 1e-6); }

// How far along a planned wall (metres from its start, clipped to it) a segment reaches.
std::pair<double, double> spanAlong(const PlannedWall& w, const Eigen::Vector2d& a,
                                    const Eigen::Vector2d& b) {
  double s0 = (a - w.start).dot(w.axis), s1 = (b - w.start).dot(w.axis);
  if (s0 > s1) std::swap(s0, s1);
  return {std::clamp(s0, 0.0, w.length), std::clamp(s1, 0.0, w.length)};
}

double unionLength(std::vector<std::pair<double, double>> spans) {
  std::sort(spans.begin(), spans.end());
  double total = 0.0, lo = 0.0, hi = -1.0;
  for (const auto& [a, b] : spans) {
    if (a > hi) {
      if (hi > lo) total += hi - lo;
      lo = a, hi = b;
    } else {
      hi = std::max(hi, b);
    }
  }
  if (hi > lo) total += hi - lo;
  return total;
}

// The share of a plan wall's exposed faces in the sensor's view from the keyframes
// (DeviationOptions, "In view"): sampled every 0.25 m, 0.1 m clear of each segment's ends. Only
// what could have been in view counts: not its windows (seen through whether the wall stands or
// not), nor a face no keyframe stood in front of (an outer wall's outer face). Until 2026-12-04
// both counted as not in view, and a façade bay not built, with a window 0.6 m short of each end,
// could never reach the missing share.
double inViewShare(const bim::AGraph& plan, const bim::WallNode& wall,
                   const std::vector<Viewpoint>& viewpoints, const DeviationOptions& options) {
  const FaceViews views(plan, wall, viewpoints, options);
  double exposed = 0.0, in_view = 0.0;
  for (int surface : {wall.left_surface, wall.right_surface}) {
    const bim::WallSurfaceNode& face = plan.surfaces[surface];
    const Eigen::Vector2d n = face.plane.normal.head<2>().normalized();
    double face_exposed = 0.0, face_in_view = 0.0;
    bool faced = false;
    for (const auto& [a, b] : face.segments) {
      const double length = (b - a).norm();
      if (length < 0.2) continue;
      const int samples = std::max(1, int((length - 0.2) / 0.25));
      const double step = (length - 0.2) / samples;
      const Eigen::Vector2d along = (b - a) / length;
      const auto windows = windowSpans(plan, wall, a, along, options.window_margin);
      for (int i = 0; i < samples; ++i) {
        const double s = 0.1 + (i + 0.5) * step;
        const bool at_window = std::any_of(windows.begin(), windows.end(), [&](const auto& w) {
          return s >= w.first && s <= w.second;
        });
        if (at_window) continue;
        face_exposed += step;
        faced = faced || views.faced(a + s * along, n);
        if (views.inView(a + s * along, n)) face_in_view += step;
      }
    }
    if (!faced) continue;
    exposed += face_exposed;
    in_view += face_in_view;
  }
  return exposed > 0.0 ? in_view / exposed : 0.0;
}

// Whether any keyframe recorded how far it saw: "in view" is then "seen past" (FaceViews).
bool withSight(const std::vector<Viewpoint>& viewpoints) {
  return std::any_of(viewpoints.begin(), viewpoints.end(),
                     [](const Viewpoint& v) { return v.hasSight(); });
}

// A piece of evidence measured from its ends: its line's offset at the planned centre along the
// planned left normal, and its direction against the planned one.
void measurePiece(WallEvidence& e, const PlannedWall& planned) {
  Eigen::Vector2d direction = (e.end_B - e.start_B).normalized();
  if (direction.dot(planned.axis) < 0.0) direction = -direction;
  const Eigen::Vector2d centre = planned.faceCentre(e.side);
  e.offset_m = cross(direction, e.start_B - centre) / cross(direction, planned.left);
  e.angle_deg = common::degrees(
      common::angleDifference(common::headingOf(direction), common::headingOf(planned.axis)));
}

// A wall's line as its consistent evidence lays it: o(s) = offset + tan(angle)·s, s along the
// planned axis from its centre, o along the left normal from each piece's planned face. Starting
// from the line of the longest piece seen often enough (observed at least `start_share` as often
// as the most observed piece: a long plane fitted on a keyframe or four, a few degrees off across
// a façade, is not where to start when a piece beside it was seen a hundred times), the pieces
// whose both ends lie within `tolerance` of it are consistent, the line is fitted to their ends
// (weighted by length), three times over. The others (a plane fitted across a corner or a door
// leaf) are kept as evidence but not believed.
void setThresholds(WallDeviation& wall, const WallThresholds& thresholds) {
  wall.shift_threshold_m = thresholds.shift_m;
  wall.angle_threshold_deg = thresholds.angle_deg;
}

struct WallFit {
  double offset_m = 0.0, angle_deg = 0.0;
  double length = 0.0;   // of the consistent pieces
  double longest = 0.0;  // the longest consistent piece
  // Of (offset, slope), from the consistent ends (DeviationOptions::end_sigma_m); the placement's
  // uncertainty is not in it.
  Eigen::Matrix2d covariance = Eigen::Matrix2d::Zero();
};

WallFit fitWall(WallDeviation& wall, const PlannedWall& planned, const DeviationOptions& options) {
  const double tolerance = options.consistent_tolerance;
  const double start_share = options.contradiction_observation_share;
  WallFit fit;
  if (wall.evidence.empty()) return fit;
  auto along = [&](const WallEvidence& e, const Eigen::Vector2d& p) {
    const Eigen::Vector2d q = p - planned.faceCentre(e.side);
    return Eigen::Vector2d(q.dot(planned.axis), q.dot(planned.left));
  };
  int most_observed = 0;
  for (const auto& e : wall.evidence) most_observed = std::max(most_observed, e.observations);
  const auto seen_often = [&](const WallEvidence& e) {
    return e.observations >= start_share * most_observed;
  };
  const auto longest = std::max_element(
      wall.evidence.begin(), wall.evidence.end(), [&](const auto& a, const auto& b) {
        return std::pair(seen_often(a), a.length_m) < std::pair(seen_often(b), b.length_m);
      });
  const Eigen::Vector2d a0 = along(*longest, longest->start_B);
  const Eigen::Vector2d a1 = along(*longest, longest->end_B);
  double slope = (a1.y() - a0.y()) / (a1.x() - a0.x());
  double offset = a0.y() - slope * a0.x();
  for (int round = 0; round < 3; ++round) {
    Eigen::Matrix2d H = Eigen::Matrix2d::Zero();
    Eigen::Vector2d g = Eigen::Vector2d::Zero();
    for (auto& e : wall.evidence) {
      const Eigen::Vector2d ends[2] = {along(e, e.start_B), along(e, e.end_B)};
      e.consistent = std::all_of(std::begin(ends), std::end(ends), [&](const auto& q) {
        return std::abs(q.y() - (offset + slope * q.x())) <= tolerance;
      });
      if (!e.consistent) continue;
      for (const auto& q : ends) {
        const Eigen::Vector2d J(1.0, q.x());
        H += 0.5 * e.length_m * J * J.transpose();
        g += 0.5 * e.length_m * J * q.y();
      }
    }
    if (H(0, 0) <= 0.0) break;
    const Eigen::Vector2d x = H.ldlt().solve(g);
    offset = x(0), slope = x(1);
  }
  fit.offset_m = offset;
  fit.angle_deg = common::degrees(std::atan(slope));
  std::vector<std::pair<Eigen::Vector2d, double>> ends;
  for (const auto& e : wall.evidence) {
    if (!e.consistent) continue;
    fit.length += e.length_m;
    fit.longest = std::max(fit.longest, e.length_m);
    ends.push_back({along(e, e.start_B), 0.5 * e.length_m});
    ends.push_back({along(e, e.end_B), 0.5 * e.length_m});
  }
  fit.covariance = lineCovariance(ends, offset, slope, options.end_sigma_m);
  return fit;
}

// The placements' prior (below), standard deviations: 5 cm, 1°.
constexpr double kPriorT = 0.05, kPriorYaw = common::radians(1.0);
Eigen::Matrix3d priorCovariance() {
  return Eigen::Vector3d(kPriorT * kPriorT, kPriorT * kPriorT, kPriorYaw * kPriorYaw).asDiagonal();
}

// A small correction of the map's place in the plan: p ↦ p + t + θ·perp(p − origin), to first
// order. Applied exactly (a rotation about the origin, then t) to what the report draws.
struct Placement {
  Eigen::Vector3d correction = Eigen::Vector3d::Zero();  // t.x, t.y, θ (rad)
  Eigen::Vector2d origin = Eigen::Vector2d::Zero();
  int walls_used = 0;
  // Of the correction (m², rad²): the inverse of the fit's information, its prior included. Where
  // no wall constrains a direction, the prior's 5 cm and 1° stand for the localizer's placement.
  Eigen::Matrix3d covariance = priorCovariance();
  // How a change of the correction moves a wall's face along its left normal, at its centre:
  // J = [l.x, l.y, l·perp(c − origin)].
  Eigen::Vector3d across(const PlannedWall& planned) const {
    const Eigen::Vector2d c = 0.5 * (planned.start + planned.end) - origin;
    return {planned.left.x(), planned.left.y(), planned.left.dot(Eigen::Vector2d(-c.y(), c.x()))};
  }
  // The standard deviation of where it places a wall's face along the wall's normal.
  double sigmaAcross(const PlannedWall& planned) const {
    const Eigen::Vector3d J = across(planned);
    return std::sqrt(std::max(0.0, J.dot(covariance * J)));
  }
  Eigen::Vector2d move(const Eigen::Vector2d& p) const {
    return origin + Eigen::Rotation2Dd(correction.z()) * (p - origin) + correction.head<2>();
  }
  void apply(WallEvidence& e, const PlannedWall& planned) const {
    e.start_B = move(e.start_B);
    e.end_B = move(e.end_B);
    measurePiece(e, planned);
  }
};

// The placement that best lays the map's walls judged as planned onto their faces: weighted least
// squares of their fitted offsets (weight: consistent length) and directions (weight: length³, a
// fitted direction's variance falling as 1/length³), under a prior of 5 cm and 1° that keeps an
// unconstrained direction where the localizer put it. Walls found deviating leave the fit, and it
// is solved again, until the set holds still (at most 5 times).
Placement refinePlacement(const std::vector<std::pair<WallDeviation, PlannedWall>>& walls,
                          const DeviationOptions& options) {
  Placement placement;
  double total = 0.0;
  for (const auto& [wall, planned] : walls) {
    for (const auto& e : wall.evidence) {
      placement.origin += e.length_m * 0.5 * (planned.start + planned.end);
      total += e.length_m;
    }
  }
  if (total <= 0.0) {
    placement.covariance.setZero();  // no wall around: no correction, and nothing it adds
    return placement;
  }
  placement.origin /= total;
  constexpr double kSigmaOffset = 0.02;
  std::vector<bool> used(walls.size(), false);
  for (int round = 0; round < 5; ++round) {
    std::vector<bool> now(walls.size(), false);
    std::vector<WallFit> fits(walls.size());
    for (std::size_t i = 0; i < walls.size(); ++i) {
      const WallDeviation& wall = walls[i].first;
      if (wall.evidence.empty() || wall.observed_share < options.judged_share) continue;
      WallDeviation moved = wall;
      for (auto& e : moved.evidence) placement.apply(e, walls[i].second);
      fits[i] = fitWall(moved, walls[i].second, options);
      now[i] = std::abs(fits[i].offset_m) < options.shift_m &&
               std::abs(fits[i].angle_deg) < options.angle_deg;
    }
    if (round > 0 && now == used) break;
    used = now;
    // Solved for the change δ from the current correction: fitted offset + J·δ = 0,
    // J = [l.x, l.y, l·perp(c)] at the wall's centre c; fitted angle (rad) + θ = 0.
    Eigen::Matrix3d H = Eigen::Matrix3d::Zero();
    Eigen::Vector3d g = Eigen::Vector3d::Zero();
    H.diagonal() << 1.0 / (kPriorT * kPriorT), 1.0 / (kPriorT * kPriorT),
        1.0 / (kPriorYaw * kPriorYaw);
    g = H * placement.correction;  // the prior holds the total correction, not the change
    placement.walls_used = 0;
    for (std::size_t i = 0; i < walls.size(); ++i) {
      if (!used[i]) continue;
      ++placement.walls_used;
      const Eigen::Vector3d J = placement.across(walls[i].second);
      const double length = fits[i].length;
      const double w = length / (kSigmaOffset * kSigmaOffset);
      H += w * J * J.transpose();
      g += w * J * fits[i].offset_m;
      const double w_angle = length * length * length / (kSigmaOffset * kSigmaOffset);
      H(2, 2) += w_angle;
      g(2) += w_angle * common::radians(fits[i].angle_deg);
    }
    placement.correction -= H.ldlt().solve(g);
    placement.covariance = H.inverse();
  }
  return placement;
}

// What a wall's evidence says beyond its measures (judge() sets those): whether it lies off the
// plan beyond the thresholds, and how often its most observed consistent piece was seen.
struct Judged {
  bool has_evidence = false;
  bool turned = false, shifted = false;
  // Beyond a threshold but not clear of the measure's uncertainty (DeviationOptions::
  // clear_factor): the evidence cannot tell.
  bool undecided = false;
  int most_observed = 0;
};

// The offset's and angle's standard deviations: the fit's, the placement's, and (evidence that
// contradicts itself, measured by the mean of its long pieces) how far those pieces spread.
void setUncertainty(WallDeviation& wall, const WallFit& fit,
                    const std::vector<const WallEvidence*>& spread_over) {
  const double slope = std::tan(common::radians(fit.angle_deg));
  // d(angle)/d(slope) = 1 / (1 + slope²).
  const double angle_fit = common::degrees(std::sqrt(fit.covariance(1, 1)) / (1.0 + slope * slope));
  double offset_var = fit.covariance(0, 0) + wall.placement_sigma_m * wall.placement_sigma_m;
  double angle_var =
      angle_fit * angle_fit + wall.placement_angle_sigma_deg * wall.placement_angle_sigma_deg;
  if (spread_over.size() > 1) {
    double length = 0.0, offset_sq = 0.0, angle_sq = 0.0;
    for (const WallEvidence* e : spread_over) {
      length += e->length_m;
      offset_sq += e->length_m * (e->offset_m - *wall.offset_m) * (e->offset_m - *wall.offset_m);
      angle_sq += e->length_m * (e->angle_deg - *wall.angle_deg) * (e->angle_deg - *wall.angle_deg);
    }
    offset_var += offset_sq / length;
    angle_var += angle_sq / length;
  }
  wall.offset_sigma_m = std::sqrt(offset_var);
  wall.angle_sigma_deg = std::sqrt(angle_var);
}

// A wall's evidence can contradict itself: its two faces, seen from two rooms, laid by the map a
// few centimetres apart. A piece left out of the fit that is at least half as long as the longest
// one it kept, and observed at least contradiction_observation_share as often as the most
// observed one kept, is such a contradiction, not an artefact; the wall is then measured by the
// length-weighted mean of all such long pieces, and called shifted (rotated) only when every one
// of them is beyond the threshold on the same side — the noise the contradiction shows must not
// make a deviation. Its status is decided apart, from what this returns (decideWallStatus).
Judged judge(WallDeviation& wall, const PlannedWall& planned, const DeviationOptions& options) {
  Judged judged;
  if (wall.evidence.empty()) return judged;
  judged.has_evidence = true;
  const WallFit fit = fitWall(wall, planned, options);
  wall.offset_m = fit.offset_m;
  wall.angle_deg = fit.angle_deg;
  int most_observed = 0;  // of the pieces kept
  for (const auto& e : wall.evidence) {
    if (e.consistent) most_observed = std::max(most_observed, e.observations);
  }
  judged.most_observed = most_observed;
  std::vector<const WallEvidence*> long_pieces;
  bool contradicted = false;
  for (const auto& e : wall.evidence) {
    if (e.length_m < 0.5 * fit.longest) continue;
    if (!e.consistent && e.observations < options.contradiction_observation_share * most_observed) {
      continue;  // a stray fit, not a face
    }
    long_pieces.push_back(&e);
    contradicted = contradicted || !e.consistent;
  }
  auto beyond = [&](auto value_of, double threshold) {
    const double first = value_of(*long_pieces.front());
    return std::all_of(long_pieces.begin(), long_pieces.end(), [&](const WallEvidence* e) {
      return std::abs(value_of(*e)) >= threshold && (value_of(*e) > 0) == (first > 0);
    });
  };
  // Set by placedLocally, never under options.shift_m and options.angle_deg.
  const double shift_threshold = wall.shift_threshold_m;
  const double angle_threshold = wall.angle_threshold_deg;
  bool turned =
      std::abs(fit.angle_deg) >= angle_threshold && fit.longest >= options.min_angle_length;
  bool shifted = std::abs(fit.offset_m) >= shift_threshold;
  if (contradicted) {
    double length = 0.0, offset = 0.0, angle = 0.0;
    for (const WallEvidence* e : long_pieces) {
      length += e->length_m;
      offset += e->length_m * e->offset_m;
      angle += e->length_m * e->angle_deg;
    }
    wall.offset_m = offset / length;
    wall.angle_deg = angle / length;
    turned = turned && beyond([](const WallEvidence& e) { return e.angle_deg; }, angle_threshold);
    shifted = shifted && beyond([](const WallEvidence& e) { return e.offset_m; }, shift_threshold);
  }
  setUncertainty(wall, fit, contradicted ? long_pieces : std::vector<const WallEvidence*>{});
  wall.fit_covariance = fit.covariance;
  // Off the plan beyond the threshold, and clear of the measure's own uncertainty.
  const double clear = options.clear_factor;
  const bool turn_clear = std::abs(*wall.angle_deg) >= clear * *wall.angle_sigma_deg;
  const bool shift_clear = std::abs(*wall.offset_m) >= clear * *wall.offset_sigma_m;
  judged.undecided = (turned && !turn_clear) || (shifted && !shift_clear);
  judged.turned = turned && turn_clear;
  judged.shifted = shifted && shift_clear;
  return judged;
}

// A rotated wall's pivot: where its line crosses the planned axis, and its name.
// Its standard deviation along the wall: the pivot is s* = −offset / slope from the centre, as
// loose as the offset over the slope, and the slope's own error moves it by s*/slope.
void setPivot(WallDeviation& wall, const PlannedWall& planned, const DeviationOptions& options) {
  wall.pivot_along_m = crossingAlong(planned.length, *wall.offset_m, *wall.angle_deg);
  if (wall.pivot_along_m) {
    wall.turned_about = pivotName(*wall.pivot_along_m, planned.length, options.pivot_name_distance);
    const double slope = std::tan(common::radians(*wall.angle_deg));
    const double slope_sigma =
        common::radians(wall.angle_sigma_deg.value_or(0.0)) * (1.0 + slope * slope);
    Eigen::Matrix2d covariance = wall.fit_covariance;
    covariance(0, 0) = std::pow(wall.offset_sigma_m.value_or(0.0), 2);
    covariance(1, 1) = slope_sigma * slope_sigma;
    const Eigen::Vector2d J(-1.0 / slope, *wall.offset_m / (slope * slope));
    wall.pivot_sigma_m = std::sqrt(std::max(0.0, J.dot(covariance * J)));
  }
}

// Between two planned axes (that do not cross: walls meet at their ends or along a side).
double wallDistance(const PlannedWall& a, const PlannedWall& b) {
  return std::min({bim::distanceToSegment(a.start, b.start, b.end),
                   bim::distanceToSegment(a.end, b.start, b.end),
                   bim::distanceToSegment(b.start, a.start, a.end),
                   bim::distanceToSegment(b.end, a.start, a.end)});
}

// Unexplained map walls of one level, opposite faces paired into one wall.
std::vector<ExtraWall> extraWalls(const std::vector<WallInB>& unexplained, const std::string& level,
                                  const DeviationOptions& options) {
  std::vector<ExtraWall> out;
  std::vector<bool> used(unexplained.size(), false);
  std::vector<std::size_t> order(unexplained.size());
  for (std::size_t i = 0; i < order.size(); ++i) order[i] = i;
  std::sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) {
    return unexplained[a].length() > unexplained[b].length();
  });
  const double parallel = std::cos(common::radians(10.0));
  for (std::size_t i : order) {
    if (used[i]) continue;
    used[i] = true;
    const WallInB& a = unexplained[i];
    const Eigen::Vector2d axis = (a.end - a.start).normalized();
    ExtraWall wall;
    wall.level = level;
    wall.planes = {a.plane};
    double s0 = 0.0, s1 = a.length();
    Eigen::Vector2d base = a.start;
    for (std::size_t j : order) {
      if (used[j]) continue;
      const WallInB& b = unexplained[j];
      if (a.normal.dot(b.normal) > -parallel) continue;
      const double gap = std::abs(a.normal.dot(b.middle() - a.middle()));
      // By value: std::minmax of temporaries returns references to them.
      const double u0 = (b.start - a.start).dot(axis), u1 = (b.end - a.start).dot(axis);
      const double t0 = std::min(u0, u1), t1 = std::max(u0, u1);
      if (gap > options.extra_pair_distance || t1 < s0 || t0 > s1) continue;
      used[j] = true;
      wall.planes.push_back(b.plane);
      s0 = std::min(s0, t0), s1 = std::max(s1, t1);
      // The wall's axis lies between its faces.
      base = a.start - 0.5 * gap * a.normal;
    }
    wall.start = base + s0 * axis;
    wall.end = base + s1 * axis;
    out.push_back(wall);
  }
  return out;
}

// Placements summed in the plane, to average: their translations and headings.
struct PlanarMean {
  Eigen::Vector2d t = Eigen::Vector2d::Zero(), heading = Eigen::Vector2d::Zero();
  int n = 0;
  void add(const Eigen::Isometry3d& T) {
    t += T.translation().head<2>();
    heading += T.linear().col(0).head<2>().normalized();
    ++n;
  }
  // At height z; none when none was added.
  std::optional<Eigen::Isometry3d> mean(double z) const {
    if (n == 0) return std::nullopt;
    Eigen::Isometry3d out = Eigen::Isometry3d::Identity();
    out.linear() =
        Eigen::AngleAxisd(common::headingOf(heading), Eigen::Vector3d::UnitZ()).toRotationMatrix();
    out.translation() << t / n, z;
    return out;
  }
};

// The planar mean of the placements of the last (up to 20) keyframes that saw a wall, with the
// height of B_T_M; none when none of them has one.
std::optional<Eigen::Isometry3d> placementOf(
    const MapWall& wall, const Eigen::Isometry3d& B_T_M,
    const std::vector<std::optional<Eigen::Isometry3d>>& keyframe_B_T_M) {
  PlanarMean sum;
  for (auto it = wall.keyframes.rbegin(); it != wall.keyframes.rend() && sum.n < 20; ++it) {
    if (*it < 0 || *it >= int(keyframe_B_T_M.size()) || !keyframe_B_T_M[*it]) continue;
    sum.add(*keyframe_B_T_M[*it]);
  }
  return sum.mean(B_T_M.translation().z());
}

}  // namespace

std::optional<double> crossingAlong(double length, double offset_m, double angle_deg) {
  const double slope = std::tan(common::radians(angle_deg));
  if (std::abs(slope) < 1e-9) return std::nullopt;
  return 0.5 * length - offset_m / slope;
}

std::string pivotName(double along_m, double length, double name_distance) {
  const std::pair<const char*, double> named[] = {
      {"start", 0.0}, {"centre", 0.5 * length}, {"end", length}};
  const char* nearest = nullptr;
  double nearest_distance = name_distance;
  for (const auto& [name, at] : named) {
    if (std::abs(along_m - at) <= nearest_distance) {
      nearest = name;
      nearest_distance = std::abs(along_m - at);
    }
  }
  if (nearest != nullptr) return nearest;
  return along_m >= 0.0 && along_m <= length ? "along" : "beyond";
}

int DeviationReport::count(WallStatus status) const {
  return int(std::count_if(walls.begin(), walls.end(),
                           [&](const WallDeviation& w) { return w.status == status; }));
}

namespace {

using LevelWalls = std::vector<std::pair<WallDeviation, PlannedWall>>;

// How well a placement lays the map's walls around `wall` (their middles within local_radius of
// its own, in M; not itself) on the plan: the length of those whose ends and middle all lie
// within consistent_tolerance of the faces they would be evidence for. A count of agreement, not
// a mean distance: on a site where half the walls are built off, those are off under either
// placement, and only the walls as planned can tell the placements apart.
double agreementAround(const bim::AGraph& plan, const MapDiagnostics& map, const MapWall& wall,
                       const Eigen::Isometry3d& placement, const DeviationOptions& options) {
  const Eigen::Vector2d middle = 0.5 * (wall.start + wall.end);
  double agreeing = 0.0;
  for (const MapWall& other : map.walls) {
    if (other.id == wall.id ||
        (0.5 * (other.start + other.end) - middle).norm() > options.local_radius) {
      continue;
    }
    const WallInB in_B = toB(other, placement);
    if (in_B.length() < options.min_wall_length) continue;
    const int level = levelAt(plan, 0.5 * (in_B.z_min + in_B.z_max));
    if (level < 0) continue;
    const int s = surfaceOf(plan, plan.floors[level].id, in_B, options);
    if (s < 0) continue;
    const bim::Plane& face = plan.surfaces[s].plane;
    const Eigen::Vector2d n = face.normal.head<2>().normalized();
    const bool agrees =
        std::max({std::abs(n.dot(in_B.start) + face.d), std::abs(n.dot(in_B.middle()) + face.d),
                  std::abs(n.dot(in_B.end) + face.d)}) <= options.consistent_tolerance;
    if (agrees) agreeing += in_B.length();
  }
  return agreeing;
}

// The map's walls in B, long enough to judge: placed by the final B_T_M, unless the robot's
// poses of the time put the wall farther from it than their own noise: there either the map has
// bent since (a long run: the final B_T_M puts walls seen long ago off) or the robot was
// localized worse then than the final map is (an answer held off for a while): of the two
// placements, the one that lays more of the map's walls around it on the plan (agreementAround)
// places it; the poses of the time when neither does better.
// `placed_by_keyframes`, when given, gets for each of map.walls the placement of its keyframes when
// that placed it.
std::vector<WallInB> wallsInB(
    const bim::AGraph& plan, const MapDiagnostics& map, const Eigen::Isometry3d& B_T_M,
    const DeviationOptions& options,
    const std::vector<std::optional<Eigen::Isometry3d>>& keyframe_B_T_M,
    std::vector<std::optional<Eigen::Isometry3d>>* placed_by_keyframes = nullptr) {
  std::vector<WallInB> walls_in_B;
  if (placed_by_keyframes) placed_by_keyframes->assign(map.walls.size(), std::nullopt);
  for (const auto& w : map.walls) {
    Eigen::Isometry3d placement = B_T_M;
    if (const auto of_its_keyframes = placementOf(w, B_T_M, keyframe_B_T_M)) {
      const Eigen::Vector3d middle(0.5 * (w.start.x() + w.end.x()), 0.5 * (w.start.y() + w.end.y()),
                                   0.0);
      const double moved = ((*of_its_keyframes * middle) - (B_T_M * middle)).head<2>().norm();
      const double turned =
          Eigen::AngleAxisd(of_its_keyframes->linear() * B_T_M.linear().transpose()).angle();
      if (moved > options.bend_distance || turned > common::radians(options.bend_angle_deg)) {
        const double by_final = agreementAround(plan, map, w, B_T_M, options);
        const double by_keyframes = agreementAround(plan, map, w, *of_its_keyframes, options);
        if (by_keyframes >= by_final) {
          placement = *of_its_keyframes;
          if (placed_by_keyframes)
            (*placed_by_keyframes)[std::size_t(&w - map.walls.data())] = placement;
        }
      }
    }
    WallInB in_B = toB(w, placement);
    in_B.behind_walls = w.observations < options.min_deviation_observations &&
                        seenOnlyThroughWalls(map, w, options.min_deviation_observations,
                                             options.see_through_margin);
    if (in_B.length() >= options.min_wall_length) walls_in_B.push_back(in_B);
  }
  return walls_in_B;
}

// Each planned wall of `level` with the map's evidence for its two faces, measured piece by
// piece, and the share of it observed.
LevelWalls levelWalls(const bim::AGraph& plan, const std::string& level,
                      const std::map<int, std::vector<const WallInB*>>& evidence_of_surface) {
  LevelWalls level_walls;
  for (int w = 0; w < int(plan.walls.size()); ++w) {
    const bim::WallNode& node = plan.walls[w];
    // A rectangular column is judged as a column, from the map's points (its faces are shorter
    // than a map wall needs to be evidence): docs/deviations.md, "Columns".
    if (node.level != level || node.column) continue;
    const PlannedWall planned = plannedWall(plan, w);
    WallDeviation wall;
    wall.wall = node.id;
    wall.level = level;
    wall.planned_start = planned.start;
    wall.planned_end = planned.end;
    wall.thickness = planned.thickness;
    std::vector<std::pair<double, double>> spans;
    for (const auto& [surface, side] :
         {std::pair{node.left_surface, +1}, std::pair{node.right_surface, -1}}) {
      const auto it = evidence_of_surface.find(surface);
      if (it == evidence_of_surface.end()) continue;
      for (const WallInB* m : it->second) {
        WallEvidence e;
        e.plane = m->plane;
        e.side = side;
        e.length_m = m->length();
        e.observations = m->observations;
        e.start_B = m->start;
        e.end_B = m->end;
        e.confirmed = m->confirmed;
        measurePiece(e, planned);
        wall.evidence.push_back(e);
        spans.push_back(spanAlong(planned, m->start, m->end));
      }
    }
    wall.observed_share = planned.length > 0.0 ? unionLength(spans) / planned.length : 0.0;
    level_walls.push_back({wall, planned});
  }
  return level_walls;
}

// The map's own error around a wall (DeviationThreshold): what the walls around it found as
// planned keep of offset and angle once the local placement is applied.
void setLocalThresholds(WallDeviation& wall, const PlannedWall& its_plan, const LevelWalls& around,
                        const Placement& local, const DeviationOptions& options) {
  DeviationThreshold threshold(options);
  for (const auto& [neighbour, planned] : around) {
    if (neighbour.evidence.empty() || neighbour.observed_share < options.judged_share) continue;
    WallDeviation moved = neighbour;
    for (auto& e : moved.evidence) local.apply(e, planned);
    const WallFit fit = fitWall(moved, planned, options);
    threshold.addNeighbour(fit.length, fit.longest, fit.offset_m, fit.angle_deg);
  }
  wall.local_offset_noise_m = threshold.offsetNoise();
  wall.local_angle_noise_deg = threshold.angleNoise();
  // And how well those walls fix where the map lies across this one: along a direction none of
  // them constrains (the walls around all run across it, or are all built off), the placement's
  // prior stands for the localizer's, and the wall's own offset cannot be told from the map's.
  wall.placement_sigma_m = local.sigmaAcross(its_plan);
  wall.placement_angle_sigma_deg =
      common::degrees(std::sqrt(std::max(0.0, local.covariance(2, 2))));
  setThresholds(wall, threshold.thresholds(wall.placement_sigma_m));
}

// Each wall against its neighbours alone (DeviationOptions::local_radius): a long map bends a
// little, and a wall is measured against the walls around it, not against the far end of the
// building. Its own evidence stays out of its placement. Its thresholds follow the error those
// neighbours leave (setLocalThresholds).
LevelWalls placedLocally(const LevelWalls& level_walls, const DeviationOptions& options) {
  LevelWalls judged = level_walls;
  for (auto& [wall, planned] : judged) setThresholds(wall, DeviationThreshold::fixed(options));
  for (std::size_t i = 0; i < level_walls.size(); ++i) {
    if (level_walls[i].first.evidence.empty()) continue;
    LevelWalls around;
    for (std::size_t j = 0; j < level_walls.size(); ++j) {
      if (j != i && !level_walls[j].first.evidence.empty() &&
          wallDistance(level_walls[i].second, level_walls[j].second) <= options.local_radius) {
        around.push_back(level_walls[j]);
      }
    }
    const Placement local = refinePlacement(around, options);
    for (auto& e : judged[i].first.evidence) local.apply(e, judged[i].second);
    setLocalThresholds(judged[i].first, judged[i].second, around, local, options);
  }
  return judged;
}

// How much of a judged wall is built. A wall without evidence is not sampled (its views were
// counted for `missing` already): not built when missing, else not seen.
WallProgress progressOf(const bim::AGraph& plan, const WallDeviation& wall,
                        const PlannedWall& planned, const std::vector<Viewpoint>& viewpoints,
                        const DeviationOptions& options) {
  Intervals evidence;
  for (const auto& e : wall.evidence) {
    if (e.confirmed.empty()) {
      evidence.push_back(spanAlong(planned, e.start_B, e.end_B));
      continue;
    }
    for (const auto& [a, b] : e.confirmed) {
      evidence.push_back(spanAlong(planned, e.start_B + a * (e.end_B - e.start_B),
                                   e.start_B + b * (e.end_B - e.start_B)));
    }
  }
  if (!evidence.empty()) {
    // Where the wall stands off its axis at each place along it: its fitted line, a turn's swing
    // included.
    BuiltLine built;
    built.centre = planned.start + 0.5 * planned.length * planned.axis;
    built.axis = planned.axis;
    built.offset_m = wall.offset_m.value_or(0.0);
    built.slope = std::tan(common::radians(wall.angle_deg.value_or(0.0)));
    return measureProgress(plan, plan.walls[planned.index], planned.start, planned.axis,
                           planned.length, evidence, viewpoints, options, built);
  }
  WallProgress progress = measureProgress(plan, plan.walls[planned.index], planned.start,
                                          planned.axis, planned.length, {}, {}, options);
  progress.not_seen_m = progress.planned_m;
  if (wall.status == WallStatus::kMissing) {
    progress.status = ProgressStatus::kNotBuilt;
    progress.not_built_m = wall.in_view_share.value_or(0.0) * progress.planned_m;
    progress.not_seen_m = progress.planned_m - progress.not_built_m;
  }
  return progress;
}

// One level of the report: its walls judged, its placement, the walls the plan lacks.
void measureLevel(const bim::AGraph& plan, int f, const std::vector<WallInB>& walls_in_B,
                  const std::vector<Viewpoint>& viewpoints, const DeviationOptions& options,
                  DeviationReport& report) {
  const std::string& level = plan.floors[f].id;
  report.levels.push_back(level);
  // Each map wall standing on this level to the plan surface it is evidence for, if any.
  std::vector<WallInB> unexplained;
  std::map<int, std::vector<const WallInB*>> evidence_of_surface;
  std::deque<WallInB> pieces;  // of map walls along several faces in line, held in place
  for (const auto& m : walls_in_B) {
    if (levelAt(plan, 0.5 * (m.z_min + m.z_max)) != f) continue;
    SortedMapWall sorted = sortMapWall(plan, level, m, options);
    switch (sorted.role) {
      case MapWallRole::kEvidence:
        evidence_of_surface[sorted.surface].push_back(&m);
        break;
      case MapWallRole::kAlongFacesInLine:
        for (auto& [surface, piece] : sorted.pieces) {
          pieces.push_back(std::move(piece));
          evidence_of_surface[surface].push_back(&pieces.back());
        }
        break;
      case MapWallRole::kUnexplained:
        unexplained.push_back(m);
        break;
      case MapWallRole::kOnColumn:
      case MapWallRole::kStray:
        break;  // judged with the columns; a stray fit, nothing
    }
  }
  LevelWalls level_walls = levelWalls(plan, level, evidence_of_surface);
  // The map's place in the plan, refined on the walls as planned (DeviationOptions,
  // "Placement"), then every wall judged after it.
  const Placement placement = refinePlacement(level_walls, options);
  report.placements.push_back({level, placement.correction, placement.walls_used});
  for (auto& [wall, planned] : level_walls) {
    for (auto& e : wall.evidence) placement.apply(e, planned);
  }
  LevelWalls judged = placedLocally(level_walls, options);
  const bool with_sight = withSight(viewpoints);
  for (std::size_t i = 0; i < judged.size(); ++i) {
    auto& [wall, planned] = judged[i];
    const double planned_length = planned.length;  // a lambda may not capture a binding (clang)
    const auto evidenceOf = [&](const WallDeviation& w, const Judged& j) {
      return StatusEvidence{j.has_evidence, w.observed_share, j.turned,
                            j.shifted,      j.most_observed,  w.in_view_share,
                            with_sight,     planned_length,   j.undecided};
    };
    Judged judged_wall = judge(wall, planned, options);
    // Too few walls around as planned to tell the map's error there (no local noise): the local
    // placement rests on one or two walls, and their own error moves it. A deviation is then
    // believed only when the level's placement, fitted on all its walls, finds it too.
    const WallStatus locally = decideWallStatus(evidenceOf(wall, judged_wall), options);
    if (!wall.local_offset_noise_m &&
        (locally == WallStatus::kShifted || locally == WallStatus::kRotated)) {
      WallDeviation by_level = level_walls[i].first;
      setThresholds(by_level, DeviationThreshold::fixed(options));
      const Judged judged_by_level = judge(by_level, planned, options);
      if (decideWallStatus(evidenceOf(by_level, judged_by_level), options) ==
          WallStatus::kAsPlanned) {
        wall = by_level;
        judged_wall = judged_by_level;
      }
    }
    // Seen too little to judge: how much of it was in view says whether it is missing.
    if (wall.observed_share < options.judged_share) {
      wall.in_view_share = inViewShare(plan, plan.walls[planned.index], viewpoints, options);
    }
    wall.status = decideWallStatus(evidenceOf(wall, judged_wall), options);
    if (wall.status == WallStatus::kRotated) setPivot(wall, planned, options);
    wall.progress = progressOf(plan, wall, planned, viewpoints, options);
    report.walls.push_back(wall);
  }
  for (auto& m : unexplained) {
    m.start = placement.move(m.start);
    m.end = placement.move(m.end);
    m.normal = Eigen::Rotation2Dd(placement.correction.z()) * m.normal;
  }
  for (auto& extra : extraWalls(unexplained, level, options)) {
    report.extra_walls.push_back(std::move(extra));
  }
}

}  // namespace

namespace {

// Where each map keyframe stood in B, for its sight lines (none: left out). In the current
// segment, B_T_M places it, unless most of the walls it saw were placed by their keyframes
// (wallsInB: the final B_T_M put them off where the map had bent): then the mean of those walls'
// placements does, so that its sight lines meet the walls where the report has them. A keyframe of
// a segment that ended is placed where the localizer had it then, or not at all.
std::vector<std::optional<Eigen::Isometry3d>> keyframesInB(
    const MapDiagnostics& map, const Eigen::Isometry3d& B_T_M,
    const std::vector<std::optional<Eigen::Isometry3d>>& keyframe_B_T_M,
    const std::vector<std::optional<Eigen::Isometry3d>>& placed_by_keyframes) {
  std::vector<int> walls_seen(map.keyframes.size(), 0);
  std::vector<PlanarMean> bent(map.keyframes.size());
  for (std::size_t w = 0; w < map.walls.size(); ++w) {
    for (int k : map.walls[w].keyframes) {
      if (k < 0 || k >= int(map.keyframes.size())) continue;
      ++walls_seen[std::size_t(k)];
      if (w < placed_by_keyframes.size() && placed_by_keyframes[w]) {
        bent[std::size_t(k)].add(*placed_by_keyframes[w]);
      }
    }
  }
  std::vector<std::optional<Eigen::Isometry3d>> placements(map.keyframes.size());
  for (std::size_t i = 0; i < map.keyframes.size(); ++i) {
    if (i < map.current_segment) {
      if (i < keyframe_B_T_M.size()) placements[i] = keyframe_B_T_M[i];
    } else if (2 * bent[i].n > walls_seen[i]) {
      placements[i] = bent[i].mean(B_T_M.translation().z());
    } else {
      placements[i] = B_T_M;
    }
  }
  return placements;
}

}  // namespace

std::map<int, std::vector<Viewpoint>> viewpointsOnLevels(
    const bim::AGraph& plan, const MapDiagnostics& map,
    const std::vector<std::optional<Eigen::Isometry3d>>& keyframes_in_B) {
  std::map<int, std::vector<Viewpoint>> viewpoints_on;
  Eigen::Vector2d last(std::nan(""), std::nan(""));
  for (std::size_t i = 0; i < map.keyframes.size(); ++i) {
    if (i >= keyframes_in_B.size() || !keyframes_in_B[i]) continue;
    const MapKeyframe& kf = map.keyframes[i];
    const Eigen::Isometry3d B_T_R = *keyframes_in_B[i] * kf.estimate;
    const Eigen::Vector3d p = B_T_R.translation();
    if ((p.head<2>() - last).norm() < 0.5) continue;
    last = p.head<2>();
    const int level = levelAt(plan, p.z());
    if (level < 0) continue;
    viewpoints_on[level].push_back(
        {(B_T_R * kf.sight.sensor_R).head<2>(), common::yawOf(B_T_R.linear()), &kf.sight});
  }
  return viewpoints_on;
}

DeviationReport measureDeviations(
    const bim::AGraph& plan, const MapDiagnostics& map, const Eigen::Isometry3d& B_T_M,
    const DeviationOptions& options,
    const std::vector<std::optional<Eigen::Isometry3d>>& keyframe_B_T_M) {
  if (const auto invalid = options.invalidField()) {
    throw std::invalid_argument("deviation options: " + *invalid);
  }
  DeviationReport report;
  report.options = options;
  std::vector<std::optional<Eigen::Isometry3d>> placed_by_keyframes;
  const std::vector<WallInB> walls_in_B =
      wallsInB(plan, map, B_T_M, options, keyframe_B_T_M, &placed_by_keyframes);
  report.keyframes_in_B = keyframesInB(map, B_T_M, keyframe_B_T_M, placed_by_keyframes);
  std::map<int, std::vector<Viewpoint>> viewpoints_on =
      viewpointsOnLevels(plan, map, report.keyframes_in_B);
  for (int f = 0; f < int(plan.floors.size()); ++f) {
    if (!viewpoints_on.count(f)) continue;
    measureLevel(plan, f, walls_in_B, viewpoints_on[f], options, report);
  }
  return report;
}

}  // namespace isg::slam
