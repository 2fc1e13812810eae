// How the deviation report's evidence follows the map's own error: the threshold a wall is judged
// against (the error the walls around it leave), and which of two placements lays a wall in the
// plan (the one its surroundings agree with). Maps made by hand from the built faces, M = B.

#include <gtest/gtest.h>

#include <cmath>

#include "bim/as_built_wall.hpp"
#include "bim/plan_parser.hpp"
#include "common/json_reader.hpp"
#include "slam/deviations/plan_deviations.hpp"

namespace isg::slam {
namespace {

// Five rooms of 3 m × 4 m in a row: W1 (south) and W3 (north) 15 m long, W2 and W4 the ends,
// partitions P3, P6, P9 and P12 at x = 3, 6, 9, 12.
bim::Plan fiveRooms() {
  const nlohmann::json document = nlohmann::json::parse(R"({
    "format": "isg.plan", "version": 1, "name": "five rooms",
    "levels": [{
      "id": "L0", "elevation": 0.0, "height": 3.0,
      "walls": [
        {"id": "W1", "start": [0, 0], "end": [15, 0], "thickness": 0.2},
        {"id": "W2", "start": [15, 0], "end": [15, 4], "thickness": 0.2},
        {"id": "W3", "start": [15, 4], "end": [0, 4], "thickness": 0.2},
        {"id": "W4", "start": [0, 4], "end": [0, 0], "thickness": 0.2},
        {"id": "P3", "start": [3, 0], "end": [3, 4], "thickness": 0.1},
        {"id": "P6", "start": [6, 0], "end": [6, 4], "thickness": 0.1},
        {"id": "P9", "start": [9, 0], "end": [9, 4], "thickness": 0.1},
        {"id": "P12", "start": [12, 0], "end": [12, 4], "thickness": 0.1}
      ]
    }]
  })");
  const common::JsonSource source{"five-rooms.json", nullptr};
  return bim::parsePlan(common::JsonNode(document, "", source));
}

// Every face of the plan built with `as_built`'s shifts as a map wall seen by every keyframe; the
// keyframes along the rooms' middle.
MapDiagnostics builtMap(const bim::Plan& plan, const bim::AsBuilt& as_built) {
  bim::Plan built = plan;
  for (auto& wall : built.levels[0].walls) wall = bim::builtWall(wall, as_built);
  const bim::AGraph faces = bim::buildAGraph(built);
  MapDiagnostics map;
  for (double x = 0.5; x <= 14.5; x += 0.5) {
    MapKeyframe keyframe;
    keyframe.estimate.translation() = Eigen::Vector3d(x, 2.0, 0.5);
    map.keyframes.push_back(keyframe);
  }
  std::vector<int> all(map.keyframes.size());
  for (std::size_t k = 0; k < all.size(); ++k) all[k] = int(k);
  int id = 0;
  for (const auto& surface : faces.surfaces) {
    for (const auto& [a, b] : surface.segments) {
      map.walls.push_back({id++, surface.plane.normal, surface.plane.d, a, b, 0.2, 2.6, 20, all});
    }
  }
  return map;
}

const WallDeviation& thresholdWallOf(const DeviationReport& report, const std::string& id) {
  for (const auto& w : report.walls) {
    if (w.wall == id) return w;
  }
  throw std::runtime_error("no wall " + id);
}

// P6 built 8 cm off: beyond the 6 cm threshold, found where the map around it lies true. With the
// walls around it 4 cm off in turn (W4 and P9 +4 cm, P3 and P12 −4 cm along +x, each under the
// threshold), the map there is known to within no better than that: the local placement leaves
// ±4 cm on the four partitions and nothing on W1 and W3, a length-weighted RMS of
// 0.04·√(4·3.8 / (4·3.8 + 2·14.8)) = 0.0233 m over n = 6 walls, 0.0233·√(6/3) = 0.033 m; three
// times that is 0.099 m, and 8 cm is no longer evidence of a wall built off.
TEST(DeviationThresholds, AWallIsJudgedAgainstTheMapsOwnErrorAroundIt) {
  const bim::Plan plan = fiveRooms();
  const bim::AGraph planned = bim::buildAGraph(plan);
  bim::AsBuilt clean;
  clean.wall_shifts = {{"P6", -0.08}};  // the left normal of a wall drawn +y is −x
  const DeviationReport true_around =
      measureDeviations(planned, builtMap(plan, clean), Eigen::Isometry3d::Identity());
  const WallDeviation& found = thresholdWallOf(true_around, "P6");
  EXPECT_EQ(found.status, WallStatus::kShifted);
  EXPECT_NEAR(*found.offset_m, -0.08, 0.002);
  EXPECT_NEAR(found.shift_threshold_m, 0.06, 1e-12);
  EXPECT_NEAR(found.angle_threshold_deg, 1.5, 1e-12);
  ASSERT_TRUE(found.local_offset_noise_m);
  EXPECT_LT(*found.local_offset_noise_m, 0.002);

  bim::AsBuilt noisy = clean;
  noisy.wall_shifts.push_back({"W4", 0.04});  // drawn −y: its left normal is +x
  noisy.wall_shifts.push_back({"P3", 0.04});
  noisy.wall_shifts.push_back({"P9", -0.04});
  noisy.wall_shifts.push_back({"P12", 0.04});
  const DeviationReport noisy_around =
      measureDeviations(planned, builtMap(plan, noisy), Eigen::Isometry3d::Identity());
  const WallDeviation& told = thresholdWallOf(noisy_around, "P6");
  EXPECT_EQ(told.status, WallStatus::kAsPlanned);
  EXPECT_NEAR(*told.offset_m, -0.08, 0.02);
  ASSERT_TRUE(told.local_offset_noise_m);
  EXPECT_NEAR(*told.local_offset_noise_m, 0.033, 0.006);
  EXPECT_NEAR(told.shift_threshold_m, 3.0 * *told.local_offset_noise_m, 1e-12);
}

// The same map placed two ways: by the final B_T_M and by the poses of the keyframes that saw
// each wall. Where they differ by 8 cm in x and in y, the one that lays the walls around each wall
// on the plan places it, whichever it is: no wall is reported off in either case.
TEST(DeviationThresholds, AWallIsPlacedAsTheMapAroundItAgreesWithThePlan) {
  const bim::Plan plan = fiveRooms();
  const bim::AGraph planned = bim::buildAGraph(plan);
  const MapDiagnostics map = builtMap(plan, {});
  Eigen::Isometry3d off = Eigen::Isometry3d::Identity();
  off.translation() = Eigen::Vector3d(0.08, 0.08, 0.0);
  const Eigen::Isometry3d right = Eigen::Isometry3d::Identity();
  for (const bool keyframes_off : {true, false}) {
    const std::vector<std::optional<Eigen::Isometry3d>> keyframe_B_T_M(map.keyframes.size(),
                                                                       keyframes_off ? off : right);
    const DeviationReport report =
        measureDeviations(planned, map, keyframes_off ? right : off, {}, keyframe_B_T_M);
    for (const auto& w : report.walls) {
      EXPECT_EQ(w.status, WallStatus::kAsPlanned)
          << w.wall << (keyframes_off ? " (keyframes off)" : "");
      EXPECT_NEAR(*w.offset_m, 0.0, 0.002) << w.wall;
    }
  }
}

// Where the sight lines start. The final B_T_M 8 cm off and the keyframes' own placements right:
// the walls are placed by the keyframes', and so are the keyframes that saw them (a sight line from
// 8 cm off sees past the end of a wall that stands). A segment that ended is placed by the
// keyframes' own placements alone, and left out without them.
TEST(DeviationThresholds, AKeyframeSeesFromWhereTheReportPlacesTheWallsItSaw) {
  const bim::Plan plan = fiveRooms();
  const bim::AGraph planned = bim::buildAGraph(plan);
  MapDiagnostics map = builtMap(plan, {});
  Eigen::Isometry3d off = Eigen::Isometry3d::Identity();
  off.translation() = Eigen::Vector3d(0.08, 0.08, 0.0);
  const Eigen::Isometry3d right = Eigen::Isometry3d::Identity();
  // The viewpoints' places (x, y), one per keyframe 0.5 m apart (the keyframes stand at x = 0.5,
  // 1.0, … 14.5, y = 2).
  const auto places = [&](const Eigen::Isometry3d& B_T_M,
                          const std::vector<std::optional<Eigen::Isometry3d>>& keyframe_B_T_M) {
    const DeviationReport report = measureDeviations(planned, map, B_T_M, {}, keyframe_B_T_M);
    std::vector<Eigen::Vector2d> out;
    for (const auto& [level, viewpoints] :
         viewpointsOnLevels(planned, map, report.keyframes_in_B)) {
      for (const auto& v : viewpoints) out.push_back(v.position);
    }
    return out;
  };
  const std::vector<std::optional<Eigen::Isometry3d>> placed_right(map.keyframes.size(), right);
  const auto bent = places(off, placed_right);
  EXPECT_GE(bent.size(), map.keyframes.size() - 1);
  for (const auto& p : bent) EXPECT_NEAR(p.y(), 2.0, 1e-9);
  const std::vector<std::optional<Eigen::Isometry3d>> placed_off(map.keyframes.size(), off);
  for (const auto& p : places(right, placed_off)) {
    EXPECT_NEAR(p.y(), 2.0, 1e-9);  // B_T_M lays the walls on the plan: it places them all
  }
  // The first 10 keyframes (x ≤ 5) of a segment that ended: where the localizer had them, or
  // nowhere.
  map.current_segment = 10;
  const auto ended = places(right, placed_off);
  EXPECT_GE(ended.size(), map.keyframes.size() - 1);
  for (const auto& p : ended) EXPECT_NEAR(p.y(), p.x() < 5.25 ? 2.08 : 2.0, 1e-9) << p.x();
  for (const auto& p : places(right, {})) EXPECT_GT(p.x(), 5.25);
  EXPECT_GE(places(right, {}).size(), map.keyframes.size() - 11);
}

}  // namespace
}  // namespace isg::slam
