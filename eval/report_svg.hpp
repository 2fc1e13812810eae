#pragma once

#include <Eigen/Core>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "eval/tum.hpp"

namespace isg::eval {

// A run's report as one SVG picture: the plan (as polygons the caller draws it with), the
// ground-truth and estimated trajectories in B, where localization happened, and the APE over
// time below. Plain data in, so that eval stays free of the plan model.
struct ReportInput {
  std::string title;
  std::vector<std::string> summary;  // lines printed under the title
  std::vector<std::vector<Eigen::Vector2d>> walls;
  std::vector<std::pair<std::string, Eigen::Vector2d>> labels;  // room names at their centres
  Trajectory ground_truth;
  Trajectory estimate;  // in B, from the first localized pose on
  Trajectory odometry;  // odometry placed at the true start (dead reckoning), drawn faintly
  std::vector<std::pair<double, double>> error_over_time;  // (t, APE metres)
  std::optional<double> localized_at;                      // seconds
};

std::string reportSvg(const ReportInput& input);

}  // namespace isg::eval
