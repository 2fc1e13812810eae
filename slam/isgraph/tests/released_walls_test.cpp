// The walls released from the merge (ReleasedWalls): a wall built 12 cm off its plan among eight
// that stand where planned is released after `strikes` keyframes in a row, and only it.
#include "slam/isgraph/released_walls.hpp"

#include <gtest/gtest.h>

#include "slam/isgraph/tests/eight_walls.hpp"

namespace isg::slam {
namespace {

// The eight walls of testing::eightWallRoom, the first (x = −2 on the south side) standing `off`
// metres inside the room.
std::vector<HeldWall> roomWith(double off) {
  std::vector<HeldWall> walls = testing::eightWallRoom();
  walls[0].middle.y() += off;
  walls[0].offset = off;
  return walls;
}

// Whether S-plane `plane` may be held on `surface` where wall k of the eight walls lies (its seen
// segment in P).
bool allowsOn(const ReleasedWalls& released, int plane, int surface, std::size_t k) {
  const HeldWall w = testing::eightWallRoom()[k];
  const Eigen::Vector2d half = 0.5 * w.length * Eigen::Vector2d(-w.normal.y(), w.normal.x());
  return released.allows(plane, surface, w.middle - half, w.middle + half);
}

// S-plane 10 + k held on surface 20 + k.
std::vector<std::pair<int, int>> heldPairs(std::size_t n) {
  std::vector<std::pair<int, int>> held;
  for (std::size_t k = 0; k < n; ++k) held.emplace_back(10 + int(k), 20 + int(k));
  return held;
}

TEST(ReleasedWalls, AWallOffItsPlanIsReleasedAfterItsStrikes) {
  ReleasedWalls released(WallReleaseOptions{});  // 6 cm, 3 strikes
  const auto walls = roomWith(0.12);
  const auto held = heldPairs(walls.size());
  std::map<int, int> matches(held.begin(), held.end());
  for (int keyframe = 0; keyframe < 2; ++keyframe) {
    released.judge(walls, held, keyframe, 3, matches);
    EXPECT_EQ(matches.size(), 8u) << keyframe;
    EXPECT_TRUE(allowsOn(released, 10, 20, 0));
  }
  released.judge(walls, held, 2.0, 3, matches);
  EXPECT_EQ(matches.size(), 7u);
  EXPECT_FALSE(matches.count(10));
  EXPECT_FALSE(allowsOn(released, 10, 99, 0));  // its S-plane
  EXPECT_FALSE(allowsOn(released, 99, 20, 0));  // its surface where it was seen
  EXPECT_TRUE(allowsOn(released, 11, 21, 1));
  ASSERT_EQ(released.log().size(), 1u);
  EXPECT_EQ(released.log()[0].stamp, 2.0);
  EXPECT_NEAR(released.log()[0].offset, 0.12, 0.01);
  EXPECT_NEAR(*released.offsetOf(20), 0.12, 0.01);
  EXPECT_FALSE(released.offsetOf(21).has_value());
}

TEST(ReleasedWalls, ALongWallIsReleasedWhereItWasSeenOffAndHeldBeyond) {
  // Wall 0 seen off its plan over x = -3.5 .. -0.5 (y = -3): released there and 1 m beyond its
  // ends (a doorway's gap); another S-plane of the same surface seen farther along it may be held.
  ReleasedWalls released(WallReleaseOptions{});
  const auto held = heldPairs(8);
  std::map<int, int> matches(held.begin(), held.end());
  released.judge(roomWith(0.12), held, 0.0, 1, matches);
  ASSERT_EQ(released.log().size(), 1u);
  const double y = -3.0;
  EXPECT_FALSE(released.allows(30, 20, {-2.0, y}, {-1.0, y}));  // inside the stretch
  EXPECT_FALSE(released.allows(30, 20, {0.4, y}, {4.0, y}));    // 0.9 m beyond its end
  EXPECT_FALSE(released.allows(30, 20, {4.0, y}, {0.4, y}));    // either way round
  EXPECT_TRUE(released.allows(30, 20, {0.6, y}, {4.0, y}));     // 1.1 m beyond
  EXPECT_TRUE(released.allows(30, 20, {-9.0, y}, {-4.6, y}));   // 1.1 m before its start
  EXPECT_FALSE(released.allows(30, 20, {-9.0, y}, {-4.4, y}));
  EXPECT_FALSE(released.allows(10, 20, {0.6, y}, {4.0, y}));   // its own S-plane: never
  EXPECT_TRUE(released.allows(30, 21, {-2.0, y}, {-1.0, y}));  // another surface
}

TEST(ReleasedWalls, AStreakBrokenStartsAgain) {
  ReleasedWalls released(WallReleaseOptions{});
  const auto held = heldPairs(8);
  std::map<int, int> matches(held.begin(), held.end());
  released.judge(roomWith(0.12), held, 0.0, 3, matches);
  released.judge(roomWith(0.12), held, 1.0, 3, matches);
  released.judge(roomWith(0.0), held, 2.0, 3, matches);  // within: its strikes forgotten
  released.judge(roomWith(0.12), held, 3.0, 3, matches);
  released.judge(roomWith(0.12), held, 4.0, 3, matches);
  EXPECT_EQ(matches.size(), 8u);
  released.judge(roomWith(0.12), held, 5.0, 3, matches);
  EXPECT_EQ(matches.size(), 7u);
}

TEST(ReleasedWalls, ReopenedByAMoveForgottenByANewAnswer) {
  ReleasedWalls released(WallReleaseOptions{});
  const auto held = heldPairs(8);
  std::map<int, int> matches(held.begin(), held.end());
  released.judge(roomWith(0.12), held, 0.0, 1, matches);  // a new answer's: judged at once
  ASSERT_FALSE(allowsOn(released, 10, 20, 0));
  MatchPlane other, seen;
  other.id = 11;
  seen.id = 10;
  released.reopen({other});
  EXPECT_FALSE(allowsOn(released, 10, 20, 0));  // not among the planes the move concerns
  released.reopen({seen});
  EXPECT_TRUE(allowsOn(released, 10, 20, 0));
  EXPECT_TRUE(allowsOn(released, 99, 20, 0));  // its stretch reopened with it
  EXPECT_EQ(released.log().size(), 1u);        // the log keeps it
  released.clear();
  EXPECT_TRUE(released.log().empty());
}

TEST(ReleasedWalls, MostWallsOffIsAnAnswerOffTheBuildingNotWallsOffThePlan) {
  ReleasedWalls released(WallReleaseOptions{});
  // Five of eight faces 12 cm off: the correction of the others cannot explain them, and more
  // than half are due: nothing is released.
  std::vector<HeldWall> walls = roomWith(0.0);
  for (int k : {0, 1, 2, 4, 5}) {
    walls[k].middle += 0.12 * walls[k].normal;
    walls[k].offset = 0.12;
  }
  // Each of the five is beyond the thresholds on its own ...
  const auto residuals = residualsAgainstOthers(walls, WallReleaseOptions{});
  int beyond = 0;
  for (const auto& r : residuals) beyond += r.beyond(WallReleaseOptions{}) ? 1 : 0;
  EXPECT_GE(beyond, 5);
  // ... but not one is released.
  const auto held = heldPairs(8);
  std::map<int, int> matches(held.begin(), held.end());
  released.judge(walls, held, 0.0, 1, matches);
  EXPECT_EQ(matches.size(), 8u);
  EXPECT_TRUE(released.log().empty());
}

}  // namespace
}  // namespace isg::slam
