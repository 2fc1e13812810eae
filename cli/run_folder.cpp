#include "cli/run_folder.hpp"

#include <cstdio>
#include <filesystem>

#include "bim/agraph_json.hpp"
#include "bim/input_error.hpp"
#include "bim/plan_geometry.hpp"
#include "eval/ape.hpp"
#include "eval/coverage.hpp"
#include "eval/report_svg.hpp"
#include "sim/atomic_folder.hpp"

namespace isg::cli {

namespace fs = std::filesystem;

namespace {

nlohmann::json statisticsJson(const eval::Statistics& s) {
  return {{"count", s.count}, {"rmse", s.rmse}, {"mean", s.mean}, {"median", s.median},
          {"std", s.std},     {"min", s.min},   {"max", s.max},   {"sse", s.sse}};
}

// Odometry with its frame M placed at the true start pose: dead reckoning.
eval::Trajectory odometryInPlan(const RunRecord& run) {
  eval::Trajectory out;
  if (run.ground_truth.empty() || run.odometry.empty()) return out;
  const Eigen::Isometry3d B_T_M =
      run.ground_truth.front().pose * run.odometry.front().pose.inverse();
  for (const auto& p : run.odometry) out.push_back({p.t, B_T_M * p.pose});
  return out;
}

}  // namespace

RunEvaluation evaluateRun(const RunRecord& run) {
  RunEvaluation evaluation;
  nlohmann::json& m = evaluation.metrics;
  m["world"] = run.world;
  m["method"] = run.method;
  m["seed"] = run.seed;
  m["scans"] = run.scans;
  m["sim_seconds"] = run.sim_seconds;
  m["wall_seconds"] = run.wall_seconds;
  m["real_time_factor"] = run.wall_seconds > 0 ? run.sim_seconds / run.wall_seconds : 0.0;
  const eval::Coverage coverage = eval::localizationCoverage(run.ground_truth, run.estimate);
  m["localized"] = coverage.localized;
  if (coverage.localized) {
    m["time_to_localize"] = coverage.time_to_first;
    m["share_localized"] = coverage.share;
  }
  eval::ErrorOptions planar;
  planar.align = eval::Alignment::kNone;
  planar.project_xy = true;
  if (!run.estimate.empty()) {
    const auto ape = eval::absolutePoseError(run.ground_truth, run.estimate, planar);
    m["ape_B"] = statisticsJson(ape.translation_stats);
    m["ape_B_rotation_deg"] = statisticsJson(ape.rotation_stats);
    for (std::size_t i = 0; i < ape.translation.size(); ++i) {
      evaluation.error_over_time.emplace_back(run.estimate[ape.association.estimate[i]].t,
                                              ape.translation[i]);
    }
  }
  if (run.estimate_map.size() >= 3) {
    eval::ErrorOptions se3 = planar;
    se3.align = eval::Alignment::kSE3;
    m["ape_M_se3"] = statisticsJson(
        eval::absolutePoseError(run.ground_truth, run.estimate_map, se3).translation_stats);
  }
  evaluation.dead_reckoning = odometryInPlan(run);
  if (!evaluation.dead_reckoning.empty()) {
    m["ape_odometry_from_true_start"] =
        statisticsJson(eval::absolutePoseError(run.ground_truth, evaluation.dead_reckoning, planar)
                           .translation_stats);
  }
  if (run.graph.contains("matching")) {
    const auto& matching = run.graph["matching"];
    m["matching_status"] = matching.value("status", "");
    m["matching_events"] = matching.value("events", nlohmann::json::array());
  }
  return evaluation;
}

namespace {

std::string reportFor(const RunRecord& run, const RunEvaluation& evaluation) {
  const nlohmann::json& metrics = evaluation.metrics;
  eval::ReportInput input;
  input.title = "isg run: " + run.world + " — " + run.method;
  char line[256];
  if (metrics.value("localized", false)) {
    std::snprintf(line, sizeof line,
                  "localized at t = %.1f s (%.0f %% of the run); APE in B (2D, no alignment) "
                  "rmse %.3f m, max %.3f m",
                  metrics["time_to_localize"].get<double>(),
                  100.0 * metrics["share_localized"].get<double>(),
                  metrics["ape_B"]["rmse"].get<double>(), metrics["ape_B"]["max"].get<double>());
  } else {
    std::snprintf(line, sizeof line, "never localized in the plan");
  }
  input.summary.push_back(line);
  if (metrics.contains("ape_odometry_from_true_start")) {
    std::snprintf(line, sizeof line,
                  "odometry from the true start: APE rmse %.3f m; %.1f s of robot time in %.1f s "
                  "(%.1fx real time), seed %llu",
                  metrics["ape_odometry_from_true_start"]["rmse"].get<double>(), run.sim_seconds,
                  run.wall_seconds, metrics["real_time_factor"].get<double>(),
                  static_cast<unsigned long long>(run.seed));
    input.summary.push_back(line);
  }
  if (run.plan) {
    const bim::Level* level = run.plan->findLevel(run.level);
    if (level == nullptr && !run.plan->levels.empty()) level = &run.plan->levels[0];
    if (level != nullptr) {
      const auto geometry = bim::computeLevelGeometry(*level);
      for (const auto& wall : geometry.walls) {
        input.walls.push_back(wall.footprint());
      }
    }
  }
  if (run.agraph) {
    for (const auto& room : run.agraph->rooms) {
      if (room.level == run.level) input.labels.emplace_back(room.id, room.centre);
    }
  }
  input.ground_truth = run.ground_truth;
  input.estimate = run.estimate;
  input.odometry = evaluation.dead_reckoning;
  input.error_over_time = evaluation.error_over_time;
  input.localized_at = run.localized_at;
  return eval::reportSvg(input);
}

}  // namespace

void writeRunFolder(const std::string& dir, const RunRecord& run, const RunEvaluation& evaluation,
                    bool force) {
  sim::writeFolderAtomically(dir, force, [&](const fs::path& temporary) {
    sim::writeFile(temporary / "groundtruth.tum", eval::toTumText(run.ground_truth));
    sim::writeFile(temporary / "odometry.tum", eval::toTumText(run.odometry));
    sim::writeFile(temporary / "estimate.tum", eval::toTumText(run.estimate));
    sim::writeFile(temporary / "estimate_map.tum", eval::toTumText(run.estimate_map));
    sim::writeFile(temporary / "metrics.json", evaluation.metrics.dump(2) + "\n");
    if (run.agraph) {
      sim::writeFile(temporary / "agraph.json",
                     bim::agraphJsonText(bim::agraphToJson(*run.agraph)));
    }
    sim::writeFile(temporary / "sgraph.json", run.graph.dump(1) + "\n");
    sim::writeFile(temporary / "report.svg", reportFor(run, evaluation));
  });
}

std::string runSummary(const std::string& command, const std::string& dir,
                       const nlohmann::json& m) {
  char text[1024];
  std::string out;
  std::snprintf(text, sizeof text, "%s: wrote %s (%s on %s, seed %llu)\n", command.c_str(),
                dir.c_str(), m["method"].get<std::string>().c_str(),
                m["world"].get<std::string>().c_str(),
                static_cast<unsigned long long>(m["seed"].get<std::uint64_t>()));
  out += text;
  if (m.value("localized", false)) {
    std::snprintf(text, sizeof text,
                  "  localized at t = %.1f s (%.0f %% of the run localized)\n"
                  "  APE in B (2D, no alignment, from then on): rmse %.3f m, median %.3f m, "
                  "max %.3f m over %d poses\n",
                  m["time_to_localize"].get<double>(), 100.0 * m["share_localized"].get<double>(),
                  m["ape_B"]["rmse"].get<double>(), m["ape_B"]["median"].get<double>(),
                  m["ape_B"]["max"].get<double>(), m["ape_B"]["count"].get<int>());
    out += text;
  } else {
    out += "  not localized in the plan";
    if (m.contains("matching_status")) {
      out += " (matching: " + m["matching_status"].get<std::string>() + ")";
    }
    out += "\n";
  }
  if (m.contains("ape_M_se3")) {
    std::snprintf(text, sizeof text, "  APE in M after SE(3) alignment: rmse %.3f m\n",
                  m["ape_M_se3"]["rmse"].get<double>());
    out += text;
  }
  if (m.contains("ape_odometry_from_true_start")) {
    std::snprintf(text, sizeof text, "  odometry from the true start: APE rmse %.3f m\n",
                  m["ape_odometry_from_true_start"]["rmse"].get<double>());
    out += text;
  }
  if (m["sim_seconds"].get<double>() > 0) {
    std::snprintf(text, sizeof text, "  %.1f s of robot time in %.1f s: %.1fx real time\n",
                  m["sim_seconds"].get<double>(), m["wall_seconds"].get<double>(),
                  m["real_time_factor"].get<double>());
    out += text;
  }
  return out;
}

}  // namespace isg::cli
