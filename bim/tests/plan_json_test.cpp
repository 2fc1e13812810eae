// The one writer of the plan format (bim::planToJson): a dataset's complete record, a plan as
// people write it (isg generate, isg import), and names kept or left out; the as-built writer.
#include "bim/plan_json.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "bim/as_built_wall.hpp"
#include "bim/scenario.hpp"
#include "bim/tests/test_plans.hpp"

namespace isg::bim {
namespace {

using testing::parsePlanJson;
using testing::twoRoomPlanJson;

// The two-room plan with a name on its level, a wall, a door, a window and where it came from.
nlohmann::json namedPlanJson() {
  nlohmann::json doc = twoRoomPlanJson();
  doc["imported_from"] = {{"file", "house.ifc"}, {"schema", "IFC4"}};
  doc["levels"][0]["name"] = "Ground floor";
  doc["levels"][0]["walls"][4]["name"] = "Partition";
  doc["levels"][0]["doors"][0]["name"] = "Oak door";
  doc["levels"][0]["windows"] = {{{"id", "G1"},
                                  {"wall", "W2"},
                                  {"offset", 2.0},
                                  {"width", 1.2},
                                  {"sill", 0.9},
                                  {"height", 1.2},
                                  {"name", "Window 1"}}};
  return doc;
}

TEST(PlanJson, EveryDefaultWrittenByDefault) {
  const nlohmann::ordered_json written = planToJson(parsePlanJson(twoRoomPlanJson()));
  const auto& level = written["levels"][0];
  // W1 gave no height: the level's 3 m written; W5 its own 2.8 m; every base 0.
  EXPECT_EQ(level["walls"][0]["height"], 3.0);
  EXPECT_EQ(level["walls"][4]["height"], 2.8);
  EXPECT_EQ(level["walls"][0]["base"], 0.0);
  // D1's rooms were inferred from the outlines, the one on the wall's left first (W5 runs +y:
  // its left is the west, R1); D2's given.
  EXPECT_EQ(level["doors"][0]["rooms"], nlohmann::ordered_json({"R1", "R2"}));
  EXPECT_EQ(level["doors"][1]["rooms"], nlohmann::ordered_json({"R2", "outside"}));
  // Keys in the format's order.
  std::vector<std::string> keys;
  for (const auto& item : written.items()) keys.push_back(item.key());
  EXPECT_EQ(keys, (std::vector<std::string>{"format", "version", "name", "levels"}));
}

TEST(PlanJson, AsPeopleWriteItLeavesOutWhatTheParserFillsIn) {
  const nlohmann::ordered_json written = planToJson(
      parsePlanJson(twoRoomPlanJson()), {.every_wall_height = false, .inferred_door_rooms = false});
  const auto& level = written["levels"][0];
  EXPECT_FALSE(level["walls"][0].contains("height"));
  EXPECT_FALSE(level["walls"][0].contains("base"));
  EXPECT_EQ(level["walls"][4]["height"], 2.8);  // not the level's: kept
  EXPECT_FALSE(level["doors"][0].contains("rooms"));
  EXPECT_EQ(level["doors"][1]["rooms"], nlohmann::ordered_json({"R2", "outside"}));
  // It reads back to the same plan, door rooms inferred again.
  const Plan again = parsePlanJson(nlohmann::json::parse(written.dump()));
  EXPECT_EQ(again.levels[0].walls[0].height, 3.0);
  EXPECT_EQ(again.levels[0].doors[0].rooms[0], "R1");
  EXPECT_TRUE(again.levels[0].doors[0].rooms_inferred);
}

TEST(PlanJson, NamesAndOriginRoundTripAndCanBeLeftOut) {
  const Plan plan = parsePlanJson(namedPlanJson());
  ASSERT_TRUE(plan.imported_from.has_value());
  EXPECT_EQ(plan.imported_from->schema, "IFC4");
  EXPECT_EQ(plan.levels[0].name, "Ground floor");
  const nlohmann::ordered_json written = planToJson(plan);
  EXPECT_EQ(written["imported_from"],
            nlohmann::ordered_json({{"file", "house.ifc"}, {"schema", "IFC4"}}));
  EXPECT_EQ(written["levels"][0]["name"], "Ground floor");
  EXPECT_EQ(written["levels"][0]["walls"][4]["name"], "Partition");
  EXPECT_FALSE(written["levels"][0]["walls"][0].contains("name"));
  EXPECT_EQ(written["levels"][0]["doors"][0]["name"], "Oak door");
  EXPECT_EQ(written["levels"][0]["windows"][0]["name"], "Window 1");
  const Plan again = parsePlanJson(nlohmann::json::parse(written.dump()));
  EXPECT_EQ(again.levels[0].walls[4].name, "Partition");
  EXPECT_EQ(again.levels[0].windows[0].name, "Window 1");
  // Without names: the geometry alone, equal to the unnamed plan's.
  const nlohmann::ordered_json bare = planToJson(plan, {.names = false});
  EXPECT_FALSE(bare.contains("imported_from"));
  EXPECT_FALSE(bare["levels"][0].contains("name"));
  nlohmann::json unnamed = twoRoomPlanJson();
  unnamed["levels"][0]["windows"] = namedPlanJson()["levels"][0]["windows"];
  unnamed["levels"][0]["windows"][0].erase("name");
  EXPECT_EQ(bare["levels"], planToJson(parsePlanJson(unnamed))["levels"]);
}

TEST(PlanJson, AControlCharacterInAWallNameIsRefused) {
  nlohmann::json doc = twoRoomPlanJson();
  doc["levels"][0]["walls"][1]["name"] = "bad\nname";
  try {
    parsePlanJson(doc);
    FAIL() << "accepted";
  } catch (const common::InputError& e) {
    EXPECT_EQ(e.pointer(), "/levels/0/walls/1/name");
  }
}

// An as-built object written, read back as a dataset's metadata.json is read.
AsBuilt readBack(const nlohmann::ordered_json& written, const Plan& plan) {
  const nlohmann::json document = nlohmann::json::parse(written.dump());
  const common::JsonSource source{"metadata.json", nullptr};
  return parseAsBuiltJson(common::JsonNode(document, "/as_built", source), plan, "L0");
}

TEST(AsBuiltJson, TurnedWallsAreRecordedOnlyWhereThereAreSome) {
  AsBuilt as_built;
  as_built.wall_shifts.push_back({"W5", 0.1});
  EXPECT_FALSE(asBuiltToJson(as_built).contains("wall_rotations"));
  as_built.wall_rotations.push_back({"W2", 3.5, WallRotation::About::kStart});
  const nlohmann::ordered_json written = asBuiltToJson(as_built);
  EXPECT_EQ(
      written["wall_rotations"],
      nlohmann::ordered_json::array({{{"wall", "W2"}, {"angle_deg", 3.5}, {"about", "start"}}}));
  // And the scenario reader takes it back.
  const AsBuilt again = readBack(written, parsePlanJson(twoRoomPlanJson()));
  ASSERT_EQ(again.wall_rotations.size(), 1u);
  EXPECT_EQ(again.wall_rotations[0].wall, "W2");
  EXPECT_EQ(again.wall_rotations[0].angle_deg, 3.5);
  EXPECT_EQ(again.wall_rotations[0].about, WallRotation::About::kStart);
}

// A turn about a point along the wall is written as its metres from the wall's start, and read
// back as such.
TEST(AsBuiltJson, ATurnAboutAPointAlongTheWallIsWrittenInMetres) {
  AsBuilt as_built;
  as_built.wall_rotations.push_back({"W2", -2.0, WallRotation::About::kAlong, 1.25});
  const nlohmann::ordered_json written = asBuiltToJson(as_built);
  EXPECT_EQ(written["wall_rotations"][0]["about"], 1.25);
  const Plan plan = parsePlanJson(twoRoomPlanJson());
  const AsBuilt again = readBack(written, plan);
  ASSERT_EQ(again.wall_rotations.size(), 1u);
  EXPECT_EQ(again.wall_rotations[0].about, WallRotation::About::kAlong);
  EXPECT_EQ(again.wall_rotations[0].along_m, 1.25);
  // W2 runs (6, 0) → (6, 4): turned −2° about (6, 1.25).
  const Wall* planned = plan.levels[0].findWall("W2");
  ASSERT_NE(planned, nullptr);
  const Wall built = builtWall(*planned, again);
  const double s = std::sin(2.0 * std::numbers::pi / 180.0);
  EXPECT_NEAR(built.start.x(), 6.0 - 1.25 * s, 1e-12);
  EXPECT_NEAR(built.end.x(), 6.0 + 2.75 * s, 1e-12);
  EXPECT_NEAR(rotationPivotAlong(*planned, again.wall_rotations[0]), 1.25, 1e-12);
}

// Written as a person writes a scenario (isg generate): only the lists that hold something, an
// extra wall's base and level and a box's level only where not their defaults; read back the same.
TEST(AsBuiltJson, WrittenForPeopleItLeavesOutEmptyListsAndDefaultsAndReadsBackTheSame) {
  AsBuilt as_built;
  as_built.closed_doors = {"D1"};
  ExtraWall partition;
  partition.start = {1.0, 1.0};
  partition.end = {1.0, 3.0};
  as_built.extra_walls.push_back(partition);
  Clutter box;
  box.center = {2.0, 2.0, 0.25};
  box.size = {0.5, 0.5, 0.5};
  box.yaw = 0.1;
  as_built.clutter.push_back(box);
  const AsBuiltJsonStyle for_people{.empty_lists = false, .default_fields = false};
  const nlohmann::ordered_json written = asBuiltToJson(as_built, for_people);
  std::vector<std::string> keys;
  for (const auto& [key, value] : written.items()) keys.push_back(key);
  EXPECT_EQ(keys, (std::vector<std::string>{"extra_walls", "closed_doors", "clutter"}));
  EXPECT_EQ(written["extra_walls"][0].dump(),
            R"({"start":[1.0,1.0],"end":[1.0,3.0],"thickness":0.1})");
  EXPECT_EQ(written["clutter"][0].dump(),
            R"({"shape":"box","center":[2.0,2.0,0.25],"size":[0.5,0.5,0.5],"yaw":0.1})");
  // Where they differ from their defaults, they are written.
  as_built.extra_walls[0].base = 0.5;
  as_built.extra_walls[0].level = "L0";
  as_built.clutter[0].level = "L0";
  const nlohmann::ordered_json spelt = asBuiltToJson(as_built, for_people);
  EXPECT_EQ(spelt["extra_walls"][0]["base"], 0.5);
  EXPECT_EQ(spelt["extra_walls"][0]["level"], "L0");
  EXPECT_EQ(spelt["clutter"][0]["level"], "L0");
  // A dataset's style writes every list it always did, empty or not.
  keys.clear();
  const nlohmann::ordered_json for_a_dataset = asBuiltToJson(as_built);
  for (const auto& [key, value] : for_a_dataset.items()) keys.push_back(key);
  EXPECT_EQ(keys, (std::vector<std::string>{"missing_walls", "extra_walls", "wall_shifts",
                                            "closed_doors", "clutter"}));
  // Read back, the people's file gives the same deviations.
  const AsBuilt again = readBack(written, parsePlanJson(twoRoomPlanJson()));
  EXPECT_EQ(again.closed_doors, as_built.closed_doors);
  ASSERT_EQ(again.extra_walls.size(), 1u);
  EXPECT_EQ(again.extra_walls[0].end, partition.end);
  EXPECT_EQ(again.extra_walls[0].base, 0.0);
  ASSERT_EQ(again.clutter.size(), 1u);
  EXPECT_EQ(again.clutter[0].center, box.center);
  EXPECT_TRUE(again.wall_shifts.empty() && again.missing_walls.empty());
}

}  // namespace
}  // namespace isg::bim
