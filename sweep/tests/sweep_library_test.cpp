// The sweep library's pieces without the isg executable: a suite into cells, sweep.json read back,
// Slurm's arrays and their commands, a table's world names. (The command's behaviour end to end,
// with real child processes, is in cli/tests/sweep_test.cpp and sweep_integrity_test.cpp.)
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "common/input_error.hpp"
#include "common/json_reader.hpp"
#include "common/version.hpp"
#include "run/builtin_methods.hpp"
#include "sweep/run_table.hpp"
#include "sweep/slurm_backend.hpp"
#include "sweep/suite.hpp"

namespace isg::sweep {
namespace {

using ::testing::ElementsAre;
using ::testing::HasSubstr;

Suite suiteOf(const std::string& text) {
  const nlohmann::json document = nlohmann::json::parse(text);
  const common::JsonSource source{"suite.json", nullptr};
  return parseSuite(common::JsonNode(document, "", source), "suite.json", run::builtinMethods());
}

TEST(SweepLibrary, ASuiteIsItsCellsInWorldMethodSeedOrder) {
  const Suite suite = suiteOf(R"({"format": "isg.suite", "version": 1, "name": "s",
      "worlds": ["builtin:d1", "builtin:d2.asbuilt"], "methods": ["odometry", "is-graphs"],
      "seeds": [3, 1], "run": {"duration": 2.5, "threads": 1}})");
  const std::vector<SweepCell> cells = sweepCells(suite);
  ASSERT_EQ(cells.size(), 8u);
  EXPECT_EQ(cells[0].dir, "d1/odometry/seed-3");
  EXPECT_EQ(cells[1].dir, "d1/odometry/seed-1");
  EXPECT_EQ(cells[2].dir, "d1/is-graphs/seed-3");
  EXPECT_EQ(cells[7].dir, "d2.asbuilt/is-graphs/seed-1");
  EXPECT_THAT(cells[7].arguments, ElementsAre("run", "builtin:d2.asbuilt", "--method", "is-graphs",
                                              "--seed", "1", "-o", "d2.asbuilt/is-graphs/seed-1",
                                              "--threads", "1", "-q", "--duration", "2.5"));
}

// Cells from the true start: every world's own first pose, given to isg run as "truth"; a pose in
// numbers is refused (it would be one building's).
TEST(SweepLibrary, AStartPoseIsEachWorldsTruth) {
  const Suite suite = suiteOf(R"({"format": "isg.suite", "version": 1, "name": "s",
      "worlds": ["builtin:d1"], "methods": ["is-graphs"], "seeds": [1],
      "run": {"start_pose": "truth"}})");
  EXPECT_THAT(sweepCells(suite)[0].arguments,
              ElementsAre("run", "builtin:d1", "--method", "is-graphs", "--seed", "1", "-o",
                          "d1/is-graphs/seed-1", "--threads", "1", "-q", "--start-pose", "truth"));
  try {
    suiteOf(R"({"format": "isg.suite", "version": 1, "worlds": ["builtin:d1"],
        "methods": ["is-graphs"], "seeds": [1], "run": {"start_pose": "1,2,0"}})");
    FAIL() << "a start pose in numbers was taken";
  } catch (const common::InputError& e) {
    EXPECT_THAT(e.what(), HasSubstr("/run/start_pose: must be \"truth\" (isg run --start-pose "
                                    "truth: each world's own first pose)"));
  }
}

TEST(SweepLibrary, SweepJsonReadsBackItsCells) {
  const Suite suite = suiteOf(R"({"format": "isg.suite", "version": 1, "name": "s",
      "worlds": ["builtin:d1"], "methods": ["odometry"], "seeds": [1, 2]})");
  const std::vector<SweepCell> cells = sweepCells(suite);
  const nlohmann::json written = nlohmann::json::parse(sweepPlanJson(suite, cells));
  const common::JsonSource source{"sweep.json", nullptr};
  const SweepPlan plan = parseSweepPlan(common::JsonNode(written, "", source));
  ASSERT_EQ(plan.cells.size(), 2u);
  EXPECT_EQ(plan.cells[1].dir, cells[1].dir);
  EXPECT_EQ(plan.cells[1].arguments, cells[1].arguments);
  // What made its runs: the build, and each method's options as its runs use them.
  EXPECT_EQ(written["build_version"], common::buildVersion());
  EXPECT_EQ(written["method_options"], nlohmann::json({{"odometry", nlohmann::json::object()}}));
}

TEST(SweepLibrary, SweepJsonRecordsEachMethodsOptionsWithTheirDefaults) {
  const Suite suite = suiteOf(R"({"format": "isg.suite", "version": 1, "name": "s",
      "worlds": ["builtin:d1"], "methods": ["amcl", "is-graphs"], "seeds": [1],
      "run": {"method_options": {"amcl": {"particles": 3000}}}})");
  const nlohmann::json written =
      nlohmann::json::parse(sweepPlanJson(suite, sweepCells(suite)))["method_options"];
  EXPECT_EQ(written["amcl"]["particles"], 3000.0);
  EXPECT_EQ(written["amcl"]["min_particles"], 500.0);  // nav2's default, not given
  EXPECT_EQ(written["is-graphs"], nlohmann::json::object());
}

TEST(SweepLibrary, AWorldNamedAfterAFileOfTheSweepIsRefused) {
  try {
    suiteOf(R"({"format": "isg.suite", "version": 1, "worlds": ["builtin:d1", "builtin:d1"],
        "methods": ["odometry"], "seeds": [1]})");
    FAIL();
  } catch (const common::InputError& e) {
    EXPECT_THAT(e.what(), HasSubstr("/worlds/1: a second world named \"d1\""));
  }
}

TEST(SweepLibrary, SlurmArraysSplitAtTheSitesMaxArraySize) {
  const auto arrays = slurmArrays(2500, 1001);
  ASSERT_EQ(arrays.size(), 3u);
  EXPECT_EQ(arrays[0].offset, 0u);
  EXPECT_EQ(arrays[0].count, 1001u);
  EXPECT_EQ(arrays[1].offset, 1001u);
  EXPECT_EQ(arrays[2].offset, 2002u);
  EXPECT_EQ(arrays[2].count, 498u);
  EXPECT_TRUE(slurmArrays(0, 1001).empty());
  EXPECT_EQ(slurmArrays(3, 0).size(), 3u);  // a size of 0 is taken as 1
  EXPECT_EQ(sbatchCommand("/s/it's.sbatch", arrays[2], "--parsable"),
            "sbatch --parsable --array=0-497 '/s/it'\\''s.sbatch' 2002");
}

TEST(SweepLibrary, ATablesWorldIsItsShortName) {
  EXPECT_EQ(shortWorld("builtin:d3.asbuilt"), "d3.asbuilt");
  EXPECT_EQ(shortWorld("plans/w.json"), "plans/w.json");
}

}  // namespace
}  // namespace isg::sweep
