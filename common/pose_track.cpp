#include "common/pose_track.hpp"

#include <cmath>
#include <cstring>

#include "common/tum.hpp"

namespace isg::common {

namespace {

// A quaternion step as a row stores it (|steps| ≤ 1e9 < 2^31, the sign of a zero kept), and back.
std::int32_t stepCode(double steps) {
  return steps == 0.0 && std::signbit(steps) ? PoseTrack::kNegativeZero : std::int32_t(steps);
}

double stepsOf(std::int32_t code) { return code == PoseTrack::kNegativeZero ? -0.0 : code; }

Eigen::Matrix3d rotationOfCodes(const std::int32_t q[4]) {
  return rotationOfTumSteps({stepsOf(q[0]), stepsOf(q[1]), stepsOf(q[2]), stepsOf(q[3])});
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
  // The nine decimals rebuild a rounded rotation but where normalising moved one (about 1.5 %
  // of them); those and any unrounded or non-finite rotation are kept whole.
  bool whole = !rotation.allFinite();
  if (!whole) {
    const std::array<double, 4> steps = tumQuaternionSteps(rotation);
    for (int i = 0; i < 4; ++i) row.q[i] = stepCode(steps[i]);
    const Eigen::Matrix3d rebuilt = rotationOfCodes(row.q);
    whole = std::memcmp(rebuilt.data(), rotation.data(), sizeof(Eigen::Matrix3d)) != 0;
  }
  if (whole) {
    row.q[0] = kWhole;
    row.q[1] = std::int32_t(whole_.size());
    whole_.push_back(rotation);
  }
  rows_.push_back(row);
}

void PoseTrack::pushQuantised(const StampedPose& pose) {
  // common::quantise's steps, keeping the quaternion's integers.
  const Eigen::Vector3d p = quantisedPosition(pose.pose.translation());
  Row row{quantisedTime(pose.t), p.x(), p.y(), p.z(), {}};
  const std::array<double, 4> steps = tumQuaternionSteps(pose.pose.linear());
  for (int i = 0; i < 4; ++i) row.q[i] = stepCode(steps[i]);
  rows_.push_back(row);
}

StampedPose PoseTrack::operator[](std::size_t i) const {
  const Row& row = rows_[i];
  StampedPose out;
  out.t = row.t;
  out.pose.translation() = Eigen::Vector3d(row.x, row.y, row.z);
  out.pose.linear() = row.q[0] == kWhole ? whole_[std::size_t(row.q[1])] : rotationOfCodes(row.q);
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
