#include "eval/ape.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <numeric>
#include <stdexcept>

namespace isg::eval {

namespace {

double angleDeg(const Eigen::Matrix3d& a, const Eigen::Matrix3d& b) {
  const double c = std::clamp(((a.transpose() * b).trace() - 1.0) / 2.0, -1.0, 1.0);
  return std::acos(c) * 180.0 / std::numbers::pi;
}

// The associated pairs and the alignment; each pair's poses, aligned and projected, are made when
// asked for (`pair`), so that hours of poses are never copied (two copies of a two-hour odometry
// were ~100 MB).
struct Prepared {
  Association association;
  std::optional<Similarity> alignment;
  const common::PoseSequence* ref = nullptr;
  const common::PoseSequence* est = nullptr;
  std::optional<Eigen::Isometry3d> placement;  // applied to the estimate's poses first
  bool project_xy = false;

  Eigen::Isometry3d estimatePose(std::size_t i) const {
    const Eigen::Isometry3d pose = (*est)[association.estimate[i]].pose;
    return placement ? Eigen::Isometry3d(*placement * pose) : pose;
  }

  std::size_t size() const { return association.reference.size(); }
  // Pair i as the comparison sees it: reference and estimate, aligned, then projected.
  std::pair<Eigen::Isometry3d, Eigen::Isometry3d> pair(std::size_t i) const {
    Eigen::Isometry3d reference = (*ref)[association.reference[i]].pose;
    Eigen::Isometry3d estimate = estimatePose(i);
    if (alignment) estimate = alignment->apply(estimate);
    if (project_xy) {
      reference = projectXY(reference);
      estimate = projectXY(estimate);
    }
    return {reference, estimate};
  }
};

Prepared prepare(const common::PoseSequence& ref, const common::PoseSequence& est,
                 const ErrorOptions& options,
                 const std::optional<Eigen::Isometry3d>& placement = std::nullopt) {
  Prepared p;
  p.association = associate(ref, est, options.max_diff);
  p.ref = &ref;
  p.est = &est;
  p.placement = placement;
  p.project_xy = options.project_xy;
  const std::size_t n = p.size();
  if (n == 0) {
    throw std::invalid_argument("no pose of the estimate is within " +
                                std::to_string(options.max_diff) + " s of a reference pose");
  }
  if (options.align != Alignment::kNone) {
    std::vector<Eigen::Vector3d> from, to;
    from.reserve(n);
    to.reserve(n);
    for (std::size_t i = 0; i < n; ++i) {
      from.push_back(p.estimatePose(i).translation());
      to.push_back(ref[p.association.reference[i]].pose.translation());
    }
    p.alignment = umeyama(from, to, options.align == Alignment::kSim3);
  }
  return p;
}

ErrorResult finish(Prepared p, std::vector<double> translation, std::vector<double> rotation) {
  ErrorResult out;
  out.association = std::move(p.association);
  out.alignment = p.alignment;
  out.translation_stats = statistics(translation);
  out.rotation_stats = statistics(rotation);
  out.translation = std::move(translation);
  out.rotation_deg = std::move(rotation);
  return out;
}

}  // namespace

Statistics statistics(std::vector<double> v) {
  Statistics s;
  s.count = int(v.size());
  if (v.empty()) return s;
  double sum = 0.0, sse = 0.0;
  for (double x : v) {
    sum += x;
    sse += x * x;
  }
  s.mean = sum / v.size();
  s.sse = sse;
  s.rmse = std::sqrt(sse / v.size());
  double var = 0.0;
  for (double x : v) var += (x - s.mean) * (x - s.mean);
  s.std = std::sqrt(var / v.size());
  std::sort(v.begin(), v.end());
  s.min = v.front();
  s.max = v.back();
  const std::size_t m = v.size() / 2;
  s.median = v.size() % 2 ? v[m] : 0.5 * (v[m - 1] + v[m]);
  return s;
}

Eigen::Isometry3d projectXY(const Eigen::Isometry3d& pose) {
  Eigen::Isometry3d out = Eigen::Isometry3d::Identity();
  out.translation() = Eigen::Vector3d(pose.translation().x(), pose.translation().y(), 0.0);
  const double yaw = std::atan2(pose.linear()(1, 0), pose.linear()(0, 0));
  out.linear() = Eigen::AngleAxisd(yaw, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  return out;
}

ErrorResult absolutePoseError(common::PoseSequence reference, common::PoseSequence estimate,
                              const ErrorOptions& options) {
  return absolutePoseError(reference, estimate, options, std::nullopt);
}

ErrorResult absolutePoseError(common::PoseSequence reference, common::PoseSequence estimate,
                              const ErrorOptions& options,
                              const std::optional<Eigen::Isometry3d>& placement) {
  Prepared p = prepare(reference, estimate, options, placement);
  std::vector<double> translation, rotation;
  translation.reserve(p.size());
  rotation.reserve(p.size());
  for (std::size_t i = 0; i < p.size(); ++i) {
    const auto [ref, est] = p.pair(i);
    translation.push_back((est.translation() - ref.translation()).norm());
    rotation.push_back(angleDeg(ref.linear(), est.linear()));
  }
  return finish(std::move(p), std::move(translation), std::move(rotation));
}

ErrorResult relativePoseError(common::PoseSequence reference, common::PoseSequence estimate,
                              const ErrorOptions& options) {
  if (options.rpe_delta < 1) throw std::invalid_argument("RPE delta must be at least 1");
  Prepared p = prepare(reference, estimate, options);
  std::vector<double> translation, rotation;
  for (std::size_t i = 0; i + options.rpe_delta < p.size(); ++i) {
    const std::size_t j = i + options.rpe_delta;
    const auto [ref_i, est_i] = p.pair(i);
    const auto [ref_j, est_j] = p.pair(j);
    const Eigen::Isometry3d ref = ref_i.inverse() * ref_j;
    const Eigen::Isometry3d est = est_i.inverse() * est_j;
    const Eigen::Isometry3d error = ref.inverse() * est;
    translation.push_back(error.translation().norm());
    rotation.push_back(angleDeg(Eigen::Matrix3d::Identity(), error.linear()));
  }
  return finish(std::move(p), std::move(translation), std::move(rotation));
}

const char* toString(Alignment a) {
  switch (a) {
    case Alignment::kNone:
      return "none";
    case Alignment::kSE3:
      return "se3";
    case Alignment::kSim3:
      return "sim3";
  }
  return "?";
}

}  // namespace isg::eval
