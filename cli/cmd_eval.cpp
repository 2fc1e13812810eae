#include "cli/cmd_eval.hpp"

#include <cstdio>
#include <iostream>
#include <nlohmann/json.hpp>

#include "common/atomic_folder.hpp"
#include "common/output_path.hpp"
#include "eval/ape.hpp"
#include "eval/coverage.hpp"
#include "eval/floor_plan_score.hpp"
#include "eval/floor_plan_score_svg.hpp"
#include "eval/report_svg.hpp"
#include "formats/trajectory_file.hpp"

namespace isg::cli {

namespace {

void printStatistics(const char* title, const std::string& alignment, const eval::Statistics& s) {
  std::printf("%s\n(%s)\n\n", title, alignment.c_str());
  const std::pair<const char*, double> rows[] = {
      {"max", s.max},   {"mean", s.mean}, {"median", s.median}, {"min", s.min},
      {"rmse", s.rmse}, {"sse", s.sse},   {"std", s.std}};
  for (const auto& [name, value] : rows) std::printf("%10s\t%.6f\n", name, value);
  std::printf("\n");
}

nlohmann::ordered_json toJson(const eval::Statistics& s) {
  return {{"count", s.count}, {"rmse", s.rmse}, {"mean", s.mean}, {"median", s.median},
          {"std", s.std},     {"min", s.min},   {"max", s.max},   {"sse", s.sse}};
}

}  // namespace

EvalCommand::EvalCommand(CLI::App& parent) {
  app_ =
      parent.add_subcommand("eval", "Absolute (and relative) pose error of a trajectory, as evo");
  app_->footer(
      "Both files are TUM trajectories (t tx ty tz qx qy qz qw). Poses are associated as evo "
      "does: for each stamp of the shorter trajectory, the nearest stamp of the other within "
      "--t-max-diff seconds, no interpolation. Alignment is none by default (global "
      "localization is judged in the plan frame); se3 / sim3 use Umeyama's method on the "
      "associated positions. --project xy then zeroes z and keeps only yaw (the paper's 2D "
      "APE). Statistics: rmse, mean, median, std (population), min, max, sse; translation in "
      "metres, rotation as the angle of R_ref⁻¹·R_est in degrees.");
  app_->add_option("reference", reference_, "ground truth, TUM")->option_text("GT.tum")->required();
  app_->add_option("estimate", estimate_, "estimated trajectory, TUM")
      ->option_text("EST.tum")
      ->required();
  app_->add_option("--align", align_, "none, se3 or sim3")
      ->check(CLI::IsMember({"none", "se3", "sim3"}))
      ->capture_default_str();
  app_->add_option("--project", project_, "xy: compare in the plane")->check(CLI::IsMember({"xy"}));
  app_->add_option("--t-max-diff", max_diff_, "association window in seconds")
      ->check(positiveNumber())
      ->capture_default_str();
  app_->add_option("--rpe", rpe_delta_, "also the relative pose error over this many poses")
      ->check(CLI::Range(1, 1000000));
  app_->add_flag("--json", json_, "print JSON instead of evo's text layout");
  app_->add_option("--plot", plot_,
                   "also draw both trajectories from above and the APE over time (as evo's "
                   "--plot); with --floor-plan-score, each pose's score and error over time")
      ->option_text("OUT.svg");
  auto* score =
      app_->add_flag("--floor-plan-score", floor_plan_score_,
                     "score EST.txt as the Hilti x Trimble 2026 floor-plan localization benchmark "
                     "scores a submission: the file as given, from 5 s after the run's start, "
                     "evo's association within 10 ms, 2D error, 100*e^(-0.4605*error) averaged, "
                     "0 below 99 % coverage (docs/evaluation.md, \"The floor-plan score\")");
  app_->add_option("--run-start", run_start_,
                   "with --floor-plan-score: when the run started, in the reference's clock "
                   "(default: 10000 s for a reference in the benchmark's clock, whose stamps "
                   "start within a minute after it; else the reference's first stamp)")
      ->option_text("SECONDS")
      ->needs(score);
}

std::string EvalCommand::rpeNotComputable(std::size_t associated) const {
  return "not computable: no two associated poses are " + std::to_string(rpe_delta_) +
         " frames apart (" + std::to_string(associated) + " poses associated)";
}

void EvalCommand::writePlot(const common::Trajectory& reference, const common::Trajectory& estimate,
                            const eval::ErrorResult& ape, const std::string& how,
                            const eval::Coverage& coverage) const {
  eval::ReportInput input;
  input.title = "isg eval: " + estimate_ + " against " + reference_;
  char line[256];
  std::snprintf(line, sizeof line,
                "APE (%s): rmse %.3f m, median %.3f m, max %.3f m over %d poses; rotation rmse "
                "%.2f deg",
                how.c_str(), ape.translation_stats.rmse, ape.translation_stats.median,
                ape.translation_stats.max, ape.translation_stats.count, ape.rotation_stats.rmse);
  input.summary.push_back(line);
  input.ground_truth = reference;
  // The estimate as it was compared: aligned when an alignment was asked for.
  common::Trajectory compared;
  compared.reserve(estimate.size());
  for (const auto& pose : estimate) {
    compared.push_back({pose.t, ape.alignment ? ape.alignment->apply(pose.pose) : pose.pose});
  }
  input.estimate = compared;
  input.estimate_label = ape.alignment ? "estimate, aligned" : "estimate";
  // The first pose is marked as a localization only when the estimate starts after the reference
  // and was not aligned after the fact.
  input.estimate_is_localization =
      !ape.alignment && coverage.localized && coverage.time_to_first > 0.0;
  input.error_title = "APE (" + how + ")";
  for (std::size_t i = 0; i < ape.translation.size(); ++i) {
    const double t = estimate[ape.association.estimate[i]].t;
    input.error_over_time.emplace_back(t, ape.translation[i]);
    input.heading_error_over_time.emplace_back(t, ape.rotation_deg[i]);
  }
  if (input.estimate_is_localization) {
    input.localized_at = reference.front().t + coverage.time_to_first;
  }
  common::writeFileAtomically(plot_,
                              common::outputMark(common::OutputKind::kSvg, eval::reportSvg(input)));
}

int EvalCommand::scoreFloorPlan(const common::Trajectory& reference,
                                const common::Trajectory& estimate) const {
  eval::FloorPlanScoreOptions options;
  options.run_start = run_start_;
  const eval::FloorPlanScore score = eval::floorPlanScore(reference, estimate, options);
  std::vector<double> errors;
  for (const auto& pose : score.per_pose) errors.push_back(pose.error);
  const eval::Statistics error = eval::statistics(errors);
  const double from = score.run_start + options.skip;
  char line[320];
  std::vector<std::string> summary;
  std::snprintf(line, sizeof line, "floor-plan score %.2f of 100%s", score.score,
                score.coverage < options.min_coverage ? " (coverage under 99 %: scored 0)" : "");
  summary.push_back(line);
  std::snprintf(line, sizeof line,
                "%d reference poses from %.3f s on (the run's start %.3f s + %.0f s), %d "
                "associated within %.0f ms: coverage %.2f %%",
                score.poses, from, score.run_start, options.skip, score.associated,
                1e3 * options.max_diff, 100.0 * score.coverage);
  summary.push_back(line);
  if (error.count > 0) {
    std::snprintf(line, sizeof line,
                  "error in the plane: mean %.3f m, median %.3f m, max %.3f m (z not scored)",
                  error.mean, error.median, error.max);
    summary.push_back(line);
  }
  if (!plot_.empty()) {
    const std::string svg = eval::floorPlanScoreSvg(
        score, "isg eval --floor-plan-score: " + estimate_ + " against " + reference_, summary);
    common::writeFileAtomically(plot_, common::outputMark(common::OutputKind::kSvg, svg));
  }
  if (json_) {
    const nlohmann::ordered_json out = {{"reference", reference_},
                                        {"estimate", estimate_},
                                        {"floor_plan_score",
                                         {{"score", score.score},
                                          {"coverage", score.coverage},
                                          {"poses", score.poses},
                                          {"associated", score.associated},
                                          {"run_start", score.run_start},
                                          {"scored_from", from}}},
                                        {"error", toJson(error)}};
    std::cout << out.dump(2) << "\n";
    return kExitOk;
  }
  for (const auto& text : summary) std::printf("%s\n", text.c_str());
  return kExitOk;
}

int EvalCommand::run() {
  if (!plot_.empty()) {
    common::checkOutputPath(plot_,
                            {common::OutputKind::kSvg, {reference_, estimate_}, true, false});
  }
  const common::Trajectory reference = formats::readTrajectoryFile(reference_);
  const common::Trajectory estimate = formats::readTrajectoryFile(estimate_);
  if (floor_plan_score_) return scoreFloorPlan(reference, estimate);
  eval::ErrorOptions options;
  options.align = align_ == "se3"
                      ? eval::Alignment::kSE3
                      : (align_ == "sim3" ? eval::Alignment::kSim3 : eval::Alignment::kNone);
  options.project_xy = project_ == "xy";
  options.max_diff = max_diff_;
  eval::ErrorResult ape;
  try {
    ape = eval::absolutePoseError(reference, estimate, options);
  } catch (const std::invalid_argument& e) {
    throw common::InputError(estimate_, "", e.what());
  }
  std::optional<eval::ErrorResult> rpe;
  if (rpe_delta_ > 0) {
    options.rpe_delta = rpe_delta_;
    rpe = eval::relativePoseError(reference, estimate, options);
  }
  const std::string alignment =
      options.align == eval::Alignment::kNone
          ? "not aligned"
          : (options.align == eval::Alignment::kSE3 ? "with SE(3) Umeyama alignment"
                                                    : "with Sim(3) Umeyama alignment");
  const std::string how = alignment + (options.project_xy ? ", projected to xy" : "");
  const eval::Coverage coverage = eval::localizationCoverage(reference, estimate);
  // As a run scores itself: the estimate at the reference's stamps (--floor-plan-score: as is).
  const eval::FloorPlanScore score = eval::runFloorPlanScore(reference, estimate);
  if (!plot_.empty()) writePlot(reference, estimate, ape, how, coverage);
  if (json_) {
    nlohmann::ordered_json out = {
        {"reference", reference_},
        {"estimate", estimate_},
        {"align", eval::toString(options.align)},
        {"project", options.project_xy ? "xy" : "none"},
        {"t_max_diff", options.max_diff},
        {"pairs", ape.association.reference.size()},
        {"localized", coverage.localized},
        {"time_to_localize", coverage.time_to_first},
        {"share_localized", coverage.share},
        {"floor_plan_score",
         {{"score", score.score}, {"coverage", score.coverage}, {"poses", score.poses}}},
        {"ape", toJson(ape.translation_stats)},
        {"ape_rotation_deg", toJson(ape.rotation_stats)}};
    if (ape.alignment) out["alignment"] = {{"scale", ape.alignment->scale}};
    if (rpe) {
      out["rpe_delta"] = rpe_delta_;
      if (rpe->translation_stats.count == 0) {
        // No statistics of nothing: a 0 would read as a perfect estimate.
        out["rpe"] = nullptr;
        out["rpe_rotation_deg"] = nullptr;
        out["rpe_note"] = rpeNotComputable(ape.association.reference.size());
      } else {
        out["rpe"] = toJson(rpe->translation_stats);
        out["rpe_rotation_deg"] = toJson(rpe->rotation_stats);
      }
    }
    std::cout << out.dump(2) << "\n";
    return kExitOk;
  }
  std::printf(
      "Found %zu of max. %zu possible matching timestamps between\n\t%s\nand:\t%s\n"
      "...with max. time diff.: %g (s)\n\n",
      ape.association.reference.size(), std::min(reference.size(), estimate.size()),
      reference_.c_str(), estimate_.c_str(), options.max_diff);
  std::printf("localized after %.2f s, for %.1f %% of the run\n", coverage.time_to_first,
              100.0 * coverage.share);
  std::printf(
      "floor-plan score %.1f (%d poses from 5 s on, %.1f %% of them estimated; the estimate "
      "resampled at the reference's stamps, as isg run scores itself)\n\n",
      score.score, score.poses, 100.0 * score.coverage);
  printStatistics("APE w.r.t. translation part (m)", how, ape.translation_stats);
  printStatistics("APE w.r.t. rotation angle in degrees (deg)", how, ape.rotation_stats);
  if (rpe) {
    char title[96];
    std::snprintf(title, sizeof title, "RPE w.r.t. translation part (m) for delta = %d (frames)",
                  rpe_delta_);
    if (rpe->translation_stats.count == 0) {
      std::printf("%s: %s\n", title, rpeNotComputable(ape.association.reference.size()).c_str());
    } else {
      printStatistics(title, how, rpe->translation_stats);
    }
  }
  return kExitOk;
}

}  // namespace isg::cli
