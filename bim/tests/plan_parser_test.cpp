#include "bim/plan_parser.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "bim/plan_json.hpp"
#include "bim/tests/test_plans.hpp"

namespace isg::bim {
namespace {

using testing::parsePlanJson;
using testing::twoRoomPlanJson;

TEST(PlanParser, ReadsEveryFieldAndFillsDefaults) {
  const Plan plan = parsePlanJson(twoRoomPlanJson());
  EXPECT_EQ(plan.name, "two rooms");
  ASSERT_EQ(plan.levels.size(), 1u);
  const Level& level = plan.levels[0];
  EXPECT_EQ(level.id, "L0");
  EXPECT_DOUBLE_EQ(level.height, 3.0);
  ASSERT_EQ(level.walls.size(), 5u);
  EXPECT_EQ(level.walls[0].end, Eigen::Vector2d(6, 0));
  EXPECT_DOUBLE_EQ(level.walls[0].thickness, 0.2);
  EXPECT_DOUBLE_EQ(level.walls[0].height, 3.0);  // inherited from the level
  EXPECT_DOUBLE_EQ(level.walls[4].height, 2.8);  // its own
  EXPECT_DOUBLE_EQ(level.walls[0].base, 0.0);
  ASSERT_EQ(level.doors.size(), 2u);
  EXPECT_DOUBLE_EQ(level.doors[0].offset, 2.0);
  EXPECT_EQ(level.rooms[1].name, "East");
  EXPECT_EQ(level.rooms[1].outline.size(), 4u);
}

TEST(PlanParser, ReadsWindowsAndWritesThemBack) {
  auto doc = twoRoomPlanJson();
  doc["levels"][0]["windows"] = nlohmann::json::parse(
      R"([{"id": "V1", "wall": "W2", "offset": 2.0, "width": 1.2, "sill": 0.9, "height": 1.2}])");
  const Plan plan = parsePlanJson(doc);
  const Window* window = plan.levels[0].findWindow("V1");
  ASSERT_NE(window, nullptr);
  EXPECT_EQ(window->wall, "W2");
  EXPECT_DOUBLE_EQ(window->offset, 2.0);
  EXPECT_DOUBLE_EQ(window->width, 1.2);
  EXPECT_DOUBLE_EQ(window->sill, 0.9);
  EXPECT_DOUBLE_EQ(window->height, 1.2);
  const Plan again = parsePlanJson(nlohmann::json::parse(planToJson(plan).dump()));
  ASSERT_EQ(again.levels[0].windows.size(), 1u);
  EXPECT_DOUBLE_EQ(again.levels[0].windows[0].sill, 0.9);
  // A plan without windows is written without the key, as before the extension.
  EXPECT_FALSE(planToJson(parsePlanJson(twoRoomPlanJson()))["levels"][0].contains("windows"));
  // Window ids share the file's one namespace.
  doc["levels"][0]["windows"][0]["id"] = "D1";
  EXPECT_THROW(parsePlanJson(doc), common::InputError);
}

TEST(PlanParser, NameDefaultsToTheFileStem) {
  auto doc = twoRoomPlanJson();
  doc.erase("name");
  EXPECT_EQ(parsePlanJson(doc, nullptr, "plans/office.json").name, "office");
}

TEST(PlanParser, ClockwiseOutlineIsReversedWithAWarning) {
  auto doc = twoRoomPlanJson();
  doc["levels"][0]["rooms"][0]["outline"] = {{0.1, 0.1}, {0.1, 3.9}, {2.95, 3.9}, {2.95, 0.1}};
  common::Warnings warnings;
  const Plan plan = parsePlanJson(doc, &warnings);
  ASSERT_EQ(warnings.size(), 1u);
  EXPECT_EQ(warnings[0].str(),
            "test.json: /levels/0/rooms/0/outline: outline is clockwise; taken in "
            "counter-clockwise order");
  EXPECT_EQ(plan.levels[0].rooms[0].outline[0], Eigen::Vector2d(2.95, 0.1));
  EXPECT_EQ(plan.levels[0].rooms[0].outline[1], Eigen::Vector2d(2.95, 3.9));
}

TEST(PlanParser, UnknownFieldsAreWarningsNotErrors) {
  auto doc = twoRoomPlanJson();
  doc["levels"][0]["walls"][2]["colour"] = "red";
  doc["levels"][0]["rooms"][1]["a/b"] = 1;
  common::Warnings warnings;
  EXPECT_NO_THROW(parsePlanJson(doc, &warnings));
  ASSERT_EQ(warnings.size(), 2u);
  EXPECT_EQ(warnings[0].str(),
            "test.json: /levels/0/walls/2/colour: unknown field \"colour\" (ignored)");
  // JSON pointers escape '/' as ~1 (RFC 6901).
  EXPECT_EQ(warnings[1].pointer, "/levels/0/rooms/1/a~1b");
}

TEST(PlanParser, DoorWithRoomsThatCannotBeInferredWarns) {
  auto doc = twoRoomPlanJson();
  doc["levels"][0]["doors"].erase(1);
  doc["levels"][0]["rooms"].erase(1);  // no room east of the partition: D1 leads "outside"
  common::Warnings warnings;
  const Plan plan = parsePlanJson(doc, &warnings);
  EXPECT_EQ(plan.levels[0].doors[0].rooms[1], "outside");
  EXPECT_TRUE(warnings.empty());
  doc["levels"][0]["rooms"].erase(0);  // no rooms at all: outside on both sides
  parsePlanJson(doc, &warnings);
  ASSERT_FALSE(warnings.empty());
  EXPECT_THAT(warnings[0].message, ::testing::HasSubstr("cannot infer the rooms"));
}

TEST(PlanParser, ErrorCarriesFilePointerAndReason) {
  auto doc = twoRoomPlanJson();
  doc["levels"][0]["walls"][3]["thickness"] = -0.2;
  try {
    parsePlanJson(doc, nullptr, "plans/bad.json");
    FAIL() << "expected an InputError";
  } catch (const common::InputError& e) {
    EXPECT_EQ(e.file(), "plans/bad.json");
    EXPECT_EQ(e.pointer(), "/levels/0/walls/3/thickness");
    EXPECT_EQ(e.reason(), "must be in [0.001, 10], got -0.2");
    EXPECT_STREQ(e.what(),
                 "plans/bad.json: /levels/0/walls/3/thickness: must be in [0.001, 10], got -0.2");
  }
}

TEST(PlanParser, IfcGlobalIdsAreReadCheckedAndWrittenBack) {
  auto doc = twoRoomPlanJson();
  doc["levels"][0]["ifc_guid"] = "2O2Fr$t4X7Zf8NOew3FLOH";
  doc["levels"][0]["walls"][0]["ifc_guid"] = "3vB2YO$MX4xv5uCqZZG05x";
  doc["levels"][0]["doors"][0]["ifc_guid"] = "0Tif_$wI1FwAwq$OJt24I8";
  doc["levels"][0]["rooms"][1]["ifc_guid"] = "1mhmzb7$56gQVyIFfXmT4K";
  const Plan plan = parsePlanJson(doc);
  EXPECT_EQ(plan.levels[0].ifc_guid, "2O2Fr$t4X7Zf8NOew3FLOH");
  EXPECT_EQ(plan.levels[0].walls[0].ifc_guid, "3vB2YO$MX4xv5uCqZZG05x");
  EXPECT_EQ(plan.levels[0].walls[1].ifc_guid, "");
  const auto written = planToJson(plan);
  EXPECT_EQ(written["levels"][0]["doors"][0]["ifc_guid"], "0Tif_$wI1FwAwq$OJt24I8");
  EXPECT_EQ(written["levels"][0]["rooms"][1]["ifc_guid"], "1mhmzb7$56gQVyIFfXmT4K");
  EXPECT_FALSE(written["levels"][0]["walls"][1].contains("ifc_guid"));
  EXPECT_EQ(parsePlanJson(nlohmann::json::parse(written.dump())).levels[0].walls[0].ifc_guid,
            "3vB2YO$MX4xv5uCqZZG05x");
  // 22 characters of IFC's base64, the first 0-3: a UUID as text, a short one, a first 4 are not.
  for (const char* bad : {"3f2504e0-4f89-11d3-9a0c-0305e82c3301", "3vB2YO$MX4xv5uCqZZG05",
                          "4vB2YO$MX4xv5uCqZZG05x", "3vB2YO$MX4xv5uCqZZG05-"}) {
    doc["levels"][0]["walls"][0]["ifc_guid"] = bad;
    try {
      parsePlanJson(doc, nullptr, "plans/guid.json");
      FAIL() << "expected an InputError for " << bad;
    } catch (const common::InputError& e) {
      EXPECT_EQ(e.pointer(), "/levels/0/walls/0/ifc_guid");
      EXPECT_EQ(e.reason(),
                std::string("expected an IFC GlobalId: 22 characters of 0-9, A-Z, a-z, _ and $, "
                            "the first 0-3, not \"") +
                    bad + "\"");
    }
  }
}

TEST(PlanParser, SyntaxErrorNamesLineAndColumn) {
  try {
    common::parseJsonText("{\n  \"format\": \"isg.plan\",\n  \"version\": 1,,\n}", "bad.json");
    FAIL() << "expected an InputError";
  } catch (const common::InputError& e) {
    EXPECT_EQ(e.file(), "bad.json");
    EXPECT_THAT(e.reason(), ::testing::StartsWith("invalid JSON at line 3, column 16: "));
  }
}

TEST(PlanParser, MissingFileIsAnInputError) {
  try {
    loadPlan("/nonexistent/plan.json");
    FAIL() << "expected an InputError";
  } catch (const common::InputError& e) {
    EXPECT_STREQ(e.what(), "/nonexistent/plan.json: cannot open file: No such file or directory");
  }
}

}  // namespace
}  // namespace isg::bim

namespace isg::bim {
namespace {

TEST(PlanJson, WrittenPlanParsesToTheSamePlan) {
  const Plan plan = testing::parsePlanJson(testing::twoRoomPlanJson());
  const nlohmann::json written = nlohmann::json::parse(planToJson(plan).dump());
  common::Warnings warnings;
  const Plan again = testing::parsePlanJson(written, &warnings, "again.json");
  EXPECT_TRUE(warnings.empty());
  ASSERT_EQ(again.levels.size(), 1u);
  const Level& a = plan.levels[0];
  const Level& b = again.levels[0];
  ASSERT_EQ(a.walls.size(), b.walls.size());
  for (std::size_t i = 0; i < a.walls.size(); ++i) {
    EXPECT_EQ(a.walls[i].start, b.walls[i].start);
    EXPECT_EQ(a.walls[i].height, b.walls[i].height);
  }
  ASSERT_EQ(a.doors.size(), b.doors.size());
  EXPECT_EQ(b.doors[0].rooms, a.doors[0].rooms);  // inferred rooms are written out
  EXPECT_FALSE(b.doors[0].rooms_inferred);
  EXPECT_EQ(b.rooms[1].outline, a.rooms[1].outline);
}

}  // namespace
}  // namespace isg::bim
