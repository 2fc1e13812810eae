#include "slam/isgraph/flight_footprints.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "bim/agraph.hpp"
#include "bim/plan_parser.hpp"

namespace isg::slam {
namespace {

// builtin:storeys: flight S1, 1 m wide, from (9, 0.85) on L0 (elevation 0) up to (13.5, 0.85) on
// L1 (elevation 3.2).
TEST(FlightFootprints, TheRectangleOfEachFlightFromItsFacesAndTheFloorsItJoins) {
  const bim::AGraph graph =
      bim::buildAGraph(bim::loadPlan(std::string(ISG_SOURCE_DIR) + "/worlds/plans/storeys.json"));
  const auto flights = flightFootprints(graph);
  ASSERT_EQ(flights.size(), 1u);
  const FlightFootprint& s1 = flights[0];
  EXPECT_EQ(s1.stair, "S1");
  EXPECT_NEAR((s1.bottom - Eigen::Vector2d(9.0, 0.85)).norm(), 0.0, 1e-9);
  EXPECT_NEAR((s1.top - Eigen::Vector2d(13.5, 0.85)).norm(), 0.0, 1e-9);
  EXPECT_NEAR(s1.half_width, 0.5, 1e-9);
  EXPECT_NEAR(s1.z_low, 0.0, 1e-9);
  EXPECT_NEAR(s1.z_high, 3.2, 1e-9);
  // Inside: 0; beside it, in front of its foot, beyond its head's corner: by hand.
  EXPECT_DOUBLE_EQ(s1.distance({11.0, 1.2}), 0.0);
  EXPECT_NEAR(s1.distance({11.0, 0.85 + 0.5 + 0.7}), 0.7, 1e-9);
  EXPECT_NEAR(s1.distance({8.0, 0.85}), 1.0, 1e-9);
  EXPECT_NEAR(s1.distance({13.5 + 0.3, 0.85 - 0.5 - 0.4}), 0.5, 1e-9);
  EXPECT_TRUE(s1.joins(0.0, 1.0));
  EXPECT_TRUE(s1.joins(3.4, 1.0));
  EXPECT_FALSE(s1.joins(6.4, 1.0));
  EXPECT_FALSE(s1.joins(1.6, 1.0));  // half way up is no floor
}

TEST(FlightFootprints, NoneWithoutStairs) {
  const bim::AGraph graph =
      bim::buildAGraph(bim::loadPlan(std::string(ISG_SOURCE_DIR) + "/worlds/plans/d1.json"));
  EXPECT_TRUE(flightFootprints(graph).empty());
}

}  // namespace
}  // namespace isg::slam
