#include "formats/foxglove_json.hpp"

#include <gtest/gtest.h>

#include <cmath>

namespace isg::formats::foxglove {
namespace {

TEST(FoxgloveJson, FrameTransformHoldsThePoseAndTheStamp) {
  // Child turned 90 degrees about z and moved by (1, 2, 3) in the parent.
  Eigen::Isometry3d parent_T_child = Eigen::Isometry3d::Identity();
  parent_T_child.linear() = Eigen::AngleAxisd(M_PI / 2, Eigen::Vector3d::UnitZ()).matrix();
  parent_T_child.translation() = Eigen::Vector3d(1, 2, 3);
  const Json t =
      frameTransform(RosTime::fromSeconds(1.5, 1000000000), "map", "base_link", parent_T_child);
  EXPECT_EQ(t["timestamp"]["sec"], 1000000001u);
  EXPECT_EQ(t["timestamp"]["nsec"], 500000000u);
  EXPECT_EQ(t["parent_frame_id"], "map");
  EXPECT_EQ(t["child_frame_id"], "base_link");
  EXPECT_DOUBLE_EQ(t["translation"]["x"].get<double>(), 1.0);
  EXPECT_DOUBLE_EQ(t["translation"]["z"].get<double>(), 3.0);
  // cos(45°) and sin(45°): a rotation of 90° about z.
  EXPECT_NEAR(t["rotation"]["z"].get<double>(), std::sqrt(0.5), 1e-15);
  EXPECT_NEAR(t["rotation"]["w"].get<double>(), std::sqrt(0.5), 1e-15);
  EXPECT_NEAR(t["rotation"]["x"].get<double>(), 0.0, 1e-15);
}

TEST(FoxgloveJson, AnEntityCarriesEveryListItsSchemaRequires) {
  const Json entity = sceneEntity(RosTime{7, 0}, "plan", "plan/walls");
  const Json required =
      Json::parse(sceneUpdateSchema().json_schema)["properties"]["entities"]["items"]["required"];
  ASSERT_EQ(required.size(), 14u);
  for (const Json& key : required) EXPECT_TRUE(entity.contains(key.get<std::string>())) << key;
  EXPECT_TRUE(entity["cubes"].empty());
  EXPECT_EQ(entity["lifetime"], Json({{"sec", 0}, {"nsec", 0}}));  // never expires
  EXPECT_EQ(entity["frame_id"], "plan");
}

TEST(FoxgloveJson, PrimitivesAreLaidOutAsFoxgloveReadsThem) {
  const Json lines = lineList({{0, 0, 0}, {1, 0, 0}}, 0.05, {1, 0, 0, 1});
  EXPECT_EQ(lines["type"], 2);  // LINE_LIST
  EXPECT_EQ(lines["points"].size(), 2u);
  EXPECT_EQ(lineLoop({{0, 0, 0}}, 0.05, {})["type"], 1);  // LINE_LOOP
  const Json ball = sphere({1, 2, 3}, 0.5, {});
  EXPECT_EQ(ball["size"], Json({{"x", 0.5}, {"y", 0.5}, {"z", 0.5}}));
  EXPECT_EQ(ball["pose"]["position"], Json({{"x", 1.0}, {"y", 2.0}, {"z", 3.0}}));
  EXPECT_EQ(log(RosTime{1, 2}, LogLevel::kWarning, "lost", "isg.matching")["level"], 3);
  const Json update = sceneUpdate({sceneEntity(RosTime{}, "map", "a")});
  EXPECT_TRUE(update["deletions"].empty());
  EXPECT_EQ(update["entities"][0]["id"], "a");
}

TEST(FoxgloveJson, SchemasAreJsonSchemasNamedAsFoxglovesTypes) {
  for (const SchemaText& s :
       {frameTransformSchema(), posesInFrameSchema(), logSchema(), sceneUpdateSchema()}) {
    const Json schema = Json::parse(s.json_schema);
    EXPECT_EQ(schema["title"], s.name);
    EXPECT_EQ(schema["type"], "object");
    EXPECT_EQ(s.name.rfind("foxglove.", 0), 0u);
    EXPECT_FALSE(schema["required"].empty()) << s.name;
  }
}

}  // namespace
}  // namespace isg::formats::foxglove
