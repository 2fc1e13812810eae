#include "slam/isgraph/level_matching.hpp"

#include <gtest/gtest.h>

#include <random>
#include <string>
#include <vector>

#include "bim/agraph.hpp"
#include "bim/plan_parser.hpp"
#include "slam/isgraph/tests/synthetic_sgraph.hpp"

namespace isg::slam {
namespace {

bim::AGraph builtinAGraph(const std::string& name) {
  return bim::buildAGraph(
      bim::loadPlan(std::string(ISG_SOURCE_DIR) + "/worlds/plans/" + name + ".json"));
}

std::vector<int> roomsOf(const bim::AGraph& graph, const std::vector<std::string>& ids) {
  std::vector<int> out;
  for (const auto& id : ids) {
    out.push_back(graph.findRoom(id));
    EXPECT_GE(out.back(), 0) << id;
  }
  return out;
}

TEST(LevelGraph, HoldsOneLevelAndMapsBackToTheWholeGraph) {
  const bim::AGraph whole = builtinAGraph("storeys");
  const LevelGraph upper = levelGraph(whole, 1);
  ASSERT_EQ(upper.graph.floors.size(), 1u);
  EXPECT_EQ(upper.graph.floors[0].id, "L1");
  EXPECT_EQ(upper.graph.rooms.size(), 4u);
  ASSERT_EQ(upper.room_in_whole.size(), upper.graph.rooms.size());
  for (int r = 0; r < int(upper.graph.rooms.size()); ++r) {
    const auto& room = upper.graph.rooms[r];
    EXPECT_EQ(room.id, whole.rooms[upper.room_in_whole[r]].id);
    EXPECT_EQ(room.floor, 0);
    for (const auto& pair : room.pairs) {
      for (int s : pair) {
        ASSERT_GE(s, 0);
        EXPECT_EQ(upper.graph.surfaces[s].id, whole.surfaces[upper.surface_in_whole[s]].id);
        EXPECT_EQ(upper.graph.surfaces[s].level, "L1");
      }
    }
  }
  for (const auto& wall : upper.graph.walls) {
    EXPECT_EQ(upper.graph.surfaces[wall.left_surface].wall, wall.id);
    EXPECT_EQ(upper.graph.surfaces[wall.right_surface].wall, wall.id);
  }
}

// Floors that differ: the rooms walked on one floor are matched on that level, with the whole
// graph's indices, and never on the other; walls of both levels stand in the same place.
TEST(LevelMatching, FloorsThatDifferAreMatchedOnTheirOwnLevel) {
  const bim::AGraph whole = builtinAGraph("storeys");
  const LevelMatcher matcher(whole, {});
  std::mt19937_64 rng(5);
  const std::vector<std::pair<std::vector<std::string>, std::string>> walks = {
      {{"R1", "R4", "R2"}, "L0"}, {{"R11", "R14", "R12"}, "L1"}, {{"R13", "R14", "R11"}, "L1"}};
  for (const auto& [rooms, level] : walks) {
    for (int trial = 0; trial < 4; ++trial) {
      const Eigen::Vector3d truth = testing::randomPlanarTransform(rng);
      const auto cut = testing::cutSGraph(whole, roomsOf(whole, rooms), truth, rng, 0.01);
      const LevelMatch match = matcher.match(cut.input);
      ASSERT_EQ(match.result.status, MatchStatus::kMatched) << match.result.reason;
      EXPECT_EQ(whole.floors[match.level].id, level) << match.result.reason;
      EXPECT_TRUE(match.alike_levels.empty());
      for (const auto& [s, a] : match.result.best.rooms) {
        EXPECT_EQ(a, cut.a_room_of_s_room[s]) << match.result.reason;
      }
      for (const auto& [s, a] : match.result.best.planes) {
        EXPECT_EQ(whole.surfaces[a].level, level);
      }
    }
  }
}

// Two floors alike but for their stairs: what the robot maps of the rooms on one is explained
// alike by the other, and the result is ambiguous, naming both, until it sees what differs: the
// flight that rises from one of them, or the floor that differs.
TEST(LevelMatching, AlikeFloorsAreAmbiguousNeverAGuess) {
  const bim::AGraph whole = builtinAGraph("twin-storeys");
  const LevelMatcher matcher(whole, {});
  std::mt19937_64 rng(9);
  for (int trial = 0; trial < 4; ++trial) {
    const Eigen::Vector3d truth = testing::randomPlanarTransform(rng);
    const auto upper =
        testing::cutSGraph(whole, roomsOf(whole, {"R14", "R11", "R12", "R13"}), truth, rng, 0.01);
    const LevelMatch alike = matcher.match(upper.input);
    EXPECT_EQ(alike.result.status, MatchStatus::kAmbiguous) << alike.result.reason;
    ASSERT_EQ(alike.alike_levels.size(), 1u) << alike.result.reason;
    std::vector<std::string> ids{whole.floors[alike.level].id,
                                 whole.floors[alike.alike_levels[0]].id};
    std::sort(ids.begin(), ids.end());
    EXPECT_EQ(ids, (std::vector<std::string>{"L1", "L2"})) << alike.result.reason;
    EXPECT_NE(alike.result.reason.find("explain the map alike"), std::string::npos);

    // The flight rising from L1 (S2, along the corridor) seen: its side and its high end, which
    // L2 does not have, decide for L1.
    testing::CutSGraph with_flight = upper;
    const Eigen::Rotation2Dd R_MB(-truth.z());
    auto to_M = [&](const Eigen::Vector2d& p) {
      return Eigen::Vector2d(R_MB * (p - truth.head<2>()));
    };
    for (const std::string id : {"S2:stair-left", "S2:stair-end"}) {
      const auto& face = whole.surfaces[whole.findSurface(id)];
      MatchPlane plane;
      plane.id = int(with_flight.input.planes.size());
      plane.start = to_M(face.segments[0].first);
      plane.end = to_M(face.segments[0].second);
      const Eigen::Vector2d n = R_MB * face.plane.normal.head<2>();
      plane.plane =
          bim::Plane::throughPoint({n.x(), n.y(), 0.0}, {plane.start.x(), plane.start.y(), 1.0});
      with_flight.input.planes.push_back(plane);
    }
    const LevelMatch separated = matcher.match(with_flight.input);
    ASSERT_EQ(separated.result.status, MatchStatus::kMatched) << separated.result.reason;
    EXPECT_EQ(whole.floors[separated.level].id, "L1");

    const auto ground =
        testing::cutSGraph(whole, roomsOf(whole, {"R01", "R02", "R03"}), truth, rng, 0.01);
    const LevelMatch distinct = matcher.match(ground.input);
    ASSERT_EQ(distinct.result.status, MatchStatus::kMatched) << distinct.result.reason;
    EXPECT_EQ(whole.floors[distinct.level].id, "L0");
  }
}

}  // namespace
}  // namespace isg::slam
