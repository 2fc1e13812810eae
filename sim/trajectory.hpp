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

// A kidnap makes a new leg: at its time the robot is lifted from wherever the current leg has it
// and put down at the new leg's first waypoint, facing its start yaw.
class Trajectory {
 public:
  Trajectory(const std::vector<Eigen::Vector2d>& waypoints, double start_yaw, double speed,
             double floor_z, const GaitConfig& gait);

  // Continues with a new leg from `time` on (after the current leg's start, before its end).
  void appendLeg(double time, const std::vector<Eigen::Vector2d>& waypoints, double start_yaw);

  // When the last leg ends: the robot stops there.
  double duration() const { return legs_.back().end(); }
  int legs() const { return int(legs_.size()); }
  // When the robot reaches waypoint `index` of leg `leg` (the leg's start for index 0).
  double arrival(int leg, int index) const { return legs_[leg].arrivals[index]; }
  // The kidnaps' times (each leg's start but the first).
  std::vector<double> jumps() const;
  // The pose at `t` as the leg before t's leg had it: where the robot was lifted, at a jump.
  Eigen::Isometry3d poseBefore(double t) const;

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
  struct Leg {
    double start = 0.0;
    Eigen::Vector2d from = Eigen::Vector2d::Zero();
    double yaw = 0.0;
    std::vector<Segment> segments;
    std::vector<double> arrivals;  // per waypoint
    double end() const { return segments.empty() ? start : segments.back().t1; }
  };
  Leg makeLeg(double start, const std::vector<Eigen::Vector2d>& waypoints, double start_yaw) const;
  int legAt(double t) const;
  PlanarState planarInLeg(const Leg& leg, double t) const;
  Eigen::Isometry3d poseOf(const PlanarState& p, double t) const;

  std::vector<Leg> legs_;
  GaitConfig gait_;
  double floor_z_;
  double speed_;
};

}  // namespace isg::sim
