#pragma once

#include <Eigen/Core>

namespace isg::slam {

// What the map says of one opposed pair of a matched four-wall room, for the merge's room factor.
struct RoomPairEvidence {
  double map_width = 0.0;   // m, between the S-room's two planes of the pair, through its centre
  double plan_width = 0.0;  // m, between the plan room's two surfaces of the pair
  // m, the largest |offset| at which a wall of the pair was released as built off; 0 if none.
  double released_offset = 0.0;
};

// Whether the merge holds the S-room's centre on the plan room's along this pair's normal. A wall
// built off by d moves the S-centre by d/2: beyond sigma_room of width mismatch or of release, a
// bias beyond half the factor's sigma, it is not held. The width tells a wall built off from a
// map that drifted (drift moves both walls of a room alike); the release does not, but catches a
// pair the map has not closed yet.
bool holdsAlongPair(const RoomPairEvidence& pair, double sigma_room);

// The width between two planes [n, d] (n·x + d = 0, n not necessarily unit, in the plane z = 0)
// measured through `point`: the sum of its distances from both.
double widthThrough(const Eigen::Vector2d& point, const Eigen::Vector4d& a,
                    const Eigen::Vector4d& b);

}  // namespace isg::slam
