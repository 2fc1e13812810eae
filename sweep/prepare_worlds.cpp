#include "sweep/prepare_worlds.hpp"

#include <filesystem>

#include "common/atomic_folder.hpp"
#include "common/content_hash.hpp"
#include "common/input_error.hpp"
#include "common/json_reader.hpp"
#include "common/limits.hpp"
#include "sim/simulation.hpp"
#include "worlds/reference_plans.hpp"
#include "worlds/world_hash.hpp"

namespace isg::sweep {

namespace {

namespace fs = std::filesystem;

// Writes `text` to `path` unless the file already holds exactly it.
void writeIfChanged(const fs::path& path, const std::string& text) {
  if (fs::is_regular_file(path)) {
    try {
      if (common::readCheckedFile(path.string(), common::limits::kMaxJsonFileBytes) == text) return;
    } catch (const common::InputError&) {
      // Unreadable: written anew below.
    }
  }
  common::writeFileAtomically(path.string(), text);
}

// A file's bytes as far as they can be read ("" when not at all).
std::string rawBytes(const std::string& path) {
  try {
    return common::readCheckedFile(path, common::limits::kMaxJsonFileBytes);
  } catch (const common::InputError&) {
    return "";
  }
}

}  // namespace

void prepareSweepWorlds(Suite& suite, const std::string& sweep_dir) {
  const fs::path dir(sweep_dir);
  for (auto& world : suite.worlds) {
    if (!world.generate) {
      try {
        common::Warnings warnings;
        world.hash = worlds::worldHash(worlds::loadScenarioOrBuiltin(world.input, &warnings));
      } catch (const common::InputError&) {
        // A world that does not read fails its own cells (recorded, the others go on); its
        // file's bytes still tell when it has changed.
        world.hash = common::contentHash("unreadable world\n" + rawBytes(world.input));
      }
      continue;
    }
    // The same spec gives the same bytes: a file that differs is of an older spec, rewritten.
    const worlds::GeneratedBuilding b = worlds::generateBuilding(*world.generate);
    const fs::path scenario_path = dir / world.input;
    std::error_code error;
    fs::create_directories(scenario_path.parent_path(), error);
    writeIfChanged(dir / kSweepWorldsFolder / (b.name + ".json"), b.plan.dump(2) + "\n");
    writeIfChanged(scenario_path, b.scenario.dump(2) + "\n");
    common::Warnings warnings;
    const bim::Scenario scenario = bim::loadScenario(scenario_path.string(), &warnings);
    const sim::Simulation simulation(scenario);
    if (const std::string part = sim::unreachedPart(simulation.route()); !part.empty()) {
      throw common::InputError(suite.file, "/worlds",
                               "generated world " + world.name + ": its tour cannot reach " + part +
                                   sim::coarseCellsNote(simulation.route()) +
                                   "; change the generator's parameters");
    }
    world.hash = worlds::worldHash(scenario);
  }
}

std::vector<ChangedWorld> changedWorlds(const Suite& suite, const SweepPlan& before) {
  std::vector<ChangedWorld> changed;
  for (const auto& world : suite.worlds) {
    const auto it = before.world_hashes.find(world.name);
    if (it == before.world_hashes.end() || it->second == world.hash) continue;
    changed.push_back({world.name, it->second, world.hash});
  }
  return changed;
}

}  // namespace isg::sweep
