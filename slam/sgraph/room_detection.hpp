#pragma once

#include <Eigen/Core>
#include <array>
#include <optional>
#include <vector>

#include "bim/plane.hpp"
#include "slam/sgraph/plane_map.hpp"

namespace isg::slam {

// Rooms from the S-Graph's wall planes (docs/slam.md; their code uses a free-space skeleton
// we do not have, so we use our own evidence). Around a point the robot walked through, a
// four-wall room is two opposed x-planes and two opposed y-planes — normals facing each other,
// the point between them, the nearest such walls on each side, widths ≥ 1 m — whose observed
// extents cover enough of the rectangle's sides. A two-wall room (a corridor) is one opposed pair
// whose walls run along the point while the other direction stays open or long.
struct RoomDetectionOptions {
  double min_width = 1.0;
  double max_width = 15.0;
  double min_coverage = 0.5;  // share of a side its wall's observed extent must cover
  double axis_tolerance_deg = 15.0;
  double corridor_min_length_ratio = 2.5;  // corridor: observed length ≥ this × width
  // A room's wall has been seen over at least this height: a box of clutter has not.
  double min_wall_height = 1.2;
};

struct RoomCandidate {
  bool four_wall = false;
  // Plane indices: pairs[0] always set, pairs[1] for four-wall rooms. First of each pair is the
  // plane on the negative side of the room along that pair's direction.
  std::array<std::array<int, 2>, 2> pairs{{{-1, -1}, {-1, -1}}};
  Eigen::Vector2d centre = Eigen::Vector2d::Zero();
  std::array<double, 2> widths{0.0, 0.0};
};

// The room around `point` (in M), if the planes give one. `dominant_yaw`: the building's
// direction, from dominantYaw over the map's walls.
std::optional<RoomCandidate> detectRoom(const Eigen::Vector2d& point,
                                        const std::vector<MapPlane>& planes, double dominant_yaw,
                                        const RoomDetectionOptions& options = {});

}  // namespace isg::slam
