#include "slam/baselines/amcl_motion_model.hpp"

#include <algorithm>

namespace isg::slam {

namespace {

double turnSize(double rot) {
  return std::min(std::abs(common::angleDifference(rot, 0.0)),
                  std::abs(common::angleDifference(rot, M_PI)));
}

}  // namespace

double OdometryMotion::sigmaRot1(const OdometryMotionNoise& n) const {
  return std::sqrt(n.alpha1 * rot1_noise * rot1_noise + n.alpha2 * trans * trans);
}

double OdometryMotion::sigmaTrans(const OdometryMotionNoise& n) const {
  return std::sqrt(n.alpha3 * trans * trans + n.alpha4 * rot1_noise * rot1_noise +
                   n.alpha4 * rot2_noise * rot2_noise);
}

double OdometryMotion::sigmaRot2(const OdometryMotionNoise& n) const {
  return std::sqrt(n.alpha1 * rot2_noise * rot2_noise + n.alpha2 * trans * trans);
}

OdometryMotion decomposeOdometry(const Pose2& from, const Pose2& to) {
  OdometryMotion m;
  const double dx = to.x - from.x, dy = to.y - from.y;
  m.trans = std::hypot(dx, dy);
  m.rot1 = m.trans < 0.01 ? 0.0 : common::angleDifference(std::atan2(dy, dx), from.yaw);
  m.rot2 = common::angleDifference(common::angleDifference(to.yaw, from.yaw), m.rot1);
  m.rot1_noise = turnSize(m.rot1);
  m.rot2_noise = turnSize(m.rot2);
  return m;
}

Pose2 sampleOdometryMotion(const Pose2& particle, const OdometryMotion& motion,
                           const OdometryMotionNoise& noise, std::mt19937_64& rng) {
  std::normal_distribution<double> gauss(0.0, 1.0);
  const double rot1 = common::angleDifference(motion.rot1, motion.sigmaRot1(noise) * gauss(rng));
  const double trans = motion.trans - motion.sigmaTrans(noise) * gauss(rng);
  const double rot2 = common::angleDifference(motion.rot2, motion.sigmaRot2(noise) * gauss(rng));
  Pose2 out = particle;
  out.x += trans * std::cos(particle.yaw + rot1);
  out.y += trans * std::sin(particle.yaw + rot1);
  out.yaw = common::angleDifference(particle.yaw + rot1 + rot2, 0.0);
  return out;
}

}  // namespace isg::slam
