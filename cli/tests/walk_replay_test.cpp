#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <numbers>
#include <string>

#include "cli/tests/cli_runner.hpp"
#include "common/angles.hpp"
#include "common/tum.hpp"
#include "sensors/mount_transform.hpp"

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
  const auto given =
      sandbox.run("run walk.json --threads 2 --start-pose truth -q -o g --submission sub");
  ASSERT_EQ(given.exit_code, 0) << given.err;
  const auto scored = nlohmann::json::parse(sandbox.read("g/metrics.json"));
  const double run_score = scored["floor_plan_score"]["score"].get<double>();
  EXPECT_GT(run_score, 95.0);
  // The submission: the estimate at the walk's own stamps, in its clock, named after its file;
  // scored by isg eval --floor-plan-score as the run scored itself, give or take the walk's
  // smoothing (the run is scored against the path walked, the file against the file).
  const common::Trajectory submitted = common::parseTum(sandbox.read("sub/walk.txt"), "walk.txt");
  EXPECT_EQ(sandbox.read("sub/walk.txt").rfind("# written by isg\n# timestamp tx ty tz", 0), 0u);
  EXPECT_GE(submitted.size(), file.size() - 2);
  EXPECT_NEAR(submitted.back().t, file.back().t, 1e-6);
  const auto score = sandbox.run("eval --floor-plan-score walk.tum sub/walk.txt --json");
  ASSERT_EQ(score.exit_code, 0) << score.err;
  const auto benchmark = nlohmann::json::parse(score.out)["floor_plan_score"];
  EXPECT_GE(benchmark["coverage"].get<double>(), 0.99);
  EXPECT_NEAR(benchmark["score"].get<double>(), run_score, 1.0);

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
  // D1's outer wall W1 runs from (0, 0) to (12, 0), 0.3 m thick: the step from (2.5, 1) to
  // (3, 0.05) enters it 2 cm deep at y = 0.13 (the first point of the step 2 cm apart inside).
  EXPECT_EQ(refused("# a walk\n0 2 2 0 0 0 0 1\n1 2.5 1 0 0 0 0 1\n2 3 0.05 0 0 0 0 1\n", "",
                    "{\"trajectory\": \"walk.tum\", \"crossed\": \"refuse\"}"),
            "isg run: error: walk.tum: line 4: the walk at (2.963, 0.120) is inside wall \"W1\" "
            "on level \"L0\" as built (is the walk in the plan frame of robot.level? a wall not "
            "built yet goes in as_built.missing_walls, one built in part in "
            "as_built.shortened_walls)\n");
  EXPECT_EQ(refused("0 2 2 0 0 0 0 1\n1 2.5 2 0 0 0 0 1\n", "",
                    "{\"trajectory\": \"walk.tum\", \"crossed\": \"through\"}"),
            "isg run: error: s.json: /robot/route/crossed: unknown value \"through\" (expected "
            "\"not_built\", \"opening\" or \"refuse\")\n");
  EXPECT_EQ(refused("", "", "{\"rooms\": [\"R1\"], \"crossed\": \"opening\"}"),
            "isg run: error: s.json: /robot/route/crossed: \"crossed\" goes with \"trajectory\" "
            "only\n");
  EXPECT_EQ(refused("0 2 2 0 0 0 0 1\n0.1 2.8 2 0 0 0 0 1\n"),
            "isg run: error: walk.tum: line 2: the walk moves 0.800 m in 0.100 s since line 1 "
            "(8.0 m/s; nobody carries a sensor faster than 6 m/s: a jump, or a pose in another "
            "frame?)\n");
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
  sandbox.write("walk.tum", "0 3 1.1 0 0 0 0 1\n1 3 2.2 0 0 0 0 1\n2 3 3.3 0 0 0 0 1\n");
  const auto scenario = [](const std::string& crossed, const std::string& as_built = "") {
    std::string text = scenarioWith(
        "d1", "handheld",
        "{\"trajectory\": \"walk.tum\"" +
            (crossed.empty() ? std::string() : ", \"crossed\": \"" + crossed + "\"") + "}");
    if (as_built.empty()) return text;
    text.pop_back();
    return text + ", \"as_built\": " + as_built + "}";
  };
  // Listed as missing, it is walked through whatever the route says.
  sandbox.write("missing.json", scenario("refuse", "{\"missing_walls\": [\"W5\"]}"));
  const auto listed = sandbox.run("simulate missing.json -q -o d");
  EXPECT_EQ(listed.exit_code, 0) << listed.err;
  EXPECT_EQ(listed.err.find("crosses"), std::string::npos) << listed.err;

  // By default a planned wall the walk crosses was not built on the day: said, and in the truth.
  sandbox.write("default.json", scenario(""));
  const auto taken = sandbox.run("simulate default.json -q -o n");
  ASSERT_EQ(taken.exit_code, 0) << taken.err;
  EXPECT_EQ(taken.err,
            "isg simulate: warning: default.json: /robot/route/trajectory: walk.tum: the walk "
            "crosses wall \"W5\" at (3.000, 2.200) (lines 2–3): taken as not built yet on the "
            "day of the walk\n");
  const auto metadata = nlohmann::json::parse(sandbox.read("n/metadata.json"));
  EXPECT_EQ(metadata["as_built"]["missing_walls"], nlohmann::json::array({"W5"}));
  EXPECT_EQ(metadata["robot"]["trajectory"]["crossed"],
            nlohmann::json::parse(R"({"mode": "not_built", "passes": [{"element": "W5",
                "kind": "wall", "taken_as": "not_built", "at": [3.0, 2.2], "lines": [2, 3]}]})"));

  // As an opening: a door-wide gap (0.9 m) about where it crossed, the rest of W5 standing.
  sandbox.write("opening.json", scenario("opening"));
  const auto opened = sandbox.run("simulate opening.json -q -o o");
  ASSERT_EQ(opened.exit_code, 0) << opened.err;
  EXPECT_NE(opened.err.find("taken as built with a door-wide opening where it was crossed"),
            std::string::npos);
  const auto opened_metadata = nlohmann::json::parse(sandbox.read("o/metadata.json"));
  const auto& parts = opened_metadata["as_built"]["shortened_walls"][0];
  EXPECT_EQ(parts["wall"], "W5");
  ASSERT_EQ(parts["built"].size(), 2u);
  EXPECT_NEAR(parts["built"][0][1].get<double>(), 2.55, 1e-9);
  EXPECT_NEAR(parts["built"][1][0].get<double>(), 3.45, 1e-9);

  // Refused, as before the walk crossed walls: at the first point of its step 2 cm inside.
  sandbox.write("built.json", scenario("refuse"));
  const auto refused = sandbox.run("simulate built.json -q -o e");
  EXPECT_EQ(refused.exit_code, 1);
  EXPECT_NE(refused.err.find("walk.tum: line 2: the walk at (3.000, 2.160) is inside wall \"W5\""),
            std::string::npos)
      << refused.err;
  // Built in part (W5 runs (0, 2.2) → (12, 2.2)): through its gap from 2.6 to 3.6 m the walk
  // passes; with the gap from 1.5 to 2.5 m it meets the second part.
  const auto shortened = [&](const std::string& built) {
    return scenario("refuse",
                    "{\"shortened_walls\": [{\"wall\": \"W5\", \"built\": " + built + "}]}");
  };
  sandbox.write("gap.json", shortened("[[0, 2.6], [3.6, 12]]"));
  const auto through = sandbox.run("simulate gap.json -q -o f");
  EXPECT_EQ(through.exit_code, 0) << through.err;
  sandbox.write("beside.json", shortened("[[0, 1.5], [2.5, 12]]"));
  const auto beside = sandbox.run("simulate beside.json -q -o g");
  EXPECT_EQ(beside.exit_code, 1);
  EXPECT_NE(beside.err.find("walk.tum: line 2: the walk at (3.000, 2.160) is inside wall \"W5#2\""),
            std::string::npos)
      << beside.err;
}

TEST(WalkReplay, AColumnInTheWayWasNotBuiltYet) {
  testing::Sandbox sandbox("walk_replay_columns");
  // A 10 × 6 m hall with a round column at (3, 3) and a square one at (6, 3), walked along y = 3.
  sandbox.write("hall.json", R"({"format": "isg.plan", "version": 1, "levels": [{"id": "L0",
      "elevation": 0, "height": 3, "walls": [
      {"id": "S", "start": [0, 0], "end": [10, 0], "thickness": 0.2},
      {"id": "E", "start": [10, 0], "end": [10, 6], "thickness": 0.2},
      {"id": "N", "start": [10, 6], "end": [0, 6], "thickness": 0.2},
      {"id": "W", "start": [0, 6], "end": [0, 0], "thickness": 0.2}],
      "columns": [{"id": "C1", "center": [3, 3], "diameter": 0.4},
                  {"id": "C2", "center": [6, 3], "size": [0.4, 0.4]}],
      "rooms": [{"id": "H", "outline": [[0.1, 0.1], [9.9, 0.1], [9.9, 5.9], [0.1, 5.9]]}]}]})");
  std::string walk;
  for (int i = 0; i <= 16; ++i)
    walk += std::to_string(0.5 * i) + " " + std::to_string(1 + 0.5 * i) + " 3 0 0 0 0 1\n";
  sandbox.write("walk.tum", walk);
  for (const std::string mode : {"not_built", "opening"}) {
    sandbox.write("s.json",
                  "{\"format\": \"isg.scenario\", \"version\": 1, \"plan\": "
                  "\"hall.json\", \"robot\": {\"carrier\": \"handheld\", \"route\": "
                  "{\"trajectory\": \"walk.tum\", \"crossed\": \"" +
                      mode + "\"}}}");
    const auto run = sandbox.run("simulate s.json -q --force -o d");
    ASSERT_EQ(run.exit_code, 0) << run.err;
    // A column has no opening: in either mode it was not built.
    EXPECT_EQ(run.err,
              "isg simulate: warning: s.json: /robot/route/trajectory: walk.tum: the walk crosses "
              "column \"C1\" at (3.000, 3.000) (lines 5–6): taken as not built yet on the day of "
              "the walk\n"
              "isg simulate: warning: s.json: /robot/route/trajectory: walk.tum: the walk crosses "
              "column \"C2\" at (6.000, 3.000) (lines 11–12): taken as not built yet on the day "
              "of the walk\n");
    const auto metadata = nlohmann::json::parse(sandbox.read("d/metadata.json"));
    EXPECT_EQ(metadata["as_built"]["missing_columns"], nlohmann::json::array({"C1", "C2"}));
    const auto& passes = metadata["robot"]["trajectory"]["crossed"]["passes"];
    ASSERT_EQ(passes.size(), 2u);
    EXPECT_EQ(passes[0]["kind"], "column");
    EXPECT_EQ(passes[1]["taken_as"], "not_built");
  }
}

TEST(WalkReplay, ASingleGlitchIsBridgedAndSaidAJumpRefused) {
  testing::Sandbox sandbox("walk_replay_glitch");
  // Along D1's corridor (y 1.1) at 0.5 m/s, 10 Hz; line 12 (t 1.0) is 3 m off: a glitch.
  const auto walkWith = [](const std::vector<int>& off_lines) {
    std::string walk;
    char line[96];
    for (int i = 0; i <= 60; ++i) {
      const bool off = std::find(off_lines.begin(), off_lines.end(), i + 2) != off_lines.end();
      std::snprintf(line, sizeof line, "%.1f %.3f %.3f 0 0 0 0 1\n", 0.1 * i, 1.0 + 0.05 * i,
                    off ? 4.1 : 1.1);
      walk += line;
    }
    return "# a walk\n" + walk;
  };
  sandbox.write("s.json", scenarioWith("d1", "handheld", "{\"trajectory\": \"walk.tum\"}"));
  sandbox.write("walk.tum", walkWith({12}));
  const auto bridged = sandbox.run("simulate s.json -q -o d");
  ASSERT_EQ(bridged.exit_code, 0) << bridged.err;
  EXPECT_EQ(bridged.err,
            "isg simulate: warning: s.json: /robot/route/trajectory: walk.tum: line 12: a single "
            "pose 3.000 m off the walk (lines 11 and 13 agree): left out, the walk bridged across "
            "it\n");
  EXPECT_EQ(nlohmann::json::parse(sandbox.read("d/metadata.json"))["robot"]["trajectory"]["poses"],
            60);
  // Two in a row are a jump: refused, naming the first.
  sandbox.write("walk.tum", walkWith({12, 13}));
  const auto jump = sandbox.run("simulate s.json -q -o e");
  EXPECT_EQ(jump.exit_code, 1);
  EXPECT_EQ(jump.err,
            "isg simulate: error: walk.tum: line 12: the walk moves 3.000 m in 0.100 s since line "
            "11 (30.0 m/s; nobody carries a sensor faster than 6 m/s: a jump, or a pose in another "
            "frame?)\n");
}

// A walk as the floor-plan benchmark gives one: a camera's path at 33 Hz in the benchmark's clock
// (from 10 003.2 s), named after its run, with one glitched pose, through a partition the plan
// has and the site had not built yet (WX across D3's corridor, which the walk crosses 3 times).
TEST(WalkReplay, ARecordedLookingWalkThroughAPlannedWallReplaysAndScores) {
  testing::Sandbox sandbox("walk_replay_site");
  const auto made = sandbox.run("simulate builtin:d3.handheld --duration 90 -q -o tour");
  ASSERT_EQ(made.exit_code, 0) << made.err;
  nlohmann::json plan =
      nlohmann::json::parse(sandbox.read(std::string(ISG_SOURCE_DIR) + "/worlds/plans/d3.json"));
  plan.erase("$schema");
  plan["levels"][0]["walls"].push_back(
      {{"id", "WX"}, {"start", {9.5, 4}}, {"end", {9.5, 6}}, {"thickness", 0.15}});
  sandbox.write("d3x.json", plan.dump());
  const common::Trajectory truth =
      common::readTum((sandbox.dir() / "tour/groundtruth.tum").string());
  common::Trajectory walk, glitched;
  for (std::size_t i = 0; i < truth.size(); i += 3) {
    walk.push_back(truth[i]);
    walk.back().t += 10003.2;
  }
  glitched = walk;
  glitched[1500].pose.translation().x() += 2.0;
  sandbox.write("clean.txt", common::toTumText(walk));
  sandbox.write("floor_8_2026-01-01_run_1.txt", common::toTumText(glitched));
  sandbox.write("x.json",
                "{\"format\": \"isg.scenario\", \"version\": 1, \"plan\": \"d3x.json\", "
                "\"robot\": {\"carrier\": \"handheld\", \"route\": {\"trajectory\": "
                "\"floor_8_2026-01-01_run_1.txt\"}}}");
  const auto run =
      sandbox.run("run x.json --start-pose truth --threads 2 -q -o r --submission entry");
  ASSERT_EQ(run.exit_code, 0) << run.err;
  EXPECT_NE(run.err.find("line 1501: a single pose 2.000 m off the walk"), std::string::npos)
      << run.err;
  EXPECT_NE(run.err.find("the walk crosses wall \"WX\" at (9.50"), std::string::npos) << run.err;
  EXPECT_NE(run.err.find("taken as not built yet on the day of the walk"), std::string::npos);
  // The run's truth has WX as not built (the report draws it so), and its as-built report finds
  // it missing: graded found against that truth.
  EXPECT_NE(sandbox.read("r/report.svg").find("wall not built"), std::string::npos);
  const auto metrics = nlohmann::json::parse(sandbox.read("r/metrics.json"));
  EXPECT_EQ(metrics["deviations"]["graded"]["missing"]["found"].get<int>(), 1);
  EXPECT_EQ(metrics["deviations"]["graded"]["false_reports"].get<int>(), 0);
  const auto deviations = nlohmann::json::parse(sandbox.read("r/deviations.json"));
  bool found_missing = false;
  for (const auto& wall : deviations["walls"]) {
    if (wall["wall"] == "WX") found_missing = wall["status"] == "missing";
  }
  EXPECT_TRUE(found_missing);
  // Given its start: every stamp of the recording estimated, the glitch's too; score ≥ 97.
  EXPECT_EQ(metrics["time_wrongly_localized"].get<double>(), 0.0);
  const auto score =
      sandbox.run("eval --floor-plan-score clean.txt entry/floor_8_2026-01-01_run_1.txt --json");
  ASSERT_EQ(score.exit_code, 0) << score.err;
  const auto scored = nlohmann::json::parse(score.out)["floor_plan_score"];
  EXPECT_DOUBLE_EQ(scored["coverage"].get<double>(), 1.0);
  EXPECT_GE(scored["score"].get<double>(), 97.0);
}

// Started as the benchmark starts a run: the camera's pose at about 10 005 s from its start pose
// table (another run's row first, written as the benchmark writes some: blanks after commas).
void startsFromItsTableRow(testing::Sandbox& sandbox, const common::Trajectory& camera) {
  const auto at = std::find_if(camera.begin(), camera.end(),
                               [](const common::StampedPose& p) { return p.t >= 10005.0; });
  ASSERT_NE(at, camera.end());
  const Eigen::Quaterniond q(at->pose.linear());
  char row[300];
  std::snprintf(
      row, sizeof row,
      "floor_7_2026-01-01_run_1,floor_7.png,%.9f,%.9f,%.9f,%.9f,%.12f,%.12f,%.12f,%.12f\n", at->t,
      at->pose.translation().x(), at->pose.translation().y(), at->pose.translation().z(), q.x(),
      q.y(), q.z(), q.w());
  sandbox.write("starts.csv",
                "#Sequence Name,Floor Plan,timestamp,tx,ty,tz,qx,qy,qz,qw\n"
                "floor_6_2026-01-01_run_1,floor_6.png,10005.0, 1, 2, 1, 0, 0, 0, 1\n" +
                    std::string(row));
  const auto given =
      sandbox.run("run c.json --start-pose starts.csv --threads 2 -o r2 --submission e2");
  ASSERT_EQ(given.exit_code, 0) << given.err;
  char words[160];
  std::snprintf(words, sizeof words,
                "starting localized at the start pose of floor_7_2026-01-01_run_1 (starts.csv line "
                "3) at %.3f s",
                at->t - camera.front().t);
  EXPECT_NE(given.err.find(words), std::string::npos) << given.err;
  const auto started = nlohmann::json::parse(sandbox.read("r2/metrics.json"));
  // Taken at the first keyframe from its stamp on, matched nowhere before it.
  const auto& first = started["matching_events"][0];
  EXPECT_EQ(first["reason"], "the start pose given");
  EXPECT_GE(first["stamp"].get<double>(), at->t - camera.front().t - 0.1);
  EXPECT_LT(first["stamp"].get<double>(), at->t - camera.front().t + 1.0);
  EXPECT_EQ(started["time_wrongly_localized"].get<double>(), 0.0);
  EXPECT_LT(started["ape_B"]["rmse"].get<double>(), 0.03);
  const auto rescored = sandbox.run(
      "eval --floor-plan-score floor_7_2026-01-01_run_1.txt e2/floor_7_2026-01-01_run_1.txt "
      "--json");
  ASSERT_EQ(rescored.exit_code, 0) << rescored.err;
  const auto entry = nlohmann::json::parse(rescored.out)["floor_plan_score"];
  EXPECT_GE(entry["coverage"].get<double>(), 0.99);
  EXPECT_GE(entry["score"].get<double>(), 97.0);
  // A row of another clock: said, nothing run.
  sandbox.write("late.csv", "floor_7_2026-01-01_run_1,floor_7.png,20005,1,2,1,0,0,0,1\n");
  const auto late = sandbox.run("run c.json --start-pose late.csv -q -o r3");
  EXPECT_EQ(late.exit_code, 1);
  EXPECT_NE(late.err.find("late.csv: line 1: the start pose's stamp 20005.000000 is not within "
                          "the run (the walk's clock 10003.200000 … "),
            std::string::npos)
      << late.err;
  EXPECT_FALSE(std::filesystem::exists(sandbox.dir() / "r3"));
}

// A camera's path (the benchmark's references are cam0's): the camera 10 cm ahead of the tour's
// base R, 15 cm up, a camera's frame (x left, y up, z ahead). Replayed with the LiDAR stated on its
// rig, the LiDAR goes where it went on the tour, and the entry is the camera's.
TEST(WalkReplay, ACameraPathIsFollowedExactlyWithTheLidarOnItsRig) {
  testing::Sandbox sandbox("walk_replay_camera");
  const auto made = sandbox.run("simulate builtin:d3.handheld --duration 60 -q -o tour");
  ASSERT_EQ(made.exit_code, 0) << made.err;
  Eigen::Isometry3d R_T_C = Eigen::Isometry3d::Identity();
  R_T_C.translation() = Eigen::Vector3d(0.1, -0.05, 0.15);
  R_T_C.linear() << 0, 0, 1, 1, 0, 0, 0, 1, 0;              // x left, y up, z ahead
  Eigen::Isometry3d R_T_L = Eigen::Isometry3d::Identity();  // the default mount
  R_T_L.translation() = Eigen::Vector3d(0.0, 0.0, 0.25);
  const common::Trajectory truth =
      common::readTum((sandbox.dir() / "tour/groundtruth.tum").string());
  common::Trajectory camera;
  for (std::size_t i = 0; i < truth.size(); i += 3) {
    camera.push_back({truth[i].t + 10003.2, truth[i].pose * R_T_C});
  }
  sandbox.write("floor_7_2026-01-01_run_1.txt", common::toTumText(camera));
  const auto rig = sensors::mountXyzRpy(R_T_C.inverse() * R_T_L);
  char rig_text[200];
  std::snprintf(rig_text, sizeof rig_text, "[%.9f, %.9f, %.9f, %.9f, %.9f, %.9f]", rig[0], rig[1],
                rig[2], rig[3], rig[4], rig[5]);
  sandbox.write("c.json", scenarioWith("d3", "handheld",
                                       "{\"trajectory\": \"floor_7_2026-01-01_run_1.txt\", "
                                       "\"orientation\": \"file\", \"rig\": " +
                                           std::string(rig_text) + "}"));
  const auto run = sandbox.run("run c.json --start-pose truth --threads 2 -q -o r --submission e");
  ASSERT_EQ(run.exit_code, 0) << run.err;
  // The base is where the tour's was, within the fit's millimetres (the file's z used: the
  // camera's height, not the carrier's).
  const common::Trajectory replayed =
      common::readTum((sandbox.dir() / "r/groundtruth.tum").string());
  std::vector<double> offsets;
  std::size_t k = 0;
  for (const auto& pose : truth) {
    if (pose.t < 0.5 || pose.t > replayed.back().t - 0.5) continue;
    while (k + 1 < replayed.size() && replayed[k + 1].t <= pose.t + 1e-9) ++k;
    if (std::abs(replayed[k].t - pose.t) > 1e-6) continue;
    offsets.push_back((replayed[k].pose.translation() - pose.pose.translation()).norm());
  }
  ASSERT_GT(offsets.size(), 1000u);
  std::nth_element(offsets.begin(), offsets.begin() + offsets.size() / 2, offsets.end());
  EXPECT_LT(offsets[offsets.size() / 2], 0.005);
  const auto metrics = nlohmann::json::parse(sandbox.read("r/metrics.json"));
  EXPECT_EQ(metrics["time_wrongly_localized"].get<double>(), 0.0);
  EXPECT_LT(metrics["ape_B"]["rmse"].get<double>(), 0.03);
  // The entry is the camera's path: scored against the file as the benchmark would.
  const auto score = sandbox.run(
      "eval --floor-plan-score floor_7_2026-01-01_run_1.txt e/floor_7_2026-01-01_run_1.txt --json");
  ASSERT_EQ(score.exit_code, 0) << score.err;
  const auto scored = nlohmann::json::parse(score.out)["floor_plan_score"];
  EXPECT_GE(scored["coverage"].get<double>(), 0.99);
  EXPECT_GE(scored["score"].get<double>(), 97.0);

  startsFromItsTableRow(sandbox, camera);
}

// A start pose table needs a replayed walk (its stamps are a recording's); a method given its
// start by the truth takes none without odometry to carry it back to the run's start.
TEST(WalkReplay, AStartPoseTableWithoutARecordingIsRefused) {
  testing::Sandbox sandbox("walk_replay_table_refused");
  sandbox.write("t.csv", "d1,d1.png,5,1,1,0,0,0,0,1\n");
  const auto tour = sandbox.run("run builtin:d1 --duration 5 -q -o r --start-pose t.csv:d1");
  EXPECT_EQ(tour.exit_code, 1);
  EXPECT_NE(tour.err.find("--start-pose: a start pose table (t.csv) is read for a replayed walk"),
            std::string::npos)
      << tour.err;
  const auto option = sandbox.run("run builtin:d1 --duration 5 -q -o r --start-pose t.txt:d1");
  EXPECT_EQ(option.exit_code, 2);  // a usage error, as every option check
  EXPECT_NE(option.err.find("expected X,Y,YAW (three numbers), 'truth' or FILE.csv[:SEQUENCE]"),
            std::string::npos)
      << option.err;
}

TEST(WalkReplay, ASensorsSwingIsAcceptedAJumpRefused) {
  testing::Sandbox sandbox("walk_replay_swing");
  // Along D1's corridor (y 1.1) at 0.8 m/s, 10 Hz, with 1 s at 3.5 m/s (a camera swung round
  // as its walker turns), or one step of 0.8 m in 0.1 s (a jump).
  const auto walkWith = [](double fast_speed) {
    std::string walk;
    char line[96];
    double x = 1.0;
    for (int i = 0; i <= 80; ++i) {
      std::snprintf(line, sizeof line, "%.1f %.3f 1.1 0 0 0 0 1\n", 0.1 * i, x);
      walk += line;
      x += 0.1 * (i >= 30 && i < 30 + (fast_speed > 5 ? 1 : 10) ? fast_speed : 0.8);
    }
    return walk;
  };
  const auto run = [&](const std::string& route) {
    sandbox.write("s.json", scenarioWith("d1", "handheld", route));
    return sandbox.run("simulate s.json -q --force -o d");
  };
  // A recorded path is a sensor's: its swing is replayed, as a body's path (smoothed) or as a
  // sensor's (exactly).
  sandbox.write("walk.tum", walkWith(3.5));
  const auto body = run("{\"trajectory\": \"walk.tum\"}");
  EXPECT_EQ(body.exit_code, 0) << body.err;
  EXPECT_EQ(
      nlohmann::json::parse(sandbox.read("d/metadata.json"))["robot"]["trajectory"]["path_of"],
      "body");
  const auto sensor = run("{\"trajectory\": \"walk.tum\", \"orientation\": \"file\"}");
  ASSERT_EQ(sensor.exit_code, 0) << sensor.err;
  const auto metadata = nlohmann::json::parse(sandbox.read("d/metadata.json"));
  EXPECT_EQ(metadata["robot"]["trajectory"]["path_of"], "sensor");
  EXPECT_EQ(metadata["robot"]["trajectory"]["rig"], nlohmann::json::parse("[0,0,0,0,0,0]"));
  sandbox.write("walk.tum", walkWith(8.0));
  const auto jump = run("{\"trajectory\": \"walk.tum\", \"orientation\": \"file\"}");
  EXPECT_EQ(jump.exit_code, 1);
  EXPECT_NE(jump.err.find("(8.0 m/s; nobody carries a sensor faster than 6 m/s"), std::string::npos)
      << jump.err;
  // A sensor's path carries its orientation; a rig goes with a sensor's path.
  const auto travel =
      run("{\"trajectory\": \"walk.tum\", \"orientation\": \"travel\", \"path_of\": \"sensor\"}");
  EXPECT_EQ(travel.err,
            "isg simulate: error: s.json: /robot/route/path_of: a sensor's path carries its "
            "orientation: give \"orientation\": \"file\" with it\n");
  const auto rigged =
      run("{\"trajectory\": \"walk.tum\", \"path_of\": \"body\", \"rig\": [0, 0, 0, 0, 0, 0]}");
  EXPECT_EQ(rigged.err,
            "isg simulate: error: s.json: /robot/route/rig: \"rig\" goes with a sensor's path "
            "(\"path_of\": \"sensor\")\n");
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
