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

struct Prepared {
  Association association;
  std::optional<Similarity> alignment;
  std::vector<Eigen::Isometry3d> reference, estimate;  // associated, aligned, projected
};

Prepared prepare(const common::Trajectory& ref, const common::Trajectory& est,
                 const ErrorOptions& options) {
  Prepared p;
  p.association = associate(ref, est, options.max_diff);
  const std::size_t n = p.association.reference.size();
  if (n == 0) {
    throw std::invalid_argument("no pose of the estimate is within " +
                                std::to_string(options.max_diff) + " s of a reference pose");
  }
  for (std::size_t i = 0; i < n; ++i) {
    p.reference.push_back(ref[p.association.reference[i]].pose);
    p.estimate.push_back(est[p.association.estimate[i]].pose);
  }
  if (options.align != Alignment::kNone) {
    std::vector<Eigen::Vector3d> from, to;
    for (std::size_t i = 0; i < n; ++i) {
      from.push_back(p.estimate[i].translation());
      to.push_back(p.reference[i].translation());
    }
    p.alignment = umeyama(from, to, options.align == Alignment::kSim3);
    for (auto& pose : p.estimate) pose = p.alignment->apply(pose);
  }
  if (options.project_xy) {
    for (auto& pose : p.reference) pose = projectXY(pose);
    for (auto& pose : p.estimate) pose = projectXY(pose);
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

ErrorResult absolutePoseError(const common::Trajectory& reference,
                              const common::Trajectory& estimate, const ErrorOptions& options) {
  Prepared p = prepare(reference, estimate, options);
  std::vector<double> translation, rotation;
  for (std::size_t i = 0; i < p.reference.size(); ++i) {
    translation.push_back((p.estimate[i].translation() - p.reference[i].translation()).norm());
    rotation.push_back(angleDeg(p.reference[i].linear(), p.estimate[i].linear()));
  }
  return finish(std::move(p), std::move(translation), std::move(rotation));
}

ErrorResult relativePoseError(const common::Trajectory& reference,
                              const common::Trajectory& estimate, const ErrorOptions& options) {
  if (options.rpe_delta < 1) throw std::invalid_argument("RPE delta must be at least 1");
  Prepared p = prepare(reference, estimate, options);
  std::vector<double> translation, rotation;
  for (std::size_t i = 0; i + options.rpe_delta < p.reference.size(); ++i) {
    const std::size_t j = i + options.rpe_delta;
    const Eigen::Isometry3d ref = p.reference[i].inverse() * p.reference[j];
    const Eigen::Isometry3d est = p.estimate[i].inverse() * p.estimate[j];
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
