#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <numbers>
#include <string>

#include "cli/tests/cli_runner.hpp"
#include "common/angles.hpp"
#include "common/tum.hpp"

namespace isg::cli {
namespace {

std::string scenarioWith(const std::string& plan, const std::string& carrier,
                         const std::string& route, const std::string& robot_extra = "") {
  std::string text = "{\"format\": \"isg.scenario\", \"version\": 1, \"seed\": 1, \"plan\": \"";
  text += std::string(ISG_SOURCE_DIR) + "/worlds/plans/" + plan + ".json\", \"robot\": {";
  text += "\"carrier\": \"" + carrier + "\", \"route\": " + route + robot_extra + "}}";
  return text;
}

// A walk as a lab records it: the truth of a simulated hand-held tour, every tenth pose (10 Hz),
// on a Unix epoch clock.
std::string recordedWalk(const testing::Sandbox& sandbox, const std::string& truth_file) {
  const common::Trajectory truth = common::readTum((sandbox.dir() / truth_file).string());
  common::Trajectory walk;
  for (std::size_t i = 0; i < truth.size(); i += 10) {
    walk.push_back(truth[i]);
    walk.back().t += 1.7e9;
  }
  return common::toTumText(walk);
}

TEST(WalkReplay, ARecordedWalkIsFollowedAndLocalizedOn) {
  testing::Sandbox sandbox("walk_replay");
  const auto made = sandbox.run("simulate builtin:d3.handheld --duration 60 -q -o tour");
  ASSERT_EQ(made.exit_code, 0) << made.err;
  sandbox.write("walk.tum", recordedWalk(sandbox, "tour/groundtruth.tum"));
  sandbox.write("walk.json", scenarioWith("d3", "handheld", "{\"trajectory\": \"walk.tum\"}"));
  const auto run = sandbox.run("run walk.json --threads 2 -q -o r");
  ASSERT_EQ(run.exit_code, 0) << run.err;
  const auto metrics = nlohmann::json::parse(sandbox.read("r/metrics.json"));
  EXPECT_TRUE(metrics["localized"].get<bool>());
  EXPECT_EQ(metrics["time_wrongly_localized"].get<double>(), 0.0);
  EXPECT_LT(metrics["ape_B"]["rmse"].get<double>(), 0.03);
  // The replayed carrier is where the file says at the file's times (made relative to its first):
  // within the walker's own sway (2.5 cm, added on the recorded one) and the path's smoothing.
  const common::Trajectory file = common::parseTum(sandbox.read("walk.tum"), "walk.tum");
  const common::Trajectory replayed =
      common::readTum((sandbox.dir() / "r/groundtruth.tum").string());
  ASSERT_GT(replayed.size(), 100u);
  EXPECT_NEAR(replayed.back().t, file.back().t - file.front().t, 0.1);
  double worst = 0.0;
  std::size_t k = 0;
  for (const auto& pose : file) {
    const double t = pose.t - file.front().t;
    while (k + 1 < replayed.size() && replayed[k + 1].t <= t + 1e-9) ++k;
    if (std::abs(replayed[k].t - t) > 1e-6) continue;
    worst = std::max(worst,
                     (replayed[k].pose.translation() - pose.pose.translation()).head<2>().norm());
  }
  EXPECT_LT(worst, 0.06);
  EXPECT_GT(worst, 0.0);

  // Given its first pose, the challenge's score is above 95.
  const auto given = sandbox.run("run walk.json --threads 2 --start-pose truth -q -o g");
  ASSERT_EQ(given.exit_code, 0) << given.err;
  const auto scored = nlohmann::json::parse(sandbox.read("g/metrics.json"));
  EXPECT_GT(scored["floor_plan_score"]["score"].get<double>(), 95.0);

  // A legged base facing the file's yaw: its heading is the file's, give or take the smoothing.
  sandbox.write("legged.json", scenarioWith("d3", "legged",
                                            "{\"trajectory\": \"walk.tum\", "
                                            "\"orientation\": \"file\"}"));
  const auto legged = sandbox.run("simulate legged.json --duration 30 -q -o l");
  ASSERT_EQ(legged.exit_code, 0) << legged.err;
  const auto metadata = nlohmann::json::parse(sandbox.read("l/metadata.json"));
  EXPECT_EQ(metadata["robot"]["trajectory"]["orientation"], "file");
  EXPECT_EQ(metadata["robot"]["trajectory"]["poses"].get<int>(), int(file.size()));
  EXPECT_LT(metadata["robot"]["trajectory"]["deviation_median_m"].get<double>(), 0.01);
  const common::Trajectory truth = common::readTum((sandbox.dir() / "l/groundtruth.tum").string());
  std::vector<double> errors;
  k = 0;
  for (const auto& pose : file) {
    const double t = pose.t - file.front().t;
    if (t > 29.0) break;
    while (k + 1 < truth.size() && truth[k + 1].t <= t + 1e-9) ++k;
    errors.push_back(std::abs(common::wrapAngle(common::yawOf(truth[k].pose.linear()) -
                                                common::yawOf(pose.pose.linear()))));
  }
  std::nth_element(errors.begin(), errors.begin() + errors.size() / 2, errors.end());
  EXPECT_LT(errors[errors.size() / 2] * 180 / std::numbers::pi, 2.0);
}

TEST(WalkReplay, AWalkThatCannotBeWalkedIsRefusedNamingItsLine) {
  testing::Sandbox sandbox("walk_replay_bad");
  const auto refused = [&](const std::string& walk, const std::string& robot_extra = "",
                           const std::string& route = "{\"trajectory\": \"walk.tum\"}") {
    sandbox.write("walk.tum", walk);
    sandbox.write("s.json", scenarioWith("d1", "handheld", route, robot_extra));
    const auto run = sandbox.run("run s.json -q -o r");
    EXPECT_EQ(run.exit_code, 1);
    EXPECT_FALSE(sandbox.exists("r"));
    return run.err;
  };
  // D1's outer wall W1 runs from (0, 0) to (12, 0), 0.2 m thick: (3, 0.05) is inside it.
  EXPECT_EQ(refused("# a walk\n0 2 2 0 0 0 0 1\n1 2.5 1 0 0 0 0 1\n2 3 0.05 0 0 0 0 1\n"),
            "isg run: error: walk.tum: line 4: the walk at (3.000, 0.050) is inside wall \"W1\" "
            "on level \"L0\" as built (is the walk in the plan frame of robot.level? a wall not "
            "built yet goes in as_built.missing_walls, one built in part in "
            "as_built.shortened_walls)\n");
  EXPECT_EQ(refused("0 2 2 0 0 0 0 1\n0.1 2.5 2 0 0 0 0 1\n"),
            "isg run: error: walk.tum: line 2: the walk moves 0.500 m in 0.100 s since line 1 "
            "(5.0 m/s; at most 3 m/s is walked)\n");
  EXPECT_EQ(refused("0 2 2 0 0 0 0 1\n"),
            "isg run: error: walk.tum: one pose only: a walk needs two or more\n");
  EXPECT_EQ(refused("0 2 2 0 0 0 0 1\n1 2 x 0 0 0 0 1\n"),
            "isg run: error: walk.tum: line 2: field 3 (\"x\") is not a finite decimal number; "
            "expected 8 numbers: t tx ty tz qx qy qz qw\n");
  EXPECT_EQ(refused("0 2 2 0 0 0 0 1\n1 nan 2 0 0 0 0 1\n"),
            "isg run: error: walk.tum: line 2: field 2 (\"nan\") is not a finite decimal "
            "number; expected 8 numbers: t tx ty tz qx qy qz qw\n");
  EXPECT_EQ(refused("0 2 2 0 0 0 0 1\n1 2.5 2 0 0 0 0 1\n", ", \"start\": {\"room\": \"R1\"}"),
            "isg run: error: s.json: /robot/start: robot.start does not go with a trajectory "
            "route: it starts at its file's first pose\n");
  EXPECT_EQ(refused("", "", "{\"trajectory\": \"none.tum\"}"),
            "isg run: error: s.json: /robot/route/trajectory: trajectory file \"none.tum\" does "
            "not exist\n");
  EXPECT_EQ(refused("0 2 2 0 0 0 0 1\n1 2.5 2 0 0 0 0 1\n", "",
                    "{\"trajectory\": \"walk.tum\", \"orientation\": \"ahead\"}"),
            "isg run: error: s.json: /robot/route/orientation: unknown orientation \"ahead\" "
            "(expected \"travel\" or \"file\")\n");
  // Every pose is held while the run goes: a file beyond 64 MiB is refused before it is read (a
  // sparse file here: its size is all that is looked at).
  sandbox.write("s.json", scenarioWith("d1", "handheld", "{\"trajectory\": \"walk.tum\"}"));
  sandbox.write("walk.tum", "0 2 2 0 0 0 0 1\n");
  std::filesystem::resize_file(sandbox.dir() / "walk.tum", 65ull << 20);
  const auto huge = sandbox.run("run s.json -q -o r");
  EXPECT_EQ(huge.exit_code, 1);
  EXPECT_EQ(huge.err,
            "isg run: error: walk.tum: the walk's file is 68157440 bytes; at most 67108864 are "
            "read (docs/simulation.md, \"Replayed walks\"): thin it out (a pose every 0.01 s is "
            "plenty) or cut it\n");
  EXPECT_FALSE(sandbox.exists("r"));
}

TEST(WalkReplay, AWallNotBuiltYetIsWalkedThrough) {
  testing::Sandbox sandbox("walk_replay_missing");
  // From D1's corridor (y 1.1) north through W5 (y 2.2, no door at x = 3) into office R1.
  sandbox.write("walk.tum", "0 3 1.1 0 0 0 0 1\n2 3 2.2 0 0 0 0 1\n4 3 3.3 0 0 0 0 1\n");
  std::string scenario = scenarioWith("d1", "handheld", "{\"trajectory\": \"walk.tum\"}");
  scenario.pop_back();
  scenario += ", \"as_built\": {\"missing_walls\": [\"W5\"]}}";
  sandbox.write("s.json", scenario);
  const auto run = sandbox.run("simulate s.json -q -o d");
  EXPECT_EQ(run.exit_code, 0) << run.err;
  // The same walk with W5 built is refused at the pose in it.
  sandbox.write("built.json", scenarioWith("d1", "handheld", "{\"trajectory\": \"walk.tum\"}"));
  const auto refused = sandbox.run("simulate built.json -q -o e");
  EXPECT_EQ(refused.exit_code, 1);
  EXPECT_NE(refused.err.find("walk.tum: line 2: the walk at (3.000, 2.200) is inside wall \"W5\""),
            std::string::npos)
      << refused.err;
  // Built in part (W5 runs (0, 2.2) → (12, 2.2)): through its gap from 2.6 to 3.6 m the walk
  // passes; with the gap from 1.5 to 2.5 m it meets the second part.
  const auto shortened = [&](const std::string& built) {
    std::string text = scenarioWith("d1", "handheld", "{\"trajectory\": \"walk.tum\"}");
    text.pop_back();
    return text + ", \"as_built\": {\"shortened_walls\": [{\"wall\": \"W5\", \"built\": " + built +
           "}]}}";
  };
  sandbox.write("gap.json", shortened("[[0, 2.6], [3.6, 12]]"));
  const auto through = sandbox.run("simulate gap.json -q -o f");
  EXPECT_EQ(through.exit_code, 0) << through.err;
  sandbox.write("beside.json", shortened("[[0, 1.5], [2.5, 12]]"));
  const auto beside = sandbox.run("simulate beside.json -q -o g");
  EXPECT_EQ(beside.exit_code, 1);
  EXPECT_NE(beside.err.find("walk.tum: line 2: the walk at (3.000, 2.200) is inside wall \"W5#2\""),
            std::string::npos)
      << beside.err;
}

TEST(WalkReplay, AGapInTimeIsSaidAndWalkedAcross) {
  testing::Sandbox sandbox("walk_replay_gap");
  // Through D1's corridor at 0.5 m/s, with 3 s missing in the middle.
  std::string walk;
  char line[96];
  for (int i = 0; i <= 100; ++i) {
    if (i > 40 && i < 70) continue;
    std::snprintf(line, sizeof line, "%.1f %.3f 1.1 0 0 0 0 1\n", 0.1 * i, 1.0 + 0.05 * i);
    walk += line;
  }
  sandbox.write("walk.tum", walk);
  sandbox.write("s.json", scenarioWith("d1", "handheld", "{\"trajectory\": \"walk.tum\"}"));
  const auto run = sandbox.run("simulate s.json -q -o d");
  ASSERT_EQ(run.exit_code, 0) << run.err;
  EXPECT_NE(run.err.find("isg simulate: warning: s.json: /robot/route/trajectory: walk.tum: lines "
                         "41–42: 3.00 s without a pose; the walk is interpolated across the gap\n"),
            std::string::npos)
      << run.err;
  // Across the gap the walk goes on straight at its pace: at 5.5 s it is 2.75 m along.
  const common::Trajectory truth = common::readTum((sandbox.dir() / "d/groundtruth.tum").string());
  for (const auto& pose : truth) {
    if (std::abs(pose.t - 5.5) > 1e-6) continue;
    EXPECT_NEAR(pose.pose.translation().x(), 3.75, 0.03);
    EXPECT_NEAR(pose.pose.translation().y(), 1.1, 0.03);
  }
  EXPECT_NEAR(truth.back().t, 10.0, 1e-6);
}

}  // namespace
}  // namespace isg::cli
