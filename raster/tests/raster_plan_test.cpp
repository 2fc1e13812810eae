#include "raster/raster_plan.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "bim/plan_geometry.hpp"
#include "bim/plan_parser.hpp"
#include "bim/plan_transform.hpp"
#include "bim/synthetic_plan.hpp"
#include "common/json_reader.hpp"
#include "raster/tests/raster_drawing.hpp"

namespace isg::raster {
namespace {

using bim::GridPlanSpec;
using bim::Level;
using bim::LevelGeometry;
using bim::loadPlan;
using bim::parsePlan;
using bim::Plan;
using bim::planarMotion;
using bim::Wall;

constexpr double kPi = 3.14159265358979323846;

std::string planPath(const std::string& name) {
  std::string path = ISG_SOURCE_DIR;  // appended piece by piece: GCC 12 warns falsely on a + b + c
  path += "/worlds/plans/";
  path += name;
  path += ".json";
  return path;
}

// How well the imported walls give back the drawn ones: every 5 cm along each drawn wall's solid
// axis (away from its ends by its own thickness, outside its doors), is there an imported wall
// within `distance` of the point, turned at most `angle` from it, whose extent covers it and whose
// thickness is within `distance`? And every imported wall's middle: on a drawn wall, likewise?
struct RoundTrip {
  int samples = 0, covered = 0;
  int imported = 0, on_a_drawn_wall = 0;
  double worst_offset = 0.0, worst_angle = 0.0, worst_thickness = 0.0;
};

double angleBetween(const Eigen::Vector2d& a, const Eigen::Vector2d& b) {
  return std::acos(std::min(1.0, std::abs(a.normalized().dot(b.normalized())))) * 180.0 / kPi;
}

RoundTrip compare(const Level& drawn, const Level& imported, double distance, double angle) {
  RoundTrip out;
  const LevelGeometry geometry = computeLevelGeometry(drawn);
  const auto matches = [&](const Wall& a, const Eigen::Vector2d& p, const Eigen::Vector2d& axis,
                           double thickness, RoundTrip* worst) {
    const Eigen::Vector2d d = (a.end - a.start).normalized();
    const Eigen::Vector2d n(-d.y(), d.x());
    const double along = (p - a.start).dot(d), length = (a.end - a.start).norm();
    const double offset = std::abs((p - a.start).dot(n));
    const double turn = angleBetween(d, axis);
    if (along < -distance || along > length + distance || turn > angle || offset > distance ||
        std::abs(a.thickness - thickness) > distance)
      return false;
    if (worst) {
      worst->worst_offset = std::max(worst->worst_offset, offset);
      worst->worst_angle = std::max(worst->worst_angle, turn);
      worst->worst_thickness = std::max(worst->worst_thickness, std::abs(a.thickness - thickness));
    }
    return true;
  };
  for (const auto& wall : geometry.walls) {
    const double length = wall.length, t = wall.wall->thickness;
    for (double s = t; s <= length - t; s += 0.05) {
      bool in_door = false;
      for (const auto& door : drawn.doors) {
        if (door.wall == wall.wall->id && std::abs(s - door.offset) < 0.5 * door.width + t) {
          in_door = true;
        }
      }
      if (in_door) continue;
      ++out.samples;
      const Eigen::Vector2d p = wall.pointAt(s);
      for (const auto& candidate : imported.walls) {
        if (matches(candidate, p, wall.axis, t, &out)) {
          ++out.covered;
          break;
        }
      }
    }
  }
  for (const auto& wall : imported.walls) {
    ++out.imported;
    const Eigen::Vector2d middle = 0.5 * (wall.start + wall.end);
    for (const auto& candidate : drawn.walls) {
      if (matches(candidate, middle, wall.end - wall.start, wall.thickness, nullptr)) {
        ++out.on_a_drawn_wall;
        break;
      }
    }
  }
  return out;
}

RasterPlanImport importDrawn(const Level& level, double resolution) {
  Eigen::Vector2d origin;
  const OccupancyImage image = testing::drawLevel(level, resolution, 0.5, &origin);
  RasterPlanOptions options;
  options.resolution = resolution;
  options.origin = origin;
  options.height = level.height;
  return rasterPlanFromImage(image, "drawn.png", options);
}

TEST(RasterPlan, APlanDrawnAtACentimetreImportsBackItsWalls) {
  for (const char* name : {"d1", "d2", "d3", "d4", "d5", "d6"}) {
    SCOPED_TRACE(name);
    const Plan plan = loadPlan(planPath(name));
    const Level& level = plan.levels.front();
    const RasterPlanImport result = importDrawn(level, 0.01);
    const Level& imported = result.plan.levels.front();
    const RoundTrip trip = compare(level, imported, 0.02, 1.0);
    std::printf(
        "%s: %d/%d samples covered, %d/%d imported on a drawn wall; worst %.4f m %.3f° "
        "thickness %.4f; %zu walls, %zu doors (drawn %zu walls %zu doors), %zu rooms "
        "(drawn %zu)\n",
        name, trip.covered, trip.samples, trip.on_a_drawn_wall, trip.imported, trip.worst_offset,
        trip.worst_angle, trip.worst_thickness, imported.walls.size(), imported.doors.size(),
        level.walls.size(), level.doors.size(), imported.rooms.size(), level.rooms.size());
    for (const auto& line : result.log) std::printf("  %s\n", line.c_str());
    EXPECT_EQ(trip.covered, trip.samples);
    EXPECT_EQ(trip.on_a_drawn_wall, trip.imported);
    EXPECT_EQ(imported.walls.size(), level.walls.size());
    EXPECT_EQ(imported.doors.size(), level.doors.size());
    EXPECT_EQ(imported.rooms.size(), level.rooms.size());
    EXPECT_LE(trip.worst_offset, 0.02);
    EXPECT_LE(trip.worst_angle, 1.0);
    EXPECT_TRUE(result.log.empty());
  }
}

TEST(RasterPlan, AFloorOfTwoHundredRoomsImportsBackItsWallsAndDoors) {
  GridPlanSpec spec;
  spec.rows = 10;
  spec.cols = 20;
  const common::JsonSource source{"grid.json", nullptr};
  const Plan plan = parsePlan(common::JsonNode(makeGridPlan(spec), "", source));
  const Level& level = plan.levels.front();
  const RasterPlanImport result = importDrawn(level, 0.01);
  const Level& imported = result.plan.levels.front();
  const RoundTrip trip = compare(level, imported, 0.02, 1.0);
  EXPECT_EQ(trip.covered, trip.samples);
  EXPECT_EQ(trip.on_a_drawn_wall, trip.imported);
  EXPECT_EQ(imported.doors.size(), level.doors.size());
  EXPECT_EQ(imported.rooms.size(), 200u);
  std::printf("200 rooms: %zu walls (drawn %zu), %zu doors (drawn %zu), worst %.4f m %.3f°\n",
              imported.walls.size(), level.walls.size(), imported.doors.size(), level.doors.size(),
              trip.worst_offset, trip.worst_angle);
}

// Turned off the image's axes, walls come back as well, but for short pieces where thinning
// bends around a corner or a jamb (under 0.5 m, counted apart) and now and then a doorway beside
// a corner (the wall's stub beyond it too short to be a wall by its own line): measured, at least
// 99.5 % of each plan's wall length and 90 % of its doorways over the angles.
TEST(RasterPlan, APlanTurnedToAnyAngleImportsBackItsWalls) {
  int doors = 0, doors_drawn = 0;
  for (const char* name : {"d1", "d3", "d6"}) {
    for (double degrees : {17.0, 33.0, 45.0, 71.5}) {
      SCOPED_TRACE(std::string(name) + " turned " + std::to_string(degrees));
      const Plan plan = transformedPlan(
          loadPlan(planPath(name)), planarMotion(Eigen::Vector2d(3.0, -2.0), degrees * kPi / 180));
      const Level& level = plan.levels.front();
      const RasterPlanImport result = importDrawn(level, 0.01);
      const Level& imported = result.plan.levels.front();
      const RoundTrip trip = compare(level, imported, 0.02, 1.0);
      std::printf("%s turned %.1f°: %d of %d samples, worst %.4f m, %.3f°\n", name, degrees,
                  trip.covered, trip.samples, trip.worst_offset, trip.worst_angle);
      EXPECT_GE(trip.covered, 0.995 * trip.samples);
      int long_walls = 0, long_on_drawn = 0;
      for (const auto& wall : imported.walls) {
        if ((wall.end - wall.start).norm() < 0.5) continue;
        ++long_walls;
        Level one = imported;
        one.walls = {wall};
        long_on_drawn += compare(level, one, 0.02, 1.0).on_a_drawn_wall;
      }
      EXPECT_EQ(long_on_drawn, long_walls);
      EXPECT_LE(trip.worst_offset, 0.02);
      EXPECT_LE(trip.worst_angle, 1.0);
      doors += int(imported.doors.size());
      doors_drawn += int(level.doors.size());
    }
  }
  std::printf("doorways back: %d of %d\n", doors, doors_drawn);
  EXPECT_GE(doors, 0.9 * doors_drawn);
  EXPECT_LE(doors, doors_drawn);
}

}  // namespace
}  // namespace isg::raster

namespace isg::raster {
namespace {

// An image of `width` × `height` pixels at 1 cm, light, with the pixels inside `dark` occupied.
template <class Inside>
OccupancyImage imageOf(int width, int height, Inside dark) {
  OccupancyImage image;
  image.width = width, image.height = height;
  image.pixels.assign(std::size_t(width) * height, PixelClass::kFree);
  for (int row = 0; row < height; ++row) {
    for (int c = 0; c < width; ++c) {
      // The pixel's centre in metres, y up from the bottom edge.
      const Eigen::Vector2d p(0.01 * (c + 0.5), 0.01 * (height - row - 0.5));
      if (dark(p)) image.pixels[std::size_t(row) * width + c] = PixelClass::kOccupied;
    }
  }
  return image;
}

TEST(RasterWalls, CompactBlobsAreColumnsSquareOrRound) {
  // A wall 4 m long, a 0.4 m square pillar turned 20°, a round one 0.5 m across, a speck.
  const Eigen::Rotation2Dd turn(20.0 * kPi / 180.0);
  const OccupancyImage image = imageOf(600, 400, [&](const Eigen::Vector2d& p) {
    const bool wall = p.x() >= 1.0 && p.x() <= 5.0 && std::abs(p.y() - 3.5) <= 0.1;
    const Eigen::Vector2d q = turn.inverse() * (p - Eigen::Vector2d(2.0, 1.5));
    const bool square = std::abs(q.x()) <= 0.2 && std::abs(q.y()) <= 0.2;
    const bool round = (p - Eigen::Vector2d(4.0, 1.5)).norm() <= 0.25;
    const bool speck = (p - Eigen::Vector2d(5.5, 0.5)).norm() <= 0.02;
    return wall || square || round || speck;
  });
  RasterWallOptions options;
  const RasterWalls traced = traceRasterWalls(image, options);
  ASSERT_EQ(traced.walls.size(), 3u);
  EXPECT_EQ(traced.specks, 1);
  int columns = 0;
  for (const auto& wall : traced.walls) {
    const Eigen::Vector2d middle = 0.5 * (wall.start + wall.end);
    const double length = (wall.end - wall.start).norm();
    if (wall.kind == RasterWall::Kind::kWall) {
      EXPECT_NEAR(middle.x(), 3.0, 0.01);
      EXPECT_NEAR(middle.y(), 3.5, 0.01);
      EXPECT_NEAR(length, 4.0, 0.02);
      EXPECT_NEAR(wall.thickness, 0.2, 0.01);
    } else if (wall.kind == RasterWall::Kind::kColumn) {
      ++columns;
      EXPECT_NEAR(middle.x(), 2.0, 0.01);
      EXPECT_NEAR(middle.y(), 1.5, 0.01);
      EXPECT_NEAR(length, 0.4, 0.02);
      EXPECT_NEAR(wall.thickness, 0.4, 0.02);
      // Its sides along the pillar's: 20° (or 110°) off the image's axes.
      const double angle = std::atan2(wall.end.y() - wall.start.y(), wall.end.x() - wall.start.x());
      const double off = std::remainder(angle - 20.0 * kPi / 180.0, kPi / 2);
      EXPECT_NEAR(off, 0.0, 2.0 * kPi / 180.0);
    } else {
      ++columns;
      EXPECT_NEAR(middle.x(), 4.0, 0.01);
      EXPECT_NEAR(middle.y(), 1.5, 0.01);
      EXPECT_NEAR(wall.thickness, 0.5, 0.02);
    }
  }
  EXPECT_EQ(columns, 2);
}

TEST(RasterWalls, APillarSeenAsItsOutlineIsARoundColumn) {
  // A ring 0.4 m across, 3 cm thick (a LiDAR map's pillar: its inside never seen), beside a wall.
  const OccupancyImage image = imageOf(300, 300, [&](const Eigen::Vector2d& p) {
    const double r = (p - Eigen::Vector2d(1.5, 1.0)).norm();
    const bool ring = r <= 0.2 && r >= 0.17;
    const bool wall = p.x() >= 0.2 && p.x() <= 2.8 && std::abs(p.y() - 2.5) <= 0.05;
    return ring || wall;
  });
  const RasterWalls traced = traceRasterWalls(image, RasterWallOptions{});
  ASSERT_EQ(traced.walls.size(), 2u);
  int round = 0;
  for (const auto& wall : traced.walls) {
    if (wall.kind != RasterWall::Kind::kRoundColumn) continue;
    ++round;
    EXPECT_NEAR(0.5 * (wall.start + wall.end).x(), 1.5, 0.01);
    EXPECT_NEAR(0.5 * (wall.start + wall.end).y(), 1.0, 0.01);
    EXPECT_NEAR(wall.thickness, 0.4, 0.02);
  }
  EXPECT_EQ(round, 1);
  EXPECT_EQ(traced.symbols, 0);
}

TEST(RasterPlan, ADoorwayThatJoinsNoRoomsIsAGapBetweenWallParts) {
  // A 4 × 3 m room (walls 0.2 m thick) with a 0.9 m doorway to the outside in its south wall, and
  // a free-standing wall from x 5 to 9 at y 5 with a 1 m gap from 6.5 to 7.5: outside both sides.
  const OccupancyImage image = imageOf(1000, 700, [&](const Eigen::Vector2d& p) {
    const bool band_x = p.x() >= 0.9 && p.x() <= 5.1, band_y = p.y() >= 0.9 && p.y() <= 4.1;
    const bool room = band_x && band_y &&
                      (p.x() <= 1.1 || p.x() >= 4.9 || p.y() <= 1.1 || p.y() >= 3.9) &&
                      !(p.y() <= 1.1 && p.x() >= 2.55 && p.x() <= 3.45);
    const bool free_wall = std::abs(p.y() - 5.5) <= 0.1 && p.x() >= 6.0 && p.x() <= 9.5 &&
                           !(p.x() >= 7.0 && p.x() <= 8.0);
    return room || free_wall;
  });
  RasterPlanOptions options;
  options.resolution = 0.01;
  const RasterPlanImport imported = rasterPlanFromImage(image, "gaps.png", options);
  const Level& level = imported.plan.levels.at(0);
  ASSERT_EQ(level.rooms.size(), 1u);
  ASSERT_EQ(level.doors.size(), 1u);  // the room's, to the outside
  EXPECT_NE(level.doors[0].rooms[0], level.doors[0].rooms[1]);
  int free_parts = 0;
  for (const auto& wall : level.walls) {
    if (std::abs(wall.start.y() - 5.5) > 0.02) continue;
    ++free_parts;
    const double lo = std::min(wall.start.x(), wall.end.x()),
                 hi = std::max(wall.start.x(), wall.end.x());
    EXPECT_TRUE(hi <= 7.0 + 0.02 || lo >= 8.0 - 0.02) << lo << " … " << hi;
  }
  EXPECT_EQ(free_parts, 2);
  EXPECT_EQ(imported.doors, 1);
  EXPECT_EQ(imported.doorway_gaps, 1);
  // The plan as written reads back without a warning.
  common::Warnings warnings;
  const nlohmann::json document = nlohmann::json::parse(imported.plan_json.dump());
  const common::JsonSource source{"gaps.json", &warnings};
  bim::parsePlan(common::JsonNode(document, "", source));
  EXPECT_TRUE(warnings.empty()) << warnings.front().str();
}

TEST(RasterWalls, TextAndCurvesAreSaidNotTurnedIntoWalls) {
  // A straight wall with the letter "S" (strokes 2 cm) beside it, and a quarter circle of wall
  // (radius 2 m, 0.2 m thick) joined to nothing.
  const OccupancyImage image = imageOf(800, 600, [&](const Eigen::Vector2d& p) {
    const bool wall = p.x() >= 0.5 && p.x() <= 3.5 && std::abs(p.y() - 5.0) <= 0.1;
    const Eigen::Vector2d letter = p - Eigen::Vector2d(2.0, 4.0);
    const bool s_shape = std::abs(letter.x()) <= 0.15 && std::abs(letter.y()) <= 0.2 &&
                         (std::abs(letter.y() - 0.19) <= 0.01 || std::abs(letter.y()) <= 0.01 ||
                          std::abs(letter.y() + 0.19) <= 0.01 ||
                          (letter.y() > 0 && std::abs(letter.x() + 0.14) <= 0.01) ||
                          (letter.y() < 0 && std::abs(letter.x() - 0.14) <= 0.01));
    const Eigen::Vector2d arc = p - Eigen::Vector2d(5.0, 0.5);
    const bool curve = arc.x() >= 0 && arc.y() >= 0 && std::abs(arc.norm() - 2.0) <= 0.1;
    return wall || s_shape || curve;
  });
  RasterWallOptions options;
  const RasterWalls traced = traceRasterWalls(image, options);
  EXPECT_EQ(traced.symbols, 1);
  bool letter_said = false, curve_said = false;
  for (const auto& line : traced.left_out) {
    if (line.find("neither a wall nor a column") != std::string::npos) letter_said = true;
    if (line.find("a curved wall around (6.") != std::string::npos) curve_said = true;
  }
  EXPECT_TRUE(letter_said);
  // The arc is cut into straight runs within the skeleton's tolerance, and that is said.
  EXPECT_TRUE(curve_said);
  int straight = 0;
  for (const auto& wall : traced.walls) {
    if (std::abs(0.5 * (wall.start + wall.end).y() - 5.0) < 0.02) ++straight;
  }
  EXPECT_EQ(straight, 1);
  EXPECT_GE(traced.walls.size(), 4u);
}

}  // namespace
}  // namespace isg::raster
