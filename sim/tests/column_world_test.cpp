#include <gtest/gtest.h>

#include <random>

#include "bim/tests/test_plans.hpp"
#include "sim/mujoco_world.hpp"
#include "sim/occupancy_grid.hpp"
#include "sim/ray_caster.hpp"
#include "sim/scan_caster.hpp"
#include "sim/vlp16.hpp"
#include "worlds/mjcf_generator.hpp"

namespace isg::sim {
namespace {

constexpr unsigned kColumnGroups = (1u << worlds::kBuildingGroup) | (1u << worlds::kCeilingGroup);

const bim::Plan& columnHall() {
  static const bim::Plan plan = bim::testing::parsePlanJson(bim::testing::columnHallPlanJson());
  return plan;
}

int geomNamed(const MujocoWorld& world, const std::string& name) {
  return mj_name2id(&world.model(), mjOBJ_GEOM, name.c_str());
}

TEST(ColumnWorld, RectangularColumnsAreBoxesAndRoundOnesCylinders) {
  const MujocoWorld world = MujocoWorld::fromXml(worlds::generateMjcf(columnHall()));
  const mjModel& m = world.model();
  const int c1 = geomNamed(world, "column/C1");
  ASSERT_GE(c1, 0);
  EXPECT_EQ(m.geom_type[c1], mjGEOM_BOX);
  EXPECT_NEAR(m.geom_size[3 * c1 + 0], 0.2, 1e-9);
  EXPECT_NEAR(m.geom_size[3 * c1 + 1], 0.15, 1e-9);
  EXPECT_NEAR(m.geom_size[3 * c1 + 2], 1.5, 1e-9);
  const int c4 = geomNamed(world, "column/C4");
  ASSERT_GE(c4, 0);
  EXPECT_EQ(m.geom_type[c4], mjGEOM_CYLINDER);
  EXPECT_NEAR(m.geom_size[3 * c4 + 0], 0.25, 1e-9);  // radius
  EXPECT_NEAR(m.geom_size[3 * c4 + 1], 1.25, 1e-9);  // half of 2.6 − 0.1
  EXPECT_NEAR(world.data().geom_xpos[3 * c4 + 2], 1.35, 1e-9);
  for (const char* id : {"column/C2", "column/C3", "column/C5"}) EXPECT_GE(geomNamed(world, id), 0);
}

TEST(ColumnWorld, TheCasterSeesColumnsExactlyAsMjRay) {
  const MujocoWorld world = MujocoWorld::fromXml(worlds::generateMjcf(columnHall()));
  const mjModel& m = world.model();
  const RayCaster caster(m, world.data(), kColumnGroups);
  // By hand: from (3, 4) at 1 m, north onto C3 (r 0.2 about (3, 6)) after 1.8 m, south onto C1's
  // north face (y = 2.15) after 1.85 m; from (9, 6 − 1) north-east grazing nothing but C4.
  auto hit = caster.cast({3, 4, 1}, {0, 1, 0});
  ASSERT_TRUE(hit);
  EXPECT_EQ(world.geomName(hit->geom), "column/C3");
  EXPECT_NEAR(hit->distance, 1.8, 1e-9);
  hit = caster.cast({3, 4, 1}, {0, -1, 0});
  ASSERT_TRUE(hit);
  EXPECT_EQ(world.geomName(hit->geom), "column/C1");
  EXPECT_NEAR(hit->distance, 1.85, 1e-9);
  // Below C4's plinth (base 0.1 m) a ray passes under it.
  hit = caster.cast({9, 4, 0.05}, {0, 1, 0});
  ASSERT_TRUE(hit);
  EXPECT_NE(world.geomName(hit->geom), "column/C4");
  // And every random ray, from anywhere, as mj_ray: the hierarchy and the per-turn sectors.
  const auto mask = groupArray(kColumnGroups);
  ScanCaster scan(caster);
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  std::normal_distribution<double> n(0.0, 1.0);
  int hits = 0, cylinder_hits = 0;
  for (int turn = 0; turn < 40; ++turn) {
    const Eigen::Vector2d centre(0.5 + 11 * u(rng), 0.5 + 7 * u(rng));
    scan.prepare(centre, 0.08);
    for (int k = 0; k < 400; ++k) {
      const Eigen::Vector3d origin(centre.x() + 0.1 * (u(rng) - 0.5),
                                   centre.y() + 0.1 * (u(rng) - 0.5), 0.2 + 2.6 * u(rng));
      const Eigen::Vector3d dir = Eigen::Vector3d(n(rng), n(rng), 0.2 * n(rng)).normalized();
      int geom = -1;
      const double expected =
          mj_ray(&m, &world.data(), origin.data(), dir.data(), mask.data(), 1, -1, &geom);
      for (const auto& got : {caster.cast(origin, dir), scan.cast(origin, dir)}) {
        if (expected < 0) {
          EXPECT_FALSE(got);
          continue;
        }
        ASSERT_TRUE(got) << "turn " << turn << " ray " << k;
        EXPECT_EQ(got->geom, geom) << "turn " << turn << " ray " << k;
        EXPECT_NEAR(got->distance, expected, 1e-9);
      }
      hits += expected >= 0;
      cylinder_hits += expected >= 0 && m.geom_type[geom] == mjGEOM_CYLINDER;
    }
  }
  EXPECT_GT(hits, 15000);
  EXPECT_GT(cylinder_hits, 100);
}

TEST(ColumnWorld, TheRouteGridGoesRoundColumns) {
  const OccupancyGrid grid(columnHall(), {}, "L0");
  EXPECT_TRUE(grid.blocked(grid.cellOf({3, 6})));     // round
  EXPECT_TRUE(grid.blocked(grid.cellOf({3.17, 6})));  // its edge
  EXPECT_TRUE(grid.blocked(grid.cellOf({9, 2.15})));  // C2, 0.4 m deep in y: to 2.2
  EXPECT_FALSE(grid.blocked(grid.cellOf({6, 4})));
  // 0.6 m from C3's centre: 0.4 m from its surface, less one cell's diagonal (0.07 m).
  EXPECT_NEAR(grid.clearanceAt({3.6, 6.0}), 0.4, 0.1);
  EXPECT_LE(grid.clearanceAt({3.6, 6.0}), 0.4);
}

}  // namespace
}  // namespace isg::sim
