#include "cli/common.hpp"

#include <cstdio>
#include <iostream>

#include "worlds/reference_plans.hpp"

namespace isg::cli {

bim::Scenario loadInput(const std::string& argument, const std::string& command) {
  bim::Warnings warnings;
  bim::Scenario scenario = worlds::loadScenarioOrBuiltin(argument, &warnings);
  for (const auto& w : warnings) std::cerr << "isg " << command << ": warning: " << w.str() << "\n";
  return scenario;
}

std::string builtinWorldsHelp() {
  std::string names;
  for (const auto& n : worlds::builtinNames()) names += (names.empty() ? "" : ", ") + n;
  return "PLAN|SCENARIO is a file in the isg.plan or isg.scenario format (docs/formats.md), or a "
         "built-in world written builtin:NAME, NAME one of: " +
         names + ".";
}

}  // namespace isg::cli
