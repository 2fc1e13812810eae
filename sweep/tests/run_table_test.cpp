#include <gtest/gtest.h>

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

}  // namespace
}  // namespace isg::sweep
