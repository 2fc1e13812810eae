// The deviation report on a map made by hand: the map's walls are the faces of the building as
// built (one wall shifted, one turned, one missing, one extra), placed in the plan 3 cm and 0.3°
// off, as a localizer would place them. Every number below is a hand calculation.

#include "slam/deviations/plan_deviations.hpp"
#include "bim/as_built_wall.hpp"
#include "bim/plan_parser.hpp"
#include "common/json_reader.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <optional>
#include <tuple>

namespace isg::slam {
namespace {

bim::Plan threeRooms() {
  const nlohmann::json document = nlohmann::json::parse(R"({
    "format": "isg.plan", "version": 1, "name": "three rooms",
    "levels": [{
      "id": "L0", "elevation": 0.0, "height": 3.0,
      "walls": [
        {"id": "W1", "start": [0, 0], "end": [9, 0], "thickness": 0.2},
        {"id": "W2", "start": [9, 0], "end": [9, 4], "thickness": 0.2},
        {"id": "W3", "start": [9, 4], "end": [0, 4], "thickness": 0.2},
        {"id": "W4", "start": [0, 4], "end": [0, 0], "thickness": 0.2},
        {"id": "W5", "start": [3, 0], "end": [3, 4], "thickness": 0.1},
        {"id": "W6", "start": [6, 0], "end": [6, 4], "thickness": 0.1}
      ],
      "doors": [
        {"id": "D1", "wall": "W5", "offset": 2.0, "width": 0.9, "height": 2.1},
        {"id": "D2", "wall": "W6", "offset": 2.0, "width": 0.9, "height": 2.1}
      ],
      "rooms": [
        {"id": "R1", "outline": [[0.1, 0.1], [2.95, 0.1], [2.95, 3.9], [0.1, 3.9]]},
        {"id": "R2", "outline": [[3.05, 0.1], [5.95, 0.1], [5.95, 3.9], [3.05, 3.9]]},
        {"id": "R3", "outline": [[6.05, 0.1], [8.9, 0.1], [8.9, 3.9], [6.05, 3.9]]}
      ]
    }]
  })");
  const common::JsonSource source{"three-rooms.json", nullptr};
  return bim::parsePlan(common::JsonNode(document, "", source));
}

// W3 shifted 0.15 m along its left normal (to y = 3.85), W5 turned 4° about its start, W6 not
// built (with its door), a 1 m partition standing free in R1.
bim::AsBuilt deviations() {
  bim::AsBuilt as_built;
  as_built.wall_shifts = {{"W3", 0.15}};
  as_built.wall_rotations = {{"W5", 4.0, bim::WallRotation::About::kStart}};
  as_built.missing_walls = {"W6"};
  return as_built;
}

bim::Plan builtPlan(const bim::Plan& plan, const bim::AsBuilt& as_built) {
  bim::Plan built = plan;
  bim::Level& level = built.levels[0];
  std::erase_if(level.walls, [](const bim::Wall& w) { return w.id == "W6"; });
  std::erase_if(level.doors, [](const bim::Door& d) { return d.wall == "W6"; });
  for (auto& wall : level.walls) wall = bim::builtWall(wall, as_built);
  bim::Wall partition;
  partition.id = "X1";
  partition.start = {1.0, 2.0};
  partition.end = {2.0, 2.0};
  partition.thickness = 0.1;
  partition.height = 3.0;
  level.walls.push_back(partition);
  return built;
}

// Keyframes along y = `y` from `x0` to `x1` every `step`, M = B.
void walkAlong(MapDiagnostics& map, double y, double x0, double x1, double step) {
  for (double x = x0; x <= x1; x += step) {
    MapKeyframe keyframe;
    keyframe.estimate.translation() = Eigen::Vector3d(x, y, 0.5);
    map.keyframes.push_back(keyframe);
  }
}

// Every face of the built walls as a map wall, in a map frame M = B; and keyframes along y = `y`
// from `x0` to `x1` every `step`.
MapDiagnostics facesAndWalk(const bim::AGraph& built, double y, double x0, double x1, double step) {
  MapDiagnostics map;
  int id = 0;
  for (const auto& surface : built.surfaces) {
    for (const auto& [a, b] : surface.segments) {
      map.walls.push_back(
          {id++, surface.plane.normal, surface.plane.d, a, b, 0.2, 2.6, 20, std::vector<int>()});
    }
  }
  walkAlong(map, y, x0, x1, step);
  return map;
}

// The three rooms' map: their faces, and keyframes along the rooms' middle.
MapDiagnostics mapOf(const bim::AGraph& built) { return facesAndWalk(built, 1.0, 0.5, 8.5, 0.25); }

const WallDeviation& deviationWallOf(const DeviationReport& report, const std::string& id) {
  for (const auto& w : report.walls) {
    if (w.wall == id) return w;
  }
  throw std::runtime_error("no wall " + id);
}

TEST(PlanDeviations, FindsTheShiftedTurnedMissingAndExtraWallsByHand) {
  const bim::Plan plan = threeRooms();
  const bim::AGraph planned = bim::buildAGraph(plan);
  const bim::AGraph built = bim::buildAGraph(builtPlan(plan, deviations()));
  // The localizer's placement, off by 3 cm in x and 0.3° in yaw.
  Eigen::Isometry3d B_T_M = Eigen::Isometry3d::Identity();
  B_T_M.linear() = Eigen::AngleAxisd(0.3 * std::numbers::pi / 180.0, Eigen::Vector3d::UnitZ())
                       .toRotationMatrix();
  B_T_M.translation() = Eigen::Vector3d(0.03, 0.0, 0.0);
  const DeviationReport report = measureDeviations(planned, mapOf(built), B_T_M);

  ASSERT_EQ(report.levels, std::vector<std::string>{"L0"});
  ASSERT_EQ(report.walls.size(), 6u);
  for (const char* id : {"W1", "W2", "W4"}) {
    const WallDeviation& w = deviationWallOf(report, id);
    EXPECT_EQ(w.status, WallStatus::kAsPlanned) << id;
    EXPECT_NEAR(*w.offset_m, 0.0, 0.002) << id;
    EXPECT_NEAR(*w.angle_deg, 0.0, 0.02) << id;
  }
  const WallDeviation& shifted = deviationWallOf(report, "W3");
  EXPECT_EQ(shifted.status, WallStatus::kShifted);
  EXPECT_NEAR(*shifted.offset_m, 0.15, 0.002);
  EXPECT_NEAR(*shifted.angle_deg, 0.0, 0.02);
  EXPECT_GT(shifted.observed_share, 0.9);
  // Turned 4° about (3, 0): at the planned centre, 2·tan 4° along the left normal (−x).
  const WallDeviation& turned = deviationWallOf(report, "W5");
  EXPECT_EQ(turned.status, WallStatus::kRotated);
  EXPECT_NEAR(*turned.angle_deg, 4.0, 0.02);
  EXPECT_NEAR(*turned.offset_m, 2.0 * std::tan(4.0 * std::numbers::pi / 180.0), 0.002);
  ASSERT_TRUE(turned.pivot_along_m);
  EXPECT_NEAR(*turned.pivot_along_m, 0.0, 0.03);
  EXPECT_EQ(turned.turned_about, "start");
  EXPECT_FALSE(shifted.pivot_along_m);
  // Nothing of W6 in the map, though the keyframes east of W5 saw all of it.
  const WallDeviation& missing = deviationWallOf(report, "W6");
  EXPECT_EQ(missing.status, WallStatus::kMissing);
  EXPECT_TRUE(missing.evidence.empty());
  ASSERT_TRUE(missing.in_view_share);
  EXPECT_GE(*missing.in_view_share, 0.6);
  // The partition: its two faces paired into one wall on its axis, y = 2.
  ASSERT_EQ(report.extra_walls.size(), 1u);
  const ExtraWall& extra = report.extra_walls[0];
  EXPECT_EQ(extra.planes.size(), 2u);
  EXPECT_NEAR(0.5 * (extra.start + extra.end).y(), 2.0, 0.005);
  EXPECT_NEAR(0.5 * (extra.start + extra.end).x(), 1.5, 0.005);
  EXPECT_NEAR(extra.length(), 1.0, 0.11);  // the faces' ends, within the wall's thickness
  // The placement fitted on the walls as planned takes the localizer's error out.
  ASSERT_EQ(report.placements.size(), 1u);
  EXPECT_NEAR(report.placements[0].correction.z() * 180.0 / std::numbers::pi, -0.3, 0.005);
  EXPECT_EQ(report.placements[0].walls_used, 3);
}

// Each verdict carries its uncertainty: the fitted line's from its ends (1 cm each, as the map's
// walls here lie exactly on the faces) with the local placement's; a pivot's along the wall. With
// ends taken to lie on their faces only to 20 cm, a 0.15 m shift is no longer clear of its
// uncertainty (2 σ): not enough data, not_seen.
TEST(PlanDeviations, EachVerdictCarriesItsUncertainty) {
  const bim::Plan plan = threeRooms();
  const bim::AGraph planned = bim::buildAGraph(plan);
  const bim::AGraph built = bim::buildAGraph(builtPlan(plan, deviations()));
  const DeviationReport report =
      measureDeviations(planned, mapOf(built), Eigen::Isometry3d::Identity());
  const WallDeviation& shifted = deviationWallOf(report, "W3");
  ASSERT_TRUE(shifted.offset_sigma_m && shifted.angle_sigma_deg);
  // At least the placement's, at most it with one end's 1 cm.
  EXPECT_GE(*shifted.offset_sigma_m, shifted.placement_sigma_m);
  EXPECT_LE(*shifted.offset_sigma_m, std::hypot(shifted.placement_sigma_m, 0.01) + 1e-12);
  EXPECT_GT(*shifted.offset_sigma_m, 0.0);
  // A 9 m wall's direction to a few hundredths of a degree from its ends, with the placement's.
  EXPECT_LT(*shifted.angle_sigma_deg, 0.3);
  const WallDeviation& turned = deviationWallOf(report, "W5");
  ASSERT_TRUE(turned.pivot_sigma_m);
  // σ_pivot ≈ σ_offset / tan 4° (the slope's share is small at a pivot near the start).
  EXPECT_GT(*turned.pivot_sigma_m,
            0.8 * *turned.offset_sigma_m / std::tan(4.0 * std::numbers::pi / 180.0));
  EXPECT_LT(*turned.pivot_sigma_m, 0.3);
  EXPECT_FALSE(shifted.pivot_sigma_m);

  DeviationOptions loose;
  loose.end_sigma_m = 0.2;
  const DeviationReport unclear =
      measureDeviations(planned, mapOf(built), Eigen::Isometry3d::Identity(), loose);
  const WallDeviation& w3 = deviationWallOf(unclear, "W3");
  EXPECT_GT(2.0 * *w3.offset_sigma_m, 0.15);
  EXPECT_EQ(w3.status, WallStatus::kNotSeen);
  EXPECT_NEAR(*w3.offset_m, 0.15, 0.002);  // measured all the same
}

// The same building, its map's walls each seen from 2 keyframes: too few to believe a deviation
// (min_deviation_observations, 3). W3 (shifted 0.15 m) and W5 (turned 4°) are not seen rather
// than off, the walls as planned stay as planned; seen from 3, both are found again.
TEST(PlanDeviations, ADeviationSeenFromFewerThanThreeKeyframesIsNotBelieved) {
  const bim::Plan plan = threeRooms();
  const bim::AGraph planned = bim::buildAGraph(plan);
  const bim::AGraph built = bim::buildAGraph(builtPlan(plan, deviations()));
  for (int observations : {2, 3}) {
    MapDiagnostics map = mapOf(built);
    for (auto& wall : map.walls) wall.observations = observations;
    const DeviationReport report = measureDeviations(planned, map, Eigen::Isometry3d::Identity());
    for (const char* id : {"W1", "W2", "W4"}) {
      EXPECT_EQ(deviationWallOf(report, id).status, WallStatus::kAsPlanned)
          << id << " " << observations;
    }
    const bool believed = observations >= 3;
    EXPECT_EQ(deviationWallOf(report, "W3").status,
              believed ? WallStatus::kShifted : WallStatus::kNotSeen);
    EXPECT_EQ(deviationWallOf(report, "W5").status,
              believed ? WallStatus::kRotated : WallStatus::kNotSeen);
    // What was measured is still said.
    EXPECT_NEAR(*deviationWallOf(report, "W3").offset_m, 0.15, 0.002) << observations;
  }
}

// The partition standing free in R1 (an extra wall) as its map planes would be fitted from one
// keyframe whose attitude was 2° off: both lean 2°. Seen once, leaning, it is a stray fit, not an
// extra wall (max_stray_lean_deg, 1°); seen once standing plumb, or from 3 keyframes leaning, it
// is the extra wall it is.
TEST(PlanDeviations, APlaneSeenOnceThatLeansIsNoExtraWall) {
  const bim::Plan plan = threeRooms();
  const bim::AGraph planned = bim::buildAGraph(plan);
  const bim::AGraph built = bim::buildAGraph(builtPlan(plan, deviations()));
  const double lean = 2.0 * std::numbers::pi / 180.0;
  for (const auto& [observations, leaning, reported] :
       {std::tuple{1, true, false}, {1, false, true}, {3, true, true}}) {
    MapDiagnostics map = mapOf(built);
    for (auto& wall : map.walls) {
      // The partition's faces: y = 1.95 and 2.05, x from 1 to 2.
      if (std::abs(std::abs(wall.d) - 1.95) > 1e-6 && std::abs(std::abs(wall.d) - 2.05) > 1e-6) {
        continue;
      }
      if (std::abs(0.5 * (wall.start + wall.end).x() - 1.5) > 0.1) continue;
      wall.observations = observations;
      if (leaning) {
        wall.normal = Eigen::Vector3d(0.0, wall.normal.y() * std::cos(lean), std::sin(lean));
      }
    }
    const DeviationReport report = measureDeviations(planned, map, Eigen::Isometry3d::Identity());
    EXPECT_EQ(report.extra_walls.size(), reported ? 1u : 0u)
        << observations << " observations, leaning " << leaning;
  }
}

// W5 (4 m, (3, 0) → (3, 4)) turned 2° (its ends swing up to 14 cm) about its start, its centre,
// its end or a point 1.2 m along it: the report finds it turned, by 2°, and the point it turned
// about, where its line crosses the planned axis. A turn about the centre moves no point of the
// wall's middle, and a wall measured by its offset alone would pass as planned.
TEST(PlanDeviations, ATurnIsFoundAboutWhicheverPointOfTheWallItWasTurned) {
  const bim::Plan plan = threeRooms();
  const bim::AGraph planned = bim::buildAGraph(plan);
  using About = bim::WallRotation::About;
  const struct {
    About about;
    double along_m, pivot_m;
    const char* name;
  } cases[] = {{About::kStart, 0.0, 0.0, "start"},
               {About::kCentre, 0.0, 2.0, "centre"},
               {About::kEnd, 0.0, 4.0, "end"},
               {About::kAlong, 1.2, 1.2, "along"}};
  for (const auto& c : cases) {
    SCOPED_TRACE(c.name);
    bim::AsBuilt as_built = deviations();
    as_built.wall_rotations = {{"W5", 2.0, c.about, c.along_m}};
    const bim::AGraph built = bim::buildAGraph(builtPlan(plan, as_built));
    const DeviationReport report =
        measureDeviations(planned, mapOf(built), Eigen::Isometry3d::Identity());
    const WallDeviation& turned = deviationWallOf(report, "W5");
    EXPECT_EQ(turned.status, WallStatus::kRotated);
    EXPECT_NEAR(*turned.angle_deg, 2.0, 0.02);
    // At the planned centre, (2 − pivot)·tan 2° along the left normal (−x).
    EXPECT_NEAR(*turned.offset_m, (2.0 - c.pivot_m) * std::tan(2.0 * std::numbers::pi / 180.0),
                0.002);
    ASSERT_TRUE(turned.pivot_along_m);
    EXPECT_NEAR(*turned.pivot_along_m, c.pivot_m, 0.06);
    EXPECT_EQ(turned.turned_about, c.name);
  }
}

TEST(PlanDeviations, APivotIsNamedWithinItsDistanceAndBeyondOffTheWall) {
  EXPECT_EQ(pivotName(0.25, 5.0, 0.3), "start");
  EXPECT_EQ(pivotName(2.3, 5.0, 0.3), "centre");
  EXPECT_EQ(pivotName(5.2, 5.0, 0.3), "end");
  EXPECT_EQ(pivotName(1.0, 5.0, 0.3), "along");
  EXPECT_EQ(pivotName(-0.5, 5.0, 0.3), "beyond");
  EXPECT_EQ(pivotName(0.5, 0.6, 0.3), "end");  // nearer the end than the centre
  // offset 0.1 m at the centre of a 5 m wall turned atan(0.05): its line crosses 2 m before it.
  EXPECT_NEAR(*crossingAlong(5.0, 0.1, std::atan(0.05) * 180.0 / std::numbers::pi), 0.5, 1e-12);
  EXPECT_FALSE(crossingAlong(5.0, 0.1, 0.0));
}

// W1 (9 m, (0, 0) → (9, 0)) built only over its first 5 m. Its outer face runs its whole length
// and is in the map up to x = 5 (the map here has every face of the building as built), never in
// view beyond; its inner face, exposed from x = 0.1 to 8.9 but where W5 and W6 meet it
// (2.95–3.05, 5.95–6.05), is built up to 5.0 and in view, not built, beyond: 0.95 + 2.85 m. W5,
// turned about (3, 0), cuts a few centimetres out of both faces there: not in view, bridged.
// W6 not built at all; the other walls whole.
// The three rooms as built (deviations()) with W1 built from its start to x = `end_x` only.
DeviationReport withW1BuiltTo(double end_x) {
  const bim::Plan plan = threeRooms();
  bim::Plan built_plan = builtPlan(plan, deviations());
  for (auto& wall : built_plan.levels[0].walls) {
    if (wall.id == "W1") wall.end = {end_x, 0.0};
  }
  return measureDeviations(bim::buildAGraph(plan), mapOf(bim::buildAGraph(built_plan)),
                           Eigen::Isometry3d::Identity());
}

TEST(PlanDeviations, AWallBuiltInPartHasItsBuiltLengthAndIntervals) {
  const DeviationReport report = withW1BuiltTo(5.0);
  const WallProgress& cut = deviationWallOf(report, "W1").progress;
  EXPECT_EQ(cut.status, ProgressStatus::kPartlyBuilt);
  EXPECT_NEAR(cut.planned_m, 9.0, 1e-9);
  EXPECT_NEAR(cut.built_m, 5.0, 0.06);
  EXPECT_NEAR(cut.not_built_m, 0.95 + 2.85, 0.06);
  ASSERT_EQ(cut.built.size(), 1u);
  EXPECT_NEAR(cut.built[0].first, 0.0, 0.03);
  EXPECT_NEAR(cut.built[0].second, 5.0, 0.03);
  EXPECT_EQ(deviationWallOf(report, "W1").status,
            WallStatus::kAsPlanned);  // where it stands, as planned
  EXPECT_EQ(deviationWallOf(report, "W6").progress.status, ProgressStatus::kNotBuilt);
  for (const char* id : {"W2", "W3", "W4"}) {
    const WallProgress& whole = deviationWallOf(report, id).progress;
    EXPECT_EQ(whole.status, ProgressStatus::kBuilt) << id;
    EXPECT_NEAR(whole.built_m, whole.planned_m - whole.not_seen_m, 1e-9) << id;
  }
  EXPECT_NEAR(overlapLength({{0.0, 2.0}, {3.0, 5.0}}, {{1.0, 4.0}}), 2.0, 1e-12);
}

// W1 cut at x = 5.02, between two of the report's 5 cm samples (their steps meet at 5.00 and
// 5.05): the built part ends where the map's wall does, not at the boundary of a step, and the
// built length is 5.02 m, not 5.00.
TEST(PlanDeviations, ABuiltPartEndsWhereTheMapsWallDoesNotAtTheStepOfASample) {
  const DeviationReport report = withW1BuiltTo(5.02);
  const WallProgress& cut = deviationWallOf(report, "W1").progress;
  EXPECT_EQ(cut.status, ProgressStatus::kPartlyBuilt);
  ASSERT_EQ(cut.built.size(), 1u);
  EXPECT_NEAR(cut.built[0].second, 5.02, 0.002);
  EXPECT_NEAR(cut.built_m, 5.02, 0.002);
}

// The same map, seen only from R1: walls beyond R1 were never in view and are not seen, not
// missing; W5 (R1's east wall, turned) is still judged.
TEST(PlanDeviations, WallsOutOfViewAreNotSeenRatherThanMissing) {
  const bim::Plan plan = threeRooms();
  const bim::AGraph planned = bim::buildAGraph(plan);
  const bim::AGraph built = bim::buildAGraph(builtPlan(plan, deviations()));
  MapDiagnostics map = mapOf(built);
  std::erase_if(map.keyframes,
                [](const MapKeyframe& k) { return k.estimate.translation().x() > 2.5; });
  // What R1 sees: the faces facing into it (x < 3).
  std::erase_if(map.walls, [](const MapWall& w) { return std::min(w.start.x(), w.end.x()) > 3.1; });
  const DeviationReport report = measureDeviations(planned, map, Eigen::Isometry3d::Identity());
  EXPECT_EQ(deviationWallOf(report, "W6").status, WallStatus::kNotSeen);
  EXPECT_EQ(deviationWallOf(report, "W2").status, WallStatus::kNotSeen);
  EXPECT_EQ(deviationWallOf(report, "W5").status, WallStatus::kRotated);
}

// A 2.4 m plane standing 12 cm east of W5's planned east face (x = 3.05), unlike the turned
// wall's faces: left out of W5's fit. Seen on two keyframes against the faces' twenty, it is a
// stray fit and W5 keeps its 4°; seen as often as they are, it is a face that contradicts them
// (DeviationOptions::contradiction_observation_share), and W5 is measured by all its long pieces.
TEST(PlanDeviations, AStrayPlaneSeenOnAKeyframeOrTwoDoesNotContradictAWall) {
  const bim::Plan plan = threeRooms();
  const bim::AGraph planned = bim::buildAGraph(plan);
  const bim::AGraph built = bim::buildAGraph(builtPlan(plan, deviations()));
  auto measureW5 = [&](int stray_observations) {
    MapDiagnostics map = mapOf(built);
    map.walls.push_back({int(map.walls.size()), Eigen::Vector3d::UnitX(), -3.17,
                         Eigen::Vector2d(3.17, 0.8), Eigen::Vector2d(3.17, 3.2), 0.2, 2.6,
                         stray_observations, std::vector<int>()});
    const DeviationReport report = measureDeviations(planned, map, Eigen::Isometry3d::Identity());
    const WallDeviation& w5 = deviationWallOf(report, "W5");
    const auto stray = std::find_if(w5.evidence.begin(), w5.evidence.end(),
                                    [&](const auto& e) { return e.plane == map.walls.back().id; });
    EXPECT_NE(stray, w5.evidence.end());
    if (stray != w5.evidence.end()) {
      EXPECT_FALSE(stray->consistent);
    }
    return w5;
  };
  const WallDeviation stray = measureW5(2);
  EXPECT_EQ(stray.status, WallStatus::kRotated);
  EXPECT_NEAR(*stray.angle_deg, 4.0, 0.02);
  EXPECT_NEAR(*stray.offset_m, 2.0 * std::tan(4.0 * std::numbers::pi / 180.0), 0.002);
  const WallDeviation face = measureW5(20);
  // The length-weighted mean of the turned faces' pieces (4°, cut by the door and the corners)
  // and the stray (0°, 2.4 m): the faces hold about three quarters of the length.
  EXPECT_GT(*face.angle_deg, 2.5);
  EXPECT_LT(*face.angle_deg, 3.5);
}

// Where a ray from `from` toward `direction` (unit) first meets a segment, if anywhere.
std::optional<double> firstHit(const Eigen::Vector2d& from, const Eigen::Vector2d& direction,
                               const std::vector<std::pair<Eigen::Vector2d, Eigen::Vector2d>>& s) {
  std::optional<double> nearest;
  for (const auto& [a, b] : s) {
    const Eigen::Vector2d e = b - a, w = a - from;
    const double denominator = direction.x() * e.y() - direction.y() * e.x();
    if (std::abs(denominator) < 1e-12) continue;
    const double t = (w.x() * e.y() - w.y() * e.x()) / denominator;
    const double u = (w.x() * direction.y() - w.y() * direction.x()) / denominator;
    if (t > 0.0 && u >= 0.0 && u <= 1.0 && (!nearest || t < *nearest)) nearest = t;
  }
  return nearest;
}

// Each keyframe's sight profile cast by hand, in 2D, against the built faces and `clutter`: per
// degree its first hit, out of range where it meets nothing (the building stands in the open).
void castSight(MapDiagnostics& map, const bim::AGraph& built,
               const std::vector<std::pair<Eigen::Vector2d, Eigen::Vector2d>>& clutter) {
  auto segments = clutter;
  for (const auto& surface : built.surfaces) {
    segments.insert(segments.end(), surface.segments.begin(), surface.segments.end());
  }
  for (auto& keyframe : map.keyframes) {
    keyframe.sight.range_cm.assign(SightProfile::kBins, SightProfile::kOutOfRange);
    const Eigen::Vector2d from = keyframe.estimate.translation().head<2>();
    for (int bin = 0; bin < SightProfile::kBins; ++bin) {
      const double a = (bin + 0.5) * std::numbers::pi / 180.0;
      if (const auto t = firstHit(from, {std::cos(a), std::sin(a)}, segments)) {
        keyframe.sight.range_cm[bin] = std::uint16_t(std::lround(100.0 * *t));
      }
    }
  }
}

// W1 built over its first 5 m of 9, as above, the keyframes now recording how far they saw. Seen
// past, its last 4 m are not built; with a box standing in front of them (x 4.9–8.9, y 0.15–0.9,
// not a wall of the map), no sight line reaches them: they are not seen, never not built, and
// the wall is not reported partly built.
TEST(PlanDeviations, AWallIsNotBuiltOnlyWhereTheSensorSawPastIt) {
  const bim::Plan plan = threeRooms();
  const bim::AGraph planned = bim::buildAGraph(plan);
  bim::Plan built_plan = builtPlan(plan, deviations());
  for (auto& wall : built_plan.levels[0].walls) {
    if (wall.id == "W1") wall.end = {5.0, 0.0};
  }
  const bim::AGraph built = bim::buildAGraph(built_plan);
  MapDiagnostics open = mapOf(built);
  castSight(open, built, {});
  const DeviationReport seen_past = measureDeviations(planned, open, Eigen::Isometry3d::Identity());
  const WallProgress& cut = deviationWallOf(seen_past, "W1").progress;
  EXPECT_EQ(cut.status, ProgressStatus::kPartlyBuilt);
  EXPECT_NEAR(cut.built_m, 5.0, 0.06);
  // In view as without sight lines (0.95 + 2.85 m), less the last 0.1–0.2 m before W2: the sight
  // lines past it meet the end of W2's outer face within the wall's 0.2 m and the margin's 0.2 m.
  EXPECT_GE(cut.not_built_m, 0.95 + 2.85 - 0.25);
  EXPECT_LE(cut.not_built_m, 0.95 + 2.85 + 1e-9);
  EXPECT_EQ(deviationWallOf(seen_past, "W6").status,
            WallStatus::kMissing);  // seen through from R2, R3

  const Eigen::Vector2d lo(4.9, 0.15), hi(8.9, 0.9);
  MapDiagnostics boxed = mapOf(built);
  castSight(boxed, built,
            {{lo, {hi.x(), lo.y()}},
             {{hi.x(), lo.y()}, hi},
             {hi, {lo.x(), hi.y()}},
             {{lo.x(), hi.y()}, lo}});
  const DeviationReport hidden = measureDeviations(planned, boxed, Eigen::Isometry3d::Identity());
  const WallProgress& behind = deviationWallOf(hidden, "W1").progress;
  EXPECT_NE(behind.status, ProgressStatus::kPartlyBuilt);
  EXPECT_NEAR(behind.built_m, 5.0, 0.06);
  EXPECT_LT(behind.not_built_m, 0.3);
  EXPECT_NEAR(behind.not_seen_m, 3.8, 0.3);
}

}  // namespace
}  // namespace isg::slam

namespace isg::slam {
namespace {

// A façade of three bays in line (F1, F2, F3 from x = 0 to 19 along y = 0, between two columns
// in the façade) and a square column C1 standing free at (6.25, 4), 0.6 m across.
bim::Plan facadeOfBays() {
  const nlohmann::json document = nlohmann::json::parse(R"({
    "format": "isg.plan", "version": 1, "name": "bays",
    "levels": [{
      "id": "L0", "elevation": 0.0, "height": 3.0,
      "walls": [
        {"id": "F1", "start": [0, 0], "end": [6, 0], "thickness": 0.2},
        {"id": "F2", "start": [6.5, 0], "end": [12.5, 0], "thickness": 0.2},
        {"id": "F3", "start": [13, 0], "end": [19, 0], "thickness": 0.2},
        {"id": "W4", "start": [19, 0], "end": [19, 8], "thickness": 0.2},
        {"id": "W5", "start": [19, 8], "end": [0, 8], "thickness": 0.2},
        {"id": "W6", "start": [0, 8], "end": [0, 0], "thickness": 0.2}
      ],
      "columns": [{"id": "C1", "center": [6.25, 4], "size": [0.6, 0.6]}]
    }]
  })");
  const common::JsonSource source{"bays.json", nullptr};
  return bim::parsePlan(common::JsonNode(document, "", source));
}

// The S-Graph sees the façade's inner face y = 0.1 as one plane 18.8 m long, a third along none
// of its three bays: it is evidence for each bay along its length, not an extra wall. The
// column's end face x = 5.95 (the A-Graph keeps only a column's two long faces, y = 3.7 and 4.3,
// as surfaces) is the column's, not an extra wall either. Before, both were extra walls.
TEST(PlanDeviations, APlaneAlongBaysInLineIsEachBaysAndAColumnsFaceIsNoExtraWall) {
  const bim::Plan plan = facadeOfBays();
  const bim::AGraph graph = bim::buildAGraph(plan);
  MapDiagnostics map;
  map.walls.push_back({0,
                       Eigen::Vector3d::UnitY(),
                       -0.1,
                       {0.1, 0.1},
                       {18.9, 0.1},
                       0.2,
                       2.6,
                       20,
                       std::vector<int>()});
  map.walls.push_back({1,
                       -Eigen::Vector3d::UnitX(),
                       5.95,
                       {5.95, 3.7},
                       {5.95, 4.3},
                       0.2,
                       2.6,
                       20,
                       std::vector<int>()});
  // A free-standing partition the plan lacks, in the open (2 m long at x = 12): an extra wall.
  map.walls.push_back({2,
                       Eigen::Vector3d::UnitX(),
                       -12.0,
                       {12.0, 3.0},
                       {12.0, 5.0},
                       0.2,
                       2.6,
                       20,
                       std::vector<int>()});
  walkAlong(map, 2.0, 1.0, 18.0, 1.0);
  const DeviationReport report = measureDeviations(graph, map, Eigen::Isometry3d::Identity());
  for (const char* bay : {"F1", "F2", "F3"}) {
    const WallDeviation& wall = deviationWallOf(report, bay);
    EXPECT_EQ(wall.status, WallStatus::kAsPlanned) << bay;
    EXPECT_GT(wall.observed_share, 0.95) << bay;
    ASSERT_EQ(wall.evidence.size(), 1u) << bay;
    EXPECT_NEAR(*wall.offset_m, 0.0, 1e-9) << bay;
  }
  // F1's piece runs from the plane's start to the bay's end (its face's exposed extent).
  EXPECT_NEAR(deviationWallOf(report, "F1").evidence[0].start_B.x(), 0.1, 1e-9);
  ASSERT_EQ(report.extra_walls.size(), 1u);
  EXPECT_NEAR(report.extra_walls[0].start.x(), 12.0, 1e-9);
  // The column is not among the walls.
  for (const auto& wall : report.walls) EXPECT_NE(wall.wall, "C1");
}

// The middle bay F2 not built yet, with a window 0.6 m short of each of its ends, seen from the
// floor inside (keyframes every 0.5 m along y = 2.5, sight lines cast against what stands). Only
// its inner face could be in view, and only beside its window could a sight line tell it is
// not built: over that part it was seen past, so it is missing. Before, its outer face and its
// window counted as not in view, and at most 0.9 of 12 m of faces was "seen past": not seen.
TEST(PlanDeviations, AFacadeBayNotBuiltIsMissingThoughOnlyItsInnerFaceBesideItsWindowCanBeSeen) {
  bim::Plan plan = facadeOfBays();
  bim::Window window;
  window.id = "V1";
  window.wall = "F2";
  window.offset = 3.0;
  window.width = 4.8;
  window.sill = 0.9;
  window.height = 1.5;
  plan.levels[0].windows.push_back(window);
  const bim::AGraph graph = bim::buildAGraph(plan);
  bim::Plan built_plan = plan;
  std::erase_if(built_plan.levels[0].walls, [](const bim::Wall& w) { return w.id == "F2"; });
  built_plan.levels[0].windows.clear();
  const bim::AGraph built = bim::buildAGraph(built_plan);
  MapDiagnostics map = facesAndWalk(built, 2.5, 1.0, 18.0, 0.5);
  castSight(map, built, {});
  const DeviationReport report = measureDeviations(graph, map, Eigen::Isometry3d::Identity());
  const WallDeviation& bay = deviationWallOf(report, "F2");
  EXPECT_EQ(bay.status, WallStatus::kMissing);
  // Its inner face beside the window, 0.6 − 0.15 (the window's margin) m at each end, less the
  // 0.1 m left clear at each end of the face: seen past over nearly all of it.
  ASSERT_TRUE(bay.in_view_share.has_value());
  EXPECT_GT(*bay.in_view_share, 0.9);
  EXPECT_EQ(bay.progress.status, ProgressStatus::kNotBuilt);
  for (const char* standing : {"F1", "F3", "W4", "W5", "W6"}) {
    EXPECT_EQ(deviationWallOf(report, standing).status, WallStatus::kAsPlanned) << standing;
  }
}

}  // namespace
}  // namespace isg::slam

namespace isg::slam {
namespace {

// The A-Graph of a plan by hand: one level L0, 3 m high, of `walls` (a JSON array).
bim::AGraph graphOfWalls(const std::string& walls) {
  const nlohmann::json document = nlohmann::json::parse(
      R"({"format": "isg.plan", "version": 1, "name": "by hand",
          "levels": [{"id": "L0", "elevation": 0.0, "height": 3.0, "walls": )" +
      walls + "}]}");
  const common::JsonSource source{"by-hand.json", nullptr};
  return bim::buildAGraph(bim::parsePlan(common::JsonNode(document, "", source)));
}

// The S-Graph sees the façade's first two bays (F1, x 0 → 6, and F2, x 6.5 → 12.5) as one plane,
// y = 0.1 from x = 0.1 to 12.4, seen from 100 keyframes: a third along each, and so, before,
// evidence for the first of them alone. F2 was then judged on a plane fitted 3° off across it
// from 4 keyframes, longer than F2's piece of the good one, and reported turned. Now the plane
// along both is evidence for each by its piece, and F2's fit starts from the piece seen 100 times:
// the stray, seen 4 times, neither turns it nor contradicts it.
TEST(PlanDeviations, APlaneAlongTwoBaysIsEvidenceForBothAndTheFitStartsFromTheOftenSeen) {
  const bim::AGraph graph = bim::buildAGraph(facadeOfBays());
  MapDiagnostics map;
  map.walls.push_back(
      {0, Eigen::Vector3d::UnitY(), -0.1, {0.1, 0.1}, {12.4, 0.1}, 0.2, 2.6, 100, {}});
  const double turn = 3.0 * std::numbers::pi / 180.0;
  const Eigen::Vector2d direction(std::cos(turn), std::sin(turn));
  const Eigen::Vector2d centre(9.5, 0.1);
  const Eigen::Vector3d normal(-direction.y(), direction.x(), 0.0);
  map.walls.push_back({1,
                       normal,
                       -normal.head<2>().dot(centre),
                       centre - 3.0 * direction,
                       centre + 3.0 * direction,
                       0.2,
                       2.6,
                       4,
                       {}});
  walkAlong(map, 2.0, 1.0, 18.0, 1.0);
  const DeviationReport report = measureDeviations(graph, map, Eigen::Isometry3d::Identity());
  for (const char* bay : {"F1", "F2"}) {
    const WallDeviation& wall = deviationWallOf(report, bay);
    EXPECT_EQ(wall.status, WallStatus::kAsPlanned) << bay;
    EXPECT_GT(wall.observed_share, 0.95) << bay;
    ASSERT_TRUE(wall.offset_m && wall.angle_deg) << bay;
    EXPECT_NEAR(*wall.offset_m, 0.0, 1e-6) << bay;
    EXPECT_NEAR(*wall.angle_deg, 0.0, 1e-6) << bay;
  }
  EXPECT_EQ(deviationWallOf(report, "F2").evidence.size(), 2u);
}

// A plane 0.7 m outside the façade, seen once from a keyframe inside: the sight lines to it cross
// the façade's inner face, which the map saw 20 times (a plane fitted once from a scan skewed in a
// fast turn lies so, behind the face it was fitted to). It is no extra wall. Seen from 3
// keyframes it is believed (min_deviation_observations), and reported.
TEST(PlanDeviations, APlaneSeenOnceOnlyThroughAWallIsNoExtraWall) {
  const bim::AGraph graph = bim::buildAGraph(facadeOfBays());
  for (const int observations : {1, 3}) {
    MapDiagnostics map;
    map.walls.push_back(
        {0, Eigen::Vector3d::UnitY(), -0.1, {0.1, 0.1}, {18.9, 0.1}, 0.2, 2.6, 20, {}});
    map.walls.push_back(
        {1, Eigen::Vector3d::UnitY(), 0.8, {8.0, -0.8}, {10.0, -0.8}, 0.2, 2.6, observations, {7}});
    walkAlong(map, 2.0, 1.0, 18.0, 1.0);
    const DeviationReport report = measureDeviations(graph, map, Eigen::Isometry3d::Identity());
    EXPECT_EQ(report.extra_walls.size(), observations < 3 ? 0u : 1u) << observations;
  }
}

// A long room, 20 m × 4 m: the end wall X (x = 0) has only S and N around it (E is 20 m off), and
// they run across it: nothing around tells where the map lies along x there, so the placement's
// prior (5 cm) stands for it and X is judged against three times that. Built 8 cm off, X is not
// called shifted (its offset cannot be told from the map's own error there); built 20 cm off, it
// is, by 0.20 m.
TEST(PlanDeviations, AWallIsJudgedAgainstHowWellTheWallsAroundFixTheMapAcrossIt) {
  const bim::AGraph graph = graphOfWalls(R"([
    {"id": "S", "start": [0, 0], "end": [20, 0], "thickness": 0.2},
    {"id": "E", "start": [20, 0], "end": [20, 4], "thickness": 0.2},
    {"id": "N", "start": [20, 4], "end": [0, 4], "thickness": 0.2},
    {"id": "X", "start": [0, 4], "end": [0, 0], "thickness": 0.2}])");
  for (const double built_off : {0.08, 0.20}) {
    MapDiagnostics map = facesAndWalk(graph, 2.0, 1.0, 19.0, 0.5);
    for (auto& wall : map.walls) {
      if (std::abs(wall.start.x()) > 0.2 || std::abs(wall.end.x()) > 0.2) continue;  // X's faces
      wall.d -= wall.normal.x() * built_off;
      wall.start.x() += built_off;
      wall.end.x() += built_off;
    }
    const DeviationReport report = measureDeviations(graph, map, Eigen::Isometry3d::Identity());
    const WallDeviation& x = deviationWallOf(report, "X");
    EXPECT_NEAR(x.placement_sigma_m, 0.05, 0.005) << built_off;
    EXPECT_GE(x.shift_threshold_m, 0.15) << built_off;
    EXPECT_EQ(x.status, built_off < 0.1 ? WallStatus::kAsPlanned : WallStatus::kShifted)
        << built_off;
    ASSERT_TRUE(x.offset_m.has_value());
    EXPECT_NEAR(std::abs(*x.offset_m), built_off, 0.005) << built_off;
    // S, fixed across it by N (4 m off), keeps the fixed threshold.
    EXPECT_LT(deviationWallOf(report, "S").placement_sigma_m, 0.02) << built_off;
    EXPECT_DOUBLE_EQ(deviationWallOf(report, "S").shift_threshold_m, 0.06) << built_off;
  }
}

// A room with its north-west corner cut by a diagonal wall D. X (x = 0, y 0 → 5) has three walls
// around it (S, D, N: fewer than min_noise_walls, so the map's error there is not known), and
// only D, built 5.5 cm into the room (under the 6 cm threshold: as planned), says where the map
// lies along x. Placed on those three alone, X would be moved 7.6 cm (0.055 / sin 45°, less what
// the placement's 5 cm prior holds back) and reported shifted; the level's placement, on all five
// walls, finds it as planned, and a deviation the local placement alone finds is not believed.
TEST(PlanDeviations, WithTooFewWallsAroundADeviationMustHoldUnderTheLevelsPlacementToo) {
  const bim::AGraph graph = graphOfWalls(R"([
    {"id": "S", "start": [0, 0], "end": [14, 0], "thickness": 0.2},
    {"id": "E", "start": [14, 0], "end": [14, 9], "thickness": 0.2},
    {"id": "N", "start": [14, 9], "end": [4, 9], "thickness": 0.2},
    {"id": "D", "start": [4, 9], "end": [0, 5], "thickness": 0.2},
    {"id": "X", "start": [0, 5], "end": [0, 0], "thickness": 0.2}])");
  MapDiagnostics map = facesAndWalk(graph, 3.0, 1.0, 13.0, 0.5);
  const Eigen::Vector2d into_room = 0.055 * Eigen::Vector2d(1.0, -1.0).normalized();
  int moved = 0;
  for (auto& wall : map.walls) {
    const Eigen::Vector2d along = (wall.end - wall.start).normalized();
    if (std::abs(std::abs(along.x()) - std::sqrt(0.5)) > 1e-6) continue;  // on D
    wall.d -= wall.normal.head<2>().dot(into_room);
    wall.start += into_room;
    wall.end += into_room;
    ++moved;
  }
  ASSERT_GE(moved, 2);
  const DeviationReport report = measureDeviations(graph, map, Eigen::Isometry3d::Identity());
  const WallDeviation& x = deviationWallOf(report, "X");
  EXPECT_FALSE(x.local_offset_noise_m.has_value());
  EXPECT_EQ(x.status, WallStatus::kAsPlanned);
  ASSERT_TRUE(x.offset_m.has_value());
  EXPECT_LT(std::abs(*x.offset_m), 0.06);
  EXPECT_EQ(deviationWallOf(report, "D").status, WallStatus::kAsPlanned);
}

}  // namespace
}  // namespace isg::slam
