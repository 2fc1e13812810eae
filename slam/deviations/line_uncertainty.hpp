#pragma once

#include <Eigen/Core>
#include <utility>
#include <vector>

namespace isg::slam {

// The covariance of (offset, slope) of the line o(s) = offset + slope·s that weighted least
// squares fitted to `ends` (each a point (s, o) with its weight), the line at `offset`, `slope`.
// Each end lies on the face to `end_sigma`, or to the ends' own scatter about the line when that
// is larger and there are more than two ends per parameter (with fewer, the scatter says nothing).
// The sandwich σ² H⁻¹ (Σ w² J Jᵀ) H⁻¹, J = (1, s), H = Σ w J Jᵀ: with equal weights, σ² (JᵀJ)⁻¹.
// Fewer than two ends, or all at one s: the offset's variance σ², the slope's 10⁶ (unknown).
Eigen::Matrix2d lineCovariance(const std::vector<std::pair<Eigen::Vector2d, double>>& ends,
                               double offset, double slope, double end_sigma);

}  // namespace isg::slam
