// The paper's baselines in the loop: each runs on D1 as built, and the row is checked against the
// committed baseline table (eval/baselines/table1_d1.csv), as CI's second regression check.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>

#include <nlohmann/json.hpp>

#include "cli/tests/cli_runner.hpp"

namespace isg::cli {
namespace {

using ::testing::HasSubstr;

double apeB(testing::Sandbox& sandbox, const std::string& run) {
  const auto metrics = nlohmann::json::parse(sandbox.read(run + "/metrics.json"));
  return metrics.at("ape_B").at("rmse").get<double>();
}

TEST(Baselines, D1AsBuiltAgainstTheCommittedTable) {
  testing::Sandbox sandbox("baselines");
  for (const char* method : {"is-graphs", "amcl", "odometry"}) {
    const auto r = sandbox.run(std::string("run builtin:d1.asbuilt --seed 1 --method ") + method +
                               " -o d1-" + method + " -q");
    ASSERT_EQ(r.exit_code, 0) << method << ": " << r.err;
  }
  // The tracker, from a start 0.3 m and 5° off, follows D1 as built within 0.3 m (RMSE, the mean
  // of seeds 1–3, measured 0.207 m). Whether it corrects its start offset depends on the draw:
  // over seeds 1–15 its RMSE spans 0.028–0.274 m (mean 0.144 m; 0.101 m with the simulator's
  // previous noise generator, whose seeds 1–3 happened to be three of the good ones); in seeds 1
  // and 3 it stays about 0.26 m off the whole run (docs/baselines.md).
  double ndt_mean = 0.0;
  for (const char* seed : {"1", "2", "3"}) {
    const std::string run = std::string("ndt-") + seed;
    ASSERT_EQ(sandbox
                  .run(std::string("run builtin:d1.asbuilt --method ndt-ukf -q --seed ") + seed +
                       " -o " + run)
                  .exit_code,
              0);
    const auto ndt = nlohmann::json::parse(sandbox.read(run + "/metrics.json"));
    EXPECT_TRUE(ndt["localized"].get<bool>());
    EXPECT_FALSE(ndt["wrongly_localized"].get<bool>());
    ndt_mean += apeB(sandbox, run) / 3.0;
  }
  EXPECT_LE(ndt_mean, 0.3);
  // AMCL localizes from its uniform start, and is not wrong.
  const auto amcl = nlohmann::json::parse(sandbox.read("d1-amcl/metrics.json"));
  EXPECT_TRUE(amcl["localized"].get<bool>());
  EXPECT_FALSE(amcl["wrongly_localized"].get<bool>());
  EXPECT_GT(amcl["time_to_localize"].get<double>(), 1.0);  // it had to search

  const std::string baseline = std::string(ISG_SOURCE_DIR) + "/eval/baselines/table1_d1.csv";
  const auto table = sandbox.run("table d1-is-graphs d1-amcl ndt-1 d1-odometry --baseline '" +
                                 baseline + "' --tolerance 0.02");
  EXPECT_EQ(table.exit_code, 0) << table.err;
  EXPECT_THAT(table.out, HasSubstr("| world | is-graphs | amcl | ndt-ukf | odometry |\n"));
  EXPECT_THAT(table.out, HasSubstr("Given their start pose (trackers, not global localization): "
                                   "ndt-ukf, odometry"));
  EXPECT_THAT(table.out, HasSubstr("| *localized correctly* | 1/1 | 1/1 | 1/1 | 1/1 |\n"));
  EXPECT_THAT(table.err, HasSubstr("no cell regressed"));
}

// Two seeds of a world and method make one cell: their mean, sample standard deviation and counts;
// a seed that never localized makes the cell "-"; the same seed twice is bad input. Run folders
// made without -o carry the seed in their name, so seeds do not collide.
TEST(Baselines, SeedsOfOneCellAreAggregated) {
  testing::Sandbox sandbox("baselines_seeds");
  for (const char* seed : {"1", "2"}) {
    const auto r = sandbox.run(
        std::string("run builtin:d2 --method odometry --duration 8 --seed ") + seed + " -q");
    ASSERT_EQ(r.exit_code, 0) << r.err;
  }
  ASSERT_TRUE(sandbox.exists("runs/d2-odometry-seed-1/metrics.json"));
  ASSERT_TRUE(sandbox.exists("runs/d2-odometry-seed-2/metrics.json"));
  ASSERT_EQ(
      sandbox.run("run builtin:d2 --method amcl --duration 1 --seed 1 -o amcl-1 -q").exit_code, 0);
  const double a = apeB(sandbox, "runs/d2-odometry-seed-1");
  const double b = apeB(sandbox, "runs/d2-odometry-seed-2");
  const double mean = 0.5 * (a + b);
  const double std = std::abs(a - b) / std::sqrt(2.0);  // sample deviation of two numbers
  char expected[128];
  std::snprintf(expected, sizeof expected, "d2,-,,0,1,0,0,0,%.3f,%.3f,2,2,0,0,0\n", mean, std);
  const auto csv =
      sandbox.run("table runs/d2-odometry-seed-1 runs/d2-odometry-seed-2 amcl-1 --format csv");
  ASSERT_EQ(csv.exit_code, 0) << csv.err;
  EXPECT_EQ(csv.out,
            std::string("world,amcl,amcl: std,amcl: localized,amcl: runs,amcl: wrong,amcl: failed,"
                        "amcl: not run,odometry,odometry: std,odometry: localized,odometry: runs,"
                        "odometry: wrong,odometry: failed,odometry: not run\n") +
                expected + "localized correctly,0/1,,,,,,,1/1,,,,,,\n");
  char shown[128];
  std::snprintf(shown, sizeof shown, "| d2 | 0/1 | %.3f ± %.3f 2/2 |", mean, std);
  const auto md = sandbox.run("table runs/d2-odometry-seed-1 runs/d2-odometry-seed-2 amcl-1");
  EXPECT_THAT(md.out, HasSubstr(shown));
  const auto twice = sandbox.run("table amcl-1 amcl-1");
  EXPECT_EQ(twice.exit_code, 1);
  EXPECT_EQ(twice.err, "isg table: error: amcl-1: a second run of d2 with amcl and seed 1\n");
}

TEST(Baselines, MethodOptionsAreCheckedAndNamed) {
  testing::Sandbox sandbox("baselines_options");
  const auto unknown =
      sandbox.run("run builtin:d1 --method amcl --method-option particle=100 -o r -q");
  EXPECT_EQ(unknown.exit_code, 1);
  EXPECT_EQ(unknown.err,
            "isg run: error: --method amcl: particle=100: amcl has no option particle (it has "
            "alpha_fast, alpha_slow, min_particles, particles, update_min_a, update_min_d)\n");
  const auto bad = sandbox.run("run builtin:d1 --method ndt-ukf --method-option start_error=-1 -q");
  EXPECT_EQ(bad.exit_code, 1);
  EXPECT_THAT(bad.err, HasSubstr("start_error=-1: ndt-ukf's start_error must be a number in [0"));
  const auto malformed = sandbox.run("run builtin:d1 --method amcl --method-option particles -q");
  EXPECT_EQ(malformed.exit_code, 1);
  EXPECT_EQ(malformed.err, "isg run: error: --method-option particles: expected KEY=VALUE\n");
  // A method without options takes none: a key is refused, not ignored.
  const auto none =
      sandbox.run("run builtin:d1 --method odometry --method-option particles=10 -o r -q");
  EXPECT_EQ(none.exit_code, 1);
  EXPECT_EQ(none.err,
            "isg run: error: --method odometry: particles=10: odometry has no option particles "
            "(it has none)\n");
  EXPECT_FALSE(sandbox.exists("r"));
  const auto more = sandbox.run(
      "run builtin:d2 --method amcl --duration 2 --method-option particles=5000 -o big -q");
  ASSERT_EQ(more.exit_code, 0) << more.err;
  const auto graph = nlohmann::json::parse(sandbox.read("big/sgraph.json"));
  EXPECT_EQ(graph["particles"].get<int>(), 5000);  // the uniform start, before any resampling
}

}  // namespace
}  // namespace isg::cli
