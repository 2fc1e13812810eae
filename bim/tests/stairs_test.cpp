#include "bim/stairs.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "bim/plan_json.hpp"
#include "bim/plan_transform.hpp"
#include "bim/tests/test_plans.hpp"

namespace isg::bim {
namespace {

using testing::parsePlanJson;
using testing::planErrorOf;
using testing::twoRoomPlanJson;

// The two-room box on L0 and the same box 3.2 m above it on L1 (ids suffixed "u"), joined by a
// 0.8 m wide flight in the east room running north from y = 0.2 to y = 3.8: a rise of 3.2 m over
// a run of 3.6 m.
nlohmann::json twoStoreyPlanJson() {
  auto doc = twoRoomPlanJson();
  nlohmann::json upper = doc["levels"][0];
  upper["id"] = "L1";
  upper["elevation"] = 3.2;
  for (auto* items : {&upper["walls"], &upper["doors"], &upper["rooms"]}) {
    for (auto& item : *items) item["id"] = item["id"].get<std::string>() + "u";
  }
  for (auto& door : upper["doors"]) {
    door["wall"] = door["wall"].get<std::string>() + "u";
    if (door.contains("rooms")) door["rooms"] = {"R2u", "outside"};
  }
  doc["levels"].push_back(upper);
  doc["levels"][0]["stairs"] = nlohmann::json::parse(
      R"([{"id": "S1", "start": [4.5, 0.2], "end": [4.5, 3.8], "width": 0.8, "to": "L1"}])");
  return doc;
}

TEST(Stairs, StepsAreDerivedFromTheRiseByHand) {
  const Plan plan = parsePlanJson(twoStoreyPlanJson());
  const Stair* stair = plan.levels[0].findStair("S1");
  ASSERT_NE(stair, nullptr);
  EXPECT_EQ(stair->to, "L1");
  const StairGeometry g = computeStairGeometry(*stair, plan.levels[0], plan.levels[1]);
  // 3.2 m in steps of at most 0.2 m: 16 steps of 0.2 m, each 3.6 / 16 = 0.225 m deep.
  EXPECT_EQ(g.steps, 16);
  EXPECT_NEAR(g.step_rise, 0.2, 1e-12);
  EXPECT_NEAR(g.going, 0.225, 1e-12);
  EXPECT_NEAR(g.run, 3.6, 1e-12);
  EXPECT_NEAR(std::atan(g.slope()) * 180.0 / std::numbers::pi, 41.634, 1e-3);
  EXPECT_TRUE(g.axis.isApprox(Eigen::Vector2d(0, 1)));
  // The first step stands at the start, one rise high; the last is flush with the upper floor.
  EXPECT_NEAR(g.step(0).s0, 0.0, 1e-12);
  EXPECT_NEAR(g.step(0).s1, 0.225, 1e-12);
  EXPECT_NEAR(g.step(0).top, 0.2, 1e-12);
  EXPECT_NEAR(g.step(15).top, 3.2, 1e-12);
  EXPECT_NEAR(g.walkLineZ(1.8), 1.6, 1e-12);
  EXPECT_NEAR(g.walkLineZ(-1.0), 0.0, 1e-12);
  EXPECT_NEAR(g.walkLineZ(9.0), 3.2, 1e-12);
  // The stairwell: the upper 3.6 × 2 / 3.2 = 2.25 m of the flight, y in [1.55, 3.8].
  const auto opening = g.openingFootprint();
  EXPECT_TRUE(opening[0].isApprox(Eigen::Vector2d(4.9, 1.55)));
  EXPECT_TRUE(opening[2].isApprox(Eigen::Vector2d(4.1, 3.8)));
  // Footprint: x in [4.1, 4.9], y in [0.2, 3.8].
  EXPECT_TRUE(g.contains({4.12, 0.25}));
  EXPECT_FALSE(g.contains({4.0, 1.0}));
  EXPECT_TRUE(g.contains({4.0, 1.0}, 0.11));
  // Declared on the upper level leading down, the same flight descends from start to end.
  const Stair down{"S2", {4.5, 3.8}, {4.5, 0.2}, 0.8, "L0", ""};
  const StairGeometry d = computeStairGeometry(down, plan.levels[1], plan.levels[0]);
  EXPECT_NEAR(d.walkLineZ(0.0), 3.2, 1e-12);
  EXPECT_NEAR(d.step(0).top, 3.2, 1e-12);   // at the top edge
  EXPECT_NEAR(d.step(15).top, 0.2, 1e-12);  // the step at the bottom
}

TEST(Stairs, ARiseThatIsNotAMultipleOfTheMaximumGetsOneMoreStep) {
  Level from, to;
  to.elevation = 3.05;
  const Stair stair{"S", {0, 0}, {4, 0}, 1.0, "L1", ""};
  const StairGeometry g = computeStairGeometry(stair, from, to);
  EXPECT_EQ(g.steps, 16);  // 15 steps would rise 0.2033 m each
  EXPECT_NEAR(g.step_rise, 3.05 / 16, 1e-12);
}

TEST(Stairs, ConvexOverlapIgnoresTouching) {
  const std::vector<Eigen::Vector2d> square{{0, 0}, {1, 0}, {1, 1}, {0, 1}};
  const std::vector<Eigen::Vector2d> touching{{1, 0}, {2, 0}, {2, 1}, {1, 1}};
  const std::vector<Eigen::Vector2d> into{{0.99, 0.5}, {2, 0.5}, {2, 0.6}, {0.99, 0.6}};
  // A diamond whose corner comes within 0.05 m of the square's corner, but whose edges pass it.
  const std::vector<Eigen::Vector2d> diamond{{1.6, 1.05}, {2.1, 1.55}, {1.6, 2.05}, {1.05, 1.55}};
  EXPECT_FALSE(convexPolygonsOverlap(square, touching, 1e-3));
  EXPECT_TRUE(convexPolygonsOverlap(square, into, 1e-3));
  EXPECT_FALSE(convexPolygonsOverlap(square, into, 0.02));
  EXPECT_FALSE(convexPolygonsOverlap(square, diamond, 1e-3));
}

TEST(Stairs, ParsedWrittenBackAndMovedWithThePlan) {
  const Plan plan = parsePlanJson(twoStoreyPlanJson());
  const Plan again = parsePlanJson(nlohmann::json::parse(planToJson(plan).dump()));
  ASSERT_EQ(again.levels[0].stairs.size(), 1u);
  EXPECT_EQ(again.levels[0].stairs[0].end, Eigen::Vector2d(4.5, 3.8));
  EXPECT_DOUBLE_EQ(again.levels[0].stairs[0].width, 0.8);
  // A plan without stairs is written without the key, as before the extension.
  EXPECT_FALSE(planToJson(parsePlanJson(twoRoomPlanJson()))["levels"][0].contains("stairs"));
  const Plan moved = transformedPlan(plan, planarMotion({10, 0}, std::numbers::pi / 2));
  EXPECT_TRUE(moved.levels[0].stairs[0].start.isApprox(Eigen::Vector2d(9.8, 4.5)));
}

TEST(Stairs, EachRuleHasItsExactError) {
  const std::string at = "test.json: /levels/0/stairs/0";
  auto with = [](auto edit) {
    auto doc = twoStoreyPlanJson();
    edit(doc["levels"][0]["stairs"][0], doc);
    return planErrorOf(doc);
  };
  EXPECT_EQ(with([](auto&, auto&) {}), "(accepted)");
  EXPECT_EQ(with([](auto& s, auto&) { s["to"] = "L9"; }), at + "/to: no level \"L9\"");
  EXPECT_EQ(with([](auto& s, auto&) { s["to"] = "L0"; }),
            at + "/to: a flight leads to another level, not to its own");
  EXPECT_EQ(with([](auto&, auto& doc) { doc["levels"][1]["elevation"] = 0.0; }),
            at + "/to: level \"L1\" is at the same elevation as level \"L0\" (0 m): a flight "
                 "joins levels at different heights");
  EXPECT_EQ(with([](auto& s, auto&) { s["width"] = 0.5; }),
            at + "/width: a flight 0.5 m wide is too narrow for a legged robot (at least 0.6 m; "
                 "docs/formats.md, Stairs)");
  EXPECT_EQ(with([](auto& s, auto&) {
              s["end"] = {4.5, 3.0};
            }),
            at + "/end: the flight rises 3.2 m over 2.8 m (48.8°), steeper than a legged robot "
                 "climbs (at most 42.3°: a rise of 0.2 m per 0.22 m going); it needs a run of at "
                 "least 3.52 m");
  EXPECT_EQ(with([](auto& s, auto&) { s["end"] = s["start"]; }),
            at + "/end: zero-length flight: end equals start [4.5, 0.2]");
  EXPECT_EQ(with([](auto& s, auto&) {
              s["start"] = {4.5, -3.6};
              s["end"] = {4.5, 0.0};
            }),
            at + "/start: the flight's bottom edge [4.5, -3.6] is in no room of level \"L0\"");
  EXPECT_EQ(with([](auto& s, auto&) {
              s["start"] = {3.4, 0.2};
              s["end"] = {3.4, 3.8};
            }),
            at + ": the flight runs into wall \"W5\" of level \"L0\": it must be clear of the "
                 "walls of both its levels");
  // A wall on the upper level over the flight blocks it as much as one below.
  EXPECT_EQ(with([](auto&, auto& doc) {
              doc["levels"][1]["walls"].push_back(
                  {{"id", "X"}, {"start", {4.0, 2.0}}, {"end", {5.0, 2.0}}, {"thickness", 0.1}});
            }),
            at +
                ": the flight runs into wall \"X\" of level \"L1\", over its stairwell: it must be "
                "clear of the walls of both its levels");
  // Over the flight's lower part, which rises less than 2 m towards L1 (y < 3.8 − 3.6 × 2 / 3.2
  // = 1.55), the upper floor stands, and so may a wall of L1.
  EXPECT_EQ(with([](auto&, auto& doc) {
              doc["levels"][1]["walls"].push_back(
                  {{"id", "X"}, {"start", {4.0, 1.0}}, {"end", {5.0, 1.0}}, {"thickness", 0.1}});
            }),
            "(accepted)");
  EXPECT_EQ(with([](auto&, auto& doc) {
              doc["levels"][1]["stairs"] = nlohmann::json::parse(
                  R"([{"id": "S2", "start": [4.0, 3.8], "end": [4.0, 0.2], "width": 0.8,
                       "to": "L0"}])");
            }),
            at +
                ": the flight overlaps flight \"S2\" on level \"L0\" (one flight is declared once, "
                "on either of its levels)");
  // A later flight whose `to` is wrong is reported at its own pointer; the earlier flight's checks
  // (which compare it with the flights of its levels) do not trip over it.
  {
    auto doc = twoStoreyPlanJson();
    doc["levels"][0]["stairs"].push_back(nlohmann::json::parse(
        R"({"id": "S9", "start": [1.5, 0.5], "end": [1.5, 3.5], "width": 0.8, "to": "L9"})"));
    EXPECT_EQ(planErrorOf(doc), "test.json: /levels/0/stairs/1/to: no level \"L9\"");
  }
  // A third level between the two: flights join neighbours.
  EXPECT_EQ(
      with([](auto&, auto& doc) {
        doc["levels"][1]["elevation"] = 6.4;
        nlohmann::json middle = {{"id", "LM"}, {"elevation", 3.2}, {"height", 3.0}};
        middle["walls"] = {{{"id", "WM"}, {"start", {0, 0}}, {"end", {1, 0}}, {"thickness", 0.1}}};
        doc["levels"].push_back(middle);
      }),
      at + "/to: level \"LM\" lies between \"L0\" and \"L1\": a flight joins neighbouring "
           "levels");
}

}  // namespace
}  // namespace isg::bim
