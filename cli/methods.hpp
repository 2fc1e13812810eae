#pragma once

#include <Eigen/Geometry>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "bim/agraph.hpp"
#include "slam/localizer.hpp"

namespace isg::cli {

// The localization methods the testbed runs, by name: "is-graphs" (the S-Graph matched to and
// merged with the plan), "s-graph" (SLAM in M only: never localized in B) and "dead-reckoning"
// (odometry with M placed at the true start pose: a baseline that cheats by knowing the start).
const std::vector<std::string>& methodNames();

// `B_T_M_true` is what dead-reckoning is given; the others ignore it.
std::unique_ptr<slam::Localizer> makeLocalizer(const std::string& method,
                                               const Eigen::Isometry3d& R_T_L,
                                               const bim::AGraph& plan,
                                               const Eigen::Isometry3d& B_T_M_true);

}  // namespace isg::cli
