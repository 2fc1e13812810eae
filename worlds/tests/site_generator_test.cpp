#include "worlds/site_generator.hpp"

#include <gtest/gtest.h>

#include <Eigen/Core>
#include <algorithm>
#include <set>
#include <string>

#include "bim/plan_parser.hpp"
#include "bim/scenario.hpp"
#include "common/json_reader.hpp"

namespace isg::worlds {
namespace {

bim::Plan parsed(const GeneratedBuilding& b, common::Warnings& warnings) {
  const common::JsonSource source{b.name + ".json", &warnings};
  return bim::parsePlan(common::JsonNode(b.plan, "", source));
}

TEST(SiteGenerator, AnOpenFloorOfColumnsFacadeCoreAndPartitions) {
  for (std::uint64_t seed = 1; seed <= 12; ++seed) {
    GeneratorSpec spec;
    spec.family = "site";
    spec.seed = seed;
    const GeneratedBuilding b = generateBuilding(spec);
    EXPECT_EQ(b.name, "site-" + std::to_string(seed));
    common::Warnings warnings;
    const bim::Plan plan = parsed(b, warnings);
    EXPECT_TRUE(warnings.empty()) << seed << ": " << warnings.front().str();
    ASSERT_EQ(plan.levels.size(), 1u);
    const bim::Level& level = plan.levels.front();
    // An open floor: no rooms, no doors; the inside is the façade's.
    EXPECT_TRUE(level.rooms.empty());
    EXPECT_TRUE(level.doors.empty());
    int columns = 0, facade = 0, core = 0, partitions = 0;
    for (const auto& w : level.walls) {
      if (w.name == "column") {
        ++columns;
        // A square column: a wall as long as it is thick.
        EXPECT_NEAR((w.end - w.start).norm(), w.thickness, 1.5e-3) << w.id;
        EXPECT_GE(w.thickness, 0.4);
        EXPECT_LE(w.thickness, 0.6);
      }
      facade += w.name == "facade";
      core += w.name == "core";
      partitions += w.name == "partition";
    }
    EXPECT_GE(columns, 14) << seed;
    EXPECT_GE(facade, 7) << seed;
    EXPECT_GE(core, 8) << seed;  // 2 end walls, 2–3 cross walls, the long sides in pieces
    EXPECT_GE(partitions, 1) << seed;
    // One partition at a slant (neither along x nor y): the floor is not all Manhattan.
    bool slanted = false;
    for (const auto& w : level.walls) {
      if (w.name != "partition") continue;
      const Eigen::Vector2d d = (w.end - w.start).normalized();
      slanted = slanted || (std::abs(d.x()) > 0.1 && std::abs(d.y()) > 0.1);
    }
    EXPECT_TRUE(slanted) << seed;
    // As built: only façade walls and partitions go unbuilt, and every name is the plan's.
    std::set<std::string> ids;
    for (const auto& w : level.walls) ids.insert(w.id);
    for (const auto& id : b.scenario["as_built"].value("missing_walls", nlohmann::json::array())) {
      const std::string name = id.get<std::string>();
      EXPECT_TRUE(ids.count(name)) << name;
      EXPECT_TRUE(name[0] == 'F' || name[0] == 'P') << name;
    }
    EXPECT_EQ(b.scenario["robot"]["route"], "tour");
    EXPECT_FALSE(b.scenario["robot"].contains("start"));
  }
}

TEST(SiteGenerator, TheSameSeedGivesTheSameSite) {
  GeneratorSpec spec;
  spec.family = "site";
  spec.seed = 4;
  const GeneratedBuilding a = generateBuilding(spec), again = generateBuilding(spec);
  EXPECT_EQ(a.plan.dump(), again.plan.dump());
  EXPECT_EQ(a.scenario.dump(), again.scenario.dump());
  spec.seed = 5;
  EXPECT_NE(generateBuilding(spec).plan.dump(), a.plan.dump());
}

}  // namespace
}  // namespace isg::worlds
