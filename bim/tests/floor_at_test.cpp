#include "bim/floor_at.hpp"

#include <gtest/gtest.h>

namespace isg::bim {
namespace {

FloorNode floor(const std::string& id, double elevation) {
  FloorNode node;
  node.id = id;
  node.elevation = elevation;
  return node;
}

TEST(FloorAt, TakesTheHighestLevelAtOrBelowTheBase) {
  AGraph graph;
  graph.floors = {floor("L1", 3.2), floor("L0", 0.0)};  // in any order
  EXPECT_EQ(floorAt(graph, 0.45), 1);
  EXPECT_EQ(floorAt(graph, 3.19), 1);  // on the flight, its base below the upper floor
  EXPECT_EQ(floorAt(graph, 3.2), 0);
  EXPECT_EQ(floorAt(graph, 3.65), 0);
  EXPECT_EQ(floorAt(graph, -1.0), 1);  // below every level: the lowest
  EXPECT_EQ(floorAt(AGraph{}, 1.0), -1);
}

}  // namespace
}  // namespace isg::bim
