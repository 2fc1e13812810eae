#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>

#include "cli/tests/cli_runner.hpp"

namespace isg::cli {
namespace {

// A walk in the benchmark's clock: the reference at 30 Hz from 10 003.2 s for 60 s along x, and an
// estimate at the same stamps 5 cm off in y and 1 m off in z, lost (no rows) for 0.2 s at 10 040 s.
void writeBenchmarkLikeFiles(testing::Sandbox& sandbox) {
  std::string reference = "# timestamp tx ty tz qx qy qz qw\n", estimate;
  char line[160];
  for (int k = 0; k < 1800; ++k) {
    const double t = 10003.2 + k / 30.0, x = 0.02 * k;
    std::snprintf(line, sizeof line, "%.6f %.4f 2.0 1.2 0 0 0 1\n", t, x);
    reference += line;
    if (t >= 10040.0 && t < 10040.2) continue;
    std::snprintf(line, sizeof line, "%.6f %.4f 2.05 2.2 0 0 0 1\n", t, x);
    estimate += line;
  }
  sandbox.write("floor_1_2025-05-05_run_1.txt", reference);
  sandbox.write("est.txt", estimate);
}

TEST(FloorPlanScoreCommand, ScoresAFileAsTheBenchmarkDoes) {
  testing::Sandbox sandbox("floor_plan_score_cli");
  writeBenchmarkLikeFiles(sandbox);
  const auto run =
      sandbox.run("eval --floor-plan-score floor_1_2025-05-05_run_1.txt est.txt --json");
  ASSERT_EQ(run.exit_code, 0) << run.err;
  const auto out = nlohmann::json::parse(run.out)["floor_plan_score"];
  // Scored from 10 005 s (the recording's start 10 000 s + 5 s): stamps 10 005.0 … 10 063.17,
  // 1746 of them; 6 lost (10 040.0 … 10 040.17).
  EXPECT_DOUBLE_EQ(out["run_start"].get<double>(), 10000.0);
  EXPECT_DOUBLE_EQ(out["scored_from"].get<double>(), 10005.0);
  EXPECT_EQ(out["poses"].get<int>(), 1746);
  EXPECT_EQ(out["associated"].get<int>(), 1740);
  EXPECT_NEAR(out["score"].get<double>(), 100.0 * std::exp(-0.46051701859880917 * 0.05), 1e-6);

  const auto text =
      sandbox.run("eval --floor-plan-score floor_1_2025-05-05_run_1.txt est.txt --plot s.svg");
  ASSERT_EQ(text.exit_code, 0) << text.err;
  EXPECT_EQ(text.out,
            "floor-plan score 97.72 of 100\n"
            "1746 reference poses from 10005.000 s on (the run's start 10000.000 s + 5 s), 1740 "
            "associated within 10 ms: coverage 99.66 %\n"
            "error in the plane: mean 0.050 m, median 0.050 m, max 0.050 m (z not scored)\n");
  EXPECT_NE(sandbox.read("s.svg").find("score of each associated pose"), std::string::npos);

  // Told the run started at 10 030 s: scored from 10 035 s on, 846 poses.
  const auto later = sandbox.run(
      "eval --floor-plan-score floor_1_2025-05-05_run_1.txt est.txt --run-start 10030 --json");
  ASSERT_EQ(later.exit_code, 0) << later.err;
  EXPECT_EQ(nlohmann::json::parse(later.out)["floor_plan_score"]["poses"].get<int>(), 846);
  // --run-start belongs to the score.
  const auto alone = sandbox.run("eval floor_1_2025-05-05_run_1.txt est.txt --run-start 10030");
  EXPECT_NE(alone.exit_code, 0);
  EXPECT_NE(alone.err.find("--run-start requires --floor-plan-score"), std::string::npos);
}

TEST(FloorPlanScoreCommand, ASubmissionNeverReplacesAFileIsgDidNotWrite) {
  testing::Sandbox sandbox("floor_plan_submission");
  sandbox.write("floor_1_2025-05-05_run_1.txt", "0 2 1.1 0 0 0 0 1\n1 2.5 1.1 0 0 0 0 1\n");
  sandbox.write("walk.json", "{\"format\": \"isg.scenario\", \"version\": 1, \"plan\": \"" +
                                 std::string(ISG_SOURCE_DIR) +
                                 "/worlds/plans/d1.json\", \"robot\": {\"carrier\": "
                                 "\"handheld\", \"route\": {\"trajectory\": "
                                 "\"floor_1_2025-05-05_run_1.txt\"}}}");
  std::filesystem::create_directories(sandbox.dir() / "sub");
  sandbox.write("sub/floor_1_2025-05-05_run_1.txt", "a participant's\n");
  for (const char* force : {"", " --force"}) {
    const auto run = sandbox.run(std::string("run walk.json -q -o r --submission sub") + force);
    EXPECT_EQ(run.exit_code, 1);
    EXPECT_FALSE(sandbox.exists("r"));
  }
  const auto forced = sandbox.run("run walk.json -q -o r --submission sub --force");
  EXPECT_EQ(forced.err,
            "isg run: error: sub/floor_1_2025-05-05_run_1.txt: not replaced: it is not a "
            "floor-plan benchmark submission that isg wrote (--force replaces only those); remove "
            "it yourself or give another path\n");
  EXPECT_EQ(sandbox.read("sub/floor_1_2025-05-05_run_1.txt"), "a participant's\n");
}

}  // namespace
}  // namespace isg::cli
