#pragma once

#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "cli/bcf_report.hpp"
#include "cli/common.hpp"
#include "cli/progress_bar.hpp"
#include "cli/recording_frame.hpp"
#include "run/driver.hpp"
#include "run/evaluate_run.hpp"
#include "run/foxglove/live_run_mcap.hpp"
#include "run/localizer_registry.hpp"
#include "run/run_record.hpp"

namespace isg::cli {

// What `isg run` and `isg slam` share around the run driver: the methods on offer, the progress
// line, and the end of a run (evaluate once, write the folder, print the summary).

// The footer text listing the methods of `registry`, one line each.
std::string methodHelp(const run::LocalizerRegistry& registry);

// The --method-option KEY=VALUE arguments as a map. A malformed or repeated one is bad input.
std::map<std::string, std::string> methodOptions(const std::vector<std::string>& arguments);

// Checks the method's options before anything is built, so a misspelt key fails at once and not
// after the world is made; bad input naming the method. Returns the options the method will use
// (run::LocalizerRegistry::checkOptions).
std::map<std::string, double> checkMethodOptions(const run::LocalizerRegistry& registry,
                                                 const std::string& method,
                                                 const std::map<std::string, std::string>& options);

// Builds the method; what the method refuses (an unknown option, a bad value, a plan it cannot
// use) is bad input naming the method.
std::unique_ptr<slam::Localizer> makeMethod(const run::LocalizerRegistry& registry,
                                            const std::string& method,
                                            const run::LocalizerContext& context);

// --start-pose of isg run and isg slam: "X,Y,YAW" (the base's first pose in the plan frame, on
// the robot's level) or "truth" (the ground truth's first pose). Empty: none (global
// localization, the default). Sets the context's start: a method that takes a start pose starts
// localized there (and checks it as any match); a method that is given its start anyway
// (trackers, dead reckoning) starts from this one instead of the truth; any other method refuses
// it (bad input). Returns the start's words for the summary ("" when none).
//
// Or "FILE.csv:SEQUENCE" (FILE.csv alone: the replayed walk's own sequence): the row of a start
// pose table as the floor-plan benchmark gives it (bim::readRecordedStartPose), the tracked
// sensor's pose at a stamp of the recording's clock. It needs `recording` (a replayed walk): the
// pose is made the base's through R_T_S and its stamp the run's; a method that takes a start pose
// takes it at that stamp (LocalizerContext::given_start_at), one given its start takes B_T_M from
// the streams' odometry there (none: refused).
void addStartPoseOption(CLI::App& app, std::string& value);
std::string applyStartPose(const std::string& value, const sensors::SensorStreams& streams,
                           const run::LocalizerRegistry& registry, const std::string& method,
                           run::LocalizerContext& context,
                           const std::optional<RecordingFrame>& recording = std::nullopt);

// The method behind the odometry it is given: the streams' own, or, when they have none (a
// handheld carrier, a recording without it), the one the LiDAR and the IMU make
// (run::withOdometrySource); says so on stderr unless `quiet`.
std::unique_ptr<slam::Localizer> withOdometry(const char* command,
                                              std::unique_ptr<slam::Localizer> method,
                                              const sensors::SensorStreams& streams, bool quiet);

// A progress callback drawing `bar`: robot time so far and the localizer's state.
run::RunProgress progressOn(ProgressBar& bar, double scan_period);

// What a run's deviations.bcf is made from (the report of `evaluation`, which has one, and the
// run's plan, which it has): its topics named by the run's world, or the plan's content for a
// replay.
BcfSources bcfSourcesOf(const run::RunRecord& record, const run::RunEvaluation& evaluation);

// Evaluates the run, writes its folder (run::writeRunFolder) and prints the summary (and, with
// `print_timing`, the stage timing); returns the evaluation.
run::RunEvaluation finishRun(const std::string& command, const std::string& dir, bool force,
                             const run::RunRecord& record, bool print_timing = false);

// --mcap RUN.mcap and --compression of `isg run` and `isg slam`: the run as an MCAP file to watch
// in Foxglove (docs/foxglove.md).
struct RunMcapArguments {
  std::string path;  // empty: none
  std::string compression = "zstd";
};
void addRunMcapOptions(CLI::App& app, RunMcapArguments& arguments);
// Checks the path (the output rule against `inputs`; not RUN_DIR `run_dir`) and opens the file
// before the run; null when --mcap was not given.
std::unique_ptr<run::LiveRunMcap> openRunMcap(const RunMcapArguments& arguments, bool force,
                                              std::vector<std::string> inputs,
                                              const std::string& run_dir,
                                              const run::RunSetup& setup,
                                              const sensors::SensorStreams& streams);
// The observer runLocalizer is given: the file's, or none.
run::RunObserver observerOf(const std::unique_ptr<run::LiveRunMcap>& mcap);
// Adds the end of the run, closes the file and prints what it holds.
void finishRunMcap(const std::string& command, const RunMcapArguments& arguments,
                   run::LiveRunMcap* mcap, const run::RunRecord& record,
                   const run::RunEvaluation& evaluation);

}  // namespace isg::cli
