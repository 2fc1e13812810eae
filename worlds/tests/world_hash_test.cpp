#include "worlds/world_hash.hpp"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>

namespace isg::worlds {
namespace {

TEST(WorldHash, FollowsTheScenarioThePlanAndAReplayedWalk) {
  const auto dir = std::filesystem::temp_directory_path() / "isg_world_hash_test";
  std::filesystem::create_directories(dir);
  const std::string plan = std::string(ISG_SOURCE_DIR) + "/worlds/plans/d1.json";
  std::ofstream(dir / "s.json") << "{\"format\": \"isg.scenario\", \"version\": 1, \"plan\": \""
                                << plan
                                << "\", \"robot\": {\"route\": {\"trajectory\": \"w.tum\"}}}";
  const auto hashWith = [&](const std::string& walk) {
    std::ofstream(dir / "w.tum") << walk;
    return worldHash(bim::loadScenario((dir / "s.json").string()));
  };
  const std::string a = hashWith("0 2 1 0 0 0 0 1\n1 2.5 1 0 0 0 0 1\n");
  // The same poses written otherwise (another clock, comments) are the same walk ...
  EXPECT_EQ(hashWith("# recorded\n100 2 1 0 0 0 0 1\n101 2.50 1 0 0 0 0 1\n"), a);
  // ... a walk that goes elsewhere is another run.
  EXPECT_NE(hashWith("0 2 1 0 0 0 0 1\n1 2.6 1 0 0 0 0 1\n"), a);
  // And the plan's own hash is not the walk's.
  EXPECT_NE(worldHash(bim::loadScenario(plan)), a);
  std::filesystem::remove_all(dir);
}

}  // namespace
}  // namespace isg::worlds
