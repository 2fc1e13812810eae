// What the plan gives the iS-Graph once (CompiledPlan), by hand on the box room and the two
// storeys of worlds/plans/storeys.json.
#include "slam/isgraph/compiled_plan.hpp"

#include <gtest/gtest.h>

#include <random>

#include "bim/plan_parser.hpp"
#include "slam/isgraph/tests/synthetic_sgraph.hpp"
#include "slam/sgraph/tests/box_world.hpp"

namespace isg::slam {
namespace {

bim::AGraph storeysPlan() {
  return bim::buildAGraph(
      bim::loadPlan(std::string(ISG_SOURCE_DIR) + "/worlds/plans/storeys.json"));
}

TEST(CompiledPlan, PIsBWithItsOriginAtTheMiddleOfTheWalls) {
  // The box's wall faces span x −2.2 … 8.2 and y −3.2 … 3.2: their middle is (3, 0).
  const CompiledPlan plan(testing::boxPlan(), {}, 1.0);
  EXPECT_NEAR((plan.B_t_P() - Eigen::Vector2d(3.0, 0.0)).norm(), 0.0, 1e-12);
  // Every surface moved by −(3, 0): the west wall's inner face, x = −2 in B, is x = −5 in P.
  const bim::Plane& west = plan.agraph().surfaces[6].plane;
  EXPECT_EQ(plan.agraph().surfaces[6].id, "W:left");
  EXPECT_NEAR(west.signedDistance({-5.0, 1.0, 0.0}), 0.0, 1e-12);
  // A pose of M in P and in B differ by that translation alone.
  const Eigen::Vector3d B_T_M(1.5, -0.5, 0.7);
  EXPECT_NEAR((plan.inP(B_T_M) - Eigen::Vector3d(-1.5, -0.5, 0.7)).norm(), 0.0, 1e-12);
  EXPECT_NEAR((plan.inB(plan.inP(B_T_M)) - B_T_M).norm(), 0.0, 1e-12);
  // The building: the faces' box in P, −5.2 … 5.2 by −3.2 … 3.2, grown by the 1 m margin.
  EXPECT_NEAR((plan.building().min() - Eigen::Vector2d(-6.2, -4.2)).norm(), 0.0, 1e-12);
  EXPECT_NEAR((plan.building().max() - Eigen::Vector2d(6.2, 4.2)).norm(), 0.0, 1e-12);
}

TEST(CompiledPlan, OneLevelHasOneMatcherAndNoFlights) {
  const CompiledPlan plan(testing::boxPlan(), {}, 1.0);
  EXPECT_FALSE(plan.severalLevels());
  EXPECT_TRUE(plan.flights().empty());
  EXPECT_EQ(&plan.matcherOf(0), &plan.matcher());
  EXPECT_EQ(&plan.matcherOf(3), &plan.matcher());
  int level = 7;
  const MatchResult result = plan.match(MatchInput{}, &level);
  EXPECT_EQ(level, -1);
  EXPECT_NE(result.status, MatchStatus::kMatched);
}

TEST(CompiledPlan, SeveralLevelsEachWithItsMatcherAndTheFlightBetween) {
  const CompiledPlan plan(storeysPlan(), {}, 1.0);
  ASSERT_TRUE(plan.severalLevels());
  EXPECT_NE(&plan.matcherOf(0), &plan.matcherOf(1));
  // S1 runs from (9, 0.85) to (13.5, 0.85) in B, 1 m wide, from 0 to 3.2 m.
  ASSERT_EQ(plan.flights().size(), 1u);
  const FlightFootprint& flight = plan.flights()[0];
  EXPECT_EQ(flight.stair, "S1");
  const Eigen::Vector2d middle_in_B = 0.5 * (flight.bottom + flight.top) + plan.B_t_P();
  EXPECT_NEAR((middle_in_B - Eigen::Vector2d(11.25, 0.85)).norm(), 0.0, 1e-9);
  EXPECT_NEAR(flight.half_width, 0.5, 1e-9);
  EXPECT_TRUE(flight.joins(3.2, 0.1));
}

TEST(CompiledPlan, AMapOfTheUpperFloorIsVerifiedBestOnIt) {
  const CompiledPlan plan(storeysPlan(), {}, 1.0);
  const bim::AGraph& whole = plan.agraph();
  std::vector<int> upper;
  for (int r = 0; r < int(whole.rooms.size()); ++r) {
    if (whole.rooms[r].floor == 1) upper.push_back(r);
  }
  ASSERT_EQ(upper.size(), 4u);
  // The upper floor's rooms mapped in an M placed anywhere in P, without noise.
  std::mt19937_64 rng(3);
  const Eigen::Vector3d P_T_M(2.0, -1.0, 0.4);
  const testing::CutSGraph cut = testing::cutSGraph(whole, upper, P_T_M, rng, 0.0);
  int level = -1;
  const Verification answer = plan.verifyOnBestLevel(cut.input, P_T_M, &level);
  EXPECT_EQ(level, 1);
  // Its correspondences are the whole plan's surfaces, each the truth.
  ASSERT_FALSE(answer.planes.empty());
  for (const auto& [s, a] : answer.planes) {
    EXPECT_EQ(a, cut.a_surface_of_s_plane[s]) << "S-plane " << s;
  }
}

}  // namespace
}  // namespace isg::slam
