#include "sim/walk_path.hpp"

#include <algorithm>
#include <cmath>

#include "common/angles.hpp"

namespace isg::sim {

namespace {

// The fits' smoothness weight against a sample's unit weight: negligible beside the samples
// (a 1 m/s² turn costs 1e-3 × (0.04 m)² per knot, against centimetre misfits of 1e-4 m² per
// sample), it only shapes the path across gaps.
constexpr double kSmoothness = 1e-3;

}  // namespace

WalkPath::WalkPath(const std::vector<bim::WalkPose>& walk, bool file_orientation, double turn_rate,
                   bool sensor_path)
    : sensor_path_(sensor_path) {
  std::vector<double> times, xs, ys;
  times.reserve(walk.size());
  for (const auto& pose : walk) {
    times.push_back(pose.t);
    xs.push_back(pose.xy.x());
    ys.push_back(pose.xy.y());
  }
  duration_ = times.back();
  const SmoothingSplineFit fit(times, sensor_path ? kSensorKnotSpacing : kWalkKnotSpacing,
                               kSmoothness);
  x_ = fit.fit(xs);
  y_ = fit.fit(ys);
  if (sensor_path) fitAttitude(walk, fit);

  std::vector<double> speeds(walk.size());
  for (std::size_t i = 0; i < walk.size(); ++i) {
    speeds[i] = std::hypot(x_.at(times[i]).rate, y_.at(times[i]).rate);
  }
  std::vector<double> yaws(walk.size());
  if (file_orientation) {
    yaws[0] = walk[0].yaw;
    for (std::size_t i = 1; i < walk.size(); ++i) {
      yaws[i] = yaws[i - 1] + common::wrapAngle(walk[i].yaw - walk[i - 1].yaw);
    }
  } else {
    // The way ahead where the walk moves; before it first moves, the way it first goes.
    auto travel = [&](std::size_t i) {
      return std::atan2(y_.at(times[i]).rate, x_.at(times[i]).rate);
    };
    std::size_t first = 0;
    while (first < walk.size() && speeds[first] < kHeadingSpeed) ++first;
    double yaw = first < walk.size() ? travel(first) : walk[0].yaw;
    for (std::size_t i = 0; i < walk.size(); ++i) {
      if (speeds[i] >= kHeadingSpeed && i > 0) {
        const double most = turn_rate * (times[i] - times[i - 1]);
        yaw += std::clamp(common::wrapAngle(travel(i) - yaw), -most, most);
      }
      yaws[i] = yaw;
    }
  }
  yaw_ = fit.fit(yaws);
  std::vector<double> gaits(walk.size());
  for (std::size_t i = 0; i < walk.size(); ++i) {
    gaits[i] =
        std::clamp((speeds[i] - kStandingSpeed) / (kFullGaitSpeed - kStandingSpeed), 0.0, 1.0);
  }
  // A sensor's path carries the walker's own sway: none is added.
  gait_ = fit.fit(sensor_path ? std::vector<double>(walk.size(), 0.0) : gaits);

  std::vector<double> deviations(walk.size());
  for (std::size_t i = 0; i < walk.size(); ++i) {
    deviations[i] = (at(times[i]).xy - walk[i].xy).norm();
    if (deviations[i] > max_deviation_) {
      max_deviation_ = deviations[i];
      max_deviation_line_ = walk[i].line;
    }
  }
  const auto middle = deviations.begin() + std::ptrdiff_t(deviations.size() / 2);
  std::nth_element(deviations.begin(), middle, deviations.end());
  median_deviation_ = *middle;
}

void WalkPath::fitAttitude(const std::vector<bim::WalkPose>& walk, const SmoothingSplineFit& fit) {
  std::vector<double> zs(walk.size()), rolls(walk.size()), pitches(walk.size());
  for (std::size_t i = 0; i < walk.size(); ++i) {
    zs[i] = walk[i].z;
    pitches[i] = walk[i].pitch;
    // Unwrapped, so that a roll through ±180° is a turn, not a jump.
    rolls[i] =
        i == 0 ? walk[0].roll : rolls[i - 1] + common::wrapAngle(walk[i].roll - walk[i - 1].roll);
  }
  z_ = fit.fit(zs);
  roll_ = fit.fit(rolls);
  pitch_ = fit.fit(pitches);
}

WalkPath::State WalkPath::at(double t) const {
  const auto x = x_.at(t), y = y_.at(t), yaw = yaw_.at(t), gait = gait_.at(t);
  State s;
  s.xy = {x.value, y.value};
  s.velocity = {x.rate, y.rate};
  s.acceleration = {x.acceleration, y.acceleration};
  s.yaw = yaw.value;
  s.yaw_rate = yaw.rate;
  s.yaw_acceleration = yaw.acceleration;
  if (sensor_path_) {
    s.z = z_.at(t);
    s.roll = roll_.at(t);
    s.pitch = pitch_.at(t);
  }
  // The fit may overshoot [0, 1] a little where the pace changes; the sway's weight stays in it.
  if (gait.value <= 0.0 || gait.value >= 1.0) {
    s.gait = std::clamp(gait.value, 0.0, 1.0);
  } else {
    s.gait = gait.value;
    s.gait_rate = gait.rate;
    s.gait_acceleration = gait.acceleration;
  }
  return s;
}

}  // namespace isg::sim
