#pragma once

#include <Eigen/Core>

#include "common/json_reader.hpp"

namespace isg::bim {

// A point of the plan read from a plan or scenario: [x, y] of finite numbers with |x|, |y| <=
// limits::kMaxCoordinate; anything else is an InputError at the node.
Eigen::Vector2d planPoint(const common::JsonNode& node);

}  // namespace isg::bim
