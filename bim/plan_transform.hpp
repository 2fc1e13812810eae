#pragma once

#include <Eigen/Geometry>

#include "bim/plan.hpp"
#include "bim/scenario.hpp"

namespace isg::bim {

// A plan, or a whole scenario, moved rigidly in the plane: every coordinate p becomes T·p and every
// yaw gains T's angle. What is measured along a wall (door offsets, wall shifts) and heights stay.
// The same building anywhere in B, for the tests that accuracy does not depend on B's origin
// (docs/conventions.md, "Where B's origin is").
Plan transformedPlan(const Plan& plan, const Eigen::Isometry2d& T);
Scenario transformedScenario(const Scenario& scenario, const Eigen::Isometry2d& T);

// The rigid motion that turns by `yaw` about B's origin and then moves by `translation`.
Eigen::Isometry2d planarMotion(const Eigen::Vector2d& translation, double yaw);

}  // namespace isg::bim
