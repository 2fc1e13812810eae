#include "run/run_metrics.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "common/input_error.hpp"

namespace isg::run {
namespace {

RunMetrics localizedRun() {
  RunMetrics m;
  m.world = "builtin:d1";
  m.method = "is-graphs";
  m.seed = 3;
  m.scans = 400;
  m.sim_seconds = 40.0;
  m.wall_seconds = 2.0;
  m.real_time_factor = 20.0;
  m.localized = true;
  m.time_to_localize = 14.5;
  m.distance_to_localize = 4.7;
  m.rooms_visited_to_localize = 2;
  m.share_localized = 0.64;
  Statistics s;
  s.count = 258;
  s.rmse = 0.028;
  s.max = 0.06;
  m.ape_B = s;
  m.ape_M_se3 = s;
  m.matching_status = "matched";
  m.matching_events = {{0.0, 0, slam::MatchStatus::kNotYet, "too little evidence"},
                       {14.5, 9, slam::MatchStatus::kMatched, "best"}};
  return m;
}

TEST(RunMetrics, JsonRoundTripKeepsEveryField) {
  const RunMetrics m = localizedRun();
  const nlohmann::json j = metricsToJson(m);
  EXPECT_EQ(j["ape_B"]["rmse"].get<double>(), 0.028);
  EXPECT_EQ(j["matching_events"][1]["keyframe"].get<int>(), 9);
  EXPECT_EQ(j["distance_to_localize"].get<double>(), 4.7);
  EXPECT_EQ(j["rooms_visited_to_localize"].get<int>(), 2);
  EXPECT_FALSE(j.contains("ape_B_rotation_deg"));
  const RunMetrics back = metricsFromJson(j, "metrics.json");
  EXPECT_EQ(metricsToJson(back), j);
}

// Every field of RunMetrics set to a value of its own, written and read back: each one survives,
// and a reader that dropped one would write a different document.
TEST(RunMetrics, JsonRoundTripOfARunWithEveryFieldSet) {
  RunMetrics m = localizedRun();
  m.world_hash = "sha256:" + std::string(64, 'a');
  m.method_options = std::map<std::string, double>{{"particles", 3000.0}, {"alpha_slow", 0.001}};
  m.build_version = "v0.1.0-12-gabcdef0-dirty";
  Statistics rotation;
  rotation.count = 258;
  rotation.rmse = 0.9;
  rotation.mean = 0.7;
  rotation.median = 0.6;
  rotation.std = 0.2;
  rotation.min = 0.01;
  rotation.max = 2.5;
  m.ape_B_rotation_deg = rotation;
  Statistics odometry;
  odometry.count = 400;
  odometry.rmse = 0.31;
  m.ape_odometry_from_true_start = odometry;
  m.wrongly_localized = true;
  m.time_wrongly_localized = 6.5;
  m.max_error_B = 3.25;
  m.max_height_error_B = 0.125;
  RunMetrics::EstimateStates states;
  states.coverage = 0.75;
  states.coverage_from_first = 0.96875;
  states.states.push_back({"localized", 300, *m.ape_B, 0.03});
  states.states.push_back({"lost", 12, std::nullopt, 0.5});
  states.keyframes_left_out = 7;
  m.estimate_states = states;
  m.map_to_plan = RunMetrics::MapToPlan{*m.ape_B, 56176, 0.875, 0.3};
  RunMetrics::MapToPlan::Level off_level{"L1", 30000, 0.75, 0.0165, 0.0565, 85, 6, 5.25};
  off_level.farthest = {"W4:left", -0.071, Eigen::Vector2d(0.15, 1.1375),
                        Eigen::Vector2d(0.15, 0.15)};
  m.map_to_plan->levels = {off_level, {"L0", 26176, 1.0, 0.0, 0.0, 0, 0, 0.0}};
  m.levels.push_back({"L1", 42.5, 3.25, 7.5, m.ape_B});
  m.levels.push_back({"L0", 10.0, 0.0, std::nullopt, std::nullopt});
  m.matching_events.push_back(
      {20.0, 12, slam::MatchStatus::kLost, "the scans no longer agree with the plan"});
  m.matching_events.push_back({31.5, 17, slam::MatchStatus::kMatched, "best"});
  m.lost_at = {20.0};
  m.relocalized_at = {31.5};
  RunTiming timing;
  timing.stages = {{"scans", 1.25}, {"matching", 0.5}};
  timing.scans_read = 42;
  timing.localizer_seconds = 0.75;
  timing.scan_wait_seconds = 0.125;
  timing.peak_memory_mb = 96.5;
  m.timing = timing;
  m.notes = {"APE in M not computed: too few poses"};

  const nlohmann::json j = metricsToJson(m);
  const RunMetrics back = metricsFromJson(j, "metrics.json");
  EXPECT_EQ(metricsToJson(back), j);
  EXPECT_EQ(back.world_hash, m.world_hash);
  EXPECT_EQ(back.method_options, m.method_options);
  EXPECT_EQ(back.build_version, m.build_version);
  EXPECT_EQ(j["method_options"]["particles"], 3000.0);
  ASSERT_TRUE(back.ape_B_rotation_deg);
  EXPECT_EQ(back.ape_B_rotation_deg->median, 0.6);
  EXPECT_EQ(back.ape_B_rotation_deg->min, 0.01);
  ASSERT_TRUE(back.ape_odometry_from_true_start);
  EXPECT_EQ(back.ape_odometry_from_true_start->rmse, 0.31);
  EXPECT_EQ(back.wrongly_localized, true);
  EXPECT_EQ(back.time_wrongly_localized, 6.5);
  EXPECT_EQ(back.max_error_B, 3.25);
  EXPECT_EQ(back.max_height_error_B, 0.125);
  ASSERT_TRUE(back.map_to_plan);
  EXPECT_EQ(back.map_to_plan->distance.rmse, m.ape_B->rmse);
  EXPECT_EQ(back.map_to_plan->points, 56176);
  EXPECT_EQ(back.map_to_plan->near_share, 0.875);
  EXPECT_EQ(back.map_to_plan->cutoff, 0.3);
  ASSERT_EQ(back.map_to_plan->levels.size(), 2u);
  const auto& level = back.map_to_plan->levels[0];
  EXPECT_EQ(level.level, "L1");
  EXPECT_EQ(level.points, 30000);
  EXPECT_EQ(level.p95_m, 0.0565);
  EXPECT_EQ(level.off_stretches, 6);
  EXPECT_EQ(level.off_length_m, 5.25);
  ASSERT_TRUE(level.farthest);
  EXPECT_EQ(level.farthest->surface, "W4:left");
  EXPECT_EQ(level.farthest->end, Eigen::Vector2d(0.15, 0.15));
  EXPECT_FALSE(back.map_to_plan->levels[1].farthest);
  ASSERT_EQ(back.levels.size(), 2u);
  EXPECT_EQ(back.levels[0].level, "L1");
  EXPECT_EQ(back.levels[0].seconds, 42.5);
  EXPECT_EQ(back.levels[0].arrived_at, 3.25);
  EXPECT_EQ(back.levels[0].first_estimate_at, 7.5);
  ASSERT_TRUE(back.levels[0].ape_B.has_value());
  EXPECT_EQ(back.levels[0].ape_B->rmse, m.ape_B->rmse);
  EXPECT_FALSE(back.levels[1].first_estimate_at.has_value());
  EXPECT_FALSE(back.levels[1].ape_B.has_value());
  ASSERT_EQ(back.matching_events.size(), 4u);
  EXPECT_EQ(back.matching_events[2].status, slam::MatchStatus::kLost);
  EXPECT_EQ(j["matching_events"][2]["status"], "lost");
  EXPECT_EQ(back.matching_events[2].keyframe, 12);
  EXPECT_EQ(back.lost_at, std::vector<double>{20.0});
  EXPECT_EQ(back.relocalized_at, std::vector<double>{31.5});
  ASSERT_TRUE(back.timing);
  ASSERT_EQ(back.timing->stages.size(), 2u);
  EXPECT_EQ(back.timing->stages[1].stage, "matching");
  EXPECT_EQ(back.timing->stages[1].seconds, 0.5);
  EXPECT_EQ(back.timing->scans_read, 42);
  EXPECT_EQ(back.timing->localizer_seconds, 0.75);
  EXPECT_EQ(back.timing->scan_wait_seconds, 0.125);
  EXPECT_EQ(back.timing->peak_memory_mb, 96.5);
  EXPECT_EQ(back.notes, m.notes);
  ASSERT_TRUE(back.estimate_states);
  EXPECT_EQ(back.estimate_states->coverage, 0.75);
  EXPECT_EQ(back.estimate_states->coverage_from_first, 0.96875);
  EXPECT_EQ(back.estimate_states->keyframes_left_out, 7);
  ASSERT_EQ(back.estimate_states->states.size(), 2u);
  EXPECT_EQ(back.estimate_states->states[0].state, "localized");
  EXPECT_EQ(back.estimate_states->states[0].poses, 300);
  ASSERT_TRUE(back.estimate_states->states[0].ape_B);
  EXPECT_EQ(back.estimate_states->states[0].ape_B->rmse, m.ape_B->rmse);
  EXPECT_EQ(back.estimate_states->states[1].state, "lost");
  EXPECT_FALSE(back.estimate_states->states[1].ape_B);
  EXPECT_EQ(back.estimate_states->states[1].max_sigma_xy, 0.5);
  // The derived rate is written from the stage and the robot time: 0.5 s over 40 s.
  EXPECT_EQ(j["timing"]["stages"][1]["ms_per_robot_second"].get<double>(), 12.5);
}

TEST(RunMetrics, ANotLocalizedRunHasNoApeInB) {
  RunMetrics m;
  m.world = "w";
  m.method = "s-graph";
  const nlohmann::json j = metricsToJson(m);
  EXPECT_FALSE(j.contains("ape_B"));
  EXPECT_FALSE(j.contains("matching_status"));
  EXPECT_FALSE(metricsFromJson(j, "m.json").localized);
}

TEST(RunMetrics, BadFieldsAreNamedByPointer) {
  auto message = [](nlohmann::json j) {
    try {
      metricsFromJson(j, "runs/x/metrics.json");
    } catch (const common::InputError& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  nlohmann::json j = metricsToJson(localizedRun());
  j.erase("seed");
  EXPECT_EQ(message(j), "runs/x/metrics.json: /seed: missing required field");
  j = metricsToJson(localizedRun());
  j["ape_B"]["rmse"] = "small";
  EXPECT_EQ(message(j), "runs/x/metrics.json: /ape_B/rmse: expected a number, got a string");
  j = metricsToJson(localizedRun());
  j["matching_events"][1]["status"] = 4;
  EXPECT_EQ(message(j),
            "runs/x/metrics.json: /matching_events/1/status: expected a string, got a number");
  j["matching_events"][1]["status"] = "found";
  EXPECT_EQ(message(j),
            "runs/x/metrics.json: /matching_events/1/status: unknown status \"found\" (one of "
            "\"not yet\", \"ambiguous\", \"matched\", \"contradicted\", \"lost\")");
  j = metricsToJson(localizedRun());
  j.erase("share_localized");
  EXPECT_EQ(message(j),
            "runs/x/metrics.json: /localized: a localized run needs time_to_localize and "
            "share_localized");
  j = metricsToJson(localizedRun());
  j["notes"] = {"no ground truth", 3};
  EXPECT_EQ(message(j), "runs/x/metrics.json: /notes/1: expected a string, got a number");
  j = metricsToJson(localizedRun());
  j["map_to_plan"] = {{"count", 1},  {"rmse", 0.1},       {"mean", 0.1},    {"median", 0.1},
                      {"std", 0.0},  {"min", 0.1},        {"max", 0.1},     {"sse", 0.01},
                      {"points", 1}, {"near_share", 1.0}, {"cutoff_m", 0.3}};
  j["map_to_plan"]["levels"] = {{{"level", "L0"},
                                 {"points", 1},
                                 {"near_share", 1.0},
                                 {"median_m", 0.1},
                                 {"p95_m", 0.1},
                                 {"stretches", 2},
                                 {"off_stretches", 3},
                                 {"off_length_m", 2.0}}};
  EXPECT_EQ(message(j),
            "runs/x/metrics.json: /map_to_plan/levels/0/off_stretches: must be at most "
            "stretches");
  j["map_to_plan"]["levels"][0]["off_stretches"] = 1;
  j["map_to_plan"]["levels"][0]["farthest"] = {
      {"surface", "W1:left"}, {"mean_m", 0.05}, {"start", {0.0, 1.0}}};
  EXPECT_EQ(message(j),
            "runs/x/metrics.json: /map_to_plan/levels/0/farthest/end: missing "
            "required field");
  j = metricsToJson(localizedRun());
  j["estimate_states"] = {{"coverage", 1.0},
                          {"coverage_from_first", 1.0},
                          {"keyframes_left_out", 0},
                          {"states", {{{"state", "sure"}, {"poses", 1}, {"max_sigma_xy", 0.03}}}}};
  EXPECT_EQ(message(j),
            "runs/x/metrics.json: /estimate_states/states/0/state: unknown state \"sure\" (one "
            "of \"localized\", \"tracking\", \"lost\")");
  j["estimate_states"]["states"][0]["state"] = "lost";
  j["estimate_states"]["coverage"] = 1.5;
  EXPECT_THAT(message(j),
              ::testing::StartsWith("runs/x/metrics.json: /estimate_states/coverage: "));
  EXPECT_EQ(message(nlohmann::json::array()),
            "runs/x/metrics.json: expected an object, got an array");
}

// What made a run: metrics of a run before they were recorded read without them; a method
// without options records an empty set (not "unrecorded").
TEST(RunMetrics, MethodOptionsAndBuildAreRecordedWhenKnown) {
  RunMetrics m;
  m.world = "builtin:d1";
  m.method = "is-graphs";
  nlohmann::json j = metricsToJson(m);
  EXPECT_FALSE(j.contains("method_options"));
  EXPECT_FALSE(metricsFromJson(j, "metrics.json").method_options.has_value());
  m.method_options.emplace();
  j = metricsToJson(m);
  EXPECT_EQ(j["method_options"], nlohmann::json::object());
  EXPECT_EQ(metricsFromJson(j, "metrics.json").method_options, (std::map<std::string, double>{}));
  j["method_options"] = {{"particles", "many"}};
  try {
    metricsFromJson(j, "metrics.json");
    FAIL() << "accepted";
  } catch (const common::InputError& e) {
    EXPECT_EQ(e.pointer(), "/method_options/particles");
  }
}

}  // namespace
}  // namespace isg::run
