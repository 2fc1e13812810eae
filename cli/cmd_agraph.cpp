#include "cli/cmd_agraph.hpp"

#include <cstdio>
#include <iostream>

#include "bim/agraph.hpp"
#include "bim/agraph_json.hpp"
#include "bim/agraph_svg.hpp"
#include "common/output_path.hpp"
#include "common/plural.hpp"

namespace isg::cli {

AGraphCommand::AGraphCommand(CLI::App& parent) {
  app_ = parent.add_subcommand("agraph", "Build the architectural graph (A-Graph) of a plan");
  app_->footer(
      "Nodes: wall surfaces (planes in B), walls (two opposed surfaces and a centre), rooms "
      "(four-wall, two-wall corridors, other polygons), doorways and one floor per level; edges "
      "between them. JSON format: docs/agraph.md. Given a scenario, the A-Graph is built from its "
      "plan: the localizer never sees the as-built deviations.\n\n" +
      builtinWorldsHelp());
  app_->add_option("input", input_, "plan or scenario file, or builtin:NAME")
      ->option_text("PLAN")
      ->required();
  app_->add_option("-o,--output", output_, "JSON file to write (default: standard output)");
  app_->add_option("--svg", svg_, "also write a picture of the plan with the graph over it");
  app_->add_option("--level", level_, "level to draw in the SVG (default: the first)");
}

int AGraphCommand::run() {
  const bim::Scenario scenario = loadInput(input_, "agraph");
  const bim::Plan& plan = scenario.plan;
  const std::string level = level_.empty() ? plan.levels.front().id : level_;
  if (plan.findLevel(level) == nullptr) {
    throw common::InputError(input_, "", "no level \"" + level + "\" in the plan (--level)");
  }
  // Replaced only if isg wrote them; never the plan itself.
  if (!svg_.empty()) {
    common::checkOutputPath(svg_, {common::OutputKind::kSvg, {inputFile(input_)}, true, false});
  }
  if (!output_.empty()) {
    common::checkOutputPath(
        output_, {common::OutputKind::kAgraphJson, {inputFile(input_), svg_}, true, false});
  }
  const bim::AGraph graph = bim::buildAGraph(plan);
  const std::string json = bim::agraphJsonText(bim::agraphToJson(graph));
  // Everything is computed before anything is written.
  const std::string svg = svg_.empty() ? "" : bim::agraphToSvg(plan, graph, level);
  if (!svg_.empty()) writeFileAtomically(svg_, common::outputMark(common::OutputKind::kSvg, svg));
  if (output_.empty()) {
    std::cout << json;
  } else {
    writeFileAtomically(output_, json);
  }
  int kinds[3] = {0, 0, 0};
  for (const auto& r : graph.rooms) ++kinds[int(r.kind)];
  using common::counted;
  std::fprintf(stderr, "isg agraph: %s, %s, %s (%d four-wall, %d two-wall, %d other), %s, %s\n",
               counted(graph.surfaces.size(), "wall surface").c_str(),
               counted(graph.walls.size(), "wall").c_str(),
               counted(graph.rooms.size(), "room").c_str(), kinds[0], kinds[1], kinds[2],
               counted(graph.doorways.size(), "doorway").c_str(),
               counted(graph.floors.size(), "floor").c_str());
  return kExitOk;
}

}  // namespace isg::cli
