#include "cli/cmd_slam.hpp"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <filesystem>

#include "bim/json_reader.hpp"
#include "bim/plan_parser.hpp"
#include "cli/progress_bar.hpp"
#include "eval/ape.hpp"
#include "sim/dataset_reader.hpp"
#include "sim/room_evaluation.hpp"
#include "slam/sgraph.hpp"
#include "slam/timing_report.hpp"

namespace isg::cli {

SlamCommand::SlamCommand(CLI::App& parent) {
  app_ = parent.add_subcommand("slam",
                               "Replay a dataset through the S-Graph (SLAM in the map frame M)");
  app_->footer(
      "Feeds the dataset's odometry and scans, in time order, to the S-Graph: keyframes every "
      "1 m or 0.5 rad, deskewing, wall planes from PCL RANSAC, association, and a sliding-window "
      "Ceres optimisation after each keyframe. Writes RUN_DIR/estimate_map.tum (the pose in M at "
      "each scan, as known online), keyframes.tum (the final keyframe poses) and sgraph.json. "
      "Rooms and the plan (--plan, the iS-Graph) come with issues 5 and 6.");
  app_->add_option("dataset", dataset_, "dataset folder made by isg simulate (or in its format)")
      ->required();
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
  slam::SGraph graph(dataset.R_T_L());
  const auto& odometry = dataset.odometry();
  const double turn =
      dataset.metadata().value("lidar", nlohmann::json::object()).value("rate_hz", 10.0);
  std::size_t next_odometry = 0;
  eval::Trajectory online;
  ProgressBar bar("isg slam", quiet_);
  const auto start = std::chrono::steady_clock::now();
  for (int k = 0; k < dataset.scanCount(); ++k) {
    const double stamp = dataset.scanStamp(k);
    // A scan is complete at the end of its turn: the odometry up to then is known.
    while (next_odometry < odometry.size() && odometry[next_odometry].t <= stamp + 1.0 / turn) {
      graph.addOdometry({odometry[next_odometry].t, odometry[next_odometry].pose});
      ++next_odometry;
    }
    graph.addScan(dataset.scan(k));
    if (const auto pose = graph.poseAt(stamp)) online.push_back({stamp, *pose});
    bar.update(double(k + 1) / dataset.scanCount(),
               std::to_string(graph.keyframes().size()) + " keyframes, " +
                   std::to_string(graph.planes().size()) + " planes");
  }
  bar.finish();
  const double wall =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  eval::Trajectory keyframes;
  for (const auto& kf : graph.keyframes()) keyframes.push_back({kf.stamp, kf.pose()});
  fs::create_directories(output_);
  writeFileAtomically((fs::path(output_) / "estimate_map.tum").string(), eval::toTumText(online));
  writeFileAtomically((fs::path(output_) / "keyframes.tum").string(), eval::toTumText(keyframes));
  writeFileAtomically((fs::path(output_) / "sgraph.json").string(), graph.toJson().dump(1) + "\n");
  std::printf("isg slam: %d scans, %zu keyframes, %zu wall planes, %zu rooms in %.1f s\n",
              dataset.scanCount(), graph.keyframes().size(), graph.planes().size(),
              graph.confirmedRooms().size(), wall);
  std::printf("%s", slam::formatTiming(slam::timingAt(graph.timings(), {50, 200, 500})).c_str());
  if (!dataset.groundTruth().empty() && keyframes.size() >= 3) {
    // Against the ground truth, after SE(3) alignment (M is arbitrary): the online estimate at
    // every scan, the final keyframes, and odometry alone at the same keyframe instants.
    eval::ErrorOptions se3;
    se3.align = eval::Alignment::kSE3;
    eval::Trajectory odometry_at_keyframes;
    for (const auto& kf : graph.keyframes())
      odometry_at_keyframes.push_back({kf.stamp, kf.odometry});
    const double rmse_online =
        eval::absolutePoseError(dataset.groundTruth(), online, se3).translation_stats.rmse;
    const double rmse_keyframes =
        eval::absolutePoseError(dataset.groundTruth(), keyframes, se3).translation_stats.rmse;
    const double rmse_odometry =
        eval::absolutePoseError(dataset.groundTruth(), odometry_at_keyframes, se3)
            .translation_stats.rmse;
    std::printf(
        "  APE rmse after SE(3) alignment: keyframes %.3f m (odometry at the same "
        "instants %.3f m, %.1fx), online at every scan %.3f m\n",
        rmse_keyframes, rmse_odometry, rmse_odometry / rmse_keyframes, rmse_online);
    // Rooms against the dataset's plan, when it records one.
    if (dataset.metadata().contains("plan")) {
      const bim::JsonSource source{dataset_ + "/metadata.json", nullptr};
      const bim::Plan plan =
          bim::parsePlan(bim::JsonNode(dataset.metadata()["plan"], "/plan", source));
      const auto alignment =
          *eval::absolutePoseError(dataset.groundTruth(), keyframes, se3).alignment;
      const std::string level = dataset.metadata()
                                    .value("robot", nlohmann::json::object())
                                    .value("level", plan.levels[0].id);
      const auto report = sim::evaluateRooms(plan, level, graph, dataset.groundTruth(), alignment);
      std::string missed;
      for (const auto& id : report.walked) {
        if (std::find(report.detected.begin(), report.detected.end(), id) ==
            report.detected.end()) {
          missed += (missed.empty() ? "" : ", ") + id;
        }
      }
      std::printf(
          "  rooms: %zu detected of %zu walked through (%.0f %%), widths within %.3f m%s%s\n",
          report.detected.size(), report.walked.size(), 100.0 * report.rate(),
          report.worst_width_error, missed.empty() ? "" : "; missed: ", missed.c_str());
    }
  }
  return kExitOk;
}

}  // namespace isg::cli
