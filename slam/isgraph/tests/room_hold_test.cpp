// Which pairs of a matched four-wall room the merge holds (slam/isgraph/room_hold.hpp), and the
// map's width of a pair, by hand.
#include "slam/isgraph/room_hold.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

namespace isg::slam {
namespace {

TEST(WidthThrough, SumsThePointsDistancesFromBothPlanes) {
  // x = 1 facing +x and x = 4 facing −x, through (2, 7): 1 + 2 m.
  const Eigen::Vector4d left(1.0, 0.0, 0.0, -1.0), right(-1.0, 0.0, 0.0, 4.0);
  EXPECT_NEAR(widthThrough({2.0, 7.0}, left, right), 3.0, 1e-12);
  // Normals not unit (scaled by 2): the same width.
  EXPECT_NEAR(widthThrough({2.0, 7.0}, 2.0 * left, 2.0 * right), 3.0, 1e-12);
  // The right wall turned 10° about (4, 7): the distance is measured along its normal, 2·cos 10°
  // from (2, 7) and 2·cos 10° − sin 10° from (2, 8), a metre along it.
  const double angle = 10.0 * std::numbers::pi / 180.0;
  const Eigen::Vector2d n(-std::cos(angle), -std::sin(angle));
  const Eigen::Vector4d turned(n.x(), n.y(), 0.0, -n.dot(Eigen::Vector2d(4.0, 7.0)));
  EXPECT_NEAR(widthThrough({2.0, 7.0}, left, turned), 1.0 + 2.0 * std::cos(angle), 1e-12);
  EXPECT_NEAR(widthThrough({2.0, 8.0}, left, turned), 1.0 + 2.0 * std::cos(angle) - std::sin(angle),
              1e-12);
}

TEST(HoldsAlongPair, OnlyWhileTheWidthAndTheReleasesAgreeWithinSigma) {
  const double sigma_room = 0.1;
  RoomPairEvidence pair;
  pair.plan_width = 4.0;
  pair.map_width = 4.05;  // the map's noise
  EXPECT_TRUE(holdsAlongPair(pair, sigma_room));
  pair.map_width = 3.85;  // a wall built 0.15 m in: the S-centre 7.5 cm off
  EXPECT_FALSE(holdsAlongPair(pair, sigma_room));
  pair.map_width = 4.0;
  pair.released_offset = 0.08;  // released within sigma_room: tolerated
  EXPECT_TRUE(holdsAlongPair(pair, sigma_room));
  pair.released_offset = 0.12;  // both walls shifted alike: the width cannot tell, the release can
  EXPECT_FALSE(holdsAlongPair(pair, sigma_room));
}

}  // namespace
}  // namespace isg::slam
