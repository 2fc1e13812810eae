#include "cli/cmd_import.hpp"

#include <cmath>
#include <cstdio>
#include <filesystem>

#include "ifc/ifc_import.hpp"
#include "run/interrupt.hpp"
#include "sensors/output_path.hpp"

namespace isg::cli {
namespace {

// Numbers to the micrometre: a plan a person can read and diff, far below any tolerance.
void roundNumbers(nlohmann::ordered_json& value) {
  if (value.is_number_float()) {
    const double rounded = std::round(value.get<double>() * 1e6) / 1e6;
    value = rounded == 0.0 ? 0.0 : rounded;
  } else if (value.is_structured()) {
    for (auto& child : value) roundNumbers(child);
  }
}

}  // namespace

ImportCommand::ImportCommand(CLI::App& parent) {
  app_ = parent.add_subcommand("import", "Import an IFC building model (IFC2X3, IFC4) as a plan");
  app_->footer(
      "Storeys become levels (by default every storey with walls standing on it and rooms), "
      "walls straight prismatic walls fitted to their bodies, doors and windows their openings "
      "in the walls, spaces rooms (their outline is the bottom of their body). Ids are the IFC "
      "GlobalIds, names the IFC names. Every element left out or simplified gets one line saying "
      "which and why; a summary per storey ends the output. The plan is checked with the plan "
      "format's rules before it is written; nothing is written when the model cannot be read. "
      "IFC++ reads the model in a child process: a model that makes it crash is reported like any "
      "bad model (exit code 1). The rules and their thresholds: docs/formats.md, \"Importing "
      "IFC\".\n\n"
      "Example (ifc/tests/models holds five public models):\n"
      "  isg import Office_A_20110811.ifc -o office.json\n  isg check office.json -v\n"
      "  isg run office.json -o runs/office");
  app_->add_option("model", input_, "IFC file (STEP, .ifc) to read")
      ->option_text("MODEL.ifc")
      ->required();
  app_->add_option("-o,--output", output_, "plan file to write")
      ->option_text("PLAN.json")
      ->required();
  app_->add_option("--storey", storeys_,
                   "import this storey (its IFC name; repeat for several) instead of choosing")
      ->option_text("NAME");
  app_->add_flag("--force", force_, "replace PLAN.json if isg import wrote it before");
  app_->add_flag("-q,--quiet", quiet_, "print only the summary, not each element left out");
}

int ImportCommand::run() {
  sensors::checkOutputPath(output_, {sensors::OutputKind::kImportedPlan, {input_}, force_, true});
  ifc::ImportOptions options;
  options.storeys = storeys_;
  ifc::ImportResult result;
  try {
    result = ifc::importIfc(input_, options);
  } catch (const ifc::ImportInterrupted& e) {
    std::fprintf(stderr, "isg import: %s; nothing was written\n", e.what());
    return 128 + e.signalNumber();
  }
  roundNumbers(result.plan_json);
  run::throwIfInterrupted();  // a Ctrl-C that reached isg after the model was read
  writeFileAtomically(output_, result.plan_json.dump(2) + "\n");

  if (!quiet_) {
    for (const auto& line : result.log) std::fprintf(stderr, "  %s\n", line.c_str());
    for (const auto& warning : result.warnings)
      std::fprintf(stderr, "  warning: %s\n", warning.str().c_str());
  }
  std::fprintf(
      stderr, "isg import: %s: %s%s%s, lengths in %s\n", input_.c_str(), result.schema.c_str(),
      result.application.empty() ? "" : " from ", result.application.c_str(),
      result.metres_per_unit == 1.0 ? "metres"
                                    : (std::to_string(result.metres_per_unit) + " m").c_str());
  int walls = 0, doors = 0, windows = 0, rooms = 0, levels = 0;
  for (const auto& s : result.storeys) {
    if (s.level_id.empty()) {
      std::fprintf(stderr, "  storey \"%s\" (%.3f m): not imported: %s\n", s.name.c_str(),
                   s.elevation, s.why_not.c_str());
      continue;
    }
    ++levels;
    walls += s.walls, doors += s.doors, windows += s.windows, rooms += s.rooms;
    std::fprintf(stderr,
                 "  storey \"%s\" (%.3f m) -> level %s: %d walls (%d of another storey standing "
                 "on it), %d doors, %d windows, %d rooms of %d spaces\n",
                 s.name.c_str(), s.elevation, s.level_id.c_str(), s.walls,
                 s.walls_from_other_storeys, s.doors, s.windows, s.rooms, s.spaces);
  }
  std::fprintf(stderr,
               "isg import: wrote %s: %d level%s, %d walls, %d doors, %d windows, %d rooms; %zu "
               "element%s left out or simplified%s\n",
               output_.c_str(), levels, levels == 1 ? "" : "s", walls, doors, windows, rooms,
               result.log.size(), result.log.size() == 1 ? "" : "s",
               quiet_ && !result.log.empty() ? " (run without -q to list them)" : "");
  if (!result.reader_errors.empty()) {
    std::fprintf(stderr, "isg import: IFC++ reported %zu error%s while reading (first: %s)\n",
                 result.reader_errors.size(), result.reader_errors.size() == 1 ? "" : "s",
                 result.reader_errors.front().c_str());
  }
  return kExitOk;
}

}  // namespace isg::cli
