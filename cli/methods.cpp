#include "cli/methods.hpp"

#include <stdexcept>

#include "slam/isgraph_localizer.hpp"
#include "slam/sgraph_localizer.hpp"

namespace isg::cli {

const std::vector<std::string>& methodNames() {
  static const std::vector<std::string> names{"is-graphs", "s-graph", "dead-reckoning"};
  return names;
}

std::unique_ptr<slam::Localizer> makeLocalizer(const std::string& method,
                                               const Eigen::Isometry3d& R_T_L,
                                               const bim::AGraph& plan,
                                               const Eigen::Isometry3d& B_T_M_true) {
  if (method == "is-graphs") return std::make_unique<slam::ISGraphLocalizer>(R_T_L, plan);
  if (method == "s-graph") return std::make_unique<slam::SGraphLocalizer>(R_T_L);
  if (method == "dead-reckoning") return std::make_unique<slam::DeadReckoning>(B_T_M_true);
  throw std::invalid_argument("unknown method " + method);
}

}  // namespace isg::cli
