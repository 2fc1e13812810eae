#include <gtest/gtest.h>

#include <algorithm>
#include <map>

#include "run/builtin_methods.hpp"
#include "sweep/run_table.hpp"

namespace isg::sweep {
namespace {

run::RunMetrics twoStoreyRun(std::uint64_t seed, double ape_l0, double ape_l1) {
  run::RunMetrics m;
  m.world = "builtin:storeys";
  m.method = "is-graphs";
  m.seed = seed;
  m.localized = true;
  m.time_to_localize = 2.0;
  m.share_localized = 0.9;
  eval::Statistics whole;
  whole.rmse = 0.5 * (ape_l0 + ape_l1);
  m.ape_B = whole;
  m.wrongly_localized = false;
  eval::Statistics l0, l1;
  l0.rmse = ape_l0;
  l1.rmse = ape_l1;
  m.levels = {{"L0", 100.0, 0.0, 2.0, l0}, {"L1", 80.0, 120.0, 120.5, l1}};
  return m;
}

// A row per level under the world's, in the order reached: the APE there, or the seconds from
// arriving to the first pose in B there.
TEST(RunTableLevels, ARowPerLevelUnderTheWorld) {
  std::vector<std::pair<std::string, run::RunMetrics>> runs = {{"a", twoStoreyRun(1, 0.02, 0.04)},
                                                               {"b", twoStoreyRun(2, 0.04, 0.06)}};
  const RunTable ape = tabulateRuns(runs, "ape", run::builtinMethods());
  ASSERT_EQ(ape.table.rows, (std::vector<std::string>{"storeys", "storeys / L0", "storeys / L1"}));
  ASSERT_TRUE(ape.table.find("storeys / L0", "is-graphs")->has_value());
  EXPECT_NEAR(**ape.table.find("storeys / L0", "is-graphs"), 0.03, 1e-12);
  EXPECT_NEAR(**ape.table.find("storeys / L1", "is-graphs"), 0.05, 1e-12);
  EXPECT_NEAR(**ape.table.find("storeys", "is-graphs"), 0.04, 1e-12);

  const RunTable time = tabulateRuns(runs, "time-to-localize", run::builtinMethods());
  EXPECT_NEAR(**time.table.find("storeys / L0", "is-graphs"), 2.0, 1e-12);
  EXPECT_NEAR(**time.table.find("storeys / L1", "is-graphs"), 0.5, 1e-12);

  // Measures without a per-level meaning have the world's row only; a wrong run is ✗ on each.
  EXPECT_EQ(tabulateRuns(runs, "time-wrong", run::builtinMethods()).table.rows.size(), 1u);
  runs[1].second.wrongly_localized = true;
  const RunTable wrong = tabulateRuns(runs, "ape", run::builtinMethods());
  EXPECT_TRUE(wrong.table.isWrong("storeys / L1", "is-graphs"));
  EXPECT_TRUE(wrong.table.isWrong("storeys", "is-graphs"));
}

// Runs of one method with different options (metrics.json's method_options) are not one cell:
// their columns say the options that differ. Runs that recorded none (older runs) join any.
TEST(RunTableOptions, AMethodRunWithOtherOptionsIsAColumnOfItsOwn) {
  auto amcl = [](std::uint64_t seed, std::optional<std::map<std::string, double>> options) {
    run::RunMetrics m = twoStoreyRun(seed, 0.02, 0.04);
    m.world = "builtin:d1";
    m.levels.clear();
    m.method = "amcl";
    m.method_options = std::move(options);
    return m;
  };
  const std::map<std::string, double> defaults{{"particles", 2000}, {"alpha_slow", 0.001}};
  std::map<std::string, double> more = defaults;
  more["particles"] = 5000;
  const RunTable table = tabulateRuns({{"a", amcl(1, defaults)},
                                       {"b", amcl(1, more)},
                                       {"c", amcl(2, more)},
                                       {"d", amcl(3, std::nullopt)}},
                                      "ape", run::builtinMethods());
  EXPECT_EQ(table.table.columns,
            (std::vector<std::string>{"amcl [particles=2000]", "amcl [particles=5000]", "amcl"}));
  EXPECT_NE(table.caption.find("Columns marked [KEY=VALUE]"), std::string::npos);
  // Seed 1 twice, with other options: two cells, not "a second run".
  ASSERT_EQ(table.table.stats.size(), 1u);
  EXPECT_EQ(table.table.stats[0][1].runs, 2);
  // One option set: one column, as before options were recorded.
  const RunTable same =
      tabulateRuns({{"a", amcl(1, more)}, {"b", amcl(2, more)}, {"c", amcl(3, std::nullopt)}},
                   "ape", run::builtinMethods());
  EXPECT_EQ(same.table.columns, (std::vector<std::string>{"amcl"}));
}

// Each graded measure tabulates its number of the grade, mean over the seeds that have one; a
// recall or a precision is better higher, an error lower.
TEST(RunTableGraded, EachGradedMeasureTabulatesItsNumberOfTheGrade) {
  auto graded = [](std::uint64_t seed, int missing_found, int missing_missed) {
    run::RunMetrics m = twoStoreyRun(seed, 0.02, 0.04);
    m.world = "generated";
    m.levels.clear();
    run::DeviationGrade g;
    g.recall = 0.8 + 0.1 * double(seed);
    g.precision = 1.0;
    g.offset_error_m = 0.01 * double(seed);
    g.angle_error_deg = 0.2;
    g.pivot_error_m = 0.1;
    g.partly_recall = 1.0;
    g.partly_precision = 0.5;
    g.built_length_error_m = 0.04;
    g.built_length_error_seen_m = 0.03;
    g.missing_found = missing_found;
    g.missing_missed = missing_missed;
    g.extra_precision = 0.75;
    run::DeviationMetrics d;
    d.grade = g;
    m.deviations = d;
    return m;
  };
  std::vector<std::pair<std::string, run::RunMetrics>> runs = {{"a", graded(1, 3, 1)},
                                                               {"b", graded(2, 0, 0)}};
  const std::map<std::string, double> expected = {
      {"deviation-recall", 0.95},        {"deviation-precision", 1.0},
      {"deviation-offset-error", 0.015}, {"deviation-angle-error", 0.2},
      {"deviation-pivot-error", 0.1},    {"progress-recall", 1.0},
      {"progress-precision", 0.5},       {"built-length-error", 0.04},
      {"built-length-error-seen", 0.03}, {"extra-precision", 0.75}};
  for (const auto& [measure, value] : expected) {
    EXPECT_TRUE(isGraded(measure)) << measure;
    const RunTable table = tabulateRuns(runs, measure, run::builtinMethods());
    const auto cell = table.table.find("generated", "is-graphs");
    ASSERT_TRUE(cell && cell->has_value()) << measure;
    EXPECT_NEAR(**cell, value, 1e-12) << measure;
    EXPECT_EQ(higherIsBetter(measure),
              measure.ends_with("recall") || measure.ends_with("precision"))
        << measure;
  }
  // The second run found and missed no missing wall: no recall, and so no mean for the cell (a
  // mean only when every seed gave a number); the first alone has its 3 of 4.
  const RunTable both = tabulateRuns(runs, "missing-recall", run::builtinMethods());
  const auto none = both.table.find("generated", "is-graphs");
  EXPECT_TRUE(!none || !none->has_value());
  runs.pop_back();
  const RunTable one = tabulateRuns(runs, "missing-recall", run::builtinMethods());
  const auto first = one.table.find("generated", "is-graphs");
  ASSERT_TRUE(first && first->has_value());
  EXPECT_NEAR(**first, 0.75, 1e-12);
  const auto position = [](const std::string& name) {
    return std::find(kRunTableMeasures.begin(), kRunTableMeasures.end(), name);
  };
  for (const auto& measure : kRunTableMeasures) {
    const bool graded_measure = position(measure) >= position("deviation-recall") &&
                                position(measure) < position("floor-plan-score");
    EXPECT_EQ(isGraded(measure), graded_measure) << measure;
  }
  EXPECT_FALSE(isGraded("ape"));
}

// The map against the plan: the world's row the run's median (or the length off summed over its
// levels), a row per level when there are several, whatever the method, localized or not.
TEST(RunTableMapToPlan, TheMapAgainstThePlanHasARowPerLevel) {
  auto placed = [](std::uint64_t seed, double median, double off_l0, double off_l1) {
    run::RunMetrics m = twoStoreyRun(seed, 0.02, 0.04);
    m.localized = false;
    run::RunMetrics::MapToPlan map;
    map.distance.median = median;
    map.levels = {{"L0", 100, 0.9, median - 0.005, 0.05, 10, 2, off_l0},
                  {"L1", 100, 0.9, median + 0.005, 0.06, 12, 3, off_l1}};
    m.map_to_plan = map;
    return m;
  };
  const std::vector<std::pair<std::string, run::RunMetrics>> runs = {
      {"a", placed(1, 0.02, 1.5, 2.0)}, {"b", placed(2, 0.03, 0.5, 1.0)}};
  const RunTable median = tabulateRuns(runs, "map-to-plan-median", run::builtinMethods());
  ASSERT_EQ(median.table.rows,
            (std::vector<std::string>{"storeys", "storeys / L0", "storeys / L1"}));
  EXPECT_NEAR(**median.table.find("storeys", "is-graphs"), 0.025, 1e-12);
  EXPECT_NEAR(**median.table.find("storeys / L0", "is-graphs"), 0.02, 1e-12);
  EXPECT_NEAR(**median.table.find("storeys / L1", "is-graphs"), 0.03, 1e-12);
  const RunTable off = tabulateRuns(runs, "map-to-plan-off-length", run::builtinMethods());
  EXPECT_NEAR(**off.table.find("storeys", "is-graphs"), 2.5, 1e-12);  // (3.5 + 1.5) / 2
  EXPECT_NEAR(**off.table.find("storeys / L1", "is-graphs"), 1.5, 1e-12);
  EXPECT_FALSE(higherIsBetter("map-to-plan-median"));
  EXPECT_FALSE(isGraded("map-to-plan-off-length"));
  // A run whose map was never placed has no number, and its cell no mean.
  std::vector<std::pair<std::string, run::RunMetrics>> unplaced = runs;
  unplaced[1].second.map_to_plan.reset();
  const RunTable partial = tabulateRuns(unplaced, "map-to-plan-median", run::builtinMethods());
  const auto cell = partial.table.find("storeys", "is-graphs");
  EXPECT_TRUE(!cell || !cell->has_value());
}

}  // namespace
}  // namespace isg::sweep
