// The contradiction path of the iS-Graph (docs/matching.md), in the loop: a wrong first match is
// injected and must be contradicted by the map's own evidence. In cli/tests because it drives the
// localizer's own class (slam) with the simulator (sim): only cli sees both.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "bim/agraph.hpp"
#include "cli/tests/loop/injected_match.hpp"
#include "common/angles.hpp"
#include "run/driver.hpp"
#include "sim/scan_pipeline.hpp"
#include "sim/simulation.hpp"
#include "slam/isgraph/isgraph_localizer.hpp"
#include "worlds/reference_plans.hpp"

namespace isg::sim {
namespace {

// The contradiction path (docs/matching.md): a wrong first match — the true B_T_M turned by 180°
// about the first room the S-Graph confirms, so that room still fits — is injected; the lost
// checks are switched off so that only a contradiction can correct it. The full match at a later
// room, judged on the S-Graph optimised without the plan, finds the right answer; the localizer
// adopts it and re-optimises every keyframe, so no wall stays where the wrong answer put it.
TEST(ISGraphContradiction, AWrongFirstMatchIsContradictedAndEveryKeyframeReoptimised) {
  const bim::Scenario scenario = worlds::loadScenarioOrBuiltin("builtin:d3.asbuilt", nullptr);
  const Simulation simulation(scenario);
  const bim::AGraph plan = bim::buildAGraph(scenario.plan);
  slam::ISGraphLocalizer localizer(simulation.R_T_L(), plan, testing::withTheLostChecksOff());
  sensors::SensorStreams streams = sensorStreams(simulation, -1.0);
  const Eigen::Vector3d truth = testing::trueStartXYYaw(streams);
  LookaheadScans scans(simulation, int(streams.scan_stamps.size()), 1);
  run::LocalizerDriver driver(localizer, streams.odometry, streams.scan_period);
  bool injected = false;
  Eigen::Vector3d wrong;
  for (int k = 0; k < int(streams.scan_stamps.size()); ++k) {
    sensors::Scan scan = scans.scan(k);
    scan.stamp = streams.scan_stamps[k];
    driver.feed(scan);
    const auto& graph = localizer.sgraph();
    if (injected || graph.confirmedRooms().empty()) continue;
    // 180° about the room's centre in B: B_T_M' = R(π) about c ∘ B_T_M.
    const Eigen::Vector2d centre_M = graph.roomCandidates()[graph.confirmedRooms()[0]].centre;
    const Eigen::Vector2d c = Eigen::Rotation2Dd(truth.z()) * centre_M + truth.head<2>();
    const Eigen::Vector2d t = 2.0 * c - truth.head<2>();
    wrong = Eigen::Vector3d(t.x(), t.y(),
                            std::remainder(truth.z() + std::numbers::pi, 2.0 * std::numbers::pi));
    localizer.assumeMatch(scan.stamp, wrong, "injected: the truth turned by 180 degrees");
    injected = true;
  }
  ASSERT_TRUE(injected);
  bool contradicted = false;
  for (const auto& event : localizer.events()) {
    contradicted = contradicted || event.status == slam::MatchStatus::kContradicted;
  }
  EXPECT_TRUE(contradicted);
  EXPECT_EQ(localizer.status(), slam::MatchStatus::kMatched);
  const auto final_B_T_M = localizer.mapInPlan();
  ASSERT_TRUE(final_B_T_M.has_value());
  EXPECT_LT((final_B_T_M->translation().head<2>() - truth.head<2>()).norm(), 0.15);
  EXPECT_LT(std::abs(common::wrapAngle(common::yawOf(final_B_T_M->linear()) - truth.z())), 0.02);
  // Every wall of the map, the early ones included, is where the plan has a wall: at most a
  // tenth of the S-planes' length is left unexplained (clutter and the extra wall as built).
  const slam::MatchInput input = localizer.matchInput();
  const Eigen::Vector3d now(final_B_T_M->translation().x(), final_B_T_M->translation().y(),
                            common::yawOf(final_B_T_M->linear()));
  const slam::GraphMatcher matcher(plan);
  const slam::Verification check = matcher.verify(input, now);
  double length = 0.0;
  for (const auto& p : input.planes) {
    if (p.length() >= matcher.options().min_plane_length) length += p.length();
  }
  EXPECT_LT(check.unexplained_length, 0.1 * length);
  // And the estimate in B at the end is right.
  double last_error = 1e9;
  const auto& estimate = driver.estimate();
  for (const auto& g : streams.ground_truth) {
    if (std::abs(g.t - estimate.back().t) < 0.011) {
      last_error = (g.pose.translation() - estimate.back().pose.translation()).head<2>().norm();
    }
  }
  EXPECT_LT(last_error, 0.1);
}

}  // namespace
}  // namespace isg::sim
