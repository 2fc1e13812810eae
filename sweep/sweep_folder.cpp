#include "sweep/sweep_folder.hpp"

#include <cstdio>
#include <filesystem>
#include <system_error>

#include "common/input_error.hpp"
#include "common/output_path.hpp"
#include "sweep/pool.hpp"
#include "sweep/prepare_worlds.hpp"
#include "worlds/reference_plans.hpp"

namespace isg::sweep {
namespace {

namespace fs = std::filesystem;

// Moves the finished (or damaged) cells of `worlds` aside, with their failure records: they ran
// on a world that has changed since.
void moveWorldCellsAside(const std::string& sweep_dir, const std::vector<SweepCell>& cells,
                         const std::vector<ChangedWorld>& worlds) {
  for (const auto& cell : cells) {
    bool changed = false;
    for (const auto& w : worlds) changed = changed || w.name == cell.world;
    if (!changed) continue;
    std::error_code ignored;
    fs::remove(failureRecordPath(sweep_dir, cell), ignored);
    if (!fs::exists(fs::symlink_status(fs::path(sweep_dir) / cell.dir))) continue;
    const std::string aside = moveCellAside(sweep_dir, cell);
    std::fprintf(stderr, "isg sweep: %s ran on the world before it changed; moved to %s\n",
                 cell.dir.c_str(), aside.c_str());
  }
}

}  // namespace

void startSweepFolder(const std::string& output, const std::string& suite_file,
                      const Suite& suite) {
  // The output rule: not the working directory or what holds it, not the suite or its world
  // files, and an existing folder only if it is a sweep's (or empty).
  std::vector<std::string> inputs = {suite_file};
  for (const auto& world : suite.worlds) {
    if (!world.generate && !worlds::isBuiltin(world.input)) inputs.push_back(world.input);
  }
  common::checkOutputPath(output, {common::OutputKind::kSweep, inputs});
  std::error_code made;
  fs::create_directories(output, made);
  if (made) throw common::InputError(output, "", "cannot make the sweep folder: " + made.message());
}

void checkAgainstEarlierStart(const std::string& output, const std::string& suite_file,
                              const Suite& suite, const std::vector<SweepCell>& cells,
                              bool rerun_changed) {
  const fs::path plan_path = fs::path(output) / kSweepPlanFile;
  if (!fs::exists(plan_path)) return;
  // A sweep folder holds one suite's cells: starting it again with other cells would mix them.
  const SweepPlan before = readSweepPlan(output);
  bool same = before.cells.size() == cells.size();
  for (std::size_t i = 0; same && i < cells.size(); ++i) {
    same = before.cells[i].dir == cells[i].dir && before.cells[i].arguments == cells[i].arguments;
  }
  if (!same) {
    throw common::InputError(plan_path.string(), "",
                             "this sweep folder holds another suite's cells (" +
                                 std::to_string(before.cells.size()) + " cells of " +
                                 before.suite_file + "); give another -o or remove it");
  }
  // The same cells of a changed world would mix two buildings in one row.
  const std::vector<ChangedWorld> changed = changedWorlds(suite, before);
  if (!changed.empty() && !rerun_changed) {
    std::string list;
    for (const auto& w : changed) {
      list += (list.empty() ? "" : "; ") + w.name + " (" + w.before.substr(0, 19) + "… then, " +
              w.now.substr(0, 19) + "… now)";
    }
    throw common::InputError(suite_file, "",
                             "world" + std::string(changed.size() > 1 ? "s" : "") +
                                 " changed since this sweep ran in " + output + ": " + list +
                                 "; --rerun-changed runs their cells again on the world as it is "
                                 "now (the old runs are moved to " +
                                 output + "/" + kSweepAsideFolder + "), or give another -o");
  }
  moveWorldCellsAside(output, before.cells, changed);
}

}  // namespace isg::sweep
