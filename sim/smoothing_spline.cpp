#include "sim/smoothing_spline.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <stdexcept>

namespace isg::sim {

namespace {

struct Basis {
  int segment;
  std::array<double, 4> value, rate, acceleration;  // of control points segment … segment + 3
};

// The uniform cubic B-spline's four basis functions at t (and their derivatives in t).
Basis basisAt(double t, double spacing, int segments) {
  const double s = std::clamp(t / spacing, 0.0, double(segments));
  const int i = std::min(int(std::floor(s)), segments - 1);
  const double u = s - i, v = 1.0 - u;
  Basis b;
  b.segment = i;
  b.value = {v * v * v / 6.0, (3.0 * u * u * u - 6.0 * u * u + 4.0) / 6.0,
             (-3.0 * u * u * u + 3.0 * u * u + 3.0 * u + 1.0) / 6.0, u * u * u / 6.0};
  const double h = spacing;
  b.rate = {-0.5 * v * v / h, (1.5 * u * u - 2.0 * u) / h, (-1.5 * u * u + u + 0.5) / h,
            0.5 * u * u / h};
  b.acceleration = {v / (h * h), (3.0 * u - 2.0) / (h * h), (1.0 - 3.0 * u) / (h * h), u / (h * h)};
  return b;
}

}  // namespace

UniformCubicSpline::Sample UniformCubicSpline::at(double t) const {
  const int segments = int(control_.size()) - 3;
  const bool outside = t < 0.0 || t > duration_;
  const Basis b = basisAt(std::clamp(t, 0.0, duration_), spacing_, segments);
  Sample s;
  for (int k = 0; k < 4; ++k) {
    const double c = control_[std::size_t(b.segment + k)];
    s.value += b.value[k] * c;
    s.rate += b.rate[k] * c;
    s.acceleration += b.acceleration[k] * c;
  }
  if (outside) s.rate = s.acceleration = 0.0;
  return s;
}

SmoothingSplineFit::SmoothingSplineFit(std::vector<double> times, double spacing, double smoothing)
    : times_(std::move(times)), spacing_(spacing) {
  if (times_.empty() || !(spacing > 0.0)) throw std::invalid_argument("no samples to fit");
  const double duration = std::max(times_.back(), 0.0);
  segments_ = std::max(1, int(std::ceil(duration / spacing - 1e-9)));
  const int n = segments_ + 3;
  std::vector<Eigen::Triplet<double>> entries;
  entries.reserve(times_.size() * 16 + std::size_t(n) * 9);
  for (double t : times_) {
    const Basis b = basisAt(t, spacing, segments_);
    for (int r = 0; r < 4; ++r)
      for (int c = 0; c < 4; ++c)
        entries.emplace_back(b.segment + r, b.segment + c, b.value[r] * b.value[c]);
  }
  const std::array<double, 3> second = {1.0, -2.0, 1.0};
  for (int k = 0; k + 2 < n; ++k) {
    for (int r = 0; r < 3; ++r)
      for (int c = 0; c < 3; ++c)
        entries.emplace_back(k + r, k + c, smoothing * second[r] * second[c]);
  }
  Eigen::SparseMatrix<double> normal(n, n);
  normal.setFromTriplets(entries.begin(), entries.end());
  solver_.compute(normal);
  if (solver_.info() != Eigen::Success) throw std::runtime_error("spline fit is singular");
}

UniformCubicSpline SmoothingSplineFit::fit(const std::vector<double>& values) const {
  Eigen::VectorXd rhs = Eigen::VectorXd::Zero(segments_ + 3);
  for (std::size_t i = 0; i < times_.size(); ++i) {
    const Basis b = basisAt(times_[i], spacing_, segments_);
    for (int r = 0; r < 4; ++r) rhs[b.segment + r] += b.value[r] * values[i];
  }
  const Eigen::VectorXd control = solver_.solve(rhs);
  return UniformCubicSpline(spacing_, std::max(times_.back(), 0.0),
                            std::vector<double>(control.data(), control.data() + control.size()));
}

}  // namespace isg::sim
