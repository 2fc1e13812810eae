#include "run/run_metrics.hpp"

#include <gtest/gtest.h>

#include "bim/input_error.hpp"

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
  m.matching_events = {{0.0, 0, "not yet", "too little evidence"}, {14.5, 9, "matched", "best"}};
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
    } catch (const bim::InputError& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  nlohmann::json j = metricsToJson(localizedRun());
  j.erase("seed");
  EXPECT_EQ(message(j), "runs/x/metrics.json: /seed: missing");
  j = metricsToJson(localizedRun());
  j["ape_B"]["rmse"] = "small";
  EXPECT_EQ(message(j), "runs/x/metrics.json: /ape_B/rmse: expected a number");
  j = metricsToJson(localizedRun());
  j["matching_events"][1]["status"] = 4;
  EXPECT_EQ(message(j), "runs/x/metrics.json: /matching_events/1/status: expected a string");
  j = metricsToJson(localizedRun());
  j.erase("share_localized");
  EXPECT_EQ(message(j),
            "runs/x/metrics.json: /localized: a localized run needs time_to_localize and "
            "share_localized");
  j = metricsToJson(localizedRun());
  j["notes"] = {"no ground truth", 3};
  EXPECT_EQ(message(j), "runs/x/metrics.json: /notes/1: expected a string");
  EXPECT_EQ(message(nlohmann::json::array()), "runs/x/metrics.json: expected an object");
}

}  // namespace
}  // namespace isg::run
