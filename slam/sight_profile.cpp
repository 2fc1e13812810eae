#include "slam/sight_profile.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace isg::slam {

namespace {

int binOf(double azimuth) {
  const double turns = azimuth / (2.0 * M_PI);
  const double wrapped = turns - std::floor(turns);  // [0, 1)
  return std::min(SightProfile::kBins - 1, int(wrapped * SightProfile::kBins));
}

}  // namespace

double SightProfile::rangeToward(double azimuth_R) const {
  if (range_cm.empty()) return 0.0;
  const std::uint16_t cm = range_cm[binOf(azimuth_R)];
  return cm == kOutOfRange ? std::numeric_limits<double>::infinity() : 0.01 * cm;
}

SightProfile sightProfile(const sensors::Scan& scan, const Eigen::Isometry3d& R_T_L, double z_min_R,
                          double z_max_R) {
  SightProfile profile;
  profile.sensor_R = R_T_L.translation();
  // The farthest squared horizontal range per degree (the root taken once a degree, not once a
  // return: this runs over every return of every keyframe).
  std::vector<float> farthest_sq(SightProfile::kBins, -1.0f);
  // Whether a near-level beam returned in the degree. A degree whose returns all come from beams
  // pointing down (the floor short of an opening to the outside) saw no vertical surface ahead
  // within range: its near-level beams went out. Near-level is within kLevel of horizontal: a
  // LiDAR whose rings are at most 2·kLevel apart always has one there, whatever its tilt.
  constexpr float kLevel = 0.0349f;  // tan 2°
  std::vector<char> level_return(SightProfile::kBins, 0);
  const Eigen::Matrix3f R_R_L = R_T_L.linear().cast<float>();
  const float z_lo = float(z_min_R - profile.sensor_R.z());
  const float z_hi = float(z_max_R - profile.sensor_R.z());
  constexpr float kBinsPerRadian = float(SightProfile::kBins / (2.0 * M_PI));
  for (const auto& point : scan.points) {
    // The return relative to the sensor, in R's axes.
    const Eigen::Vector3f v = R_R_L * Eigen::Vector3f(point.x, point.y, point.z);
    if (v.z() < z_lo || v.z() > z_hi) continue;
    float turn = std::atan2(v.y(), v.x()) * kBinsPerRadian;  // (−180, 180] bins
    if (turn < 0.0f) turn += float(SightProfile::kBins);
    const int bin = std::min(SightProfile::kBins - 1, int(turn));
    float& bin_sq = farthest_sq[bin];
    const float horizontal_sq = v.x() * v.x() + v.y() * v.y();
    bin_sq = std::max(bin_sq, horizontal_sq);
    if (v.z() * v.z() <= kLevel * kLevel * horizontal_sq) level_return[bin] = 1;
  }
  const auto seen =
      std::count_if(farthest_sq.begin(), farthest_sq.end(), [](float sq) { return sq >= 0.0f; });
  profile.range_cm.assign(SightProfile::kBins, 0);
  // A scan that saw too little sees past nothing.
  if (2 * seen < SightProfile::kBins) return profile;
  // Only a scan whose near-level beams returned in most degrees tells a degree where they did not
  // (a LiDAR with no ring near level, or one tilted far, keeps the farthest return alone).
  const bool level_rings =
      2 * std::count(level_return.begin(), level_return.end(), char(1)) >= SightProfile::kBins;
  for (int bin = 0; bin < SightProfile::kBins; ++bin) {
    const float sq = level_rings && !level_return[bin] ? -1.0f : farthest_sq[bin];
    // At least 1 cm, so that a return marks its degree seen.
    profile.range_cm[bin] =
        sq < 0.0f ? SightProfile::kOutOfRange
                  : std::uint16_t(std::clamp(std::round(100.0 * std::sqrt(double(sq))), 1.0,
                                             double(SightProfile::kOutOfRange - 1)));
  }
  return profile;
}

}  // namespace isg::slam
