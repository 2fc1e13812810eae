#pragma once

#include <optional>

#include "slam/deviations/deviation_options.hpp"

namespace isg::slam {

// What a wall's offset and turn must reach to be called shifted or rotated.
struct WallThresholds {
  double shift_m = 0.0;
  double angle_deg = 0.0;
};

// The one component that sets the report's thresholds, following the map's own noise around a
// wall (DeviationOptions::noise_factor, docs/deviations.md "Thresholds"): fed the walls around it
// as the local placement left them, it keeps the length-weighted mean square of their offsets
// (and, of those at least min_angle_length long, their angles), leaving out any that deviate
// themselves (their offset is their own, not the map's error). Where the map is worse, a wall is
// judged against `noise_factor` times that noise, never below the options' own thresholds.
class DeviationThreshold {
 public:
  explicit DeviationThreshold(const DeviationOptions& options) : options_(options) {}

  // A wall around whose consistent evidence (`length_m` long, its longest piece `longest_m`)
  // lies `offset_m` and `angle_deg` off its plan once the local placement is applied. Returns
  // whether it counts (false: it deviates by the options' own thresholds).
  bool addNeighbour(double length_m, double longest_m, double offset_m, double angle_deg);

  // The map's error around the wall: the RMS residual, scaled by √(n/(n−3)) for the three
  // numbers the placement fitted on the n walls; none with fewer than max(min_noise_walls, 4).
  std::optional<double> offsetNoise() const;  // m
  std::optional<double> angleNoise() const;   // degrees

  // The wall's thresholds when its local placement fixes the map across it to
  // `placement_sigma_m` (WallDeviation::placement_sigma_m): the shift at least noise_factor
  // times the offset noise and times that sigma, the turn at least noise_factor times the angle
  // noise.
  WallThresholds thresholds(double placement_sigma_m) const;

  // Where the map's noise is not known (before the local placements, or a wall judged by its
  // level's placement alone): the options' own.
  static WallThresholds fixed(const DeviationOptions& options) {
    return {options.shift_m, options.angle_deg};
  }

 private:
  std::optional<double> noise(double sum, double weight, int walls) const;

  const DeviationOptions& options_;
  double offset_weight_ = 0.0, offset_sum_ = 0.0, angle_weight_ = 0.0, angle_sum_ = 0.0;
  int offset_walls_ = 0, angle_walls_ = 0;
};

}  // namespace isg::slam
