#include "cli/cmd_run.hpp"

#include <filesystem>
#include <iostream>

#include "bim/agraph.hpp"
#include "cli/progress_bar.hpp"
#include "cli/route_check.hpp"
#include "cli/run_session.hpp"
#include "cli/submission.hpp"
#include "common/atomic_folder.hpp"
#include "sim/scan_pipeline.hpp"
#include "sim/simulation.hpp"
#include "worlds/reference_plans.hpp"
#include "worlds/world_hash.hpp"

namespace isg::cli {

RunCommand::RunCommand(CLI::App& parent) {
  app_ = parent.add_subcommand(
      "run", "Simulation in the loop: walk the robot, localize it in the plan, measure the error");
  app_->footer(
      "The robot walks the scenario's route in the building as built; its VLP-16 scans and "
      "odometry feed the localizer in-process, in time order; the iS-Graph matches its S-Graph "
      "to the plan's A-Graph and, once the match is unique, localizes in the plan frame B. "
      "Writes RUN_DIR: groundtruth.tum, odometry.tum, estimate.tum (B, rows only once "
      "localized), estimate_map.tum (M), keyframes.tum (map-building methods), metrics.json, "
      "agraph.json, sgraph.json (with the matching log and B_T_M), report.svg "
      "(docs/evaluation.md). With no PLAN|SCENARIO, runs the built-in default world (" +
      std::string(worlds::kDefaultWorld) + ").\n\n" + methodHelp(methods_) + "\n" +
      builtinWorldsHelp());
  app_->add_option("input", input_, "plan or scenario file, or builtin:NAME")
      ->option_text("PLAN|SCENARIO")
      ->default_str(std::string(worlds::kDefaultWorld));
  app_->add_option("-o,--output", output_, "RUN_DIR to create")
      ->option_text("RUN_DIR")
      ->default_str("runs/<world>-<method>-seed-<seed>");
  app_->add_option("--method", method_, "localization method (see below)")
      ->check(CLI::IsMember(methods_.acceptedNames()))
      ->capture_default_str();
  app_->add_option("--seed", seed_, "seed for every random draw")
      ->check(seedNumber())
      ->default_str("the scenario's");
  addLidarModelOption(*app_, lidar_model_);
  app_->add_option("--duration", duration_, "seconds of robot time")
      ->check(positiveNumber())
      ->default_str("the whole route");
  app_->add_option("--threads", threads_,
                   "threads: the localizer's and the simulator's; the results never depend on it")
      ->check(CLI::Range(1, 64))
      ->capture_default_str();
  app_->add_option("--method-option", method_options_,
                   "a setting of the method, KEY=VALUE (repeatable; the methods below say which)")
      ->option_text("KEY=VALUE");
  addRunMcapOptions(*app_, mcap_);
  addStartPoseOption(*app_, start_pose_);
  app_->add_option("--submission", submission_,
                   "also write the estimate as the floor-plan benchmark takes a submission: "
                   "DIR/SEQUENCE.txt, TUM, a pose at each stamp of the recording (a replayed "
                   "walk's, in its clock, SEQUENCE its file's name; else the ground truth's)")
      ->option_text("DIR");
  app_->add_flag("--force", force_,
                 "replace RUN_DIR (and RUN.mcap, and the submission's file) if it exists");
  app_->add_flag("-q,--quiet", quiet_, "no progress bar");
  app_->add_flag("--timing", timing_,
                 "print where the time went, by stage (also in metrics.json; docs/performance.md)");
}

int RunCommand::run() {
  const std::string input = input_.empty() ? std::string(worlds::kDefaultWorld) : input_;
  method_ = methods_.canonical(method_);
  const std::map<std::string, std::string> options = methodOptions(method_options_);
  const std::map<std::string, double> effective = checkMethodOptions(methods_, method_, options);
  bim::Scenario scenario = loadInput(input, "run");
  if (seed_) scenario.seed = *seed_;
  useLidarModelOption(scenario, lidar_model_);
  // The seed is in the default name, so that the seeds of one world and method do not collide.
  if (output_.empty()) {
    output_ = "runs/" + worlds::worldName(input) + "-" + method_ + "-seed-" +
              std::to_string(scenario.seed);
  }
  // Before the run, not after it: a folder that cannot be written fails at once. Nothing is made
  // yet (missing parent folders are made when the run folder is written).
  common::checkCanCreateFolder(output_, common::OutputKind::kRunFolder, force_, {inputFile(input)});
  std::optional<SubmissionTarget> submission;
  if (!submission_.empty()) {
    submission = planSubmission(submission_, scenario, input, force_, {inputFile(input)});
  }
  const sim::Simulation simulation(scenario);
  checkRoute("isg run", scenario, simulation, duration_);
  const bim::AGraph agraph = bim::buildAGraph(scenario.plan);
  sensors::SensorStreams streams =
      sim::sensorStreams(simulation, duration_, 100.0, sim::ImuDelivery::kAsTheRunGoes);

  run::LocalizerContext context;
  context.plan = &scenario.plan;
  context.agraph = &agraph;
  context.level = scenario.robot.level;
  context.R_T_L = streams.R_T_L;
  context.R_T_I = streams.R_T_I;
  context.start_B_T_M = sensors::trueStartB_T_M(streams);
  context.seed = scenario.seed;
  context.options = options;
  context.threads = threads_;
  const std::string start_words =
      applyStartPose(start_pose_, streams, methods_, method_, context, recordingFrameOf(scenario));
  if (!start_words.empty() && !quiet_) {
    std::fprintf(stderr, "isg run: starting localized at %s\n", start_words.c_str());
  }
  const auto localizer =
      withOdometry("isg run", makeMethod(methods_, method_, context), streams, quiet_);

  run::RunSetup setup{input,
                      localizer->name(),
                      scenario.seed,
                      worlds::worldHash(scenario),
                      &scenario.plan,
                      &agraph,
                      scenario.robot.level,
                      &scenario.as_built,
                      effective,
                      scenario.lidar.model};
  const auto mcap = openRunMcap(mcap_, force_, {inputFile(input)}, output_, setup, streams);
  ProgressBar bar("isg run", quiet_);
  const double period = streams.scan_period;
  const int scans = int(streams.scan_stamps.size());
  sim::LookaheadScans source(simulation, scans, threads_ - 1);
  const run::RunRecord record =
      run::runLocalizer(std::move(setup), *localizer, std::move(streams), source,
                        progressOn(bar, period), observerOf(mcap));
  bar.finish();
  const run::RunEvaluation evaluation = finishRun("isg run", output_, force_, record, timing_);
  finishRunMcap("isg run", mcap_, mcap.get(), record, evaluation);
  if (submission) {
    const auto [written, stamps] = writeSubmission(*submission, scenario, record);
    std::printf("  submission: %s, %zu poses for the %zu stamps of the recording\n",
                submission->file.string().c_str(), written, stamps);
  }
  return kExitOk;
}

}  // namespace isg::cli
