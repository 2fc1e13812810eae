#include "cli/cmd_run.hpp"

#include <cstdio>
#include <filesystem>
#include <iostream>

#include "bim/agraph.hpp"
#include "cli/methods.hpp"
#include "cli/progress_bar.hpp"
#include "cli/run_folder.hpp"
#include "sim/simulation.hpp"
#include "sim/testbed_loop.hpp"
#include "worlds/reference_plans.hpp"

namespace isg::cli {

namespace {

// "builtin:d1.asbuilt" → "d1.asbuilt", "plans/office.json" → "office".
std::string worldName(const std::string& input) {
  const std::string prefix = "builtin:";
  if (input.rfind(prefix, 0) == 0) return input.substr(prefix.size());
  return std::filesystem::path(input).stem().string();
}

}  // namespace

RunCommand::RunCommand(CLI::App& parent) {
  app_ = parent.add_subcommand(
      "run", "Simulation in the loop: walk the robot, localize it in the plan, measure the error");
  app_->footer(
      "The robot walks the scenario's route in the building as built; its VLP-16 scans and "
      "odometry feed the localizer in-process, in time order; the iS-Graph matches its S-Graph "
      "to the plan's A-Graph and, once the match is unique, localizes in the plan frame B. "
      "Writes RUN_DIR: groundtruth.tum, odometry.tum, estimate.tum (B, rows only once "
      "localized), estimate_map.tum (M), metrics.json, agraph.json, sgraph.json (with the "
      "matching log and B_T_M), report.svg. With no INPUT, runs the built-in default world (" +
      std::string(worlds::kDefaultWorld) + ").\n\n" + builtinWorldsHelp());
  app_->add_option("input", input_, "plan or scenario file, or builtin:NAME")
      ->default_str(std::string(worlds::kDefaultWorld));
  app_->add_option("-o,--output", output_, "run folder to create (default: runs/<world>-<method>)");
  app_->add_option("--method", method_, "localizer: is-graphs, s-graph or dead-reckoning")
      ->check(CLI::IsMember(methodNames()))
      ->capture_default_str();
  app_->add_option("--seed", seed_, "seed for every random draw (default: the scenario's)");
  app_->add_option("--duration", duration_, "seconds of robot time (default: the whole route)")
      ->check(CLI::PositiveNumber);
  app_->add_option("--threads", threads_, "threads: one localizes, the others cast scans ahead")
      ->check(CLI::Range(1, 64))
      ->capture_default_str();
  app_->add_flag("--force", force_, "replace RUN_DIR if it exists");
  app_->add_flag("-q,--quiet", quiet_, "no progress bar");
}

int RunCommand::run() {
  namespace fs = std::filesystem;
  const std::string input = input_.empty() ? std::string(worlds::kDefaultWorld) : input_;
  if (output_.empty()) output_ = "runs/" + worldName(input) + "-" + method_;
  if (fs::exists(output_) && !force_) {
    throw bim::InputError(output_, "", "already exists (use --force to replace it)");
  }
  bim::Scenario scenario = loadInput(input, "run");
  if (seed_) scenario.seed = *seed_;
  sim::Simulation simulation(scenario);
  for (const auto& room : simulation.route().skipped_rooms) {
    std::cerr << "isg run: warning: room " << room << " cannot be reached; the tour skips it\n";
  }
  const bim::AGraph agraph = bim::buildAGraph(scenario.plan);
  // Dead reckoning is given the true start: M is the start pose.
  const Eigen::Isometry3d B_T_M_true =
      simulation.trajectory().pose(0.0) * simulation.odometry(0.0).front().pose.inverse();
  auto localizer = makeLocalizer(method_, simulation.R_T_L(), agraph, B_T_M_true);

  sim::LoopOptions options;
  options.duration = duration_;
  options.threads = threads_;
  ProgressBar bar("isg run", quiet_);
  const double period = simulation.scanPeriod();
  options.progress = [&](int done, int total, const slam::Localizer& l) {
    if (done % 10 != 0 && done != total) return;
    char detail[160];
    std::snprintf(detail, sizeof detail, "%.0f s of robot time, %s", done * period,
                  l.mapInPlan() ? "localized" : "not localized yet");
    bar.update(total > 0 ? double(done) / total : 1.0, detail);
  };
  const sim::LoopResult loop = sim::runLoop(simulation, *localizer, options);
  bar.finish();

  RunRecord record;
  record.world = input;
  record.method = localizer->name();
  record.seed = scenario.seed;
  record.plan = &scenario.plan;
  record.agraph = &agraph;
  record.level = scenario.robot.level;
  record.ground_truth = loop.ground_truth;
  record.odometry = loop.odometry;
  record.estimate = loop.estimate;
  record.estimate_map = loop.estimate_map;
  record.localized_at = loop.localized_at;
  record.scans = loop.scans;
  record.sim_seconds = loop.sim_seconds;
  record.wall_seconds = loop.wall_seconds;
  record.graph = localizer->graph();
  const RunEvaluation evaluation = evaluateRun(record);
  if (const auto parent = fs::path(output_).parent_path(); !parent.empty()) {
    fs::create_directories(parent);
  }
  writeRunFolder(output_, record, evaluation, force_);
  std::printf("%s", runSummary("isg run", output_, evaluation.metrics).c_str());
  return kExitOk;
}

}  // namespace isg::cli
