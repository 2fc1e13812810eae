#include "ifc/ifc_import.hpp"

#include <algorithm>
#include <cstdio>

#include "bim/limits.hpp"
#include "bim/plan_parser.hpp"
#include "common/json_reader.hpp"
#include "common/plural.hpp"
#include "ifc/child_process.hpp"
#include "ifc/step_header.hpp"

namespace isg::ifc {
namespace {

// When `error` is at a flight of stairs (/levels/L/stairs/K...), removes that flight from the
// plan, logs why and returns true.
bool dropRefusedFlight(ImportResult& result, const common::InputError& error) {
  const std::string& pointer = error.pointer();
  std::size_t level = 0, stair = 0;
  char rest = 0;
  if (std::sscanf(pointer.c_str(), "/levels/%zu/stairs/%zu%c", &level, &stair, &rest) < 2) {
    return false;
  }
  auto& levels = result.plan_json["levels"];
  if (level >= levels.size() || !levels[level].contains("stairs")) return false;
  auto& stairs = levels[level]["stairs"];
  if (stair >= stairs.size()) return false;
  result.log.push_back("dropped stair flight " + stairs[stair]["id"].get<std::string>() + " (" +
                       stairs[stair].value("name", std::string()) +
                       "): the plan's rules for stairs refuse it: " + error.reason());
  stairs.erase(stair);
  if (stairs.empty()) levels[level].erase("stairs");
  return true;
}

}  // namespace

ImportInterrupted::ImportInterrupted(int signal)
    : std::runtime_error("stopped by signal " + std::to_string(signal)), signal_(signal) {}

ImportResult importIfcText(const std::string& file, std::string text,
                           const ImportOptions& options) {
  // The quick checks of the file's text here, with their exact messages; IFC++ in the child.
  readStepHeader(file, text);
  checkStepStrings(file, text);
  // More walls than every storey may hold between them is refused before IFC++ builds them
  // (10⁵ walls took 9 s and 350 MB to reach the plan's own limit).
  const std::size_t walls = countInstances(
      text, {"IFCWALL", "IFCWALLSTANDARDCASE", "IFCWALLELEMENTEDCASE", "IFCCURTAINWALL"});
  const std::size_t storeys = std::max<std::size_t>(1, countInstances(text, {"IFCBUILDINGSTOREY"}));
  if (walls > storeys * bim::limits::kMaxWallsPerLevel) {
    throw common::InputError(
        file, "",
        std::to_string(walls) + " walls in " + common::counted(storeys, "storey") + "; at most " +
            std::to_string(bim::limits::kMaxWallsPerLevel) +
            " a level are supported (docs/formats.md, Limits), however they are spread");
  }
  ImportResult result = importInChildProcess(file, std::move(text), options);
  // The plan is read back by the plan's own parser: what is written is a plan isg accepts.
  // A flight the plan's rules refuse (too steep or narrow for a legged robot, into a wall) is
  // dropped with the parser's reason, and the plan read again.
  for (;;) {
    const nlohmann::json document = nlohmann::json::parse(result.plan_json.dump());
    result.warnings.clear();
    const common::JsonSource source{file, &result.warnings};
    try {
      result.plan = bim::parsePlan(common::JsonNode(document, "", source));
      return result;
    } catch (const common::InputError& e) {
      if (!dropRefusedFlight(result, e)) {
        throw common::InputError(file, "",
                                 "the plan imported from it breaks a rule of the plan format at " +
                                     e.pointer() + ": " + e.reason());
      }
    }
  }
}

ImportResult importIfc(const std::string& path, const ImportOptions& options) {
  return importIfcText(path, common::readCheckedFile(path, kMaxIfcBytes), options);
}

}  // namespace isg::ifc
