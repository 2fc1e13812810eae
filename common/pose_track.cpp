#include "common/pose_track.hpp"

#include <bit>
#include <cmath>
#include <cstring>

#include "common/tum.hpp"

namespace isg::common {

namespace {

// A quaternion's step as a row stores it (the sign of a zero kept), and back.
std::int32_t stepCode(double steps) {
  return steps == 0.0 && std::signbit(steps) ? PoseTrack::kNegativeZero : std::int32_t(steps);
}

double stepsOf(std::int32_t code) { return code == PoseTrack::kNegativeZero ? -0.0 : code; }

Eigen::Matrix3d rotationOfCodes(const std::int32_t q[4]) {
  return rotationOfTumSteps({stepsOf(q[0]), stepsOf(q[1]), stepsOf(q[2]), stepsOf(q[3])});
}

bool sameBits(const Eigen::Vector3d& a, const Eigen::Vector3d& b) {
  return std::memcmp(a.data(), b.data(), sizeof(Eigen::Vector3d)) == 0;
}

}  // namespace

double PoseTrack::Row::time() const {
  return std::bit_cast<double>(std::uint64_t(t_high) << 32 | t_low);
}

void PoseTrack::Row::setTime(double t) {
  const auto bits = std::bit_cast<std::uint64_t>(t);
  t_low = std::uint32_t(bits);
  t_high = std::uint32_t(bits >> 32);
}

PoseTrack::PoseTrack(const Trajectory& trajectory) {
  rows_.reserve(trajectory.size());
  for (const auto& pose : trajectory) push_back(pose);
}

void PoseTrack::setPosition(Row& row, const std::array<double, 3>& steps,
                            const Eigen::Vector3d& exact, bool must_read_back) {
  if (!origin_steps_ && std::isfinite(steps[0]) && std::isfinite(steps[1]) &&
      std::isfinite(steps[2])) {
    origin_steps_ = steps;
  }
  bool whole = !origin_steps_;
  for (int i = 0; i < 3 && !whole; ++i) {
    if (steps[i] == 0.0 && std::signbit(steps[i])) {
      row.p[i] = kNegativeZero;
      continue;
    }
    const double offset = steps[i] - (*origin_steps_)[i];  // NaN, ±∞: does not fit
    whole = !(std::abs(offset) < double(INT32_MAX)) ||
            (*origin_steps_)[i] + double(std::int32_t(offset)) != steps[i];
    if (!whole) row.p[i] = std::int32_t(offset);
  }
  whole = whole || (must_read_back && !sameBits(positionOfCodes(row.p), exact));
  if (whole) {
    row.p[0] = kWhole;
    row.p[1] = std::int32_t(whole_positions_.size());
    whole_positions_.push_back(exact);
  }
}

Eigen::Vector3d PoseTrack::positionOfCodes(const std::int32_t p[3]) const {
  std::array<double, 3> steps;
  for (int i = 0; i < 3; ++i) {
    steps[i] = p[i] == kNegativeZero ? -0.0 : (*origin_steps_)[i] + double(p[i]);
  }
  return positionOfTumSteps(steps);
}

void PoseTrack::push_back(const StampedPose& pose) {
  Row row{};
  row.setTime(pose.t);
  const Eigen::Vector3d position = pose.pose.translation();
  setPosition(row, tumPositionSteps(position), position, true);
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
    row.q[1] = std::int32_t(whole_rotations_.size());
    whole_rotations_.push_back(rotation);
  }
  rows_.push_back(row);
}

void PoseTrack::pushQuantised(const StampedPose& pose) {
  // common::quantise's steps, keeping their integers.
  Row row{};
  row.setTime(quantisedTime(pose.t));
  const std::array<double, 3> position_steps = tumPositionSteps(pose.pose.translation());
  setPosition(row, position_steps, positionOfTumSteps(position_steps), false);
  const std::array<double, 4> steps = tumQuaternionSteps(pose.pose.linear());
  for (int i = 0; i < 4; ++i) row.q[i] = stepCode(steps[i]);
  rows_.push_back(row);
}

Eigen::Vector3d PoseTrack::position(std::size_t i) const {
  const Row& row = rows_[i];
  return row.p[0] == kWhole ? whole_positions_[std::size_t(row.p[1])] : positionOfCodes(row.p);
}

StampedPose PoseTrack::operator[](std::size_t i) const {
  const Row& row = rows_[i];
  StampedPose out;
  out.t = row.time();
  out.pose.translation() = position(i);
  out.pose.linear() =
      row.q[0] == kWhole ? whole_rotations_[std::size_t(row.q[1])] : rotationOfCodes(row.q);
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
  return rows_.capacity() * sizeof(Row) + whole_positions_.capacity() * sizeof(Eigen::Vector3d) +
         whole_rotations_.capacity() * sizeof(Eigen::Matrix3d);
}

}  // namespace isg::common
