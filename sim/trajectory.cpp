#include "sim/trajectory.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace isg::sim {

namespace {

double wrapAngle(double a) { return std::remainder(a, 2.0 * std::numbers::pi); }

}  // namespace

Trajectory::Trajectory(const std::vector<Eigen::Vector2d>& waypoints, double start_yaw,
                       double speed, double floor_z, const GaitConfig& gait)
    : gait_(gait), floor_z_(floor_z), speed_(speed) {
  legs_.push_back(makeLeg(0.0, waypoints, start_yaw));
}

Trajectory::Leg Trajectory::makeLeg(double start, const std::vector<Eigen::Vector2d>& waypoints,
                                    double start_yaw) const {
  Leg leg;
  leg.start = start;
  leg.from = waypoints.front();
  leg.yaw = start_yaw;
  double t = start;
  double yaw = start_yaw;
  Eigen::Vector2d at = waypoints.front();
  leg.arrivals.push_back(t);
  for (std::size_t i = 1; i < waypoints.size(); ++i) {
    const Eigen::Vector2d step = waypoints[i] - at;
    const double length = step.norm();
    if (length < 1e-6) {
      leg.arrivals.push_back(t);
      continue;
    }
    const double heading = std::atan2(step.y(), step.x());
    const double turn = wrapAngle(heading - yaw);
    if (std::abs(turn) > 1e-9) {
      const double dt = std::abs(turn) / gait_.turn_rate;
      leg.segments.push_back({t, t + dt, at, at, yaw, yaw + turn});
      t += dt;
    }
    yaw += turn;
    leg.segments.push_back({t, t + length / speed_, at, waypoints[i], yaw, yaw});
    t += length / speed_;
    at = waypoints[i];
    leg.arrivals.push_back(t);
  }
  return leg;
}

void Trajectory::appendLeg(double time, const std::vector<Eigen::Vector2d>& waypoints,
                           double start_yaw) {
  legs_.push_back(makeLeg(time, waypoints, start_yaw));
}

std::vector<double> Trajectory::jumps() const {
  std::vector<double> out;
  for (std::size_t i = 1; i < legs_.size(); ++i) out.push_back(legs_[i].start);
  return out;
}

int Trajectory::legAt(double t) const {
  int leg = 0;
  while (leg + 1 < int(legs_.size()) && legs_[leg + 1].start <= t) ++leg;
  return leg;
}

Trajectory::PlanarState Trajectory::planarInLeg(const Leg& leg, double t) const {
  if (leg.segments.empty() || t <= leg.start) return {leg.from, leg.yaw, false};
  if (t >= leg.end()) {
    const Segment& last = leg.segments.back();
    return {last.to, last.yaw1, false};
  }
  const auto it = std::upper_bound(leg.segments.begin(), leg.segments.end(), t,
                                   [](double value, const Segment& s) { return value < s.t1; });
  const Segment& s = *it;
  const double a = (t - s.t0) / (s.t1 - s.t0);
  return {s.from + a * (s.to - s.from), s.yaw0 + a * (s.yaw1 - s.yaw0), true};
}

Trajectory::PlanarState Trajectory::planar(double t) const {
  return planarInLeg(legs_[legAt(t)], t);
}

double Trajectory::swayWeight(double t) const {
  constexpr double kRamp = 0.25;
  const double d = duration();
  if (t <= 0.0 || t >= d) return 0.0;
  return std::min({1.0, t / kRamp, (d - t) / kRamp});
}

Eigen::Isometry3d Trajectory::pose(double t) const { return poseOf(planar(t), t); }

Eigen::Isometry3d Trajectory::poseBefore(double t) const {
  const int leg = legAt(t);
  return poseOf(planarInLeg(legs_[leg > 0 && legs_[leg].start == t ? leg - 1 : leg], t), t);
}

Eigen::Isometry3d Trajectory::poseOf(const PlanarState& p, double t) const {
  const double w = swayWeight(t);
  const double phase = gaitPhase(t);
  const double z = floor_z_ + gait_.standing_height + w * gait_.bob_m * std::sin(phase);
  const double roll =
      w * gait_.roll_deg * std::numbers::pi / 180.0 * std::sin(phase + std::numbers::pi / 2);
  const double pitch =
      w * gait_.pitch_deg * std::numbers::pi / 180.0 * std::sin(phase + std::numbers::pi / 3);
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  T.translation() = Eigen::Vector3d(p.xy.x(), p.xy.y(), z);
  T.linear() = (Eigen::AngleAxisd(p.yaw, Eigen::Vector3d::UnitZ()) *
                Eigen::AngleAxisd(pitch, Eigen::Vector3d::UnitY()) *
                Eigen::AngleAxisd(roll, Eigen::Vector3d::UnitX()))
                   .toRotationMatrix();
  return T;
}

}  // namespace isg::sim
