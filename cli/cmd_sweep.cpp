#include "cli/cmd_sweep.hpp"

#include <cstdio>
#include <filesystem>

#include "common/atomic_folder.hpp"
#include "common/output_path.hpp"
#include "common/plural.hpp"
#include "run/builtin_methods.hpp"
#include "run/interrupt.hpp"
#include "sweep/collect.hpp"
#include "sweep/lock.hpp"
#include "sweep/pool.hpp"
#include "sweep/prepare_worlds.hpp"
#include "sweep/run_table.hpp"
#include "sweep/slurm_backend.hpp"
#include "sweep/suite.hpp"
#include "sweep/sweep_folder.hpp"
#include "worlds/reference_plans.hpp"

namespace isg::cli {

namespace {

namespace fs = std::filesystem;

}  // namespace

SweepCommand::SweepCommand(CLI::App& parent) {
  app_ = parent.add_subcommand(
      "sweep", "Run a suite: worlds × seeds × methods, on local processes or on Slurm");
  app_->footer(
      "SUITE.json (\"isg.suite\" v1, docs/sweeps.md) names worlds (built-ins, plan or scenario "
      "files, generator specs), seeds, methods and run options. Each cell is an isg run into "
      "SWEEP_DIR/<world>/<method>/seed-<n>/; SWEEP_DIR/sweep.json records the cells. Started "
      "again, a sweep skips the cells that finished (a killed sweep finishes the rest; nothing "
      "is half-written). A failed cell is recorded in SWEEP_DIR/<world>/<method>/seed-<n>"
      ".failed.json with its error (the whole output in SWEEP_DIR/logs/) and the others go on. "
      "At the end SWEEP_DIR/table.md and table.csv hold the table isg table would make (every seed "
      "of the suite counted: failed and unrun ones are said), and the exit code is 0 only when "
      "every cell finished (5 when any failed or did not run).\n\n"
      "One sweep at a time runs in a folder (a lock; a second is refused, naming the first's pid). "
      "Every world is known by its content hash (sweep.json, and each cell's metrics.json): "
      "started again after a world changed, the sweep is refused unless --rerun-changed; a cell "
      "folder that is not a finished run of its cell (damaged, of another world) is moved to "
      "SWEEP_DIR/.aside/ and run again.\n\n"
      "--backend slurm writes SWEEP_DIR/sweep.sbatch, an array job with one task per cell left "
      "(--cpus-per-task, --time and --mem from the suite's \"slurm\" object), and submits it with "
      "sbatch (--dry-run: only writes it; --wait: waits for the array, then collects); more cells "
      "than the cluster's MaxArraySize (scontrol show config) go as several arrays of it. "
      "isg sweep --collect SWEEP_DIR makes the table from whatever is there, for either "
      "backend.\n\n"
      "Example: isg sweep suite.json -o sweeps/nightly --jobs 2; isg sweep --collect "
      "sweeps/nightly");
  app_->add_option("input", input_, "the suite; with --collect or --cell, the sweep folder")
      ->option_text("SUITE.json|SWEEP_DIR")
      ->required();
  app_->add_option("-o,--output", output_, "SWEEP_DIR: where the runs go (made if missing)")
      ->option_text("SWEEP_DIR");
  app_->add_option("--jobs", jobs_, "cells run at once (local backend)")
      ->check(CLI::Range(1, 256))
      ->capture_default_str();
  app_->add_option("--backend", backend_, "local: child processes here; slurm: an sbatch array")
      ->check(CLI::IsMember({"local", "slurm"}))
      ->capture_default_str();
  app_->add_flag("--dry-run", dry_run_, "slurm: write sweep.sbatch, do not submit it");
  app_->add_flag("--wait", wait_,
                 "slurm: wait until the arrays have ended (sbatch --wait), then "
                 "collect");
  app_->add_flag("--collect", collect_,
                 "tabulate SWEEP_DIR (table.md, table.csv) and list failed and missing cells");
  app_->add_option("--cell", cell_, "run one cell of SWEEP_DIR (what a Slurm task runs)")
      ->option_text("K")
      ->check(CLI::Range(0L, long(sweep::kMaxSweepCells) - 1));
  app_->add_option("--measure", measure_, "the table's measure, as isg table's --measure")
      ->check(CLI::IsMember(sweep::kRunTableMeasures))
      ->capture_default_str();
  app_->add_flag("--rerun-changed", rerun_changed_,
                 "when a world's content changed since the sweep folder's cells ran (its file "
                 "edited, a generator spec changed): run its cells again instead of refusing");
  app_->add_flag("-q,--quiet", quiet_, "no progress lines");
}

int SweepCommand::collect(const std::string& sweep_dir) const {
  const sweep::SweepPlan plan = sweep::readSweepPlan(sweep_dir);
  const sweep::SweepCollection c = sweep::collectSweep(sweep_dir, plan.cells, measure_);
  const std::string md =
      eval::formatTable(c.table.table, eval::TableFormat::kMarkdown, c.table.caption);
  const std::string csv = eval::formatTable(c.table.table, eval::TableFormat::kCsv);
  common::writeFileAtomically((fs::path(sweep_dir) / sweep::kSweepTableMarkdownFile).string(), md);
  common::writeFileAtomically((fs::path(sweep_dir) / sweep::kSweepTableCsvFile).string(), csv);
  std::printf("%s\n", md.c_str());
  for (const auto& f : c.failed) std::printf("failed: %s\n", f.c_str());
  for (const auto& m : c.missing) std::printf("not run: %s\n", m.c_str());
  std::printf(
      "isg sweep: %s: %d of %s finished, %zu failed, %zu not run; wrote %s/table.md "
      "and table.csv\n",
      sweep_dir.c_str(), c.finished, common::counted(plan.cells.size(), "cell").c_str(),
      c.failed.size(), c.missing.size(), sweep_dir.c_str());
  return c.failed.empty() && c.missing.empty() ? kExitOk : kExitIncomplete;
}

int SweepCommand::runOnSlurm(const sweep::Suite& suite,
                             const std::vector<sweep::SweepCell>& cells) const {
  std::vector<std::size_t> pending;
  for (std::size_t i = 0; i < cells.size(); ++i) {
    if (!sweep::cellFinished(output_, cells[i])) pending.push_back(i);
  }
  if (pending.empty()) {
    std::printf("isg sweep: every cell of %s has finished; nothing to submit\n", output_.c_str());
    return collect(output_);
  }
  const std::string isg = fs::read_symlink("/proc/self/exe").string();
  const std::size_t max_array_size =
      suite.slurm.max_array_size.value_or(sweep::slurmMaxArraySize());
  const std::string script = sweep::writeSlurmScript(output_, suite, pending, isg, max_array_size);
  const std::vector<sweep::SlurmArray> arrays = sweep::slurmArrays(pending.size(), max_array_size);
  const std::string split = arrays.size() == 1
                                ? ""
                                : " in " + std::to_string(arrays.size()) + " arrays of at most " +
                                      std::to_string(max_array_size) + " tasks";
  if (dry_run_) {
    std::printf("isg sweep: wrote %s (%zu array tasks%s); submit it with:\n", script.c_str(),
                pending.size(), split.c_str());
    for (const auto& array : arrays)
      std::printf("  %s\n", sweep::sbatchCommand(script, array).c_str());
    return kExitOk;
  }
  const std::vector<std::string> jobs = sweep::submitSlurm(script, arrays, wait_);
  std::string ids;
  for (const auto& id : jobs) ids += (ids.empty() ? "" : ", ") + id;
  std::printf("isg sweep: submitted %s as Slurm job%s %s (%zu array tasks%s)\n", script.c_str(),
              jobs.size() == 1 ? "" : "s", ids.c_str(), pending.size(), split.c_str());
  if (!wait_) {
    std::printf("isg sweep: when it has ended: isg sweep --collect %s\n", output_.c_str());
    return kExitOk;
  }
  return collect(output_);
}

int SweepCommand::runLocally(const std::vector<sweep::SweepCell>& cells) const {
  std::vector<std::size_t> all(cells.size());
  for (std::size_t i = 0; i < cells.size(); ++i) all[i] = i;
  sweep::PoolOutcome o;
  try {
    o = sweep::runCells(output_, cells, all, jobs_, quiet_);
  } catch (const run::Interrupted& e) {
    // Not "nothing was written": the cells that finished stay, and are what a restart skips.
    std::fprintf(stderr,
                 "isg sweep: %s; the running cells were stopped and left nothing, the finished "
                 "ones are kept: run the same command again to finish the sweep\n",
                 e.what());
    return 128 + e.signalNumber();
  }
  if (!quiet_) {
    std::fprintf(stderr, "isg sweep: %s ran, %d had finished before, %d failed\n",
                 common::counted(o.finished, "cell").c_str(), o.skipped, o.failed);
  }
  return collect(output_);
}

int SweepCommand::run() {
  const auto usage = [](const char* message) {
    std::fprintf(stderr, "isg sweep: %s\nRun 'isg sweep --help' for usage.\n", message);
    return kExitUsage;
  };
  if (collect_ && cell_ >= 0) return usage("--collect and --cell: give one of them");
  if (collect_) return collect(input_);
  if (cell_ >= 0) {
    const sweep::SweepPlan plan = sweep::readSweepPlan(input_);
    if (std::size_t(cell_) >= plan.cells.size()) {
      throw common::InputError((fs::path(input_) / sweep::kSweepPlanFile).string(), "/cells",
                               "no cell " + std::to_string(cell_) + " (the sweep has " +
                                   std::to_string(plan.cells.size()) + ")");
    }
    const sweep::PoolOutcome o =
        sweep::runCells(input_, plan.cells, {std::size_t(cell_)}, 1, quiet_);
    return o.failed == 0 ? kExitOk : kExitIncomplete;
  }
  if (output_.empty()) return usage("isg sweep SUITE.json needs -o SWEEP_DIR");
  sweep::Suite suite = sweep::loadSuite(input_, run::builtinMethods());
  sweep::startSweepFolder(output_, input_, suite);
  // One sweep at a time in a folder, from here to the end (the lock goes with the process). Taken
  // before anything is written in the folder, its marker included: of two sweeps started at the
  // same instant into a new folder, the second is told that the first runs.
  const sweep::SweepLock lock(output_);
  if (!common::folderOutputKind(output_))
    common::writeOutputMarker(output_, common::OutputKind::kSweep);
  // Every world read (generated ones written) and hashed, before any cell runs.
  sweep::prepareSweepWorlds(suite, output_);
  const std::vector<sweep::SweepCell> cells = sweep::sweepCells(suite);
  const std::string plan_text = sweep::sweepPlanJson(suite, cells);
  sweep::checkAgainstEarlierStart(output_, input_, suite, cells, rerun_changed_);
  common::writeFileAtomically((fs::path(output_) / sweep::kSweepPlanFile).string(), plan_text);
  return backend_ == "slurm" ? runOnSlurm(suite, cells) : runLocally(cells);
}

}  // namespace isg::cli
