#include "bim/facade.hpp"

#include <gtest/gtest.h>

#include "bim/polygon.hpp"

namespace isg::bim {
namespace {

Wall wallOf(const std::string& id, Eigen::Vector2d a, Eigen::Vector2d b, double thickness) {
  Wall wall;
  wall.id = id;
  wall.start = a, wall.end = b;
  wall.thickness = thickness;
  wall.height = 3.0;
  return wall;
}

TEST(Facade, AnOpenFloorsOutlineIsTheHullOfItsWallsAndColumns) {
  // An L of two 0.2 m walls from (0, 0) to (10, 0) and (0, 0) to (0, 6), and a 0.4 m column at
  // (8, 5): the hull is the L's outer corner (-0.1, -0.1), the far end of each wall and the
  // column's far corners.
  Level level;
  level.id = "L0";
  level.height = 3.0;
  level.walls = {wallOf("A", {0, 0}, {10, 0}, 0.2), wallOf("B", {0, 0}, {0, 6}, 0.2),
                 wallOf("C", {7.8, 5}, {8.2, 5}, 0.4)};
  const Polygon2 hull = facadeOutline(level);
  ASSERT_EQ(hull.size(), 6u);
  EXPECT_GT(signedArea(hull), 0.0);  // counter-clockwise
  // Every footprint corner lies inside (or on) the hull, and the hull's area is, by hand, the
  // polygon (-0.1,-0.1) (10,-0.1) (10,0.1) (8.2,5.2) (0.1,6) (-0.1,6): the column's corner
  // (7.8, 5.2) lies just inside the edge from (8.2, 5.2) to (0.1, 6).
  const Polygon2 by_hand = {{-0.1, -0.1}, {10, -0.1}, {10, 0.1}, {8.2, 5.2}, {0.1, 6}, {-0.1, 6}};

  EXPECT_NEAR(signedArea(hull), signedArea(by_hand), 1e-9);
  EXPECT_TRUE(containsPoint(hull, {5.0, 3.0}));
  EXPECT_FALSE(containsPoint(hull, {9.5, 4.0}));
  Level empty;
  EXPECT_TRUE(facadeOutline(empty).empty());
}

}  // namespace
}  // namespace isg::bim
