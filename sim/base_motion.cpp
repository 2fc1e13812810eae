#include "sim/base_motion.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>

#include "common/angles.hpp"

namespace isg::sim {

namespace {

// Seconds over which the trot's sway eases in at the start and out at the end.
constexpr double kSwayEase = 0.5;

// The quintic smootherstep on [0, 1] and its derivatives: 0 → 1 with zero slope and curvature at
// both ends, so a quantity eased by it stays twice differentiable.
struct Smoothstep {
  double value, rate, acceleration;
};
Smoothstep smootherstep(double u) {
  if (u <= 0.0) return {0.0, 0.0, 0.0};
  if (u >= 1.0) return {1.0, 0.0, 0.0};
  return {u * u * u * (10.0 + u * (-15.0 + 6.0 * u)), 30.0 * u * u * (1.0 - u) * (1.0 - u),
          60.0 * u * (1.0 - u) * (1.0 - 2.0 * u)};
}

std::vector<Eigen::Vector3d> onFloor(const std::vector<Eigen::Vector2d>& waypoints, double z) {
  std::vector<Eigen::Vector3d> out;
  out.reserve(waypoints.size());
  for (const auto& p : waypoints) out.emplace_back(p.x(), p.y(), z);
  return out;
}

// How much of a flight's slope the body takes at distance s along a flight of length L: eased in
// over the first `ramp` metres and out over the last, with its first and second derivatives in s.
Smoothstep inclineWeight(double s, double length, double ramp) {
  const Smoothstep in = smootherstep(s / ramp);
  const Smoothstep out = smootherstep((length - s) / ramp);
  const double in_d = in.rate / ramp, in_dd = in.acceleration / (ramp * ramp);
  const double out_d = -out.rate / ramp, out_dd = out.acceleration / (ramp * ramp);
  return {in.value * out.value, in_d * out.value + in.value * out_d,
          in_dd * out.value + 2.0 * in_d * out_d + in.value * out_dd};
}

}  // namespace

BaseMotion::BaseMotion(const std::vector<Eigen::Vector2d>& waypoints, double start_yaw,
                       double speed, double floor_z, const GaitConfig& gait)
    : gait_(gait), speed_(speed) {
  legs_.push_back(makeLeg(0.0, onFloor(waypoints, floor_z), start_yaw));
}

BaseMotion::BaseMotion(const std::vector<Eigen::Vector3d>& waypoints, double start_yaw,
                       double speed, const GaitConfig& gait)
    : gait_(gait), speed_(speed) {
  legs_.push_back(makeLeg(0.0, waypoints, start_yaw));
}

BaseMotion::BaseMotion(std::shared_ptr<const WalkPath> walk, double floor_z, const GaitConfig& gait,
                       const Eigen::Isometry3d& S_T_R)
    : gait_(gait), speed_(0.0), walk_(std::move(walk)), S_T_R_(S_T_R) {
  const WalkPath::State start = walk_->at(0.0);
  Leg leg;
  leg.from = start.xy;
  leg.from_z = floor_z;
  leg.yaw = start.yaw;
  leg.arrivals.push_back(0.0);
  legs_.push_back(leg);
}

BaseMotion::Leg BaseMotion::makeLeg(double start, const std::vector<Eigen::Vector3d>& waypoints,
                                    double start_yaw) const {
  Leg leg;
  leg.start = start;
  leg.from = waypoints.front().head<2>();
  leg.from_z = waypoints.front().z();
  leg.yaw = start_yaw;
  double t = start;
  double yaw = start_yaw;
  Eigen::Vector2d at = leg.from;
  double at_z = leg.from_z;
  leg.arrivals.push_back(t);
  for (std::size_t i = 1; i < waypoints.size(); ++i) {
    const Eigen::Vector2d to = waypoints[i].head<2>();
    const double to_z = waypoints[i].z();
    const Eigen::Vector2d step = to - at;
    const double length = step.norm();
    if (length < 1e-6) {
      leg.arrivals.push_back(t);
      continue;
    }
    const double heading = std::atan2(step.y(), step.x());
    const double turn = common::wrapAngle(heading - yaw);
    if (std::abs(turn) > 1e-9) {
      const RestToRestProfile profile(std::abs(turn), gait_.turn_rate, gait_.turn_acceleration);
      leg.segments.push_back(
          {t, t + profile.duration(), at, at, at_z, at_z, yaw, yaw + turn, profile});
      t += profile.duration();
    }
    yaw += turn;
    const bool stairs = std::abs(to_z - at_z) > 1e-9;
    const RestToRestProfile profile(length, stairs ? std::min(speed_, kStairSpeed) : speed_,
                                    gait_.acceleration);
    leg.segments.push_back({t, t + profile.duration(), at, to, at_z, to_z, yaw, yaw, profile});
    t += profile.duration();
    at = to;
    at_z = to_z;
    leg.arrivals.push_back(t);
  }
  return leg;
}

void BaseMotion::appendLeg(double time, const std::vector<Eigen::Vector3d>& waypoints,
                           double start_yaw) {
  // The scenario refuses kidnaps on a replayed walk (bim/scenario_parser.cpp).
  if (walk_) throw std::logic_error("a replayed walk has one leg");
  legs_.push_back(makeLeg(time, waypoints, start_yaw));
}

std::vector<double> BaseMotion::jumps() const {
  std::vector<double> out;
  for (std::size_t i = 1; i < legs_.size(); ++i) out.push_back(legs_[i].start);
  return out;
}

int BaseMotion::legAt(double t) const {
  int leg = 0;
  while (leg + 1 < int(legs_.size()) && legs_[leg + 1].start <= t) ++leg;
  return leg;
}

BaseMotion::PlanarState BaseMotion::planarInLeg(const Leg& leg, double t) const {
  if (walk_) {
    const WalkPath::State w = walk_->at(t);
    PlanarState state;
    state.xy = w.xy;
    state.yaw = w.yaw;
    state.velocity = w.velocity;
    state.acceleration = w.acceleration;
    state.yaw_rate = w.yaw_rate;
    state.yaw_acceleration = w.yaw_acceleration;
    state.moving = w.velocity.norm() > 0.05 || std::abs(w.yaw_rate) > 0.05;
    state.floor_z = leg.from_z;
    return state;
  }
  if (leg.segments.empty() || t <= leg.start) {
    PlanarState rest{leg.from, leg.yaw, false};
    rest.floor_z = leg.from_z;
    return rest;
  }
  if (t >= leg.end()) {
    const Segment& last = leg.segments.back();
    PlanarState rest{last.to, last.yaw1, false};
    rest.floor_z = last.z1;
    return rest;
  }
  const auto it = std::upper_bound(leg.segments.begin(), leg.segments.end(), t,
                                   [](double value, const Segment& s) { return value < s.t1; });
  const Segment& s = *it;
  const MotionState m = s.profile.at(t - s.t0);
  PlanarState state;
  state.moving = true;
  state.xy = s.from;
  state.yaw = s.yaw0;
  state.floor_z = s.z0;
  if (s.yaw1 != s.yaw0) {  // a turn on the spot
    const double sign = s.yaw1 > s.yaw0 ? 1.0 : -1.0;
    state.yaw += sign * m.distance;
    state.yaw_rate = sign * m.rate;
    state.yaw_acceleration = sign * m.acceleration;
  } else {
    const Eigen::Vector2d along = (s.to - s.from).normalized();
    state.xy += m.distance * along;
    state.velocity = m.rate * along;
    state.acceleration = m.acceleration * along;
    if (s.z1 != s.z0) {  // a flight: the floor rises along it, the body tilts to its slope
      const double length = (s.to - s.from).norm();
      const double slope = (s.z1 - s.z0) / length;
      state.floor_z += slope * m.distance;
      state.floor_rate = slope * m.rate;
      state.floor_acceleration = slope * m.acceleration;
      const double angle = std::atan(slope);
      const Smoothstep w = inclineWeight(m.distance, length, std::min(kInclineEase, 0.5 * length));
      state.incline = angle * w.value;
      state.incline_rate = angle * w.rate * m.rate;
      state.incline_acceleration =
          angle * (w.acceleration * m.rate * m.rate + w.rate * m.acceleration);
    }
  }
  return state;
}

BaseMotion::PlanarState BaseMotion::planar(double t) const {
  return planarInLeg(legs_[legAt(t)], t);
}

BaseMotion::Eased BaseMotion::sway(double t) const {
  const double d = duration();
  if (t <= 0.0 || t >= d) return {};
  const Smoothstep in = smootherstep(t / kSwayEase);
  const Smoothstep out = smootherstep((d - t) / kSwayEase);
  // The product of the two eases, and its derivatives in t (d/dt of `out` flips the sign).
  const double in_rate = in.rate / kSwayEase, in_acc = in.acceleration / (kSwayEase * kSwayEase);
  const double out_rate = -out.rate / kSwayEase;
  const double out_acc = out.acceleration / (kSwayEase * kSwayEase);
  const Eased ends{in.value * out.value, in_rate * out.value + in.value * out_rate,
                   in_acc * out.value + 2.0 * in_rate * out_rate + in.value * out_acc};
  if (!walk_) return ends;
  // A replayed walk sways as far as its pace has it: the product's derivatives by Leibniz.
  const WalkPath::State w = walk_->at(t);
  return {ends.value * w.gait, ends.rate * w.gait + ends.value * w.gait_rate,
          ends.acceleration * w.gait + 2.0 * ends.rate * w.gait_rate +
              ends.value * w.gait_acceleration};
}

Eigen::Isometry3d BaseMotion::pose(double t) const { return kinematics(t).B_T_R; }

BaseKinematics BaseMotion::kinematics(double t) const { return kinematicsOf(planar(t), t); }

Eigen::Isometry3d BaseMotion::poseBefore(double t) const {
  const int leg = legAt(t);
  return kinematicsOf(planarInLeg(legs_[leg > 0 && legs_[leg].start == t ? leg - 1 : leg], t), t)
      .B_T_R;
}

BaseKinematics BaseMotion::kinematicsOf(const PlanarState& p, double t) const {
  if (walk_ && walk_->sensorPath()) return sensorPathKinematics(p, t);
  const Eased w = sway(t);
  const double omega = 2.0 * std::numbers::pi * gait_.frequency_hz;
  const double phase = gaitPhase(t);
  // amplitude · w(t) · sin(phase + offset), with its first and second derivatives.
  auto swayed = [&](double amplitude, double offset) {
    const double s = std::sin(phase + offset), c = std::cos(phase + offset);
    return Eased{
        amplitude * w.value * s, amplitude * (w.rate * s + w.value * omega * c),
        amplitude * (w.acceleration * s + 2.0 * w.rate * omega * c - w.value * omega * omega * s)};
  };
  constexpr double kDeg = std::numbers::pi / 180.0;
  const Eased bob = swayed(gait_.bob_m, 0.0);
  // A trot rolls the body at the gait frequency; a walker's strides at half the step frequency.
  const Eased roll = gait_.handheld ? swayedAt(w, gait_.roll_deg * kDeg, 0.5 * omega, 0.0, t)
                                    : swayed(gait_.roll_deg * kDeg, std::numbers::pi / 2);
  // The trot's pitch, and the body tilted nose up (a negative pitch about y) on a flight.
  const Eased trot_pitch = swayed(gait_.pitch_deg * kDeg, std::numbers::pi / 3);
  const Eased pitch{trot_pitch.value - p.incline, trot_pitch.rate - p.incline_rate,
                    trot_pitch.acceleration - p.incline_acceleration};

  if (gait_.handheld) return withWalkersSway(p, t, w, bob, roll, pitch);
  return bodyKinematics(p, bob, roll, pitch);
}

BaseMotion::Eased BaseMotion::swayedAt(const Eased& w, double amplitude, double rate, double offset,
                                       double t) {
  const double s = std::sin(rate * t + offset), c = std::cos(rate * t + offset);
  return Eased{
      amplitude * w.value * s, amplitude * (w.rate * s + w.value * rate * c),
      amplitude * (w.acceleration * s + 2.0 * w.rate * rate * c - w.value * rate * rate * s)};
}

BaseKinematics BaseMotion::withWalkersSway(PlanarState p, double t, const Eased& w,
                                           const Eased& bob, const Eased& roll,
                                           const Eased& pitch) const {
  // Sideways along the way's left normal n(yaw) at half the step frequency: the position moves by
  // s·n, so its velocity by s'·n + s·yaw'·n' and its acceleration by s''·n + 2·s'·yaw'·n' +
  // s·(yaw''·n' − yaw'²·n), with n' = dn/dyaw = −(cos yaw, sin yaw).
  const double omega = 2.0 * std::numbers::pi * gait_.frequency_hz;
  const Eased side = swayedAt(w, gait_.sway_m, 0.5 * omega, std::numbers::pi / 2, t);
  const Eigen::Vector2d n(-std::sin(p.yaw), std::cos(p.yaw));
  const Eigen::Vector2d dn(-std::cos(p.yaw), -std::sin(p.yaw));
  const double dy = p.yaw_rate, ddy = p.yaw_acceleration;
  p.xy += side.value * n;
  p.velocity += side.rate * n + side.value * dy * dn;
  p.acceleration +=
      side.acceleration * n + 2.0 * side.rate * dy * dn + side.value * (ddy * dn - dy * dy * n);
  // The head turns: the walker glances about the way ahead.
  constexpr double kDeg = std::numbers::pi / 180.0;
  const double amplitude = gait_.head_turn_deg * kDeg;
  const std::array<double, 2> shares = {0.7, 0.3};
  for (int i = 0; i < 2; ++i) {
    const Eased turn =
        swayedAt(w, shares[i] * amplitude, 2.0 * std::numbers::pi / kHeadTurnPeriods[i],
                 gait_.head_phases[i], t);
    p.yaw += turn.value;
    p.yaw_rate += turn.rate;
    p.yaw_acceleration += turn.acceleration;
  }
  return bodyKinematics(p, bob, roll, pitch);
}

BaseKinematics BaseMotion::sensorPathKinematics(const PlanarState& p, double t) const {
  const WalkPath::State s = walk_->at(t);
  // The sensor S as bodyKinematics poses a body: at floor + standing height + "bob", so the bob
  // is the file's height less the standing height.
  const Eased height{s.z.value - gait_.standing_height, s.z.rate, s.z.acceleration};
  const BaseKinematics S =
      bodyKinematics(p, height, {s.roll.value, s.roll.rate, s.roll.acceleration},
                     {s.pitch.value, s.pitch.rate, s.pitch.acceleration});
  // R rigid with S: p_R = p_S + R_S·c, v_R = v_S + R_S·(ω×c), a_R = a_S + R_S·(α×c + ω×(ω×c)),
  // with ω, α S's body rates; R's are the same rotated into R (Q = S_R_R).
  const Eigen::Vector3d c = S_T_R_.translation();
  const Eigen::Matrix3d Q = S_T_R_.linear();
  const Eigen::Matrix3d& R_S = S.B_T_R.linear();
  const Eigen::Vector3d& w = S.angular_velocity;
  const Eigen::Vector3d& a = S.angular_acceleration;
  BaseKinematics k;
  k.B_T_R = S.B_T_R * S_T_R_;
  k.velocity = S.velocity + R_S * w.cross(c);
  k.acceleration = S.acceleration + R_S * (a.cross(c) + w.cross(w.cross(c)));
  k.angular_velocity = Q.transpose() * w;
  k.angular_acceleration = Q.transpose() * a;
  return k;
}

BaseKinematics BaseMotion::bodyKinematics(const PlanarState& p, const Eased& bob, const Eased& roll,
                                          const Eased& pitch) const {
  BaseKinematics k;
  k.B_T_R.translation() =
      Eigen::Vector3d(p.xy.x(), p.xy.y(), p.floor_z + gait_.standing_height + bob.value);
  k.B_T_R.linear() = (Eigen::AngleAxisd(p.yaw, Eigen::Vector3d::UnitZ()) *
                      Eigen::AngleAxisd(pitch.value, Eigen::Vector3d::UnitY()) *
                      Eigen::AngleAxisd(roll.value, Eigen::Vector3d::UnitX()))
                         .toRotationMatrix();
  k.velocity = Eigen::Vector3d(p.velocity.x(), p.velocity.y(), p.floor_rate + bob.rate);
  k.acceleration = Eigen::Vector3d(p.acceleration.x(), p.acceleration.y(),
                                   p.floor_acceleration + bob.acceleration);
  // Body rates of R = Rz(yaw) Ry(pitch) Rx(roll), and their derivatives in t.
  const double sr = std::sin(roll.value), cr = std::cos(roll.value);
  const double sp = std::sin(pitch.value), cp = std::cos(pitch.value);
  const double dr = roll.rate, dp = pitch.rate, dy = p.yaw_rate;
  const double ddr = roll.acceleration, ddp = pitch.acceleration, ddy = p.yaw_acceleration;
  k.angular_velocity =
      Eigen::Vector3d(dr - dy * sp, dp * cr + dy * cp * sr, -dp * sr + dy * cp * cr);
  k.angular_acceleration = Eigen::Vector3d(
      ddr - ddy * sp - dy * cp * dp,
      ddp * cr - dp * sr * dr + ddy * cp * sr - dy * sp * dp * sr + dy * cp * cr * dr,
      -ddp * sr - dp * cr * dr + ddy * cp * cr - dy * sp * dp * cr - dy * cp * sr * dr);
  return k;
}

}  // namespace isg::sim
