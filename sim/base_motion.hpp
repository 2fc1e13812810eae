#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <array>
#include <memory>
#include <numbers>
#include <vector>

#include "sim/motion_profile.hpp"
#include "sim/walk_path.hpp"

namespace isg::sim {

// How the carrier moves (docs/simulation.md): it turns on the spot at each corner of its route,
// then walks straight at its speed, starting and stopping each with bounded acceleration. While it
// moves, a legged base's trot makes its body bob, roll and pitch at the gait frequency; a person's
// steps bob and pitch the sensors at the step frequency, each stride sways them sideways and rolls
// them at half of it, and the walker turns them about the way ahead (head turns).
struct GaitConfig {
  double frequency_hz = 1.8;
  double bob_m = 0.015;
  double roll_deg = 2.0;
  double pitch_deg = 2.0;
  double standing_height = 0.46;   // base above the floor
  double turn_rate = 0.8;          // rad/s when turning on the spot
  double acceleration = 1.5;       // m/s², largest when starting or stopping a straight
  double turn_acceleration = 3.0;  // rad/s², largest when starting or stopping a turn
  // A person's walk (handheld): sideways sway and roll at half the step frequency, and head
  // turns: two incommensurate slow sines (periods kHeadTurnPeriods, 0.7 and 0.3 of the
  // amplitude) at phases drawn from the run's seed.
  bool handheld = false;
  double sway_m = 0.0;
  double head_turn_deg = 0.0;
  std::array<double, 2> head_phases = {0.0, 0.0};
};

// The periods of the head turns' two sines, seconds: slow glances about the way ahead.
inline constexpr std::array<double, 2> kHeadTurnPeriods = {6.3, 2.7};
// A handheld carrier's sensors are held this high (R above the floor), and a person turns faster
// on the spot than a legged base.
inline constexpr double kHandheldHeight = 1.2;    // m
inline constexpr double kHandheldTurnRate = 1.2;  // rad/s

// The base's motion at one instant, as an inertial sensor on it would feel it: B_T_R, the
// velocity and acceleration of R's origin in B, and R's angular velocity and acceleration in R.
struct BaseKinematics {
  Eigen::Isometry3d B_T_R = Eigen::Isometry3d::Identity();
  Eigen::Vector3d velocity = Eigen::Vector3d::Zero();
  Eigen::Vector3d acceleration = Eigen::Vector3d::Zero();
  Eigen::Vector3d angular_velocity = Eigen::Vector3d::Zero();
  Eigen::Vector3d angular_acceleration = Eigen::Vector3d::Zero();
};

// On a flight of stairs the base walks no faster than this (horizontally), as legged robots
// slow down to place their feet on steps.
inline constexpr double kStairSpeed = 0.4;  // m/s
// Over this distance at either end of a flight the body tilts from level to the slope and back.
inline constexpr double kInclineEase = 0.6;  // m

// A kidnap makes a new leg: at its time the robot is lifted from wherever the current leg has it
// and put down at the new leg's first waypoint, facing its start yaw.
class BaseMotion {
 public:
  // A route on one floor at height floor_z.
  BaseMotion(const std::vector<Eigen::Vector2d>& waypoints, double start_yaw, double speed,
             double floor_z, const GaitConfig& gait);
  // A route over floors: each waypoint is (x, y, height of the floor under it). Between two
  // waypoints at different heights the base walks a flight of stairs: its height follows the
  // straight line between them, its body pitches to the slope (eased in and out over
  // kInclineEase), and it walks at most kStairSpeed.
  BaseMotion(const std::vector<Eigen::Vector3d>& waypoints, double start_yaw, double speed,
             const GaitConfig& gait);
  // A recorded walk replayed on one floor at height floor_z: the base follows `walk` (its
  // position, heading and pace), swaying with the gait as far as the walk's pace has it. When the
  // walk is a sensor's path (WalkPath::sensorPath), the tracked sensor S follows it — its
  // position above the floor and its attitude — and the base is rigid with it: B_T_R = B_T_S ·
  // `S_T_R`, no sway added.
  BaseMotion(std::shared_ptr<const WalkPath> walk, double floor_z, const GaitConfig& gait,
             const Eigen::Isometry3d& S_T_R = Eigen::Isometry3d::Identity());

  // Continues with a new leg from `time` on (after the current leg's start, before its end).
  // Its waypoints are as the constructor over floors takes them: a kidnap may put the robot down
  // on another floor.
  void appendLeg(double time, const std::vector<Eigen::Vector3d>& waypoints, double start_yaw);

  // When the last leg ends: the robot stops there.
  double duration() const { return walk_ ? walk_->duration() : legs_.back().end(); }
  // The replayed walk, or null for a planned route.
  const WalkPath* walk() const { return walk_.get(); }
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
    Eigen::Vector2d velocity = Eigen::Vector2d::Zero();
    Eigen::Vector2d acceleration = Eigen::Vector2d::Zero();
    double yaw_rate = 0.0;
    double yaw_acceleration = 0.0;
    // The floor under the base (the line of a flight's steps on stairs) and its derivatives.
    double floor_z = 0.0, floor_rate = 0.0, floor_acceleration = 0.0;
    // How far the body is tilted nose up to a flight's slope, and its derivatives.
    double incline = 0.0, incline_rate = 0.0, incline_acceleration = 0.0;
  };
  PlanarState planar(double t) const;

  // B_T_R: the base pose in the plan frame, with the gait's sway.
  Eigen::Isometry3d pose(double t) const;
  // The pose with its first and second derivatives, exact (not differenced). A kidnap is not
  // felt: within each leg the motion is smooth, and the lift itself has no modelled motion.
  BaseKinematics kinematics(double t) const;

  // Phase of the trot (radians, growing while the robot moves) and how strongly it sways (0 at
  // rest, 1 in motion, eased in over half a second at the start and out at the end).
  double gaitPhase(double t) const { return 2.0 * std::numbers::pi * gait_.frequency_hz * t; }
  double swayWeight(double t) const { return sway(t).value; }

  const GaitConfig& gait() const { return gait_; }

 private:
  struct Segment {
    double t0, t1;
    Eigen::Vector2d from, to;
    double z0, z1;  // floor heights at from and to
    double yaw0, yaw1;
    RestToRestProfile profile;  // along from→to, or from yaw0 to yaw1
  };
  struct Eased {
    double value = 0.0, rate = 0.0, acceleration = 0.0;
  };
  Eased sway(double t) const;
  struct Leg {
    double start = 0.0;
    Eigen::Vector2d from = Eigen::Vector2d::Zero();
    double from_z = 0.0;
    double yaw = 0.0;
    std::vector<Segment> segments;
    std::vector<double> arrivals;  // per waypoint
    double end() const { return segments.empty() ? start : segments.back().t1; }
  };
  Leg makeLeg(double start, const std::vector<Eigen::Vector3d>& waypoints, double start_yaw) const;
  int legAt(double t) const;
  PlanarState planarInLeg(const Leg& leg, double t) const;
  BaseKinematics kinematicsOf(const PlanarState& p, double t) const;
  // amplitude · w(t) · sin(rate · t + offset), with its first and second derivatives in t.
  static Eased swayedAt(const Eased& w, double amplitude, double rate, double offset, double t);
  // A walker's sideways sway and head turns added to the way's planar state (handheld).
  BaseKinematics withWalkersSway(PlanarState p, double t, const Eased& w, const Eased& bob,
                                 const Eased& roll, const Eased& pitch) const;
  // The pose and its derivatives from the planar state and the body's bob, roll and pitch.
  BaseKinematics bodyKinematics(const PlanarState& p, const Eased& bob, const Eased& roll,
                                const Eased& pitch) const;
  // A sensor's path: the tracked sensor's kinematics carried to R through S_T_R_.
  BaseKinematics sensorPathKinematics(const PlanarState& p, double t) const;

  std::vector<Leg> legs_;
  GaitConfig gait_;
  double speed_;
  std::shared_ptr<const WalkPath> walk_;
  Eigen::Isometry3d S_T_R_ = Eigen::Isometry3d::Identity();
};

}  // namespace isg::sim
