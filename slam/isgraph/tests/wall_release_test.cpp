// Releasing plan walls that were not built as drawn (slam/isgraph/wall_release.hpp): a wall's
// residual after the correction the other walls agree on, by hand on a room of eight walls.
#include "slam/isgraph/wall_release.hpp"

#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <numbers>
#include <vector>

#include "slam/isgraph/tests/eight_walls.hpp"

namespace isg::slam {
namespace {

constexpr double kDegree = std::numbers::pi / 180.0;

std::vector<HeldWall> room() { return testing::eightWallRoom(); }

// The walls as seen when P_T_M is off by (t, yaw about the origin): each seen middle is carried
// by the error, its offset from its surface and its angle follow.
std::vector<HeldWall> seenUnder(std::vector<HeldWall> walls, const Eigen::Vector2d& t, double yaw) {
  const Eigen::Rotation2Dd R(yaw);
  for (auto& wall : walls) {
    const Eigen::Vector2d planned = wall.middle;
    wall.middle = R * planned + t;
    wall.offset = wall.normal.dot(wall.middle - planned);
    wall.angle = yaw;
  }
  return walls;
}

TEST(WallRelease, AnErrorOfP_T_MSharedByAllWallsIsNobodysDeviation) {
  const auto walls = seenUnder(room(), {0.07, -0.05}, 2.0 * kDegree);
  const auto residuals = residualsAgainstOthers(walls, {});
  ASSERT_EQ(residuals.size(), walls.size());
  for (const auto& r : residuals) {
    ASSERT_TRUE(r.judged);
    // Linearised about the room's centre, the 2° turn leaves a second-order 4 m · (1 − cos 2°)
    // ≈ 2.4 mm; the fit's weak prior keeps 1/200 of the turn (0.01°).
    EXPECT_NEAR(r.offset, 0.0, 0.005);
    EXPECT_NEAR(r.angle, 0.0, 0.02 * kDegree);
    EXPECT_FALSE(r.beyond({}));
  }
}

TEST(WallRelease, AShiftedWallKeepsItsOwnOffsetWhateverTheErrorOfP_T_M) {
  auto walls = seenUnder(room(), {0.03, 0.02}, 0.0);
  walls[5].offset += 0.12;  // the wall at x = 4, y = -1.5 stands 12 cm into the room
  const auto residuals = residualsAgainstOthers(walls, {});
  EXPECT_NEAR(residuals[5].offset, 0.12, 0.005);
  EXPECT_TRUE(residuals[5].beyond({}));
  for (std::size_t i = 0; i < walls.size(); ++i) {
    if (i == 5) continue;
    // The robust fit gives the shifted wall little weight: the others keep under 1 cm.
    EXPECT_NEAR(residuals[i].offset, 0.0, 0.01) << i;
    EXPECT_FALSE(residuals[i].beyond({})) << i;
  }
}

TEST(WallRelease, TwoWallsBuiltOffEachKeepTheirOwn) {
  // Walls across each other's direction, each well beyond the threshold, and a turned P_T_M: the
  // fit that judges each leaves it out, and gives the other little weight (Cauchy at 5 and 7
  // sigmas: 1/26 and 1/50).
  auto walls = seenUnder(room(), {-0.04, 0.05}, 1.0 * kDegree);
  walls[0].offset += 0.15;  // x = -2, y = -3, facing +y
  walls[5].offset -= 0.20;  // x = 4, y = -1.5, facing -x
  const auto residuals = residualsAgainstOthers(walls, {});
  EXPECT_NEAR(residuals[0].offset, 0.15, 0.01);
  EXPECT_NEAR(residuals[5].offset, -0.20, 0.01);
  for (std::size_t i = 0; i < walls.size(); ++i) {
    if (i == 0 || i == 5) continue;
    EXPECT_NEAR(residuals[i].offset, 0.0, 0.01) << i;
    EXPECT_NEAR(residuals[i].angle, 0.0, 0.1 * kDegree) << i;
    EXPECT_FALSE(residuals[i].beyond({})) << i;
  }
}

TEST(WallRelease, TheCorrectionOfAllUndoesTheErrorOfP_T_MNotAWallBuiltOff) {
  // P_T_M off by 7 cm, −5 cm and 2° about the origin; one wall also built 20 cm off. The
  // correction takes the seen walls back onto the plan: the turn by −2°, and the translation
  // −R(−2°) t, whatever the wall built off says.
  const Eigen::Vector2d t(0.07, -0.05);
  auto walls = seenUnder(room(), t, 2.0 * kDegree);
  walls[5].offset += 0.20;
  const auto correction = correctionOfAll(walls, {});
  ASSERT_TRUE(correction.has_value());
  const Eigen::Vector2d expected = -(Eigen::Rotation2Dd(-2.0 * kDegree) * t);
  EXPECT_NEAR(correction->z(), -2.0 * kDegree, 0.03 * kDegree);
  // The linearised turn about the walls' centroid leaves a few mm (see the first test).
  EXPECT_NEAR(correction->x(), expected.x(), 0.005);
  EXPECT_NEAR(correction->y(), expected.y(), 0.005);
  // Walls facing only ±y do not fix the translation along x.
  std::vector<HeldWall> one_way(walls.begin(), walls.begin() + 4);
  EXPECT_FALSE(correctionOfAll(one_way, {}).has_value());
}

TEST(WallRelease, PiecesOfOneWallDoNotVouchForEachOther) {
  // The wall at x = 4, y = −1.5 stands 12 cm into the room and was mapped as three S-planes.
  auto walls = room();
  walls[5].offset = 0.12;
  walls.push_back(walls[5]);
  walls.push_back(walls[5]);
  const auto residuals = residualsAgainstOthers(walls, {});
  for (std::size_t i : {5u, 8u, 9u}) EXPECT_NEAR(residuals[i].offset, 0.12, 0.005) << i;
  // Counted once among the others, it does not move the correction that judges them.
  for (int i = 0; i < 5; ++i) EXPECT_FALSE(residuals[i].beyond({})) << i;
  // Its pieces count as one plan wall: three others are still needed.
  std::vector<HeldWall> few = {walls[5], walls[8], walls[9], walls[0], walls[4]};
  for (const auto& r : residualsAgainstOthers(few, {})) EXPECT_FALSE(r.judged);
}

TEST(WallRelease, ATurnedWallKeepsItsOwnAngle) {
  auto walls = room();
  walls[0].angle = 3.0 * kDegree;
  const auto residuals = residualsAgainstOthers(walls, {});
  EXPECT_NEAR(residuals[0].angle, 3.0 * kDegree, 0.05 * kDegree);
  EXPECT_TRUE(residuals[0].beyond({}));
  for (std::size_t i = 1; i < walls.size(); ++i) EXPECT_FALSE(residuals[i].beyond({})) << i;
}

TEST(WallRelease, ThresholdsAreStrictAndBothWays) {
  WallResidual r{true, -0.061, 0.0};
  EXPECT_TRUE(r.beyond({}));
  r.offset = 0.059;
  EXPECT_FALSE(r.beyond({}));
  r.angle = -1.6 * kDegree;
  EXPECT_TRUE(r.beyond({}));
  r.judged = false;
  EXPECT_FALSE(r.beyond({}));
}

TEST(WallRelease, ShortWallsAndTooFewOthersAreNotJudged) {
  auto walls = room();
  walls[2].length = 0.8;  // under 1 m seen
  auto residuals = residualsAgainstOthers(walls, {});
  EXPECT_FALSE(residuals[2].judged);
  EXPECT_TRUE(residuals[3].judged);
  // Four walls: each has three others, the least that judges it.
  walls = room();
  walls.resize(4);
  walls[1] = room()[4], walls[3] = room()[5];
  walls[1].wall = 1, walls[3].wall = 3;
  residuals = residualsAgainstOthers(walls, {});
  for (const auto& r : residuals) EXPECT_TRUE(r.judged);
  walls.resize(3);
  residuals = residualsAgainstOthers(walls, {});
  for (const auto& r : residuals) EXPECT_FALSE(r.judged);
}

TEST(WallRelease, OthersThatFixOnlyOneDirectionDoNotJudge) {
  // Only the walls facing ±y, and one facing x: the x-facing one has no other across it.
  auto all = room();
  std::vector<HeldWall> walls(all.begin(), all.begin() + 4);
  walls.push_back(all[4]);
  const auto residuals = residualsAgainstOthers(walls, {});
  EXPECT_FALSE(residuals[4].judged);
  for (int i = 0; i < 4; ++i) EXPECT_TRUE(residuals[i].judged) << i;
}

}  // namespace
}  // namespace isg::slam
