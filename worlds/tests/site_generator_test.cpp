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
  int shortened_sites = 0;
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
    for (const auto& c : level.columns) {
      ++columns;
      // Square or round, 0.4–0.6 m across.
      EXPECT_EQ(c.size.x(), c.size.y()) << c.id;
      EXPECT_GE(c.size.x(), 0.4);
      EXPECT_LE(c.size.x(), 0.6);
      EXPECT_EQ(c.yaw, 0.0);
      EXPECT_EQ(c.height, level.height);
    }
    for (const auto& w : level.walls) {
      EXPECT_NE(w.name, "column") << w.id;
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
    // A wall going up: a façade wall or a partition, built from one end or with a gap, its
    // parts within it.
    for (const auto& w : b.scenario["as_built"].value("shortened_walls", nlohmann::json::array())) {
      ++shortened_sites;
      const bim::Wall* wall = level.findWall(w["wall"].get<std::string>());
      ASSERT_NE(wall, nullptr) << seed;
      EXPECT_TRUE(wall->name == "facade" || wall->name == "partition") << wall->id;
      const double length = (wall->end - wall->start).norm();
      double built = 0.0;
      for (const auto& part : w["built"]) {
        EXPECT_GE(part[0].get<double>(), 0.0);
        EXPECT_LE(part[1].get<double>(), length);
        built += part[1].get<double>() - part[0].get<double>();
      }
      EXPECT_GT(built, 0.25 * length) << seed;
      EXPECT_LT(built, 0.95 * length) << seed;
    }
    EXPECT_EQ(b.scenario["robot"]["route"], "tour");
    EXPECT_FALSE(b.scenario["robot"].contains("start"));
  }
  EXPECT_GE(shortened_sites, 3);  // about 6 in 10
  EXPECT_LE(shortened_sites, 10);
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
