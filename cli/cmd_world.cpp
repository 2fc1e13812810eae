#include "cli/cmd_world.hpp"

#include <iostream>

#include "common/output_path.hpp"
#include "sim/mujoco_world.hpp"
#include "worlds/mjcf_generator.hpp"

namespace isg::cli {

WorldCommand::WorldCommand(CLI::App& parent) {
  app_ = parent.add_subcommand("world", "Generate the MuJoCo world (MJCF) of a plan or scenario");
  app_->footer(
      "The building is the plan with the scenario's as-built deviations (missing, extra and "
      "shifted walls, closed doors, clutter). Geoms are named after the plan's ids "
      "(wall/W3/0, wall/W3/lintel/D1, door/D2, floor/L0, clutter/0, stair/S1/3: step 3 of flight "
      "S1); rooms carry a site "
      "room/R1. The world is compiled with MuJoCo before it is written, and nothing is written "
      "when the input is invalid. Look at it with: mujoco-simulate world.xml\n\n" +
      builtinWorldsHelp());
  app_->add_option("input", input_, "plan or scenario file, or builtin:NAME")
      ->option_text("PLAN|SCENARIO")
      ->required();
  app_->add_option("-o,--output", output_, "MJCF file to write (default: standard output)");
  app_->add_flag("--no-ceilings", no_ceilings_, "leave the ceiling slabs out (for looking at it)");
}

int WorldCommand::run() {
  const bim::Scenario scenario = loadInput(input_, "world");
  worlds::WorldOptions options;
  options.ceilings = !no_ceilings_;
  if (!output_.empty()) {
    common::checkOutputPath(output_, {common::OutputKind::kMjcf, {inputFile(input_)}, true, false});
  }
  const std::string mjcf = worlds::generateMjcf(scenario, options);
  // A world that MuJoCo cannot compile is our bug, never the user's: refuse to write it.
  const sim::MujocoWorld world = sim::MujocoWorld::fromXml(mjcf);
  if (output_.empty()) {
    std::cout << mjcf;
    return kExitOk;
  }
  writeFileAtomically(output_, common::outputMark(common::OutputKind::kMjcf, mjcf));
  std::cerr << "isg world: wrote " << output_ << " (" << world.model().ngeom << " geoms, "
            << world.model().nsite << " room sites)\n";
  return kExitOk;
}

}  // namespace isg::cli
