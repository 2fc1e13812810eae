// Accuracy must not depend on where the plan frame B's origin is (docs/conventions.md, "Where B's
// origin is"): IFC models place buildings in site coordinates, kilometres from their origin. Each
// reference world, turned about B's origin, is run at the origin and again moved near the corner
// of the coordinate limit; the iS-Graph localizes both and their APE in B agrees within 5 mm.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <cstdio>
#include <numbers>
#include <ostream>
#include <string>
#include <vector>

#include "bim/plan_transform.hpp"
#include "cli/tests/loop/isgraph_run.hpp"
#include "run/evaluate_run.hpp"
#include "worlds/reference_plans.hpp"

namespace isg::sim {
namespace {

// A reference world, turned about B's origin by `yaw_deg`, at the origin and moved 8 km along
// each axis (signs `corner`), run with `seed`.
struct Placement {
  std::string world;
  double yaw_deg = 0.0;
  Eigen::Vector2d corner = Eigen::Vector2d::Ones();
  std::uint64_t seed = 1;
};

void PrintTo(const Placement& p, std::ostream* out) {
  *out << p.world << " turned " << p.yaw_deg << "° at (" << 8 * p.corner.x() << " km, "
       << 8 * p.corner.y() << " km), seed " << p.seed;
}

// Every reference world, plan and as built, at each of the three turns; the corner and the seed
// go round so that the 36 cases see all four corners and seeds 1–3.
std::vector<Placement> placements() {
  const char* worlds[] = {"d1", "d2", "d3", "d4", "d5", "d6"};
  const double turns[] = {0.0, 27.0, 90.0};
  const Eigen::Vector2d corners[] = {{1, 1}, {-1, 1}, {-1, -1}, {1, -1}};
  std::vector<Placement> out;
  int k = 0;
  for (const char* world : worlds) {
    for (const char* variant : {"", ".asbuilt"}) {
      for (double turn : turns) {
        out.push_back(
            {std::string(world) + variant, turn, corners[k % 4], std::uint64_t(1 + k % 3)});
        ++k;
      }
    }
  }
  return out;
}

run::RunMetrics runIsGraph(const bim::Scenario& scenario) {
  return run::evaluateRun(testing::runIsGraphInTheLoop(scenario)).metrics;
}

class FarFromTheOrigin : public ::testing::TestWithParam<Placement> {};

TEST_P(FarFromTheOrigin, TheSameApeAsAtTheOrigin) {
  const Placement placement = GetParam();
  bim::Scenario original = worlds::loadScenarioOrBuiltin("builtin:" + placement.world, nullptr);
  original.seed = placement.seed;
  const double yaw = placement.yaw_deg * std::numbers::pi / 180.0;
  const bim::Scenario at_origin =
      bim::transformedScenario(original, bim::planarMotion(Eigen::Vector2d::Zero(), yaw));
  // 8 km along both axes: the building's far corner is still inside the ±10 km limit.
  const bim::Scenario far_away =
      bim::transformedScenario(original, bim::planarMotion(8000.0 * placement.corner, yaw));

  const run::RunMetrics near = runIsGraph(at_origin);
  const run::RunMetrics far = runIsGraph(far_away);
  ASSERT_TRUE(near.ape_B.has_value());
  ASSERT_TRUE(far.ape_B.has_value());
  // The numbers, for the record (docs/conventions.md quotes them).
  std::printf("APE %.4f m at the origin, %.4f m far away (difference %+.4f m)\n", near.ape_B->rmse,
              far.ape_B->rmse, far.ape_B->rmse - near.ape_B->rmse);
  EXPECT_FALSE(far.wrongly_localized.value_or(true));
  EXPECT_NEAR(far.ape_B->rmse, near.ape_B->rmse, 0.005);
  // The same run: localized at about the same time.
  ASSERT_TRUE(near.time_to_localize && far.time_to_localize);
  EXPECT_NEAR(*far.time_to_localize, *near.time_to_localize, 1.0);
}

INSTANTIATE_TEST_SUITE_P(ReferenceWorlds, FarFromTheOrigin, ::testing::ValuesIn(placements()),
                         [](const auto& test_info) {
                           const Placement& p = test_info.param;
                           std::string name = p.world + "_turned" + std::to_string(int(p.yaw_deg)) +
                                              "_seed" + std::to_string(p.seed);
                           for (char& c : name) {
                             if (c == '.') c = '_';
                           }
                           return name;
                         });

}  // namespace
}  // namespace isg::sim
