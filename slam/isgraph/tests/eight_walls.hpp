#pragma once

// Eight planned wall faces around an 8 × 6 m room centred on the origin of P, for the wall
// release's tests: two along each side, each seen over 3 m, normals facing inwards, each its own
// plan wall.

#include <vector>

#include "slam/isgraph/wall_release.hpp"

namespace isg::testing {

inline std::vector<slam::HeldWall> eightWallRoom() {
  std::vector<slam::HeldWall> walls;
  for (double x : {-2.0, 2.0}) {
    walls.push_back({{x, -3.0}, 3.0, {0.0, 1.0}});
    walls.push_back({{x, 3.0}, 3.0, {0.0, -1.0}});
  }
  for (double y : {-1.5, 1.5}) {
    walls.push_back({{-4.0, y}, 3.0, {1.0, 0.0}});
    walls.push_back({{4.0, y}, 3.0, {-1.0, 0.0}});
  }
  for (std::size_t i = 0; i < walls.size(); ++i) walls[i].wall = int(i);
  return walls;
}

}  // namespace isg::testing
