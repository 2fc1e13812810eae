#pragma once

#include <Eigen/SparseCholesky>
#include <vector>

namespace isg::sim {

// A uniform cubic B-spline on [0, duration]: knots every `spacing` seconds, twice continuously
// differentiable, so that what follows it can be differentiated twice (an accelerometer, a
// gyroscope's rate). Outside [0, duration] it holds its end values, at rest.
class UniformCubicSpline {
 public:
  struct Sample {
    double value = 0.0, rate = 0.0, acceleration = 0.0;
  };
  UniformCubicSpline() = default;
  UniformCubicSpline(double spacing, double duration, std::vector<double> control)
      : spacing_(spacing), duration_(duration), control_(std::move(control)) {}
  Sample at(double t) const;
  double duration() const { return duration_; }

 private:
  double spacing_ = 1.0;
  double duration_ = 0.0;
  std::vector<double> control_;
};

// Least-squares fits of uniform cubic B-splines to values at fixed times (one factorisation, any
// number of channels): the data's misfit plus `smoothness` × the squared second differences of
// the control points. The second term is tiny beside the data's wherever there are samples; it
// only decides the curve where there are none (gaps, or samples sparser than the knots), where it
// makes it the least accelerated one.
class SmoothingSplineFit {
 public:
  // `times` increasing, from 0.
  SmoothingSplineFit(std::vector<double> times, double spacing, double smoothing);
  UniformCubicSpline fit(const std::vector<double>& values) const;
  int knots() const { return segments_ + 1; }

 private:
  std::vector<double> times_;
  double spacing_;
  int segments_;
  Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>> solver_;
};

}  // namespace isg::sim
