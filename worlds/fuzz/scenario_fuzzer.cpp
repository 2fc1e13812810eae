// libFuzzer harness: bytes → the scenario reader (a plan named by file resolves among the
// built-in reference plans), and for an accepted scenario the MJCF text `isg world` would write.
#include <cstdint>
#include <string>

#include "bim/input_error.hpp"
#include "bim/json_reader.hpp"
#include "bim/plan_parser.hpp"
#include "bim/scenario.hpp"
#include "worlds/mjcf_generator.hpp"
#include "worlds/reference_plans.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace isg;
  const std::string text(reinterpret_cast<const char*>(data), size);
  try {
    const nlohmann::json document = bim::parseJsonText(text, "fuzz.json");
    bim::Warnings warnings;
    const bim::JsonSource source{"fuzz.json", &warnings};
    nlohmann::json plan_document;
    bim::JsonSource plan_source{"", &warnings};
    const bim::Scenario scenario =
        bim::parseScenario(bim::JsonNode(document, "", source), [&](const bim::JsonNode& name) {
          const auto builtin = worlds::builtinText(name.string());
          if (!builtin) name.fail("no built-in plan " + bim::inQuotes(name.string()));
          plan_source.file = name.string();
          plan_document = bim::parseJsonText(std::string(*builtin), plan_source.file);
          return bim::LoadedPlan{bim::parsePlan(bim::JsonNode(plan_document, "", plan_source)),
                                 plan_source.file};
        });
    worlds::generateMjcf(scenario);
  } catch (const bim::InputError&) {
  }
  return 0;
}
