#include "sim/scan_caster.hpp"

#include <gtest/gtest.h>

#include <random>

#include "bim/plan_parser.hpp"
#include "bim/polygon.hpp"
#include "bim/synthetic_plan.hpp"
#include "common/json_reader.hpp"
#include "sim/mujoco_world.hpp"
#include "sim/vlp16.hpp"
#include "worlds/mjcf_generator.hpp"
#include "worlds/reference_plans.hpp"

namespace isg::sim {
namespace {

constexpr unsigned kCasterGroups = (1u << worlds::kBuildingGroup) | (1u << worlds::kCeilingGroup);

// Full VLP-16 turns from every room, with the sensor wandering inside the prepared disc, and a
// few rays from outside it (the fallback): every ray must give exactly what mj_ray gives.
void expectScansMatchMjRay(const bim::Scenario& scenario, int sequence_step) {
  const MujocoWorld world = MujocoWorld::fromXml(worlds::generateMjcf(scenario));
  const mjModel& m = world.model();
  const RayCaster caster(m, world.data(), kCasterGroups);
  ScanCaster scan(caster);
  const auto mask = groupArray(kCasterGroups);
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  const double radius = 0.08;
  int rays = 0;
  for (const auto& room : scenario.plan.levels[0].rooms) {
    const Eigen::Vector2d c = bim::centroid(room.outline);
    scan.prepare(c, radius);
    for (int s = 0; s < Vlp16::sequencesPerTurn(10.0); s += sequence_step) {
      for (int l = 0; l < Vlp16::kLasers; ++l) {
        const double scale = l == 15 && s % 50 == 0 ? 3.0 : 0.7;  // some from outside the disc
        const Eigen::Vector3d origin(c.x() + scale * radius * u(rng),
                                     c.y() + scale * radius * u(rng), 0.71 + Vlp16::origin(l).z());
        const Eigen::Vector3d dir =
            Vlp16::direction(l, Vlp16::azimuth(Vlp16::firingTime(s, l), 10));
        int geom = -1;
        const double expected =
            mj_ray(&m, &world.data(), origin.data(), dir.data(), mask.data(), 1, -1, &geom);
        const auto hit = scan.cast(origin, dir);
        ++rays;
        if (expected < 0) {
          EXPECT_FALSE(hit);
          continue;
        }
        ASSERT_TRUE(hit) << room.id << " sequence " << s << " laser " << l;
        EXPECT_EQ(hit->geom, geom) << room.id << " sequence " << s << " laser " << l;
        EXPECT_NEAR(hit->distance, expected, 1e-9);
      }
    }
  }
  EXPECT_GT(rays, 1000);
}

TEST(ScanCaster, MatchesMjRayOnEveryReferenceWorld) {
  for (const char* name :
       {"d1.asbuilt", "d2.asbuilt", "d3.asbuilt", "d4.asbuilt", "d5.asbuilt", "d6.asbuilt"}) {
    SCOPED_TRACE(name);
    expectScansMatchMjRay(worlds::loadScenarioOrBuiltin(std::string("builtin:") + name, nullptr),
                          3);
  }
}

TEST(ScanCaster, MatchesMjRayOnTheTwoHundredRoomGrid) {
  const common::JsonSource source{"grid.json", nullptr};
  const nlohmann::json doc = bim::makeGridPlan({});
  bim::Scenario s;
  s.plan = bim::parsePlan(common::JsonNode(doc, "", source));
  s.plan.levels[0].rooms.resize(12);  // a dozen rooms are enough, and quick
  expectScansMatchMjRay(s, 7);
}

}  // namespace
}  // namespace isg::sim
