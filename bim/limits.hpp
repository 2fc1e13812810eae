#pragma once

#include <cstddef>
#include <cstdint>

// The limits every plan and scenario is held to (docs/formats.md, "Limits"; the file size, ids and
// free text: common/limits.hpp). They are far beyond any
// real building, and they keep every command fast and finite on hostile input: parsing and the
// geometry checks stay near-linear, the simulated world and the route grid stay within memory,
// and every number reaching MuJoCo is one it can represent.
namespace isg::bim::limits {

// Every plan coordinate, elevation and start pose, in metres from the origin.
inline constexpr double kMaxCoordinate = 10'000.0;
// The walls, outlines, as-built additions and shifts of one level fit in a square this size.
inline constexpr double kMaxLevelExtent = 1'000.0;
// Lengths, thicknesses, heights, widths and clutter extents: at least a millimetre ...
inline constexpr double kMinSize = 0.001;
// ... walls at most this thick, and nothing taller than this.
inline constexpr double kMaxThickness = 10.0;
inline constexpr double kMaxHeight = 100.0;
// How far an as-built wall shift may move a wall.
inline constexpr double kMaxWallShift = 10.0;
// Degrees an as-built wall may be turned from its planned direction.
inline constexpr double kMaxWallRotationDeg = 45.0;

inline constexpr std::size_t kMaxLevels = 100;
inline constexpr std::size_t kMaxWallsPerLevel = 20'000;
inline constexpr std::size_t kMaxRoomsPerLevel = 5'000;
inline constexpr std::size_t kMaxDoorsPerLevel = 20'000;
inline constexpr std::size_t kMaxStairsPerLevel = 1'000;
inline constexpr std::size_t kMaxOutlineVertices = 100'000;
inline constexpr std::size_t kMaxVerticesPerLevel = 200'000;
// Waypoints of a route, extra walls and clutter boxes of a scenario.
inline constexpr std::size_t kMaxScenarioItems = 10'000;
// Kidnaps of one run, and the latest robot time one may happen at (a week).
inline constexpr std::size_t kMaxKidnaps = 1'000;
inline constexpr double kMaxRobotSeconds = 604'800.0;

}  // namespace isg::bim::limits
