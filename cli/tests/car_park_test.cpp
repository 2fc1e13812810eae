// A generated car park (docs/sweeps.md, "parking"): an open floor of identical columns, walked by
// hand, where the plan gives evidence only in places. From the true start the estimate is at
// every scan and confirmed by the plan; globally it is never wrong, and once it has spoken it
// speaks at every scan.
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>
#include <string>

#include "cli/tests/cli_runner.hpp"

namespace isg::cli {
namespace {

nlohmann::json carParkMetrics(const testing::Sandbox& sandbox, const std::string& run) {
  return nlohmann::json::parse(sandbox.read(run + "/metrics.json"));
}

TEST(CarPark, WalkedByHandFromTheTrueStartAndGlobally) {
  testing::Sandbox sandbox("car_park");
  const auto made = sandbox.run("generate parking -o g --seed 2 --carrier handheld -q");
  ASSERT_EQ(made.exit_code, 0) << made.err;
  EXPECT_NE(sandbox.read("g/parking-2.asbuilt.json").find("\"carrier\": \"handheld\""),
            std::string::npos);

  const auto given = sandbox.run(
      "run g/parking-2.asbuilt.json --start-pose truth --duration 120 --threads 2 -q -o s");
  ASSERT_EQ(given.exit_code, 0) << given.err;
  const auto s = carParkMetrics(sandbox, "s");
  EXPECT_FALSE(s["wrongly_localized"].get<bool>());
  EXPECT_EQ(s["estimate_states"]["coverage_from_first"].get<double>(), 1.0);
  for (const auto& state : s["estimate_states"]["states"]) {
    EXPECT_EQ(state["state"], "localized") << state.dump();
  }
  EXPECT_LT(s["ape_B"]["rmse"].get<double>(), 0.03);
  EXPECT_LT(s["max_error_B"].get<double>(), 0.15);
  EXPECT_GE(s["floor_plan_score"]["score"].get<double>(), 97.0);

  // Globally: found from the walls and columns within the first minute and a half (40 s on this
  // floor), then an estimate at every scan, never wrong.
  const auto global =
      sandbox.run("run g/parking-2.asbuilt.json --duration 100 --threads 2 -q -o a");
  ASSERT_EQ(global.exit_code, 0) << global.err;
  const auto a = carParkMetrics(sandbox, "a");
  ASSERT_TRUE(a["localized"].get<bool>());
  EXPECT_LT(a["time_to_localize"].get<double>(), 90.0);
  EXPECT_FALSE(a["wrongly_localized"].get<bool>());
  EXPECT_EQ(a["estimate_states"]["coverage_from_first"].get<double>(), 1.0);
  EXPECT_LT(a["ape_B"]["rmse"].get<double>(), 0.03);
}

}  // namespace
}  // namespace isg::cli
