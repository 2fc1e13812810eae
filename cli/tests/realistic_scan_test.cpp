// The simulated VLP-16 in a building someone else drew: the duplex (an architect's Revit model,
// ifc/tests/models/duplex.ifc, imported by isg import's code) with the puck on the robot's body.
// Where a closed room of ours loses only the body's shadow (sim/tests/lidar_realism_test.cpp),
// a room with windows loses what a real indoor scan loses: the body's shadow below, the upward
// lasers' rays that leave through the glass above (docs/simulation.md, "Simulated vs real").

#include <gtest/gtest.h>

#include <cstdio>
#include <string>

#include "bim/scenario.hpp"
#include "cli/tests/cli_runner.hpp"
#include "formats/vlp16_statistics.hpp"
#include "ifc/ifc_import.hpp"
#include "sim/scan_statistics.hpp"
#include "sim/simulation.hpp"
#include "sim/vlp16.hpp"

namespace isg::cli {
namespace {

// The robot's first scan, standing at its route's start in the duplex's first storey, with the
// puck on its body (mount z 0.14), in the plan as imported or with its windows walled up.
formats::Vlp16Statistics firstScan(const testing::Sandbox& sandbox, bool windows) {
  nlohmann::ordered_json plan =
      ifc::importIfc(std::string(ISG_SOURCE_DIR) + "/ifc/tests/models/duplex.ifc", {}).plan_json;
  if (!windows) {
    for (auto& level : plan["levels"]) level["windows"] = nlohmann::ordered_json::array();
  }
  const std::string name = windows ? "duplex.json" : "duplex-no-windows.json";
  sandbox.write(name, plan.dump());
  bim::Scenario scenario = bim::loadScenario((sandbox.dir() / name).string());
  scenario.lidar.mount[2] = 0.14;
  sim::Simulation simulation(scenario);
  const Eigen::Isometry3d B_T_L = simulation.B_T_L(0.0);
  const sim::LidarScan scan = simulation.makeLidar()->scan(
      0.0, [&](double) { return B_T_L; }, 7);
  return sim::scanStatistics({scan}, sim::Vlp16::sequencesPerTurn(10.0));
}

TEST(RealisticScan, ARoomWithWindowsLosesWhatARealIndoorScanLoses) {
  const testing::Sandbox sandbox("realistic_scan");
  const formats::Vlp16Statistics with = firstScan(sandbox, true);
  const formats::Vlp16Statistics walled_up = firstScan(sandbox, false);
  for (int ring = 0; ring < 16; ++ring) {
    std::printf("ring %2d: lost %5.1f %% (windows walled up: %5.1f %%)\n", ring,
                100 * with.lost_by_ring[ring], 100 * walled_up.lost_by_ring[ring]);
  }
  std::printf("whole scan: lost %.1f %% (windows walled up: %.1f %%)\n", 100 * with.lost,
              100 * walled_up.lost);
  // The whole scan within the real indoor recording's range (its 49.3 %, 30–60 %).
  EXPECT_GE(with.lost, 0.30);
  EXPECT_LE(with.lost, 0.60);
  // The body takes the lowest laser whole, windows or not.
  EXPECT_EQ(with.lost_by_ring[0], 1.0);
  EXPECT_EQ(walled_up.lost_by_ring[0], 1.0);
  // Walled up, the room loses the body's shadow and hardly more (as our closed rooms do): the
  // rest is the rays that leave through the glass. The first storey's windows are glazing from
  // 0.08 m to 2.5 m, 4.8 m wide: every laser above the body's shadow looks through them over the
  // same share of its turn, so each loses the same share more; the body's lasers lose the same.
  EXPECT_LT(walled_up.lost, 0.25);
  for (int ring = 0; ring < 3; ++ring) {
    EXPECT_NEAR(with.lost_by_ring[ring], walled_up.lost_by_ring[ring], 0.01) << ring;
  }
  const double through_glass = with.lost_by_ring[15] - walled_up.lost_by_ring[15];
  EXPECT_GT(through_glass, 0.10);
  for (int ring = 5; ring < 16; ++ring) {
    EXPECT_NEAR(with.lost_by_ring[ring] - walled_up.lost_by_ring[ring], through_glass, 0.01)
        << ring;
    EXPECT_LT(walled_up.lost_by_ring[ring], 0.15) << ring;  // lasers that see walls
  }
}

}  // namespace
}  // namespace isg::cli
