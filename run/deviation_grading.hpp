#pragma once

#include <nlohmann/json.hpp>
#include <optional>

#include "bim/plan.hpp"
#include "bim/scenario.hpp"
#include "common/json_reader.hpp"
#include "slam/deviations/plan_deviations.hpp"

namespace isg::run {

// The deviation report against the building as it was simulated (docs/deviations.md,
// "Grading"). A plan wall truly deviates when it is missing, or when its built axis
// (bim::builtWall) lies at least the report's own thresholds off the planned one, measured as
// the report measures (bim::axisDeviation).
struct DeviationGrade {
  // Shifted and turned walls, among the plan walls the report saw over at least `min_share` of
  // their length: found (reported shifted or rotated and truly deviating), falsely reported, and
  // missed (reported as planned).
  double min_share = 0.5;
  int judged = 0;
  int found = 0, false_reports = 0, missed = 0;
  std::optional<double> precision, recall;  // none when there is nothing to divide by
  // Over the truly deviating walls among those: mean |measured − true|.
  std::optional<double> offset_error_m, angle_error_deg;
  // Over the truly turned walls (by the angle threshold) reported rotated: mean |measured − true|
  // of the point along the wall its line crosses the planned axis (slam::crossingAlong), metres.
  std::optional<double> pivot_error_m;
  // Progress, over the plan walls the report saw built or not over at least `min_share` of their
  // exposed length: walls built in part (as_built.shortened_walls) reported partly built or not
  // built (found), whole walls reported so (false reports), walls built in part reported built
  // (missed); over those found partly built, mean |built length − true| (the true one on the same
  // exposed parts).
  int partly_found = 0, partly_false_reports = 0, partly_missed = 0;
  std::optional<double> partly_precision, partly_recall, built_length_error_m;
  // The same mean over those of them seen end to end: less than kSeenEndToEnd of their exposed
  // length not seen (two progress samples), as the acceptance of a built length asks.
  static constexpr double kSeenEndToEnd = 0.1;  // m
  std::optional<double> built_length_error_seen_m;
  // Missing walls: reported missing and truly missing, reported but built, missing and not said.
  int missing_found = 0, missing_false_reports = 0, missing_missed = 0;
  // Extra walls: a reported one matches a true one within 10° and 0.3 m of its axis; one that lies
  // on a clutter box (its footprint grown by 0.3 m) is furniture the plan also lacks, counted
  // apart. Precision over reports, recall over the true extra walls of the levels walked.
  int extra_found = 0, extra_false_reports = 0, extra_missed = 0, extra_on_clutter = 0;
  std::optional<double> extra_precision, extra_recall;
  // Columns, among those the report judged (not not_seen): a column truly missing
  // (as_built.missing_columns) or moved by the report's threshold or more (moved_columns)
  // reported so, with the right status (found); reported missing or moved but built as planned
  // (false reports); truly deviating and reported otherwise (missed). Over those found moved, the
  // mean distance between the measured and the true offset.
  int column_found = 0, column_false_reports = 0, column_missed = 0;
  std::optional<double> column_precision, column_recall, column_offset_error_m;
};

DeviationGrade gradeDeviations(const slam::DeviationReport& report, const bim::Plan& plan,
                               const bim::AsBuilt& truth);

// What metrics.json keeps of the report: how many plan walls got each status, the extra walls,
// and the grade when the building's truth is known.
struct DeviationMetrics {
  int as_planned = 0, shifted = 0, rotated = 0, missing = 0, not_seen = 0, extra_walls = 0;
  int built = 0, partly_built = 0, not_built = 0, progress_not_seen = 0;  // by progress
  // The plan's columns on the levels walked, by status (metrics.json `deviations.columns`, there
  // when the levels walked have columns).
  int columns_as_planned = 0, columns_moved = 0, columns_missing = 0, columns_not_seen = 0;
  bool hasColumns() const {
    return columns_as_planned + columns_moved + columns_missing + columns_not_seen > 0;
  }
  std::optional<DeviationGrade> grade;
};

// `truth` and `plan` may be null (a recording): no grade then.
DeviationMetrics deviationMetrics(const slam::DeviationReport& report, const bim::Plan* plan,
                                  const bim::AsBuilt* truth);
nlohmann::json deviationMetricsJson(const DeviationMetrics& metrics);
DeviationMetrics deviationMetricsFromJson(const common::JsonNode& node);

}  // namespace isg::run
