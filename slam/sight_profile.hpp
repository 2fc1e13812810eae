#pragma once

#include <Eigen/Geometry>
#include <cstdint>
#include <vector>

#include "sensors/messages.hpp"

namespace isg::slam {

// How far the sensor saw around a keyframe, in the horizontal plane: per degree of azimuth about
// the sensor (in the base frame R, from its x axis), the farthest return's horizontal distance.
// Evidence of absence (docs/deviations.md, "Seen past"): a plan wall is not built where the
// sensor saw past it. A return's sight line runs from the sensor to it, so one at any height
// between the floor and the ceiling crossed a full-height wall between them at a height it
// stands at; only returns within a height band are taken, so that a view down a stairwell or up
// through an opening does not count.
struct SightProfile {
  static constexpr int kBins = 360;
  // A degree with no return in the band, in a scan that had returns in most, or with returns only
  // from beams pointing down (more than 2° below level: the floor short of an opening) where the
  // scan's near-level beams returned in most degrees: its near-level sight lines met nothing in
  // the sensor's range (out of an opening, into the open).
  static constexpr std::uint16_t kOutOfRange = 0xFFFF;
  Eigen::Vector3d sensor_R = Eigen::Vector3d::Zero();  // the sensor's origin in R
  // kBins ranges, or kOutOfRange; all 0 for a scan with returns in the band in fewer than half
  // of its degrees (it saw too little to say it saw past anything).
  std::vector<std::uint16_t> range_cm;

  bool empty() const { return range_cm.empty(); }
  // The farthest horizontal distance seen toward `azimuth_R` (rad, in R about sensor_R), metres;
  // infinite out of range.
  double rangeToward(double azimuth_R) const;
};

// The profile of a deskewed scan (in L) mounted by R_T_L: its returns whose height in R lies in
// [z_min_R, z_max_R].
SightProfile sightProfile(const sensors::Scan& scan, const Eigen::Isometry3d& R_T_L, double z_min_R,
                          double z_max_R);

}  // namespace isg::slam
