#include "cli/cmd_slam.hpp"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <filesystem>

#include "bim/agraph.hpp"
#include "bim/json_reader.hpp"
#include "bim/plan_parser.hpp"
#include "cli/methods.hpp"
#include "cli/progress_bar.hpp"
#include "cli/run_folder.hpp"
#include "eval/ape.hpp"
#include "sim/dataset_reader.hpp"
#include "sim/room_evaluation.hpp"
#include "sim/testbed_loop.hpp"
#include "slam/isgraph_localizer.hpp"
#include "slam/sgraph_localizer.hpp"
#include "slam/timing_report.hpp"

namespace isg::cli {

SlamCommand::SlamCommand(CLI::App& parent) {
  app_ = parent.add_subcommand("slam", "Replay a recorded dataset through a localizer");
  app_->footer(
      "Feeds the dataset's odometry and scans, in time order, to the localizer exactly as isg "
      "run does in the loop (the same seed gives the same result). With --plan, the iS-Graph "
      "localizes in that plan; without it, the S-Graph maps in M only. Writes the run folder of "
      "isg run (estimate.tum in B once localized, estimate_map.tum in M, metrics.json, "
      "sgraph.json, report.svg, ...) plus keyframes.tum, and reports APE, rooms and timings.");
  app_->add_option("dataset", dataset_, "dataset folder made by isg simulate (or in its format)")
      ->required();
  app_->add_option("--plan", plan_,
                   "the building's plan (file or builtin:NAME): localize in it (iS-Graph)");
  app_->add_option("--method", method_,
                   "localizer: is-graphs (default with --plan), s-graph (default without), "
                   "dead-reckoning")
      ->check(CLI::IsMember(methodNames()));
  app_->add_option("-o,--output", output_, "run folder to create")->required();
  app_->add_flag("--force", force_, "replace RUN_DIR if it exists");
  app_->add_flag("-q,--quiet", quiet_, "no progress bar");
}

int SlamCommand::run() {
  namespace fs = std::filesystem;
  const sim::DatasetReader dataset(dataset_);
  if (fs::exists(output_) && !force_) {
    throw bim::InputError(output_, "", "already exists (use --force to replace it)");
  }
  const std::string method = !method_.empty() ? method_ : plan_.empty() ? "s-graph" : "is-graphs";
  // The plan to localize in (--plan), or for the report only, the one the dataset records.
  std::optional<bim::Plan> plan;
  if (!plan_.empty()) {
    plan = loadInput(plan_, "slam").plan;
  } else if (dataset.metadata().contains("plan")) {
    const bim::JsonSource source{dataset_ + "/metadata.json", nullptr};
    plan = bim::parsePlan(bim::JsonNode(dataset.metadata()["plan"], "/plan", source));
  }
  if (method == "is-graphs" && plan_.empty()) {
    std::fprintf(stderr, "isg slam: --method is-graphs needs --plan PLAN\n");
    return kExitUsage;
  }
  const bim::AGraph agraph = plan ? bim::buildAGraph(*plan) : bim::AGraph{};
  const auto& odometry = dataset.odometry();
  Eigen::Isometry3d B_T_M_true = Eigen::Isometry3d::Identity();
  if (!dataset.groundTruth().empty() && !odometry.empty()) {
    B_T_M_true = dataset.groundTruth().front().pose * odometry.front().pose.inverse();
  }
  auto localizer = makeLocalizer(method, dataset.R_T_L(), agraph, B_T_M_true);
  const double turn =
      dataset.metadata().value("lidar", nlohmann::json::object()).value("rate_hz", 10.0);
  sim::LocalizerDriver driver(*localizer, odometry, 1.0 / turn);
  ProgressBar bar("isg slam", quiet_);
  const auto start = std::chrono::steady_clock::now();
  for (int k = 0; k < dataset.scanCount(); ++k) {
    driver.feed(dataset.scan(k));
    if (k % 10 == 0 || k + 1 == dataset.scanCount()) {
      bar.update(double(k + 1) / dataset.scanCount(),
                 localizer->mapInPlan() ? "localized" : "not localized yet");
    }
  }
  bar.finish();
  const double wall =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();

  RunRecord record;
  record.world = dataset_;
  record.method = localizer->name();
  record.seed = dataset.metadata().value("seed", std::uint64_t{0});
  record.plan = plan ? &*plan : nullptr;
  record.agraph = plan ? &agraph : nullptr;
  record.level = dataset.metadata()
                     .value("robot", nlohmann::json::object())
                     .value("level", plan && !plan->levels.empty() ? plan->levels[0].id : "");
  record.ground_truth = dataset.groundTruth();
  record.odometry = odometry;
  record.estimate = driver.estimate();
  record.estimate_map = driver.estimateMap();
  record.localized_at = driver.localizedAt();
  record.scans = dataset.scanCount();
  record.sim_seconds = dataset.scanCount() > 0 ? dataset.scanStamp(dataset.scanCount() - 1) -
                                                     dataset.scanStamp(0) + 1.0 / turn
                                               : 0.0;
  record.wall_seconds = wall;
  record.graph = localizer->graph();
  const RunEvaluation evaluation = evaluateRun(record);
  writeRunFolder(output_, record, evaluation, force_);

  // The S-Graph's own measures: keyframes, rooms against the plan, timings.
  const slam::SGraph* graph = nullptr;
  if (const auto* s = dynamic_cast<const slam::SGraphLocalizer*>(localizer.get())) {
    graph = &s->sgraph();
  } else if (const auto* i = dynamic_cast<const slam::ISGraphLocalizer*>(localizer.get())) {
    graph = &i->sgraph();
  }
  std::printf("%s", runSummary("isg slam", output_, evaluation.metrics).c_str());
  if (graph == nullptr) return kExitOk;
  eval::Trajectory keyframes;
  for (const auto& kf : graph->keyframes()) keyframes.push_back({kf.stamp, kf.pose()});
  writeFileAtomically((fs::path(output_) / "keyframes.tum").string(), eval::toTumText(keyframes));
  std::printf("  S-Graph: %zu keyframes, %zu wall planes, %zu rooms\n", graph->keyframes().size(),
              graph->planes().size(), graph->confirmedRooms().size());
  std::printf("%s", slam::formatTiming(slam::timingAt(graph->timings(), {50, 200, 500})).c_str());
  if (dataset.groundTruth().empty() || keyframes.size() < 3 || !plan) return kExitOk;
  eval::ErrorOptions se3;
  se3.align = eval::Alignment::kSE3;
  eval::Trajectory odometry_at_keyframes;
  for (const auto& kf : graph->keyframes())
    odometry_at_keyframes.push_back({kf.stamp, kf.odometry});
  const auto keyframe_ape = eval::absolutePoseError(dataset.groundTruth(), keyframes, se3);
  const double rmse_odometry =
      eval::absolutePoseError(dataset.groundTruth(), odometry_at_keyframes, se3)
          .translation_stats.rmse;
  std::printf(
      "  keyframes after SE(3) alignment: APE rmse %.3f m (odometry at the same instants %.3f "
      "m, %.1fx)\n",
      keyframe_ape.translation_stats.rmse, rmse_odometry,
      rmse_odometry / keyframe_ape.translation_stats.rmse);
  const auto report = sim::evaluateRooms(*plan, record.level, *graph, dataset.groundTruth(),
                                         *keyframe_ape.alignment);
  std::string missed;
  for (const auto& id : report.walked) {
    if (std::find(report.detected.begin(), report.detected.end(), id) == report.detected.end()) {
      missed += (missed.empty() ? "" : ", ") + id;
    }
  }
  std::printf("  rooms: %zu detected of %zu walked through (%.0f %%), widths within %.3f m%s%s\n",
              report.detected.size(), report.walked.size(), 100.0 * report.rate(),
              report.worst_width_error, missed.empty() ? "" : "; missed: ", missed.c_str());
  return kExitOk;
}

}  // namespace isg::cli
