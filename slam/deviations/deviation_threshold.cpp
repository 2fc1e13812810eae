#include "slam/deviations/deviation_threshold.hpp"

#include <algorithm>
#include <cmath>

namespace isg::slam {

bool DeviationThreshold::addNeighbour(double length_m, double longest_m, double offset_m,
                                      double angle_deg) {
  if (std::abs(offset_m) >= options_.shift_m || std::abs(angle_deg) >= options_.angle_deg) {
    return false;
  }
  offset_weight_ += length_m;
  offset_sum_ += length_m * offset_m * offset_m;
  ++offset_walls_;
  if (longest_m >= options_.min_angle_length) {
    angle_weight_ += length_m;
    angle_sum_ += length_m * angle_deg * angle_deg;
    ++angle_walls_;
  }
  return true;
}

std::optional<double> DeviationThreshold::noise(double sum, double weight, int walls) const {
  if (walls < std::max(options_.min_noise_walls, 4) || weight <= 0.0) return std::nullopt;
  return std::sqrt(sum / weight * double(walls) / double(walls - 3));
}

std::optional<double> DeviationThreshold::offsetNoise() const {
  return noise(offset_sum_, offset_weight_, offset_walls_);
}

std::optional<double> DeviationThreshold::angleNoise() const {
  return noise(angle_sum_, angle_weight_, angle_walls_);
}

WallThresholds DeviationThreshold::thresholds(double placement_sigma_m) const {
  const double factor = options_.noise_factor;
  return {std::max(
              {options_.shift_m, factor * offsetNoise().value_or(0.0), factor * placement_sigma_m}),
          std::max(options_.angle_deg, factor * angleNoise().value_or(0.0))};
}

}  // namespace isg::slam
