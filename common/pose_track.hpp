#pragma once

#include <Eigen/Geometry>
#include <array>
#include <cstddef>
#include <cstdint>
#include <initializer_list>
#include <iterator>
#include <optional>
#include <vector>

#include "common/trajectory.hpp"

namespace isg::common {

// A random-access iterator over anything with `operator[](i)` giving a StampedPose by value
// (PoseTrack, PoseSequence): its elements are made when read, so `*it` is a value, not a
// reference.
template <typename Rows>
class PoseIterator {
 public:
  using iterator_category = std::random_access_iterator_tag;
  using iterator_concept = std::random_access_iterator_tag;
  using value_type = StampedPose;
  using difference_type = std::ptrdiff_t;
  using reference = StampedPose;
  struct pointer {  // what `it->t` reads: the pose made for it
    StampedPose pose;
    const StampedPose* operator->() const { return &pose; }
  };

  PoseIterator() = default;
  PoseIterator(const Rows* rows, difference_type index) : rows_(rows), index_(index) {}

  StampedPose operator*() const { return (*rows_)[std::size_t(index_)]; }
  pointer operator->() const { return {**this}; }
  StampedPose operator[](difference_type n) const { return *(*this + n); }
  PoseIterator& operator++() { return ++index_, *this; }
  PoseIterator operator++(int) { return {rows_, index_++}; }
  PoseIterator& operator--() { return --index_, *this; }
  PoseIterator operator--(int) { return {rows_, index_--}; }
  PoseIterator& operator+=(difference_type n) { return index_ += n, *this; }
  PoseIterator& operator-=(difference_type n) { return index_ -= n, *this; }
  friend PoseIterator operator+(PoseIterator it, difference_type n) { return it += n; }
  friend PoseIterator operator+(difference_type n, PoseIterator it) { return it += n; }
  friend PoseIterator operator-(PoseIterator it, difference_type n) { return it -= n; }
  friend difference_type operator-(const PoseIterator& a, const PoseIterator& b) {
    return a.index_ - b.index_;
  }
  friend bool operator==(const PoseIterator& a, const PoseIterator& b) {
    return a.index_ == b.index_;
  }
  friend auto operator<=>(const PoseIterator& a, const PoseIterator& b) {
    return a.index_ <=> b.index_;
  }

 private:
  const Rows* rows_ = nullptr;
  difference_type index_ = 0;
};

// A trajectory stored in 36 bytes a pose instead of a StampedPose's 144 (a 4×4 matrix of
// doubles): the time as given, the position in steps of 1e-6 m and the rotation as its unit
// quaternion in steps of 1e-9 — what a TUM file of ours holds (common/tum.hpp) — rebuilt into a
// pose when read. Every pose reads back bit for bit as it was stored: a position or rotation that
// its decimals do not rebuild exactly (a pose that was never rounded as a TUM row, or a position
// over ±2147 m from the track's first one) is kept whole on the side.
// Why: ground truth at 100 Hz and odometry at 50 Hz are held for the whole run, for the
// evaluation at its end — 156 MB in two hours as StampedPoses (docs/performance.md, memory).
class PoseTrack {
 public:
  using const_iterator = PoseIterator<PoseTrack>;

  PoseTrack() = default;
  // The poses, each stored exactly.
  PoseTrack(const Trajectory& trajectory);  // NOLINT: implicit, a lossless copy
  PoseTrack(std::initializer_list<StampedPose> poses) : PoseTrack(Trajectory(poses)) {}

  // Stores the pose exactly as given.
  void push_back(const StampedPose& pose);
  // Stores the pose as its TUM row reads back: bit for bit what common::quantise makes of it,
  // in 36 bytes (and the position whole beside it when over ±2147 m from the first one).
  void pushQuantised(const StampedPose& pose);
  void reserve(std::size_t n) { rows_.reserve(n); }

  std::size_t size() const { return rows_.size(); }
  bool empty() const { return rows_.empty(); }
  double time(std::size_t i) const { return rows_[i].time(); }
  Eigen::Vector3d position(std::size_t i) const;
  StampedPose operator[](std::size_t i) const;
  StampedPose front() const { return (*this)[0]; }
  StampedPose back() const { return (*this)[size() - 1]; }
  const_iterator begin() const { return {this, 0}; }
  const_iterator end() const { return {this, std::ptrdiff_t(size())}; }

  // Poses [first, first + count) as a Trajectory (for a chunk of TUM text).
  Trajectory slice(std::size_t first, std::size_t count) const;
  Trajectory toTrajectory() const { return slice(0, size()); }
  // Bytes held (rows, and the positions and rotations kept whole).
  std::size_t bytes() const;

  // A row's step codes beside the steps themselves (a quaternion's |steps| ≤ 1e9 < 2^31).
  static constexpr std::int32_t kWhole = INT32_MIN;  // the position or rotation is kept whole
  static constexpr std::int32_t kNegativeZero = INT32_MIN + 1;

 private:
  struct Row {
    // The time's bits, in two halves: a double would align the row to 40 bytes.
    std::uint32_t t_low, t_high;
    // The position x y z in steps of 1e-6 m, counted from origin_steps_ (a track 8 km from the
    // plan's origin stays compact); p[0] = kWhole: the position is whole_positions_[p[1]].
    std::int32_t p[3];
    // The quaternion w x y z in steps of 1e-9 (w ≥ 0); q[0] = kWhole: the rotation is
    // whole_rotations_[q[1]]. kNegativeZero stands for −0 in either (the sign of a zero reaches
    // the pose's bits and the TUM text).
    std::int32_t q[4];

    double time() const;
    void setTime(double t);
  };
  static_assert(sizeof(Row) == 36);

  // Codes the position's steps into the row, or keeps `exact` whole when the steps do not fit
  // (non-finite, over ±2147 m from the first position) or, for an exact copy, do not read back as
  // `exact` bit for bit.
  void setPosition(Row& row, const std::array<double, 3>& steps, const Eigen::Vector3d& exact,
                   bool must_read_back);
  Eigen::Vector3d positionOfCodes(const std::int32_t p[3]) const;

  std::optional<std::array<double, 3>> origin_steps_;  // the first finite position's steps
  std::vector<Row> rows_;
  std::vector<Eigen::Vector3d> whole_positions_;
  std::vector<Eigen::Matrix3d> whole_rotations_;
};

// A read-only view of a trajectory held either way — a Trajectory or a PoseTrack — for the
// evaluation's functions, which read ground truth and odometry (tracks) and estimates or files
// (Trajectories) alike. Like std::span, it must not outlive what it views (a parameter may view a
// temporary; a variable must not).
class PoseSequence {
 public:
  using const_iterator = PoseIterator<PoseSequence>;

  PoseSequence() = default;                                             // an empty one
  PoseSequence(const Trajectory& trajectory) : vector_(&trajectory) {}  // NOLINT: a view
  PoseSequence(const PoseTrack& track) : track_(&track) {}              // NOLINT: a view

  std::size_t size() const { return vector_ ? vector_->size() : track_ ? track_->size() : 0; }
  bool empty() const { return size() == 0; }
  double time(std::size_t i) const { return vector_ ? (*vector_)[i].t : track_->time(i); }
  Eigen::Vector3d position(std::size_t i) const {
    return vector_ ? (*vector_)[i].pose.translation() : track_->position(i);
  }
  StampedPose operator[](std::size_t i) const { return vector_ ? (*vector_)[i] : (*track_)[i]; }
  // Binary searches on the times (in order): the first index whose time is not before `t`, and
  // the first whose time is after it; size() when there is none.
  std::size_t lowerBound(double t) const {
    return firstIndex([&](std::size_t i) { return !(time(i) < t); });
  }
  std::size_t upperBound(double t) const {
    return firstIndex([&](std::size_t i) { return t < time(i); });
  }
  StampedPose front() const { return (*this)[0]; }
  StampedPose back() const { return (*this)[size() - 1]; }
  const_iterator begin() const { return {this, 0}; }
  const_iterator end() const { return {this, std::ptrdiff_t(size())}; }

 private:
  // The first index where `past` holds, `past` being false then true along the sequence.
  template <typename Past>
  std::size_t firstIndex(const Past& past) const {
    std::size_t first = 0, count = size();
    while (count > 0) {
      const std::size_t half = count / 2;
      if (past(first + half)) {
        count = half;
      } else {
        first += half + 1;
        count -= half + 1;
      }
    }
    return first;
  }

  const Trajectory* vector_ = nullptr;
  const PoseTrack* track_ = nullptr;
};

}  // namespace isg::common
