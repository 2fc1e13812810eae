#pragma once

#include <nlohmann/json.hpp>
#include <string>

#include "run/deviation_grading.hpp"
#include "slam/deviations/plan_deviations.hpp"

namespace isg::run {

// deviations.json (docs/deviations.md): the thresholds, then per plan wall of the levels walked
// its status, measured offset and angle, observed share and evidence, the extra walls, and per
// column of the levels walked its status and offset.
nlohmann::json deviationReportJson(const slam::DeviationReport& report);

// deviations.svg: each level walked, the plan's walls in grey, the map's walls that were evidence
// coloured by their wall's status, missing walls red and dashed, extra walls blue, labels with
// the measured offset and angle of each deviating wall.
std::string deviationSvg(const slam::DeviationReport& report);

// The run summary's line: "as built: 5 walls as planned, 1 shifted, ..." and, graded, how many
// deviating walls were found.
std::string deviationSummaryLine(const DeviationMetrics& metrics);
// The summary's line of how much of each wall is built (and, graded, the walls built in part
// found).
std::string progressSummaryLine(const DeviationMetrics& m);
// The summary's line of the columns, for levels walked that have some: "columns: 24 as planned,
// 1 moved, 1 missing, 2 not seen" and, graded, how many deviating columns were found.
std::string columnSummaryLine(const DeviationMetrics& m);

}  // namespace isg::run
