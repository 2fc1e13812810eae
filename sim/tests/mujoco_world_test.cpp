#include "sim/mujoco_world.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "sim/world_summary.hpp"
#include "worlds/mjcf_generator.hpp"
#include "worlds/reference_plans.hpp"

namespace isg::sim {
namespace {

const char* kTwoBoxes = R"(<mujoco>
  <worldbody>
    <geom name="near" type="box" pos="2 0 0" size="0.5 1 1" group="1"/>
    <geom name="far" type="box" pos="5 0 0" size="0.5 1 1" group="2"/>
  </worldbody>
</mujoco>)";

TEST(MujocoWorld, CompilesFromTextAndRaysRespectGroups) {
  const MujocoWorld world = MujocoWorld::fromXml(kTwoBoxes);
  EXPECT_EQ(world.model().ngeom, 2);
  auto hit = world.ray({0, 0, 0}, {2, 0, 0}, 0b110);  // direction is normalised
  ASSERT_TRUE(hit);
  EXPECT_EQ(world.geomName(hit->geom), "near");
  EXPECT_NEAR(hit->distance, 1.5, 1e-12);
  hit = world.ray({0, 0, 0}, {1, 0, 0}, 0b100);  // group 2 only
  ASSERT_TRUE(hit);
  EXPECT_EQ(world.geomName(hit->geom), "far");
  EXPECT_NEAR(hit->distance, 4.5, 1e-12);
  EXPECT_FALSE(world.ray({0, 0, 0}, {-1, 0, 0}, 0b110));
}

TEST(MujocoWorld, InvalidXmlIsAClearError) {
  try {
    MujocoWorld::fromXml("<mujoco><worldbody><geom type=\"box\"/></worldbody>");
    FAIL() << "expected an error";
  } catch (const std::runtime_error& e) {
    EXPECT_THAT(e.what(), ::testing::StartsWith("MuJoCo could not compile the world: "));
  }
}

TEST(MujocoWorld, SteppingAdvancesTime) {
  MujocoWorld world = MujocoWorld::fromXml(kTwoBoxes);
  world.step(250);
  EXPECT_NEAR(world.time(), 250 * world.model().opt.timestep, 1e-9);
}

TEST(WorldSummary, CountsGeomsAndProbesEveryRoom) {
  const bim::Scenario scenario = worlds::loadScenarioOrBuiltin("builtin:d1.asbuilt", nullptr);
  MujocoWorld world = MujocoWorld::fromXml(worlds::generateMjcf(scenario));
  const WorldSummary s = summarizeWorld(scenario, world, 100, 36);
  EXPECT_EQ(s.geoms, world.model().ngeom);
  EXPECT_EQ(s.geoms_by_kind.at("lintel"), 5);
  EXPECT_EQ(s.geoms_by_kind.at("door"), 1);
  EXPECT_EQ(s.geoms_by_kind.at("clutter"), 2);
  EXPECT_EQ(s.geoms_by_kind.at("floor"), 1);
  EXPECT_NEAR(s.sim_seconds, 0.2, 1e-9);
  ASSERT_EQ(s.rooms.size(), 4u);
  // The corridor R4 spans y in [0.15, 2.125]: from its centroid the nearest face is 0.9875 m away.
  EXPECT_EQ(s.rooms[3].room, "R4");
  EXPECT_NEAR(s.rooms[3].nearest, (2.125 - 0.15) / 2, 1e-3);
  for (const auto& r : s.rooms) EXPECT_EQ(r.hits, r.rays) << r.room;  // closed building
  EXPECT_THAT(formatSummary(s), ::testing::HasSubstr("R4     \"Corridor\""));
}

}  // namespace
}  // namespace isg::sim
