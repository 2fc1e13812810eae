#include "cli/run_session.hpp"

#include <malloc.h>
#include <sys/resource.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <optional>

#include "bim/agraph.hpp"
#include "bim/limits.hpp"
#include "bim/recorded_start_pose.hpp"
#include "cli/bcf_report.hpp"
#include "cli/cmd_export.hpp"
#include "common/angles.hpp"
#include "common/decimal_number.hpp"
#include "common/input_error.hpp"
#include "common/output_path.hpp"
#include "common/plural.hpp"
#include "common/pose_interpolation.hpp"
#include "run/odometry_source.hpp"
#include "run/run_folder.hpp"
#include "run/run_report.hpp"

namespace isg::cli {

std::string methodHelp(const run::LocalizerRegistry& registry) {
  return "Methods:\n" + registry.help();
}

std::map<std::string, std::string> methodOptions(const std::vector<std::string>& arguments) {
  std::map<std::string, std::string> options;
  for (const auto& argument : arguments) {
    const std::size_t equals = argument.find('=');
    if (equals == std::string::npos || equals == 0) {
      throw common::InputError("--method-option " + argument, "", "expected KEY=VALUE");
    }
    const std::string key = argument.substr(0, equals);
    if (!options.emplace(key, argument.substr(equals + 1)).second) {
      throw common::InputError("--method-option " + argument, "", key + " is given twice");
    }
  }
  return options;
}

std::map<std::string, double> checkMethodOptions(
    const run::LocalizerRegistry& registry, const std::string& method,
    const std::map<std::string, std::string>& options) {
  try {
    return registry.checkOptions(method, options);
  } catch (const std::invalid_argument& e) {
    throw common::InputError("--method " + method, "", e.what());
  }
}

std::unique_ptr<slam::Localizer> makeMethod(const run::LocalizerRegistry& registry,
                                            const std::string& method,
                                            const run::LocalizerContext& context) {
  try {
    return registry.make(method, context);
  } catch (const std::invalid_argument& e) {
    throw common::InputError("--method " + method, "", e.what());
  }
}

namespace {

// "X,Y,YAW": three decimal numbers (common::parseDecimal); empty when the text is not that.
std::optional<Eigen::Vector3d> startPoseNumbers(const std::string& text) {
  Eigen::Vector3d out;
  std::size_t at = 0;
  for (int k = 0; k < 3; ++k) {
    const std::size_t comma = k < 2 ? text.find(',', at) : text.size();
    if (comma == std::string::npos) return std::nullopt;
    const std::optional<double> number =
        common::parseDecimal(std::string_view(text).substr(at, comma - at));
    if (!number) return std::nullopt;
    out[k] = *number;
    at = comma + 1;
  }
  return out;
}

// How far outside the plan's walls a start pose may lie: a walk may begin in a yard or a street
// the plan does not draw, never kilometres away (a typo, or a pose in another frame).
constexpr double kStartPoseMarginM = 100.0;

// Refuses a start pose no walk through the plan could begin at, before any localizer sees it: a
// number like 4e38 would otherwise reach the scan matchers' grids and trees.
void checkStartPose(const Eigen::Vector3d& xyyaw, const std::string& value,
                    const run::LocalizerContext& context) {
  constexpr double kTwoPi = 2.0 * 3.14159265358979323846;
  if (std::abs(xyyaw.z()) > kTwoPi) {
    throw common::InputError(
        "--start-pose", "",
        "yaw " + value.substr(value.rfind(',') + 1) + " is not within ±2π: the yaw is in radians");
  }
  Eigen::AlignedBox2d allowed(Eigen::Vector2d::Constant(-bim::limits::kMaxCoordinate),
                              Eigen::Vector2d::Constant(bim::limits::kMaxCoordinate));
  std::string where = "within ±" + std::to_string(int(bim::limits::kMaxCoordinate)) + " m";
  const Eigen::AlignedBox2d walls =
      context.agraph ? context.agraph->surfaceBounds() : Eigen::AlignedBox2d();
  if (!walls.isEmpty()) {
    const Eigen::Vector2d margin = Eigen::Vector2d::Constant(kStartPoseMarginM);
    allowed = allowed.intersection(Eigen::AlignedBox2d(walls.min() - margin, walls.max() + margin));
    char text[160];
    std::snprintf(
        text, sizeof text, "within %g m of the plan's walls (x %.3f … %.3f, y %.3f … %.3f)",
        kStartPoseMarginM, walls.min().x(), walls.max().x(), walls.min().y(), walls.max().y());
    where = text;
  }
  if (!allowed.contains(xyyaw.head<2>())) {
    throw common::InputError("--start-pose", "",
                             "the position " + value.substr(0, value.rfind(',')) + " is not " +
                                 where + ": the start pose is in the plan's frame");
  }
}

// "FILE.csv:SEQUENCE" or "FILE.csv": a start pose table's row (the sequence empty: the walk's).
struct StartPoseTable {
  std::string file;
  std::string sequence;
};

std::optional<StartPoseTable> startPoseTable(const std::string& text) {
  constexpr std::string_view kCsv = ".csv";
  if (text.size() > kCsv.size() && text.ends_with(kCsv)) return StartPoseTable{text, ""};
  const std::size_t at = text.rfind(".csv:");
  if (at == std::string::npos || at == 0 || at + 5 == text.size()) return std::nullopt;
  return StartPoseTable{text.substr(0, at + 4), text.substr(at + 5)};
}

std::string numbersText(const Eigen::Vector3d& xyyaw) {
  char text[96];
  std::snprintf(text, sizeof text, "%.3f,%.3f,%.4f", xyyaw.x(), xyyaw.y(), xyyaw.z());
  return text;
}

// The table's row for this run: the base's pose in B at the run's clock, or an InputError.
run::LocalizerContext::StampedStart startFromTable(const StartPoseTable& table,
                                                   const sensors::SensorStreams& streams,
                                                   const std::optional<RecordingFrame>& recording,
                                                   const run::LocalizerContext& context,
                                                   std::string& words) {
  if (!recording) {
    throw common::InputError("--start-pose", "",
                             "a start pose table (" + table.file +
                                 ") is read for a replayed walk (a scenario whose route is a "
                                 "\"trajectory\"): its stamps are in the walk's own clock");
  }
  const std::string sequence = table.sequence.empty() ? recording->sequence : table.sequence;
  const bim::RecordedStartPose row = bim::readRecordedStartPose(table.file, sequence);
  const double t = row.stamp - recording->clock_start;
  const double end = streams.scan_stamps.empty() ? 0.0 : streams.scan_stamps.back();
  if (t < 0.0 || t > end) {
    char text[200];
    std::snprintf(text, sizeof text,
                  "line %d: the start pose's stamp %.6f is not within the run (the walk's clock "
                  "%.6f … %.6f s): a row of another run, or another clock?",
                  row.line, row.stamp, recording->clock_start, recording->clock_start + end);
    throw common::InputError(table.file, "", text);
  }
  Eigen::Isometry3d B_T_R = row.pose * recording->R_T_S.inverse();
  if (recording->body_path) {
    const std::optional<Eigen::Isometry3d> body = common::interpolatePose(streams.ground_truth, t);
    if (body) {
      B_T_R.linear() = Eigen::AngleAxisd(common::yawOf(body->linear()), Eigen::Vector3d::UnitZ())
                           .toRotationMatrix();
    }
  }
  const Eigen::Vector3d xyyaw(B_T_R.translation().x(), B_T_R.translation().y(),
                              common::yawOf(B_T_R.linear()));
  checkStartPose(xyyaw, numbersText(xyyaw), context);
  char text[160];
  std::snprintf(text, sizeof text, " (%s line %d) at %.3f s, the base at %s", table.file.c_str(),
                row.line, t, numbersText(xyyaw).c_str());
  words = "the start pose of " + row.sequence + text;
  return {t, B_T_R};
}

}  // namespace

void addStartPoseOption(CLI::App& app, std::string& value) {
  app.add_option("--start-pose", value,
                 "start localized: the base's first pose in the plan frame, X,Y,YAW (m, m, rad), "
                 "'truth' for the ground truth's, or a replayed walk's row of a start pose table "
                 "as the floor-plan benchmark gives it, FILE.csv:SEQUENCE (the sequence: the "
                 "walk file's name by default; docs/benchmark.md); the localizer still checks it "
                 "(default: global localization)")
      ->option_text("X,Y,YAW|truth|FILE.csv[:SEQUENCE]")
      ->check([](const std::string& text) -> std::string {
        if (text == "truth" || startPoseNumbers(text) || startPoseTable(text)) return "";
        return "expected X,Y,YAW (three numbers), 'truth' or FILE.csv[:SEQUENCE], not '" + text +
               "'";
      });
}

std::string applyStartPose(const std::string& value, const sensors::SensorStreams& streams,
                           const run::LocalizerRegistry& registry, const std::string& method,
                           run::LocalizerContext& context,
                           const std::optional<RecordingFrame>& recording) {
  if (value.empty()) return "";
  const run::MethodInfo* info = registry.find(method);
  if (info == nullptr || (!info->takes_start_pose && !info->given_start)) {
    throw common::InputError("--start-pose", "",
                             "method " + method +
                                 " takes no start pose (is-graphs does; the trackers and "
                                 "odometry are given one anyway)");
  }
  Eigen::Isometry3d B_T_R0 = Eigen::Isometry3d::Identity();
  std::string words;
  if (const std::optional<StartPoseTable> table = startPoseTable(value)) {
    const run::LocalizerContext::StampedStart start =
        startFromTable(*table, streams, recording, context, words);
    if (info->takes_start_pose) context.given_start_at = start;
    if (info->given_start) {
      const std::optional<Eigen::Isometry3d> M_T_R =
          common::interpolatePose(streams.odometry, start.stamp);
      if (!M_T_R) {
        throw common::InputError("--start-pose", "",
                                 "method " + method +
                                     " starts from its first pose, and this run has no odometry "
                                     "to carry a later start pose back there (is-graphs takes it "
                                     "at its stamp)");
      }
      context.start_B_T_M = start.B_T_R * M_T_R->inverse();
    }
    return words;
  }
  if (value == "truth") {
    if (streams.ground_truth.empty()) {
      throw common::InputError("--start-pose", "",
                               "'truth' needs a ground truth, and there is none here: give "
                               "X,Y,YAW");
    }
    B_T_R0 = streams.ground_truth.front().pose;
    words = "the true start pose";
  } else {
    const Eigen::Vector3d xyyaw = *startPoseNumbers(value);
    checkStartPose(xyyaw, value, context);
    B_T_R0.linear() = Eigen::AngleAxisd(xyyaw.z(), Eigen::Vector3d::UnitZ()).toRotationMatrix();
    // The height is the level's (walls do not observe it): the truth's when there is one.
    const double z =
        streams.ground_truth.empty() ? 0.0 : streams.ground_truth.front().pose.translation().z();
    B_T_R0.translation() = Eigen::Vector3d(xyyaw.x(), xyyaw.y(), z);
    words = "the start pose " + value;
  }
  const Eigen::Isometry3d B_T_M = sensors::startB_T_M(streams, B_T_R0);
  if (info->takes_start_pose) context.given_start_B_T_M = B_T_M;
  if (info->given_start) context.start_B_T_M = B_T_M;
  return words;
}

std::unique_ptr<slam::Localizer> withOdometry(const char* command,
                                              std::unique_ptr<slam::Localizer> method,
                                              const sensors::SensorStreams& streams, bool quiet) {
  if (streams.odometry.empty() && !quiet) {
    std::fprintf(stderr,
                 "%s: there is no odometry: the LiDAR%s make%s it (docs/slam.md, \"Without "
                 "odometry\")\n",
                 command, streams.imu.empty() ? "" : " and the IMU",
                 streams.imu.empty() ? "s" : "");
  }
  return run::withOdometrySource(std::move(method), streams);
}

run::RunProgress progressOn(ProgressBar& bar, double scan_period) {
  return [&bar, scan_period](int done, int total, const slam::Localizer& localizer) {
    if (done % 10 != 0 && done != total) return;
    std::string state = localizer.mapInPlan() ? "localized" : "not localized yet";
    if (const auto status = localizer.searchStatus(); status && !localizer.mapInPlan()) {
      state += " (matching: " + *status + ")";
    }
    char detail[200];
    std::snprintf(detail, sizeof detail, "%.0f s of robot time, %s", done * scan_period,
                  state.c_str());
    bar.update(total > 0 ? double(done) / total : 1.0, detail);
  };
}

BcfSources bcfSourcesOf(const run::RunRecord& record, const run::RunEvaluation& evaluation) {
  const run::RunSetup& setup = record.setup;
  return {&*evaluation.deviations, setup.plan, setup.as_built,
          run::bcf::topicNames(setup.world_hash, *setup.plan, setup.method, setup.seed)};
}

run::RunEvaluation finishRun(const std::string& command, const std::string& dir, bool force,
                             const run::RunRecord& record, bool print_timing) {
  using Clock = std::chrono::steady_clock;
  auto start = Clock::now();
  // The loop's threads leave the memory they freed (scans, the IMU's chunks) in their malloc
  // arenas; handing it back before the evaluation keeps the process's peak down (two hours of
  // robot time: 253 → 234 MB; docs/performance.md).
  malloc_trim(0);
  run::RunEvaluation evaluation = run::evaluateRun(record);
  run::RunTiming& timing = *evaluation.metrics.timing;
  timing.stages.push_back(
      {"evaluation", std::chrono::duration<double>(Clock::now() - start).count()});
  struct rusage usage {};
  if (getrusage(RUSAGE_SELF, &usage) == 0) timing.peak_memory_mb = usage.ru_maxrss / 1024.0;
  start = Clock::now();
  std::optional<std::size_t> bcf_topics;
  const auto write_bcf = [&](const std::filesystem::path& folder) {
    if (!evaluation.deviations || record.setup.plan == nullptr) return;
    bcf_topics = writeDeviationBcf(folder / "deviations.bcf", bcfSourcesOf(record, evaluation));
  };
  run::writeRunFolder(dir, record, evaluation, force, write_bcf);
  const double writing = std::chrono::duration<double>(Clock::now() - start).count();
  std::printf("%s", run::runSummary(command, dir, evaluation.metrics).c_str());
  if (bcf_topics) {
    std::printf("  deviations.bcf: %s for BIM tools (BCF 3.0, docs/deviations.md)\n",
                common::counted(*bcf_topics, "topic").c_str());
  }
  if (print_timing) std::printf("%s", run::timingTable(evaluation.metrics, writing).c_str());
  return evaluation;
}

void addRunMcapOptions(CLI::App& app, RunMcapArguments& arguments) {
  CLI::Option* mcap =
      app.add_option("--mcap", arguments.path,
                     "also write the run as an MCAP file to watch in Foxglove: the plan, the "
                     "A-Graph, the S-Graph over time, matching, paths, scans, transforms, "
                     "deviations (docs/foxglove.md)")
          ->option_text("RUN.mcap");
  addMcapCompressionOption(app, arguments.compression, mcap);
}

std::unique_ptr<run::LiveRunMcap> openRunMcap(const RunMcapArguments& arguments, bool force,
                                              std::vector<std::string> inputs,
                                              const std::string& run_dir,
                                              const run::RunSetup& setup,
                                              const sensors::SensorStreams& streams) {
  if (arguments.path.empty()) return nullptr;
  namespace fs = std::filesystem;
  // RUN_DIR is written whole into a temporary folder and renamed into place: a file in it would
  // be lost.
  const fs::path within =
      fs::weakly_canonical(arguments.path).lexically_relative(fs::weakly_canonical(run_dir));
  if (!within.empty() && *within.begin() != "..") {
    throw common::InputError(arguments.path, "",
                             "--mcap names RUN_DIR or a file in it: write the MCAP file beside it");
  }
  common::checkOutputPath(arguments.path, {common::OutputKind::kMcap, std::move(inputs), force});
  run::RunMcapOptions options;
  options.compression = mcapCompression(arguments.compression);
  options.overwrite = force;
  return std::make_unique<run::LiveRunMcap>(arguments.path, options, setup, streams);
}

run::RunObserver observerOf(const std::unique_ptr<run::LiveRunMcap>& mcap) {
  return mcap ? mcap->observer() : run::RunObserver{};
}

void finishRunMcap(const std::string& command, const RunMcapArguments& arguments,
                   run::LiveRunMcap* mcap, const run::RunRecord& record,
                   const run::RunEvaluation& evaluation) {
  if (!mcap) return;
  mcap->finish(record, evaluation);
  printRunMcapSummary(command, arguments.path, mcap->writer().counts());
}

}  // namespace isg::cli
