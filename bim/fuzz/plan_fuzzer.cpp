// libFuzzer harness: bytes → the plan reader, and for an accepted plan what `isg check` and
// `isg agraph` do next (level geometry, the A-Graph). Any InputError is the expected answer to a
// bad file; anything else (a crash, a sanitizer report, another exception) is a bug.
#include <cstdint>
#include <string>

#include "bim/agraph.hpp"
#include "bim/plan_geometry.hpp"
#include "bim/plan_parser.hpp"
#include "common/input_error.hpp"
#include "common/json_reader.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  try {
    const nlohmann::json document = isg::common::parseJsonText(text, "fuzz.json");
    isg::common::Warnings warnings;
    const isg::common::JsonSource source{"fuzz.json", &warnings};
    const isg::bim::Plan plan = isg::bim::parsePlan(isg::common::JsonNode(document, "", source));
    for (const auto& level : plan.levels) isg::bim::computeLevelGeometry(level);
    isg::bim::buildAGraph(plan);
  } catch (const isg::common::InputError&) {
  }
  return 0;
}
