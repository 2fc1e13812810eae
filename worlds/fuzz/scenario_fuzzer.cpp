// libFuzzer harness: bytes → the scenario reader (a plan named by file resolves among the
// built-in reference plans), and for an accepted scenario the MJCF text `isg world` would write.
#include <cstdint>
#include <string>

#include "bim/plan_parser.hpp"
#include "bim/scenario.hpp"
#include "common/input_error.hpp"
#include "common/json_reader.hpp"
#include "worlds/mjcf_generator.hpp"
#include "worlds/reference_plans.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace isg;
  const std::string text(reinterpret_cast<const char*>(data), size);
  try {
    const nlohmann::json document = common::parseJsonText(text, "fuzz.json");
    common::Warnings warnings;
    const common::JsonSource source{"fuzz.json", &warnings};
    nlohmann::json plan_document;
    common::JsonSource plan_source{"", &warnings};
    const bim::Scenario scenario = bim::parseScenario(
        common::JsonNode(document, "", source), [&](const common::JsonNode& name) {
          const auto builtin = worlds::builtinText(name.string());
          if (!builtin) name.fail("no built-in plan " + common::inQuotes(name.string()));
          plan_source.file = name.string();
          plan_document = common::parseJsonText(std::string(*builtin), plan_source.file);
          return bim::LoadedPlan{bim::parsePlan(common::JsonNode(plan_document, "", plan_source)),
                                 plan_source.file};
        });
    worlds::generateMjcf(scenario);
  } catch (const common::InputError&) {
  }
  return 0;
}
