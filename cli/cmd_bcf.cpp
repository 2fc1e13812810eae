#include "cli/cmd_bcf.hpp"

#include <cstdio>
#include <filesystem>

#include "cli/bcf_report.hpp"
#include "common/atomic_folder.hpp"
#include "common/input_error.hpp"
#include "common/plural.hpp"
#include "run/deviation_report_reader.hpp"
#include "run/run_metrics.hpp"
#include "worlds/world_hash.hpp"

namespace isg::cli {

namespace fs = std::filesystem;

BcfCommand::BcfCommand(CLI::App& parent) {
  app_ = parent.add_subcommand(
      "bcf", "Write a run's deviation report as BCF 3.0, the issue format BIM tools open");
  app_->footer(
      "Writes RUN_DIR/deviations.bcf from RUN_DIR/deviations.json, as isg run and isg slam write "
      "it with every run placed in a plan (for a run folder made before they did, or to write it "
      "again): one topic per wall shifted, turned, missing, not built or built in part, per "
      "column moved or missing and per extra wall, each selecting its element by the IFC "
      "GlobalId the plan keeps (else by its plan id), with a viewpoint and a snapshot rendered "
      "on the CPU (docs/deviations.md, \"BCF\"). The building is the run's world as metrics.json "
      "names it, checked against the world's content hash the run recorded; --world names it "
      "when it has moved, and is needed for a replayed run (isg slam), whose world is the plan "
      "it was localized in. Topics are dated now, or SOURCE_DATE_EPOCH when set.");
  app_->add_option("run_dir", run_dir_, "a run folder (isg run, isg slam)")
      ->option_text("RUN_DIR")
      ->required();
  app_->add_option("--world", world_,
                   "the plan or scenario the run was made in (default: metrics.json's world)")
      ->option_text("PLAN|SCENARIO");
  app_->add_flag("--no-snapshots", no_snapshots_,
                 "leave the snapshots out (no rendering: faster, and no EGL needed)");
}

int BcfCommand::run() {
  const fs::path dir(run_dir_);
  const fs::path report_file = dir / "deviations.json";
  if (!fs::is_regular_file(report_file)) {
    throw common::InputError(report_file.string(), "",
                             "no deviation report: the run was not placed in a plan, or this is "
                             "not a run folder");
  }
  const run::RunMetrics metrics = run::readMetrics(run_dir_);
  const bool replay = !metrics.world_hash || metrics.world_hash->empty();
  if (world_.empty() && replay) {
    throw common::InputError((dir / run::kMetricsFile).string(), "/world",
                             "a replayed run (\"" + metrics.world +
                                 "\"): give --world PLAN, the plan it was localized in");
  }
  const std::string world = world_.empty() ? metrics.world : world_;
  const bim::Scenario scenario = loadInput(world, "bcf");
  if (!replay && worlds::worldHash(scenario) != *metrics.world_hash) {
    throw common::InputError(inputFile(world), "",
                             "not the world run " + run_dir_ +
                                 " was made in: its content hash differs from metrics.json's "
                                 "world_hash (the file changed since the run)");
  }
  const slam::DeviationReport report = run::loadDeviationReport(report_file.string());
  BcfSources sources{&report, &scenario.plan, replay ? nullptr : &scenario.as_built,
                     run::bcf::topicNames(replay ? "" : *metrics.world_hash, scenario.plan,
                                          metrics.method, metrics.seed),
                     !no_snapshots_};
  const fs::path file = dir / "deviations.bcf";
  common::AtomicFile atomic(file.string(), common::OutputKind::kBcf, true);
  const std::size_t topics = writeDeviationBcf(atomic.temporary(), sources);
  atomic.commit();
  std::printf("isg bcf: wrote %s, %s\n", file.string().c_str(),
              common::counted(topics, "topic").c_str());
  return kExitOk;
}

}  // namespace isg::cli
