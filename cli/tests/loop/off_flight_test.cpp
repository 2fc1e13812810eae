// The iS-Graph's flight check (docs/matching.md, "Several storeys"), in the loop: the robot
// changes floor only on a flight of stairs, so a match that puts a climb where the plan has no
// flight is wrong. In cli/tests because it drives the localizer's own class (slam) with the
// simulator (sim): only cli sees both.
#include <gtest/gtest.h>

#include <string>

#include "bim/agraph.hpp"
#include "cli/tests/loop/injected_match.hpp"
#include "run/driver.hpp"
#include "sim/scan_pipeline.hpp"
#include "sim/simulation.hpp"
#include "slam/isgraph/isgraph_localizer.hpp"
#include "worlds/reference_plans.hpp"

namespace isg::sim {
namespace {

// builtin:storeys as built: the robot climbs flight S1 (1 m wide, along x from (9, 0.85) on L0).
// Just before it climbs the flight a match 2 m off across the flight is injected, with every
// other check on the match switched off; on the first keyframe on the stairs the robot is lost,
// saying where it climbed and how far that is from the flight (1.5 m: 2 m less half its width).
TEST(ISGraphFlightCheck, AClimbAwayFromEveryFlightLosesTheMatch) {
  const bim::Scenario scenario = worlds::loadScenarioOrBuiltin("builtin:storeys.asbuilt", nullptr);
  const Simulation simulation(scenario);
  const bim::AGraph plan = bim::buildAGraph(scenario.plan);
  // The injected answer stays where it was put: a whole-map bend under it (bend_keyframes) would
  // pull it 0.2 m toward the walls it half fits, and the distance said is the one injected.
  slam::ISGraphOptions options = testing::withTheLostChecksOff();
  options.bend_keyframes = 0;
  slam::ISGraphLocalizer localizer(simulation.R_T_L(), plan, options);
  sensors::SensorStreams streams = sensorStreams(simulation, -1.0);
  const Eigen::Vector3d truth = testing::trueStartXYYaw(streams);
  const Eigen::Vector3d wrong = truth + Eigen::Vector3d(0.0, 2.0, 0.0);
  // When the robot starts to climb: inject 3 s before.
  double climb = 0.0;
  while (simulation.baseMotion().pose(climb).translation().z() < 0.46 + 0.05) climb += 0.1;
  ASSERT_LT(climb, simulation.duration());
  LookaheadScans scans(simulation, int(streams.scan_stamps.size()), 1);
  run::LocalizerDriver driver(localizer, streams.odometry, streams.scan_period);
  std::optional<double> injected_at;
  for (int k = 0; k < int(streams.scan_stamps.size()); ++k) {
    sensors::Scan scan = scans.scan(k);
    scan.stamp = streams.scan_stamps[k];
    driver.feed(scan);
    if (!injected_at && localizer.status() == slam::MatchStatus::kMatched &&
        scan.stamp >= climb - 3.0) {
      localizer.assumeMatch(scan.stamp, wrong, "injected: the truth moved 2 m across the flight");
      injected_at = scan.stamp;
    }
  }
  ASSERT_TRUE(injected_at.has_value());
  const slam::StatusChange* lost = nullptr;
  for (const auto& event : localizer.events()) {
    if (event.stamp >= *injected_at && event.status == slam::MatchStatus::kLost) {
      lost = &event;
      break;
    }
  }
  ASSERT_NE(lost, nullptr);
  EXPECT_NE(lost->reason.find("the robot is on stairs at ("), std::string::npos) << lost->reason;
  EXPECT_NE(lost->reason.find(", 1.5 m from every flight that joins level L0"), std::string::npos)
      << lost->reason;
  // Lost on the flight's first keyframe off a floor (more than 0.5 m above it, docs/slam.md), not
  // later: its base less than 1.5 m above L0's floor then.
  const double z = simulation.baseMotion().pose(lost->stamp).translation().z();
  EXPECT_GT(z, 0.46 + 0.5);
  EXPECT_LT(z, 0.46 + 1.5);
}

}  // namespace
}  // namespace isg::sim
