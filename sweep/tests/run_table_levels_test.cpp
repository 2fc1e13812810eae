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

}  // namespace
}  // namespace isg::sweep
