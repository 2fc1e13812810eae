#include "slam/isgraph/room_hold.hpp"

#include <cmath>

namespace isg::slam {

bool holdsAlongPair(const RoomPairEvidence& pair, double sigma_room) {
  return std::abs(pair.map_width - pair.plan_width) <= sigma_room &&
         pair.released_offset <= sigma_room;
}

double widthThrough(const Eigen::Vector2d& point, const Eigen::Vector4d& a,
                    const Eigen::Vector4d& b) {
  auto distance = [&](const Eigen::Vector4d& plane) {
    return std::abs(plane.head<2>().dot(point) + plane.w()) / plane.head<2>().norm();
  };
  return distance(a) + distance(b);
}

}  // namespace isg::slam
