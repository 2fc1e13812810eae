#include "run/builtin_methods.hpp"

namespace isg::run {

void addDeadReckoning(LocalizerRegistry& registry) {
  registry.add({.name = "odometry",
                .summary = "dead reckoning: odometry alone, its frame M placed at the true start "
                           "pose (a baseline that is given the start)",
                .given_start = true,
                .make =
                    [](const LocalizerContext& c) {
                      return std::make_unique<slam::DeadReckoning>(c.start_B_T_M);
                    },
                .aliases = {"dead-reckoning"}});
}

}  // namespace isg::run
