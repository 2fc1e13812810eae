#include "worlds/reference_plans.hpp"

#include <filesystem>

#include "bim/plan_parser.hpp"
#include "common/json_reader.hpp"
#include "worlds/walk_crossings.hpp"

namespace isg::worlds {

namespace detail {
const std::vector<std::pair<std::string_view, std::string_view>>& embeddedPlanFiles();
}  // namespace detail

namespace {

std::string withoutJson(std::string_view name) {
  std::string out(name);
  if (out.size() > 5 && out.ends_with(".json")) out.resize(out.size() - 5);
  return out;
}

}  // namespace

std::vector<std::string> builtinNames() {
  std::vector<std::string> names;
  for (const auto& [file, text] : detail::embeddedPlanFiles()) names.push_back(withoutJson(file));
  return names;
}

std::optional<std::string_view> builtinText(std::string_view name) {
  const std::string wanted = withoutJson(name);
  for (const auto& [file, text] : detail::embeddedPlanFiles()) {
    if (withoutJson(file) == wanted) return text;
  }
  return std::nullopt;
}

bool isBuiltin(std::string_view argument) { return argument.starts_with(kBuiltinPrefix); }

namespace {

bim::Scenario readScenarioOrBuiltin(const std::string& argument, common::Warnings* warnings) {
  if (!isBuiltin(argument)) return bim::loadScenario(argument, warnings);
  const std::string name = argument.substr(kBuiltinPrefix.size());
  const auto text = builtinText(name);
  if (!text) {
    std::string known;
    for (const auto& n : builtinNames()) known += (known.empty() ? "" : ", ") + n;
    throw common::InputError(argument, "", "no such built-in world (built-ins: " + known + ")");
  }
  const nlohmann::json document = common::parseJsonText(std::string(*text), argument);
  const common::JsonSource source{argument, warnings};
  return bim::parseScenario(
      common::JsonNode(document, "", source), [&](const common::JsonNode& ref) {
        const std::string plan_name = std::string(kBuiltinPrefix) + withoutJson(ref.string());
        const auto plan_text = builtinText(ref.string());
        if (!plan_text) ref.fail("no built-in plan \"" + ref.string() + "\"");
        const nlohmann::json plan_document =
            common::parseJsonText(std::string(*plan_text), plan_name);
        const common::JsonSource plan_source{plan_name, warnings};
        return bim::LoadedPlan{bim::parsePlan(common::JsonNode(plan_document, "", plan_source)),
                               plan_name};
      });
}

}  // namespace

bim::Scenario loadScenarioOrBuiltin(const std::string& argument, common::Warnings* warnings) {
  bim::Scenario scenario = readScenarioOrBuiltin(argument, warnings);
  takeCrossedSolids(scenario, warnings);
  return scenario;
}

std::string worldName(const std::string& argument) {
  if (isBuiltin(argument)) return argument.substr(kBuiltinPrefix.size());
  return std::filesystem::path(argument).stem().string();
}

}  // namespace isg::worlds
