#include "cli/cmd_inspect.hpp"

#include <iostream>

#include "sim/mujoco_world.hpp"
#include "sim/world_summary.hpp"
#include "worlds/mjcf_generator.hpp"
#include "worlds/reference_plans.hpp"

namespace isg::cli {

InspectCommand::InspectCommand(CLI::App& parent) {
  app_ = parent.add_subcommand(
      "inspect", "Generate a world, load it in MuJoCo, step it and report what it contains");
  app_->footer(
      "With no input it inspects the built-in default world (" +
      std::string(worlds::kDefaultWorld) +
      "). For every room of the robot's level it casts horizontal rays from the room's centroid "
      "and reports how many hit the building and the nearest geom.\n\n" +
      builtinWorldsHelp());
  app_->add_option("input", input_, "plan or scenario file, or builtin:NAME")
      ->option_text("PLAN|SCENARIO")
      ->default_str(std::string(worlds::kDefaultWorld));
  app_->add_option("--steps", steps_, "physics steps to run")
      ->check(CLI::Range(0, 10000000))
      ->capture_default_str();
}

int InspectCommand::run() {
  const std::string input = input_.empty() ? std::string(worlds::kDefaultWorld) : input_;
  const bim::Scenario scenario = loadInput(input, "inspect");
  sim::MujocoWorld world = sim::MujocoWorld::fromXml(worlds::generateMjcf(scenario));
  std::cout << "isg inspect: " << input << " (MuJoCo " << mj_versionString() << ")\n";
  std::cout << sim::formatSummary(sim::summarizeWorld(scenario, world, steps_));
  return kExitOk;
}

}  // namespace isg::cli
