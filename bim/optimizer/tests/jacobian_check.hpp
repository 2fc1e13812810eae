#pragma once

#include <ceres/gradient_checker.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <vector>

namespace isg::testing {

// Checks a cost function's Jacobians, in the manifolds' tangent spaces, against numeric
// differentiation at the given parameters. Mixed tolerance: relative for large entries, absolute
// for entries that are (nearly) zero, where a relative error means nothing.
inline void expectJacobiansMatchNumeric(const ceres::CostFunction& cost,
                                        const std::vector<const ceres::Manifold*>& manifolds,
                                        const std::vector<double*>& parameters) {
  ceres::NumericDiffOptions numeric;
  ceres::GradientChecker checker(&cost, &manifolds, numeric);
  ceres::GradientChecker::ProbeResults results;
  checker.Probe(parameters.data(), 1e-6, &results);
  ASSERT_EQ(results.local_jacobians.size(), parameters.size());
  ASSERT_EQ(results.local_numeric_jacobians.size(), parameters.size());
  for (std::size_t b = 0; b < results.local_jacobians.size(); ++b) {
    const auto& user = results.local_jacobians[b];
    const auto& reference = results.local_numeric_jacobians[b];
    for (int r = 0; r < user.rows(); ++r) {
      for (int c = 0; c < user.cols(); ++c) {
        EXPECT_NEAR(user(r, c), reference(r, c), 1e-6 * std::max(1.0, std::abs(reference(r, c))))
            << "block " << b << " (" << r << ", " << c << ")";
      }
    }
  }
}

}  // namespace isg::testing
