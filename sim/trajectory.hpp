#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <numbers>
#include <vector>

namespace isg::sim {

// How the legged base moves (docs/simulation.md): it turns on the spot at each corner of its
// route, as a legged robot does, then walks straight at its speed; while it moves, a trot makes
// its body bob, roll and pitch at the gait frequency.
struct GaitConfig {
  double frequency_hz = 1.8;
  double bob_m = 0.015;
  double roll_deg = 2.0;
  double pitch_deg = 2.0;
  double standing_height = 0.46;  // base above the floor
  double turn_rate = 0.8;         // rad/s when turning on the spot
};

class Trajectory {
 public:
  Trajectory(const std::vector<Eigen::Vector2d>& waypoints, double start_yaw, double speed,
             double floor_z, const GaitConfig& gait);

  double duration() const { return segments_.empty() ? 0.0 : segments_.back().t1; }

  struct PlanarState {
    Eigen::Vector2d xy = Eigen::Vector2d::Zero();
    double yaw = 0.0;
    bool moving = false;
  };
  PlanarState planar(double t) const;

  // B_T_R: the base pose in the plan frame, with the gait's sway.
  Eigen::Isometry3d pose(double t) const;

  // Phase of the trot (radians, growing while the robot moves) and how strongly it sways (0 at
  // rest, 1 in motion, ramped over a quarter of a second at the start and the end).
  double gaitPhase(double t) const { return 2.0 * std::numbers::pi * gait_.frequency_hz * t; }
  double swayWeight(double t) const;

  const GaitConfig& gait() const { return gait_; }

 private:
  struct Segment {
    double t0, t1;
    Eigen::Vector2d from, to;
    double yaw0, yaw1;
  };
  std::vector<Segment> segments_;
  GaitConfig gait_;
  double floor_z_;
  Eigen::Vector2d start_;
  double start_yaw_;
};

}  // namespace isg::sim
