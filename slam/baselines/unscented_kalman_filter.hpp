#pragma once

#include <Eigen/Core>
#include <functional>
#include <vector>

namespace isg::slam {

// An unscented Kalman filter (Julier & Uhlmann; the form hdl_localization uses): the state's
// mean and covariance are carried through non-linear process and measurement functions by 2n+1
// sigma points, weights w0 = λ/(n+λ), wi = 1/(2(n+λ)) with λ = 1 as hdl_localization. Components
// listed as angles are averaged on the circle and their differences wrapped to (−π, π].
class UnscentedKalmanFilter {
 public:
  using Vector = Eigen::VectorXd;
  using Matrix = Eigen::MatrixXd;
  using Function = std::function<Vector(const Vector&)>;

  UnscentedKalmanFilter(Vector mean, Matrix covariance, std::vector<int> angles = {},
                        double lambda = 1.0);

  // x ← f(x), P ← the sigma points' spread through f, plus the process noise Q.
  void predict(const Function& f, const Matrix& Q);
  // Corrects with a measurement z = h(x) + noise of covariance R; `angles` are z's angular
  // components. Returns the innovation z − h(x̂).
  Vector update(const Vector& z, const Function& h, const Matrix& R,
                const std::vector<int>& angles = {});

  const Vector& mean() const { return mean_; }
  const Matrix& covariance() const { return covariance_; }

 private:
  std::vector<Vector> sigmaPoints() const;
  // The weighted mean of points, circular for the components in `angles`.
  Vector weightedMean(const std::vector<Vector>& points, const std::vector<int>& angles) const;

  Vector mean_;
  Matrix covariance_;
  std::vector<int> angles_;
  double lambda_;
  std::vector<double> weights_;
};

}  // namespace isg::slam
