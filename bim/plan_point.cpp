#include "bim/plan_point.hpp"

#include "bim/limits.hpp"

namespace isg::bim {

Eigen::Vector2d planPoint(const common::JsonNode& node) {
  const Eigen::Vector2d p = node.point2();
  if (p.cwiseAbs().maxCoeff() > limits::kMaxCoordinate) {
    node.fail("coordinate " + common::formatNumber(p.cwiseAbs().maxCoeff()) +
              " is out of range: points must lie within ±" +
              common::formatNumber(limits::kMaxCoordinate) + " m of the origin");
  }
  return p;
}

}  // namespace isg::bim
