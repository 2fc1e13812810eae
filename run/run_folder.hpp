#pragma once

#include <filesystem>
#include <functional>

#include <string>

#include "run/evaluate_run.hpp"
#include "run/run_record.hpp"

namespace isg::run {

// Writes the run folder (docs/evaluation.md) all at once — into a temporary folder beside it,
// renamed into place at the end: groundtruth.tum, odometry.tum, estimate.tum (B, rows only once
// localized), estimate_map.tum (M), metrics.json, sgraph.json, report.svg; agraph.json when the
// run has a plan; keyframes.tum when the method builds a map; deviations.json and deviations.svg
// when the map was placed in a plan. An existing folder is an
// InputError unless `force`.
// `more_files`, when given, writes further files into the folder being made (its temporary path),
// such as deviations.bcf, whose snapshots need the renderer this module never sees.
void writeRunFolder(
    const std::string& dir, const RunRecord& run, const RunEvaluation& evaluation, bool force,
    const std::function<void(const std::filesystem::path& folder)>& more_files = {});

}  // namespace isg::run
