#include "common/pose_track.hpp"

#include <cmath>
#include <cstring>

#include "common/decimal_rounding.hpp"

namespace isg::common {

namespace {

constexpr double kQuaternionScale = 1e9;  // a TUM row's nine decimals

// The unit quaternion of a rotation, w ≥ 0 (as a TUM row prints it).
Eigen::Quaterniond unitQuaternion(const Eigen::Matrix3d& rotation) {
  Eigen::Quaterniond q(rotation);
  q.normalize();
  if (q.w() < 0) q.coeffs() *= -1.0;
  return q;
}

// A step count as a row stores it, and back.
std::int32_t stepCode(double steps) {
  return steps == 0.0 && std::signbit(steps) ? PoseTrack::kNegativeZero : std::int32_t(steps);
}

double stepsOf(std::int32_t code) { return code == PoseTrack::kNegativeZero ? -0.0 : code; }

// The rotation a TUM row's quaternion steps make, as the parser and common::quantise make it.
Eigen::Matrix3d rotationOfSteps(const std::int32_t q[4]) {
  const Eigen::Quaterniond read(stepsOf(q[0]) / kQuaternionScale, stepsOf(q[1]) / kQuaternionScale,
                                stepsOf(q[2]) / kQuaternionScale, stepsOf(q[3]) / kQuaternionScale);
  return read.normalized().toRotationMatrix();
}

}  // namespace

PoseTrack::PoseTrack(const Trajectory& trajectory) {
  rows_.reserve(trajectory.size());
  for (const auto& pose : trajectory) push_back(pose);
}

void PoseTrack::push_back(const StampedPose& pose) {
  const Eigen::Vector3d p = pose.pose.translation();
  Row row{pose.t, p.x(), p.y(), p.z(), {}};
  const Eigen::Matrix3d rotation = pose.pose.linear();
  const Eigen::Quaterniond q = unitQuaternion(rotation);
  const double coefficients[4] = {q.w(), q.x(), q.y(), q.z()};
  const bool finite = rotation.allFinite();
  for (int i = 0; i < 4; ++i) {
    row.q[i] = finite ? stepCode(std::nearbyint(coefficients[i] * kQuaternionScale)) : 0;
  }
  // The nine decimals rebuild most rounded rotations; the rest (about 1.5 % of rounded ones,
  // where normalising moved a decimal) and any unrounded rotation are kept whole.
  const Eigen::Matrix3d rebuilt = rotationOfSteps(row.q);
  if (!finite || std::memcmp(rebuilt.data(), rotation.data(), sizeof(Eigen::Matrix3d)) != 0) {
    row.q[0] = kWhole;
    row.q[1] = std::int32_t(whole_.size());
    whole_.push_back(rotation);
  }
  rows_.push_back(row);
}

void PoseTrack::pushQuantised(const StampedPose& pose) {
  // common::quantise's steps, keeping the quaternion's integers.
  const Eigen::Quaterniond q = unitQuaternion(pose.pose.linear());
  const Eigen::Vector3d p = pose.pose.translation();
  Row row{decimalRounded(pose.t, 1e9),
          decimalRounded(p.x(), 1e6),
          decimalRounded(p.y(), 1e6),
          decimalRounded(p.z(), 1e6),
          {}};
  const double coefficients[4] = {q.w(), q.x(), q.y(), q.z()};
  for (int i = 0; i < 4; ++i) {
    row.q[i] = stepCode(decimalSteps(coefficients[i], kQuaternionScale));
  }
  rows_.push_back(row);
}

void PoseTrack::clear() {
  rows_.clear();
  whole_.clear();
}

StampedPose PoseTrack::operator[](std::size_t i) const {
  const Row& row = rows_[i];
  StampedPose out;
  out.t = row.t;
  out.pose.translation() = Eigen::Vector3d(row.x, row.y, row.z);
  out.pose.linear() = row.q[0] == kWhole ? whole_[std::size_t(row.q[1])] : rotationOfSteps(row.q);
  out.pose.makeAffine();
  return out;
}

Trajectory PoseTrack::slice(std::size_t first, std::size_t count) const {
  Trajectory out;
  out.reserve(count);
  for (std::size_t i = first; i < first + count && i < size(); ++i) out.push_back((*this)[i]);
  return out;
}

std::size_t PoseTrack::bytes() const {
  return rows_.capacity() * sizeof(Row) + whole_.capacity() * sizeof(Eigen::Matrix3d);
}

}  // namespace isg::common
