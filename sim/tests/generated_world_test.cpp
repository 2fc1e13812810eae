// The generated worlds, checked the way the simulated LiDAR will see them: mj_ray from inside
// rooms against the faces the plan says are there.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>

#include "bim/plan_geometry.hpp"
#include "bim/plan_parser.hpp"
#include "bim/polygon.hpp"
#include "bim/stairs.hpp"
#include "bim/synthetic_plan.hpp"
#include "common/json_reader.hpp"
#include "sim/mujoco_world.hpp"
#include "worlds/mjcf_generator.hpp"
#include "worlds/reference_plans.hpp"

namespace isg::worlds {
namespace {

constexpr double kMillimetre = 1e-3;
constexpr unsigned kGeneratedBuilding = 1u << kBuildingGroup;

bim::Scenario generatedBuiltin(const std::string& name) {
  return loadScenarioOrBuiltin(std::string(kBuiltinPrefix) + name, nullptr);
}

bool startsWith(const std::string& s, const std::string& prefix) { return s.rfind(prefix, 0) == 0; }

bool inOpening(const bim::WallFace& face, double s, double margin) {
  for (const auto& o : face.openings) {
    if (s > o.lo - margin && s < o.hi + margin) return true;
  }
  return false;
}

// Whether a point of `level` lies on a flight of stairs that starts or ends there.
bool onAFlight(const bim::Plan& plan, const bim::Level& level, const Eigen::Vector2d& point) {
  for (const auto& from : plan.levels) {
    for (const auto& stair : from.stairs) {
      const bim::Level& to = *plan.findLevel(stair.to);
      if (&from != &level && &to != &level) continue;
      if (bim::computeStairGeometry(stair, from, to).contains(point, 0.05)) return true;
    }
  }
  return false;
}

// For every face that bounds a room, casts rays from points 0.5 m inside the room straight at
// the face, at 1 m height, and checks that each hits that wall at 0.5 m. Returns the rays cast.
int checkRoomFaces(const bim::Plan& plan, const sim::MujocoWorld& world) {
  int rays = 0;
  for (const auto& level : plan.levels) {
    const bim::LevelGeometry geometry = bim::computeLevelGeometry(level);
    for (const auto& b : geometry.boundaries) {
      const bim::WallGeometry& wall = *geometry.findWall(b.wall);
      const bim::WallFace& face = wall.face(b.side);
      const bim::Room& room = *level.findRoom(b.room);
      const Eigen::Vector2d a = room.outline[b.edge];
      const Eigen::Vector2d c = room.outline[(b.edge + 1) % room.outline.size()];
      const Eigen::Vector2d n2 = face.plane.normal.head<2>();
      for (double f : {0.2, 0.5, 0.8}) {
        const Eigen::Vector2d on_edge = a + f * (c - a);
        const double s = (on_edge - wall.wall->start).dot(wall.axis);
        if (inOpening(face, s, 0.3)) continue;
        bool exposed = false;
        for (const auto& piece : face.exposed) exposed |= s > piece.lo + 0.3 && s < piece.hi - 0.3;
        if (!exposed) continue;
        const Eigen::Vector2d inside = on_edge + 0.5 * n2;
        if (!bim::containsPoint(room.outline, inside)) continue;
        if (onAFlight(plan, level, inside)) continue;  // inside the steps: no ray to cast
        const Eigen::Vector3d origin(inside.x(), inside.y(), level.elevation + 1.0);
        const double expected = face.plane.signedDistance(origin);
        const auto hit = world.ray(origin, -face.plane.normal, kGeneratedBuilding);
        ++rays;
        if (!hit) {
          ADD_FAILURE() << "no hit from room " << b.room << " towards " << b.wall;
          continue;
        }
        EXPECT_NEAR(hit->distance, expected, kMillimetre) << b.room << " → " << b.wall;
        EXPECT_TRUE(startsWith(world.geomName(hit->geom), "wall/" + b.wall + "/"))
            << b.room << " → " << b.wall << " hit " << world.geomName(hit->geom);
      }
    }
  }
  return rays;
}

class ReferenceWorld : public ::testing::TestWithParam<std::string> {};

TEST_P(ReferenceWorld, RaysFromInsideRoomsHitTheExpectedInnerFaces) {
  const bim::Scenario scenario = generatedBuiltin(GetParam());
  const sim::MujocoWorld world = sim::MujocoWorld::fromXml(generateMjcf(scenario));
  const int rays = checkRoomFaces(scenario.plan, world);
  // Every room has four or more faces, most sampled at three points.
  EXPECT_GT(rays, 4 * int(scenario.plan.levels[0].rooms.size()));
}

TEST_P(ReferenceWorld, EveryOpenDoorLetsARayThroughIntoTheNextRoom) {
  const bim::Scenario scenario = generatedBuiltin(GetParam());
  const sim::MujocoWorld world = sim::MujocoWorld::fromXml(generateMjcf(scenario));
  const bim::Level& level = scenario.plan.levels[0];
  for (const auto& door : level.doors) {
    const bim::Wall& wall = *level.findWall(door.wall);
    const Eigen::Vector2d axis = (wall.end - wall.start).normalized();
    const Eigen::Vector2d left(-axis.y(), axis.x());
    const Eigen::Vector2d centre = bim::doorCentre(level, door);
    for (int side : {+1, -1}) {
      if (door.rooms[side > 0 ? 0 : 1] == bim::kOutside) continue;  // start inside the building
      const Eigen::Vector2d from = centre + side * (0.5 * wall.thickness + 0.4) * left;
      const Eigen::Vector3d origin(from.x(), from.y(), level.elevation + 1.0);
      const auto hit = world.ray(origin, Eigen::Vector3d(-side * left.x(), -side * left.y(), 0),
                                 kGeneratedBuilding);
      const double beyond_wall = 0.4 + wall.thickness + 0.05;
      if (hit) {
        EXPECT_GT(hit->distance, beyond_wall)
            << "door " << door.id << " blocked by " << world.geomName(hit->geom);
        EXPECT_FALSE(startsWith(world.geomName(hit->geom), "wall/" + wall.id + "/"));
      }
      // Just above the opening the lintel is in the way.
      const Eigen::Vector3d high(from.x(), from.y(),
                                 level.elevation + wall.base + door.height + 0.1);
      const auto lintel = world.ray(high, Eigen::Vector3d(-side * left.x(), -side * left.y(), 0),
                                    kGeneratedBuilding);
      if (door.height + 0.1 < wall.height - wall.base) {
        ASSERT_TRUE(lintel);
        EXPECT_EQ(world.geomName(lintel->geom), "wall/" + wall.id + "/lintel/" + door.id);
        EXPECT_NEAR(lintel->distance, 0.4, kMillimetre);
      }
    }
  }
}

INSTANTIATE_TEST_SUITE_P(Plans, ReferenceWorld,
                         ::testing::Values("d1", "d2", "d3", "d4", "d5", "d6"));

TEST(AsBuiltWorld, ClosedDoorStopsTheRayAtItsLeaf) {
  const bim::Scenario scenario =
      generatedBuiltin("d1.asbuilt");  // D5, the entrance in W4 (x = 0), closed
  const sim::MujocoWorld world = sim::MujocoWorld::fromXml(generateMjcf(scenario));
  // D5 is centred at y = 8 - 6.9 = 1.1 on the wall x = 0; its 4 cm leaf spans x in [-0.02, 0.02].
  const auto hit = world.ray({1.0, 1.1, 1.0}, {-1, 0, 0}, kGeneratedBuilding);
  ASSERT_TRUE(hit);
  EXPECT_EQ(world.geomName(hit->geom), "door/D5");
  EXPECT_NEAR(hit->distance, 1.0 - 0.02, kMillimetre);
  // The same opening in the plan's own world lets the ray out of the building.
  const sim::MujocoWorld plan_world = sim::MujocoWorld::fromXml(generateMjcf(scenario.plan));
  EXPECT_FALSE(plan_world.ray({1.0, 1.1, 1.0}, {-1, 0, 0}, kGeneratedBuilding));
}

TEST(PlanWorld, AWindowLetsTheRayOutBetweenItsSillAndItsHead) {
  bim::Scenario scenario = generatedBuiltin("d1");
  // W1 runs (0, 0) → (12, 0), 0.3 m thick (faces at y = ±0.15); the window spans x in [8.4, 9.6]
  // and z in [0.9, 2.1].
  bim::Level& level = scenario.plan.levels[0];
  level.windows.push_back({"V1", "W1", 9.0, 1.2, 0.9, 1.2, ""});
  const sim::MujocoWorld world = sim::MujocoWorld::fromXml(generateMjcf(scenario.plan));
  EXPECT_FALSE(world.ray({9.0, 1.0, 1.5}, {0, -1, 0}, kGeneratedBuilding));  // through the glass
  auto hit = world.ray({9.0, 1.0, 0.5}, {0, -1, 0}, kGeneratedBuilding);     // below the sill
  ASSERT_TRUE(hit);
  EXPECT_EQ(world.geomName(hit->geom), "wall/W1/sill/V1");
  EXPECT_NEAR(hit->distance, 0.85, kMillimetre);
  hit = world.ray({9.0, 1.0, 2.5}, {0, -1, 0}, kGeneratedBuilding);  // above the head
  ASSERT_TRUE(hit);
  EXPECT_EQ(world.geomName(hit->geom), "wall/W1/lintel/V1");
  hit = world.ray({8.3, 1.0, 1.5}, {0, -1, 0}, kGeneratedBuilding);  // beside it
  ASSERT_TRUE(hit);
  EXPECT_EQ(world.geomName(hit->geom), "wall/W1/0");
  EXPECT_NEAR(hit->distance, 0.85, kMillimetre);
}

TEST(AsBuiltWorld, ShiftedWallMovesAlongItsLeftNormal) {
  const bim::Scenario scenario = generatedBuiltin("d1.asbuilt");
  // W6 runs (4, 2.2) → (4, 8): its left is -x, so +0.05 moves it to x = 3.95 and its west face
  // from 3.925 to 3.875.
  const sim::MujocoWorld built = sim::MujocoWorld::fromXml(generateMjcf(scenario));
  const sim::MujocoWorld planned = sim::MujocoWorld::fromXml(generateMjcf(scenario.plan));
  const Eigen::Vector3d origin(2.0, 5.0, 1.0);
  const auto as_built = built.ray(origin, {1, 0, 0}, kGeneratedBuilding);
  const auto as_planned = planned.ray(origin, {1, 0, 0}, kGeneratedBuilding);
  ASSERT_TRUE(as_built && as_planned);
  EXPECT_NEAR(as_planned->distance, 1.925, kMillimetre);
  EXPECT_NEAR(as_built->distance, 1.875, kMillimetre);
  EXPECT_THAT(built.geomName(as_built->geom), ::testing::StartsWith("wall/W6/"));
}

TEST(AsBuiltWorld, ClutterIsWhereTheScenarioSays) {
  const bim::Scenario scenario = generatedBuiltin("d1.asbuilt");
  const sim::MujocoWorld world = sim::MujocoWorld::fromXml(generateMjcf(scenario));
  // clutter/0: centre (1.0, 7.2, 0.4), size (1.2, 0.8, 0.8): its south face is y = 6.8.
  auto hit = world.ray({1.0, 5.0, 0.4}, {0, 1, 0}, kGeneratedBuilding);
  ASSERT_TRUE(hit);
  EXPECT_EQ(world.geomName(hit->geom), "clutter/0");
  EXPECT_NEAR(hit->distance, 1.8, kMillimetre);
  // Its top is z = 0.8: a ray down from 2 m above its centre stops 1.2 m down.
  hit = world.ray({1.0, 7.2, 2.0}, {0, 0, -1}, kGeneratedBuilding);
  ASSERT_TRUE(hit);
  EXPECT_NEAR(hit->distance, 1.2, kMillimetre);
  // clutter/1: centre (10.8, 4.0), size (0.6, 1.6), yawed 0.2 rad. Coming back towards its centre
  // along its own x axis from 2 m away, the face is met after 2 - 0.3 m.
  const Eigen::Vector3d dir(std::cos(0.2), std::sin(0.2), 0.0);
  const Eigen::Vector3d from = Eigen::Vector3d(10.8, 4.0, 0.5) - 2.0 * dir;
  hit = world.ray(from, dir, kGeneratedBuilding);
  ASSERT_TRUE(hit);
  EXPECT_EQ(world.geomName(hit->geom), "clutter/1");
  EXPECT_NEAR(hit->distance, 1.7, kMillimetre);
}

TEST(AsBuiltWorld, ExtraWallStandsWhereTheScenarioSays) {
  const bim::Scenario scenario =
      generatedBuiltin("d3.asbuilt");  // 0.1 m wall at x = 17, y in [0.1, 1.8]
  const sim::MujocoWorld world = sim::MujocoWorld::fromXml(generateMjcf(scenario));
  const auto hit = world.ray({15.0, 1.0, 1.0}, {1, 0, 0}, kGeneratedBuilding);
  ASSERT_TRUE(hit);
  EXPECT_EQ(world.geomName(hit->geom), "wall/extra0/0");
  EXPECT_NEAR(hit->distance, 1.95, kMillimetre);
}

TEST(AsBuiltWorld, MissingWallIsGoneWithItsDoors) {
  bim::Scenario scenario = generatedBuiltin("d1");
  scenario.as_built.missing_walls = {"W6"};  // the wall between offices 1 and 2
  const sim::MujocoWorld world = sim::MujocoWorld::fromXml(generateMjcf(scenario));
  EXPECT_EQ(world.geomId("wall/W6/0"), -1);
  // From office 1 towards office 2 the ray now reaches W7's west face at x = 7.925.
  const auto hit = world.ray({2.0, 5.0, 1.0}, {1, 0, 0}, kGeneratedBuilding);
  ASSERT_TRUE(hit);
  EXPECT_NEAR(hit->distance, 5.925, kMillimetre);
}

TEST(GeneratedWorld, CeilingAndFloorAreAtTheLevelsHeights) {
  const bim::Scenario scenario = generatedBuiltin("d2");
  const sim::MujocoWorld world = sim::MujocoWorld::fromXml(generateMjcf(scenario));
  const auto up = world.ray({3, 3, 1}, {0, 0, 1}, 1u << kCeilingGroup);
  ASSERT_TRUE(up);
  EXPECT_EQ(world.geomName(up->geom), "ceiling/L0");
  EXPECT_NEAR(up->distance, 2.0, kMillimetre);
  const auto down = world.ray({3, 3, 1}, {0, 0, -1}, kGeneratedBuilding);
  ASSERT_TRUE(down);
  EXPECT_EQ(world.geomName(down->geom), "floor/L0");
  EXPECT_NEAR(down->distance, 1.0, kMillimetre);
  // The ceiling is in its own group: the building group alone does not see it.
  EXPECT_FALSE(world.ray({3, 3, 1}, {0, 0, 1}, kGeneratedBuilding));
}

TEST(StairsWorld, StepsStandBelowAndTheUpperFloorIsOpenOverTheFlight) {
  // builtin:storeys: S1 runs from (9, 0.85) on L0 (z = 0) to (13.5, 0.85) on L1 (z = 3.2), 1 m
  // wide: 16 steps of 0.2 m, each 4.5 / 16 = 0.28125 m deep.
  const bim::Scenario scenario = generatedBuiltin("storeys");
  const sim::MujocoWorld world = sim::MujocoWorld::fromXml(generateMjcf(scenario));
  const unsigned everything = kGeneratedBuilding | (1u << kCeilingGroup);
  // Straight down from 1 m above L1's floor over the flight at x = 11 (s = 2.0: step 7, whose
  // tread is 8 × 0.2 = 1.6 m high): through both slabs onto the step.
  auto hit = world.ray({11.0, 0.85, 4.2}, {0, 0, -1}, everything);
  ASSERT_TRUE(hit);
  EXPECT_EQ(world.geomName(hit->geom), "stair/S1/7");
  EXPECT_NEAR(hit->distance, 2.6, kMillimetre);
  // Beside the opening the first floor is there, in pieces around the stairwell.
  hit = world.ray({11.0, 2.0, 4.2}, {0, 0, -1}, everything);
  ASSERT_TRUE(hit);
  EXPECT_TRUE(startsWith(world.geomName(hit->geom), "floor/L1/")) << world.geomName(hit->geom);
  EXPECT_NEAR(hit->distance, 1.0, kMillimetre);
  // The ground floor's ceiling is open over the flight only.
  hit = world.ray({8.5, 0.85, 1.0}, {0, 0, 1}, everything);
  ASSERT_TRUE(hit);
  EXPECT_TRUE(startsWith(world.geomName(hit->geom), "ceiling/L0/")) << world.geomName(hit->geom);
  EXPECT_NEAR(hit->distance, 2.0, kMillimetre);
  // Walking up to the flight along its axis, the first riser is 1 m ahead.
  hit = world.ray({8.0, 0.85, 0.1}, {1, 0, 0}, everything);
  ASSERT_TRUE(hit);
  EXPECT_EQ(world.geomName(hit->geom), "stair/S1/0");
  EXPECT_NEAR(hit->distance, 1.0, kMillimetre);
  // Looking down the stairwell from L1's landing at 1 m, a ray at -45° reaches the steps.
  hit = world.ray({14.5, 0.85, 4.2}, Eigen::Vector3d(-1, 0, -1).normalized(), everything);
  ASSERT_TRUE(hit);
  EXPECT_TRUE(startsWith(world.geomName(hit->geom), "stair/S1/")) << world.geomName(hit->geom);
  // The rooms' faces are where the plan says, on both storeys.
  EXPECT_GT(checkRoomFaces(scenario.plan, world), 40);
}

TEST(StairsWorld, APlanWithoutStairsKeepsItsSlabsWhole) {
  bim::Scenario scenario = generatedBuiltin("storeys");
  scenario.plan.levels[0].stairs.clear();
  const sim::MujocoWorld world = sim::MujocoWorld::fromXml(generateMjcf(scenario));
  EXPECT_GE(world.geomId("floor/L1"), 0);
  EXPECT_GE(world.geomId("ceiling/L0"), 0);
  EXPECT_EQ(world.geomId("floor/L1/0"), -1);
  const std::string mjcf = generateMjcf(scenario);
  EXPECT_THAT(mjcf, ::testing::Not(::testing::HasSubstr("\"stair/")));
  EXPECT_THAT(mjcf, ::testing::Not(::testing::HasSubstr("name=\"stair\"")));
}

TEST(GeneratedWorld, NamesFollowThePlanIds) {
  const bim::Scenario scenario = generatedBuiltin("d1");
  const sim::MujocoWorld world = sim::MujocoWorld::fromXml(generateMjcf(scenario));
  // W5 holds three doors: four solid pieces and three lintels.
  for (const char* name : {"wall/W5/0", "wall/W5/1", "wall/W5/2", "wall/W5/3", "wall/W5/lintel/D1",
                           "wall/W5/lintel/D2", "wall/W5/lintel/D3", "floor/L0", "ceiling/L0"}) {
    EXPECT_GE(world.geomId(name), 0) << name;
  }
  EXPECT_EQ(world.geomId("wall/W5/4"), -1);
  EXPECT_GE(mj_name2id(&world.model(), mjOBJ_SITE, "room/R4"), 0);
  for (int g = 0; g < world.model().ngeom; ++g) {
    const int group = world.model().geom_group[g];
    EXPECT_TRUE(group == kBuildingGroup || group == kCeilingGroup) << world.geomName(g);
  }
}

TEST(GeneratedWorld, MjcfSetsAutolimits) {
  const std::string mjcf = generateMjcf(generatedBuiltin("d1").plan);
  EXPECT_THAT(mjcf, ::testing::HasSubstr("<compiler autolimits=\"true\""));
}

bim::Plan parse(const nlohmann::json& document) {
  const common::JsonSource source{"test.json", nullptr};
  return bim::parsePlan(common::JsonNode(document, "", source));
}

TEST(AnyPlan, TwoHundredRoomGridWithLongWallsAndTJunctions) {
  const bim::Plan plan = parse(bim::makeGridPlan({}));
  const sim::MujocoWorld world = sim::MujocoWorld::fromXml(generateMjcf(plan));
  EXPECT_GT(checkRoomFaces(plan, world), 200 * 4);
}

TEST(AnyPlan, SlantedWallsAndTwoLevels) {
  // A triangle room with a 45° wall, on two levels stacked with no gap between them.
  nlohmann::json level = {
      {"id", "L0"},
      {"elevation", 0.0},
      {"height", 3.0},
      {"walls",
       {{{"id", "A0"}, {"start", {0, 0}}, {"end", {6, 0}}, {"thickness", 0.2}},
        {{"id", "B0"}, {"start", {6, 0}}, {"end", {0, 6}}, {"thickness", 0.2}},
        {{"id", "C0"}, {"start", {0, 6}}, {"end", {0, 0}}, {"thickness", 0.2}}}},
      {"rooms",
       {{{"id", "T0"},
         {"outline",
          {{0.1, 0.1}, {5.9 - 0.1 * std::sqrt(2.0), 0.1}, {0.1, 5.9 - 0.1 * std::sqrt(2.0)}}}}}}};
  nlohmann::json upper = level;
  upper["id"] = "L1";
  upper["elevation"] = 3.0;
  for (auto& w : upper["walls"]) w["id"] = w["id"].get<std::string>().substr(0, 1) + "1";
  upper["rooms"][0]["id"] = "T1";
  const bim::Plan plan =
      parse({{"format", "isg.plan"}, {"version", 1}, {"levels", {level, upper}}});
  const sim::MujocoWorld world = sim::MujocoWorld::fromXml(generateMjcf(plan));
  checkRoomFaces(plan, world);
  // From (1, 1) the slanted face x + y = 6 - 0.1·√2 is at (6 - 0.1·√2 - 2)/√2 along the normal.
  const Eigen::Vector3d diagonal(1.0 / std::sqrt(2.0), 1.0 / std::sqrt(2.0), 0.0);
  for (double z : {1.0, 4.0}) {
    const auto hit = world.ray({1, 1, z}, diagonal, kGeneratedBuilding);
    ASSERT_TRUE(hit);
    EXPECT_NEAR(hit->distance, (4.0 - 0.1 * std::sqrt(2.0)) / std::sqrt(2.0), kMillimetre);
  }
  // Up from level 0 the ceiling is at 3 m; down from level 1 the floor is at 3 m too.
  const auto up = world.ray({1, 1, 1}, {0, 0, 1}, kGeneratedBuilding | (1u << kCeilingGroup));
  ASSERT_TRUE(up);
  EXPECT_NEAR(up->distance, 2.0, kMillimetre);
  const auto down = world.ray({1, 1, 4}, {0, 0, -1}, kGeneratedBuilding);
  ASSERT_TRUE(down);
  EXPECT_EQ(world.geomName(down->geom), "floor/L1");
  EXPECT_NEAR(down->distance, 1.0, kMillimetre);
}

}  // namespace
}  // namespace isg::worlds
