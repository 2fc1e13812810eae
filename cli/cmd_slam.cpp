#include "cli/cmd_slam.hpp"

#include <cstdio>
#include <filesystem>
#include <optional>

#include "bim/agraph.hpp"
#include "bim/plan_json.hpp"
#include "bim/plan_parser.hpp"
#include "cli/progress_bar.hpp"
#include "cli/run_session.hpp"
#include "common/atomic_folder.hpp"
#include "common/input_error.hpp"
#include "common/json_reader.hpp"
#include "formats/dataset_format.hpp"
#include "formats/dataset_reader.hpp"
#include "run/map_diagnosis.hpp"

namespace isg::cli {

namespace {

// The plan to localize in (--plan), or, for the report only, the one the dataset records. A
// --plan that is not the recorded one is an error unless --other-plan says it is meant: the
// result of localizing in another building is meaningless, and should never pass unnoticed.
std::optional<bim::Plan> replayPlan(const std::string& plan_argument, bool other_plan,
                                    const formats::DatasetReader& dataset, const std::string& dir) {
  const std::string metadata_file = (std::filesystem::path(dir) / "metadata.json").string();
  const common::JsonSource source{metadata_file, nullptr};
  std::optional<bim::Plan> recorded;
  if (dataset.metadata().contains("plan")) {
    recorded = bim::parsePlan(common::JsonNode(dataset.metadata()["plan"], "/plan", source));
  }
  if (plan_argument.empty()) return recorded;
  bim::Plan given = loadInput(plan_argument, "slam").plan;
  if (recorded && !other_plan) {
    // Compared as the dataset records plans, every default filled in, but without names: the
    // geometry is what makes two plans one (a dataset recorded before plans kept names has none).
    auto levels = [](const bim::Plan& plan) {
      return bim::planToJson(plan, {.names = false})["levels"];
    };
    if (levels(*recorded) != levels(given)) {
      throw common::InputError(
          metadata_file, "/plan",
          "the dataset was recorded in plan \"" + recorded->name + "\", not in " + plan_argument +
              " (give --other-plan to localize in a different plan on purpose)");
    }
  }
  return given;
}

}  // namespace

SlamCommand::SlamCommand(CLI::App& parent) {
  app_ = parent.add_subcommand("slam", "Replay a recorded dataset through a localizer");
  app_->footer(
      "Feeds the dataset's odometry, IMU and scans, in time order, to the localizer through the "
      "same driver as isg run (the same seed gives the same result, byte for byte); a dataset "
      "without odometry (an imported handheld recording) gets odometry made from its LiDAR and "
      "IMU (docs/slam.md, \"Without odometry\"). With --plan, the "
      "iS-Graph localizes in that plan; without it, the S-Graph maps in M only. Writes the run "
      "folder of isg run (estimate.tum in B once localized, estimate_map.tum in M, "
      "keyframes.tum, metrics.json, sgraph.json, report.svg, ...; docs/evaluation.md) and "
      "reports APE (with ground truth), the map against the plan's walls (with a plan), the "
      "map's rooms and per-keyframe timings.\n\n" +
      methodHelp(methods_));
  app_->add_option("dataset", dataset_, "dataset folder made by isg simulate (or in its format)")
      ->option_text("DATASET_DIR")
      ->required();
  app_->add_option("--plan", plan_,
                   "the building's plan (file or builtin:NAME): localize in it (iS-Graph)")
      ->option_text("PLAN");
  app_->add_option("--method", method_, "localization method (see below)")
      ->check(CLI::IsMember(methods_.acceptedNames()))
      ->default_str("is-graphs with --plan, s-graph without");
  app_->add_option("-o,--output", output_, "RUN_DIR to create")->option_text("RUN_DIR")->required();
  app_->add_flag("--other-plan", other_plan_,
                 "localize in a --plan other than the one the dataset was recorded in");
  app_->add_option("--method-option", method_options_,
                   "a setting of the method, KEY=VALUE (repeatable; the methods below say which)")
      ->option_text("KEY=VALUE");
  app_->add_option("--threads", threads_,
                   "threads for the localizer's own work; the results never depend on it")
      ->check(CLI::Range(1, 64))
      ->capture_default_str();
  addRunMcapOptions(*app_, mcap_);
  addStartPoseOption(*app_, start_pose_);
  app_->add_flag("--force", force_, "replace RUN_DIR (and RUN.mcap) if it exists");
  app_->add_flag("-q,--quiet", quiet_, "no progress bar");
  app_->add_flag("--timing", timing_,
                 "print where the time went, by stage (also in metrics.json; docs/performance.md)");
}

int SlamCommand::run() {
  namespace fs = std::filesystem;
  formats::DatasetReader dataset(dataset_);
  // Before the replay, not after it: a folder that cannot be written fails at once.
  common::checkCanCreateFolder(output_, common::OutputKind::kRunFolder, force_, {dataset_, plan_});
  const std::string method = !method_.empty() ? method_ : plan_.empty() ? "s-graph" : "is-graphs";
  if (methods_.find(method)->needs_plan && plan_.empty()) {
    std::fprintf(stderr, "isg slam: --method %s needs --plan PLAN\n", method.c_str());
    return kExitUsage;
  }
  const std::map<std::string, std::string> options = methodOptions(method_options_);
  const std::map<std::string, double> effective = checkMethodOptions(methods_, method, options);
  const std::optional<bim::Plan> plan = replayPlan(plan_, other_plan_, dataset, dataset_);
  const bim::AGraph agraph = plan ? bim::buildAGraph(*plan) : bim::AGraph{};
  sensors::SensorStreams streams = dataset.streams();
  const std::string fallback_level = plan && !plan->levels.empty() ? plan->levels[0].id : "";
  const std::string level = dataset.robotLevel().empty() ? fallback_level : dataset.robotLevel();

  run::LocalizerContext context;
  context.plan = plan ? &*plan : nullptr;
  context.agraph = plan ? &agraph : nullptr;
  context.level = level;
  context.R_T_L = streams.R_T_L;
  context.R_T_I = streams.R_T_I;
  context.start_B_T_M = sensors::trueStartB_T_M(streams);
  context.seed = dataset.seed();
  context.options = options;
  context.threads = threads_;
  const std::string start_words = applyStartPose(start_pose_, streams, methods_, method, context);
  if (!start_words.empty() && !quiet_) {
    std::fprintf(stderr, "isg slam: starting localized at %s\n", start_words.c_str());
  }
  const auto localizer =
      withOdometry("isg slam", makeMethod(methods_, method, context), streams, quiet_);

  // What was built differently, for the report: recorded with the dataset's own plan.
  std::optional<bim::AsBuilt> as_built;
  if (plan && (plan_.empty() || !other_plan_) && dataset.metadata().contains("as_built")) {
    const common::JsonSource source{(fs::path(dataset_) / "metadata.json").string(), nullptr};
    try {
      as_built = bim::parseAsBuiltJson(
          common::JsonNode(dataset.metadata()["as_built"], "/as_built", source), *plan, level);
    } catch (const common::InputError& e) {
      // Only the report's drawing needs it: say so, and replay without it.
      std::fprintf(stderr, "isg slam: warning: the as-built changes are not drawn: %s\n", e.what());
    }
  }
  run::RunSetup setup{
      dataset_,     localizer->name(), dataset.seed(), "",
      context.plan, context.agraph,    level,          as_built ? &*as_built : nullptr,
      effective};
  const auto mcap = openRunMcap(mcap_, force_, {dataset_, plan_}, output_, setup, streams);
  ProgressBar bar("isg slam", quiet_);
  const double period = streams.scan_period;
  const run::RunRecord record =
      run::runLocalizer(std::move(setup), *localizer, std::move(streams), dataset,
                        progressOn(bar, period), observerOf(mcap));
  bar.finish();
  const run::RunEvaluation evaluation = finishRun("isg slam", output_, force_, record, timing_);
  finishRunMcap("isg slam", mcap_, mcap.get(), record, evaluation);
  if (record.map) {
    const run::MapDiagnosis diagnosis =
        run::diagnoseMap(*record.map, record.streams.ground_truth, context.plan, level);
    std::printf("%s", run::formatMapDiagnosis(diagnosis).c_str());
  }
  return kExitOk;
}

}  // namespace isg::cli
