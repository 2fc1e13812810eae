#pragma once

#include <Eigen/Core>
#include <vector>

#include "bim/scenario.hpp"
#include "sim/smoothing_spline.hpp"

namespace isg::sim {

// A recorded walk made into a motion a carrier can follow and an IMU can feel (docs/simulation.md,
// "Replayed walks"): the file's positions fitted by a cubic B-spline with knots every
// kWalkKnotSpacing seconds (twice differentiable, so that the accelerometer sees the walk's own
// accelerations, not the file's jitter between poses), and a heading that is the file's yaw
// ("orientation": "file") or the direction of travel, turned no faster than the carrier turns and
// held while it stands (below kHeadingSpeed). The gait's sway follows the pace: none below
// kStandingSpeed (a file's jitter while its walker stands), full from kFullGaitSpeed.
inline constexpr double kWalkKnotSpacing = 0.5;  // s
inline constexpr double kHeadingSpeed = 0.2;     // m/s
inline constexpr double kStandingSpeed = 0.05;   // m/s
inline constexpr double kFullGaitSpeed = 0.3;    // m/s
// A sensor's path (bim::Route::sensor_path) is followed closer: its height, roll and pitch too,
// with knots every kSensorKnotSpacing (a walker's steps sway a hand-held camera at about 2 Hz),
// and no sway of the carrier's own is added.
inline constexpr double kSensorKnotSpacing = 0.1;  // s

class WalkPath {
 public:
  WalkPath(const std::vector<bim::WalkPose>& walk, bool file_orientation, double turn_rate,
           bool sensor_path = false);

  struct State {
    Eigen::Vector2d xy = Eigen::Vector2d::Zero();
    Eigen::Vector2d velocity = Eigen::Vector2d::Zero();
    Eigen::Vector2d acceleration = Eigen::Vector2d::Zero();
    double yaw = 0.0, yaw_rate = 0.0, yaw_acceleration = 0.0;
    // How much of the gait's sway there is: 0 standing, 1 walking, with its derivatives.
    double gait = 0.0, gait_rate = 0.0, gait_acceleration = 0.0;
    // A sensor's path: its height above the floor, roll and pitch, each with two derivatives.
    UniformCubicSpline::Sample z, roll, pitch;
  };
  State at(double t) const;
  double duration() const { return duration_; }
  bool sensorPath() const { return sensor_path_; }

  // How far the path passes from the file's positions: the largest distance and its pose's line,
  // and the median.
  double maxDeviation() const { return max_deviation_; }
  int maxDeviationLine() const { return max_deviation_line_; }
  double medianDeviation() const { return median_deviation_; }

 private:
  void fitAttitude(const std::vector<bim::WalkPose>& walk, const SmoothingSplineFit& fit);

  double duration_ = 0.0;
  bool sensor_path_ = false;
  UniformCubicSpline x_, y_, yaw_, gait_, z_, roll_, pitch_;
  double max_deviation_ = 0.0;
  int max_deviation_line_ = 0;
  double median_deviation_ = 0.0;
};

}  // namespace isg::sim
