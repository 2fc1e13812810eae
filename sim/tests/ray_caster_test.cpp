#include "sim/ray_caster.hpp"

#include <gtest/gtest.h>

#include <random>

#include "bim/plan_parser.hpp"
#include "bim/synthetic_plan.hpp"
#include "common/json_reader.hpp"
#include "sim/mujoco_world.hpp"
#include "worlds/mjcf_generator.hpp"
#include "worlds/reference_plans.hpp"

namespace isg::sim {
namespace {

constexpr unsigned kCasterBuilding = 1u << worlds::kBuildingGroup;
constexpr unsigned kBuildingAndCeilings = kCasterBuilding | (1u << worlds::kCeilingGroup);

// Casts `count` random rays from random points above the floor inside the building's footprint
// (including points inside walls) with both mj_ray and the caster; they must agree exactly.
void expectSameAsMjRay(const MujocoWorld& world, unsigned groups, int count, std::uint32_t seed,
                       int min_hits = -1) {
  const mjModel& m = world.model();
  const RayCaster caster(m, world.data(), groups);
  const auto mask = groupArray(groups);
  const double* centre = m.stat.center;
  const double extent = m.stat.extent;
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(-0.5, 0.5);
  std::normal_distribution<double> n(0.0, 1.0);
  int hits = 0;
  for (int k = 0; k < count; ++k) {
    const Eigen::Vector3d origin(centre[0] + extent * u(rng), centre[1] + extent * u(rng),
                                 0.2 + 2.6 * (u(rng) + 0.5));
    Eigen::Vector3d dir(n(rng), n(rng), 0.3 * n(rng));
    if (k % 7 == 0) dir = Eigen::Vector3d(n(rng) > 0 ? 1 : -1, 0, 0);  // axis-aligned rays too
    dir.normalize();
    int expected_geom = -1;
    const double expected =
        mj_ray(&m, &world.data(), origin.data(), dir.data(), mask.data(), 1, -1, &expected_geom);
    const auto hit = caster.cast(origin, dir);
    if (expected < 0) {
      EXPECT_FALSE(hit) << "ray " << k;
      continue;
    }
    ++hits;
    ASSERT_TRUE(hit) << "ray " << k << " mj_ray hit " << world.geomName(expected_geom);
    EXPECT_EQ(hit->geom, expected_geom) << "ray " << k;
    EXPECT_NEAR(hit->distance, expected, 1e-9) << "ray " << k;
  }
  EXPECT_GE(hits, min_hits < 0 ? count / 2 : min_hits);
}

class CasterOnReferenceWorld : public ::testing::TestWithParam<std::string> {};

TEST_P(CasterOnReferenceWorld, SameGeomAndDistanceAsMjRay) {
  const bim::Scenario s = worlds::loadScenarioOrBuiltin("builtin:" + GetParam(), nullptr);
  const MujocoWorld world = MujocoWorld::fromXml(worlds::generateMjcf(s));
  expectSameAsMjRay(world, kCasterBuilding, 4000, 1);
  expectSameAsMjRay(world, kBuildingAndCeilings, 2000, 2);
}

INSTANTIATE_TEST_SUITE_P(AsBuilt, CasterOnReferenceWorld,
                         ::testing::Values("d1.asbuilt", "d3.asbuilt", "d5.asbuilt", "d6.asbuilt"));

TEST(RayCaster, TwoHundredRoomGrid) {
  const common::JsonSource source{"grid.json", nullptr};
  const nlohmann::json doc = bim::makeGridPlan({});
  const MujocoWorld world =
      MujocoWorld::fromXml(worlds::generateMjcf(bim::parsePlan(common::JsonNode(doc, "", source))));
  expectSameAsMjRay(world, kCasterBuilding, 3000, 3);
}

TEST(RayCaster, TiesGoToTheLowerGeomIdAndOtherTypesAreHandled) {
  // Two coincident boxes (a tie on every ray) and a sphere, a capsule and a moving box.
  const MujocoWorld world = MujocoWorld::fromXml(R"(<mujoco><worldbody>
      <geom name="b" type="box" pos="3 0 0" size="0.5 1 1" group="1"/>
      <geom name="a" type="box" pos="3 0 0" size="0.5 1 1" group="1"/>
      <geom name="s" type="sphere" pos="0 3 0" size="0.5" group="1"/>
      <geom name="c" type="capsule" pos="0 -3 0" size="0.2 1" group="1"/>
      <geom name="hidden" type="box" pos="-3 0 0" size="0.5 1 1" group="1" rgba="1 1 1 0"/>
      <body pos="0 0 3"><freejoint/><geom name="m" type="box" size="0.5 0.5 0.5" group="1"/></body>
    </worldbody></mujoco>)");
  const RayCaster caster(world.model(), world.data(), kCasterBuilding);
  auto hit = caster.cast({0, 0, 0}, {1, 0, 0});
  ASSERT_TRUE(hit);
  EXPECT_EQ(world.geomName(hit->geom), "b");
  EXPECT_NEAR(hit->distance, 2.5, 1e-12);
  hit = caster.cast({0, 0, 0}, {0, 1, 0});
  ASSERT_TRUE(hit);
  EXPECT_EQ(world.geomName(hit->geom), "s");
  EXPECT_NEAR(hit->distance, 2.5, 1e-12);
  hit = caster.cast({0, 0, 0}, {0, -1, 0});
  ASSERT_TRUE(hit);
  EXPECT_EQ(world.geomName(hit->geom), "c");
  EXPECT_NEAR(hit->distance, 2.8, 1e-12);            // capsules lie along z: radius 0.2
  EXPECT_FALSE(caster.cast({0, 0, 0}, {-1, 0, 0}));  // alpha 0: invisible to rays
  hit = caster.cast({0, 0, 0}, {0, 0, 1});
  ASSERT_TRUE(hit);
  EXPECT_EQ(world.geomName(hit->geom), "m");
  EXPECT_NEAR(hit->distance, 2.5, 1e-12);
  EXPECT_EQ(caster.staticGeomCount(), 4);
  expectSameAsMjRay(world, kCasterBuilding, 500, 4, 20);
}

TEST(RayCaster, ARayLandingBesideASlabStillFindsItsSide) {
  // A 10 m × 10 m slab 0.2 m thick in a 25 m scene (nine small boxes around it): a slab, tested
  // apart from the hierarchy. A ray that crosses the slab's top plane beside it can still enter
  // through a side while within its height; one that is too steep to reach it misses.
  std::string xml = R"(<mujoco><worldbody>
      <geom name="slab" type="box" pos="0 0 0" size="5 5 0.1" group="1"/>)";
  for (int i = 0; i < 9; ++i) {
    xml += "<geom type=\"box\" size=\"0.5 0.5 1\" group=\"1\" pos=\"" +
           std::to_string(-12 + 3 * i) + " " + std::to_string(i % 2 == 0 ? 12 : -12) + " 1\"/>";
  }
  xml += "</worldbody></mujoco>";
  const MujocoWorld world = MujocoWorld::fromXml(xml);
  const RayCaster caster(world.model(), world.data(), kCasterBuilding);
  ASSERT_EQ(caster.largeCount(), 1);
  // From (6, 0, 1) down at 45° towards −x: the top plane z = 0.1 is crossed at x = 5.1, beside
  // the slab; the side x = 5 is met at z = 0, after √2 m.
  auto hit = caster.cast({6, 0, 1}, Eigen::Vector3d(-1, 0, -1).normalized());
  ASSERT_TRUE(hit);
  EXPECT_EQ(world.geomName(hit->geom), "slab");
  EXPECT_NEAR(hit->distance, std::sqrt(2.0), 1e-12);
  // Three times steeper: the top plane at x = 5.7, the bottom one at x = 5.633: never within it.
  EXPECT_FALSE(caster.cast({6, 0, 1}, Eigen::Vector3d(-1, 0, -3).normalized()));
  // From below: the bottom plane z = −0.1 at x = −5.03, beside the slab; the side x = −5 at
  // z = −0.07, after 0.08 √2 m.
  hit = caster.cast({-5.08, 0.3, -0.15}, Eigen::Vector3d(1, 0, 1).normalized());
  ASSERT_TRUE(hit);
  EXPECT_EQ(world.geomName(hit->geom), "slab");
  EXPECT_NEAR(hit->distance, 0.08 * std::sqrt(2.0), 1e-12);
  expectSameAsMjRay(world, kCasterBuilding, 3000, 8, 100);
}

}  // namespace
}  // namespace isg::sim
