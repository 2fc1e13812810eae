#include "worlds/world_hash.hpp"

#include <cstdio>

#include "common/content_hash.hpp"
#include "common/json_reader.hpp"
#include "common/limits.hpp"
#include "worlds/reference_plans.hpp"

namespace isg::worlds {

namespace {

// The bytes a world was read from: a built-in's text or a file's content.
std::string bytesOf(const std::string& name) {
  if (isBuiltin(name)) {
    const auto text = builtinText(name.substr(kBuiltinPrefix.size()));
    return text ? std::string(*text) : std::string();
  }
  return common::readCheckedFile(name, common::limits::kMaxJsonFileBytes);
}

}  // namespace

std::string worldHash(const bim::Scenario& scenario) {
  // Length-prefixed parts, so that no two different pairs of files give one text.
  const std::string scenario_bytes = bytesOf(scenario.source);
  std::string text = "isg world\n" + std::to_string(scenario_bytes.size()) + "\n" + scenario_bytes;
  if (scenario.plan_file != "<inline>" && scenario.plan_file != scenario.source) {
    const std::string plan_bytes = bytesOf(scenario.plan_file);
    text += "\n" + std::to_string(plan_bytes.size()) + "\n" + plan_bytes;
  }
  // A replayed walk is part of what was run: its poses as read (the file may exceed the JSON
  // size limit), after the files, so that scenarios without one hash as they always did.
  const auto& walk = scenario.robot.route.walk;
  if (scenario.robot.route.kind == bim::Route::Kind::kTrajectory) {
    text += "\nwalk " + std::to_string(walk.size()) + "\n";
    char row[128];
    for (const auto& pose : walk) {
      std::snprintf(row, sizeof row, "%.17g %.17g %.17g %.17g\n", pose.t, pose.xy.x(), pose.xy.y(),
                    pose.yaw);
      text += row;
    }
  }
  return common::contentHash(text);
}

}  // namespace isg::worlds
