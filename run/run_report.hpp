#pragma once

#include <string>

#include "run/evaluate_run.hpp"
#include "run/run_record.hpp"

namespace isg::run {

// report.svg of a run: the plan's walls and rooms, the trajectories in B, where localization
// happened, the APE over time (eval::reportSvg draws it).
std::string reportSvg(const RunRecord& run, const RunEvaluation& evaluation);

// The summary printed at the end of a run ("isg run: wrote DIR (...)", localization, APE, speed).
// The stage timing of metrics.timing as a table: seconds and ms per robot-second by stage, the
// loop's wall time and where the localizer's thread spent it; `writing_seconds`: the run folder.
std::string timingTable(const RunMetrics& metrics, double writing_seconds);

std::string runSummary(const std::string& command, const std::string& dir,
                       const RunMetrics& metrics);

}  // namespace isg::run
