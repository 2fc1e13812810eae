#pragma once

#include <filesystem>

#include "bim/plan.hpp"
#include "bim/scenario.hpp"
#include "run/bcf/bcf_topics.hpp"
#include "slam/deviations/plan_deviations.hpp"

namespace isg::cli {

// What a run's BCF archive is made from: the report, the plan it was measured against, what
// names the topics, and the building to take the snapshots in (the as-built world the robot
// walked; none: no snapshots).
struct BcfSources {
  const slam::DeviationReport* report = nullptr;
  const bim::Plan* plan = nullptr;
  const bim::AsBuilt* as_built = nullptr;  // null: the plan as planned
  run::bcf::TopicNames names;
  bool snapshots = true;
};

// Writes `file` (docs/deviations.md, "BCF"): one topic per element off the plan, each with its
// viewpoint and an 800 × 600 snapshot rendered on the CPU (EGL, Mesa) from the viewpoint's camera
// with the element's planned outline in red. Returns the number of topics.
std::size_t writeDeviationBcf(const std::filesystem::path& file, const BcfSources& sources);

}  // namespace isg::cli
