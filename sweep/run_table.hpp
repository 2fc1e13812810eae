#pragma once

#include <string>
#include <utility>
#include <vector>

#include "eval/table.hpp"
#include "run/localizer_registry.hpp"
#include "run/run_metrics.hpp"

namespace isg::sweep {

// "builtin:d1" → "d1"; anything else as it is.
std::string shortWorld(const std::string& world);

// Every measure a run table can show, as --measure spells them.
// The graded deviation measures (a simulated building's deviations.json against its truth,
// run::DeviationGrade) are the ones from deviation-recall on, before floor-plan-score; the
// map-to-plan measures (metrics.json's map_to_plan, with a row per level) come last.
inline const std::vector<std::string> kRunTableMeasures = {"ape",
                                                           "time-wrong",
                                                           "time-to-localize",
                                                           "distance-to-localize",
                                                           "rooms-to-localize",
                                                           "deviation-recall",
                                                           "deviation-precision",
                                                           "deviation-offset-error",
                                                           "deviation-angle-error",
                                                           "deviation-pivot-error",
                                                           "progress-recall",
                                                           "progress-precision",
                                                           "built-length-error",
                                                           "built-length-error-seen",
                                                           "missing-recall",
                                                           "missing-precision",
                                                           "extra-recall",
                                                           "extra-precision",
                                                           "column-recall",
                                                           "column-precision",
                                                           "column-offset-error",
                                                           "floor-plan-score",
                                                           "map-to-plan-median",
                                                           "map-to-plan-off-length"};

// Whether the measure is one of a graded deviation report (run::DeviationGrade).
bool isGraded(const std::string& measure);

// Measures whose larger values are better (a regression is a drop): the score, and the graded
// recalls and precisions.
inline bool higherIsBetter(const std::string& measure) {
  return measure == "floor-plan-score" || measure.ends_with("-recall") ||
         measure.ends_with("-precision");
}

// The table of `isg table` and `isg sweep --collect`: rows worlds, columns methods in the
// registry's order, cells aggregated over seeds (docs/evaluation.md), with a caption that says
// what the cells are. `runs` are (run folder, its metrics) pairs; `measure` is one of ape,
// time-wrong, time-to-localize, distance-to-localize, rooms-to-localize, the graded deviation
// measures, floor-plan-score, map-to-plan-median, map-to-plan-off-length (kRunTableMeasures). Two
// runs of one world, method and seed are bad input naming the second folder. Runs of one world name
// whose world hashes differ are different buildings: their rows are told apart by the hash ("w
// [1a2b3c4d]"). `absent` are the seeds a sweep asked for that have no run (failed, or not run):
// their cells count them, so a table never looks complete when it is not.
struct RunTable {
  eval::ResultTable table;
  std::string caption;
};
struct AbsentRun {
  std::string world, method;  // the suite's world name, the method's canonical name
  std::uint64_t seed = 0;
  bool failed = false;  // false: not run (yet)
};
RunTable tabulateRuns(std::vector<std::pair<std::string, run::RunMetrics>> runs,
                      const std::string& measure, const run::LocalizerRegistry& methods,
                      const std::vector<AbsentRun>& absent = {});

}  // namespace isg::sweep
