#include "run/builtin_methods.hpp"

namespace isg::run {

void addDeadReckoning(LocalizerRegistry& registry) {
  registry.add({"dead-reckoning",
                "odometry alone, its frame M placed at the true start pose (a baseline that is "
                "given the start)",
                /*needs_plan=*/false, /*given_start=*/true, [](const LocalizerContext& c) {
                  return std::make_unique<slam::DeadReckoning>(c.start_B_T_M);
                }});
}

}  // namespace isg::run
