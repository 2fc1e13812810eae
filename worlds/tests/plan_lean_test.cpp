// Non-Manhattan generated buildings (worlds/plan_lean.hpp): a building sheared 30° and turned 20°
// is the plain building mapped point by point; what is measured along a wall stays on the same
// stretch of wall; faces stay on the room outlines; clutter stays out of the walls; the files
// read without warning; shear and turn 0 change nothing.
#include "worlds/plan_lean.hpp"

#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <numbers>

#include "bim/scenario.hpp"
#include "worlds/plan_generator.hpp"
#include "worlds/segment_distance.hpp"

namespace isg::worlds {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;

constexpr double kShearDeg = 30.0, kTurnDeg = 20.0;

Eigen::Matrix2d leanMatrix() {
  Eigen::Matrix2d shear;
  shear << 1.0, std::tan(kShearDeg * std::numbers::pi / 180.0), 0.0, 1.0;
  return Eigen::Rotation2Dd(kTurnDeg * std::numbers::pi / 180.0).toRotationMatrix() * shear;
}

Eigen::Vector2d vec(const json& p) { return {p[0].get<double>(), p[1].get<double>()}; }

const json& wallOf(const json& plan, const std::string& id) {
  for (const json& wall : plan["levels"][0]["walls"]) {
    if (wall["id"] == id) return wall;
  }
  throw std::runtime_error("no wall " + id);
}

double lengthOf(const json& wall) { return (vec(wall["end"]) - vec(wall["start"])).norm(); }

GeneratorSpec specOf(const std::string& family) {
  GeneratorSpec spec;
  spec.family = family;
  spec.seed = 1;
  spec.shifted_walls = 0.3;
  spec.rotated_walls = 0.3;
  spec.rotation_about = "any";
  spec.shortened_walls = 0.5;
  spec.extra_walls = 0.5;
  spec.clutter_per_room = 2.0;
  return spec;
}

TEST(PlanLean, ALeanedBuildingIsThePlainOneMappedWithEveryChangeOnItsWall) {
  const Eigen::Matrix2d A = leanMatrix();
  int doors = 0, cuts = 0, turns = 0, boxes = 0;
  for (const std::string family : {"office", "l-shape", "hall"}) {
    GeneratorSpec spec = specOf(family);
    const GeneratedBuilding plain = generateBuilding(spec);
    spec.shear_deg = kShearDeg;
    spec.turn_deg = kTurnDeg;
    const GeneratedBuilding leaned = generateBuilding(spec);
    const json& walls = leaned.plan["levels"][0]["walls"];
    ASSERT_EQ(walls.size(), plain.plan["levels"][0]["walls"].size()) << family;
    for (const json& wall : walls) {
      const json& before = wallOf(plain.plan, wall["id"]);
      for (const char* end : {"start", "end"}) {
        EXPECT_LT((vec(wall[end]) - A * vec(before[end])).norm(), 1e-3) << family << " " << wall;
      }
      // A shear keeps areas, so length × thickness stays (to the rounding of each).
      EXPECT_NEAR(lengthOf(wall) * wall["thickness"].get<double>(),
                  lengthOf(before) * before["thickness"].get<double>(), 2e-3)
          << family << " " << wall;
    }
    // Walls that ran along y now meet those along x at 60°, not 90°.
    const Eigen::Vector2d x_axis = A * Eigen::Vector2d::UnitX(),
                          y_axis = A * Eigen::Vector2d::UnitY();
    EXPECT_NEAR(std::acos(x_axis.normalized().dot(y_axis.normalized())) * 180.0 / std::numbers::pi,
                60.0, 1e-9);
    // A door, a turn's pivot and the parts of a wall built in part keep their share of the wall.
    const json& plain_doors = plain.plan["levels"][0]["doors"];
    const json& leaned_doors = leaned.plan["levels"][0]["doors"];
    ASSERT_EQ(leaned_doors.size(), plain_doors.size());
    for (std::size_t d = 0; d < leaned_doors.size(); ++d) {
      const std::string wall = leaned_doors[d]["wall"];
      EXPECT_NEAR(leaned_doors[d]["offset"].get<double>() / lengthOf(wallOf(leaned.plan, wall)),
                  plain_doors[d]["offset"].get<double>() / lengthOf(wallOf(plain.plan, wall)), 1e-3)
          << family << " " << leaned_doors[d];
      ++doors;
    }
    const json& built = leaned.scenario["as_built"];
    const json& plain_built = plain.scenario["as_built"];
    EXPECT_EQ(built["wall_shifts"], plain_built["wall_shifts"]) << family;
    for (std::size_t k = 0; k < built.value("shortened_walls", json::array()).size(); ++k) {
      const std::string wall = built["shortened_walls"][k]["wall"];
      const double ratio = lengthOf(wallOf(leaned.plan, wall)) / lengthOf(wallOf(plain.plan, wall));
      const json& parts = built["shortened_walls"][k]["built"];
      const json& plain_parts = plain_built["shortened_walls"][k]["built"];
      for (std::size_t p = 0; p < parts.size(); ++p) {
        for (int e : {0, 1}) {
          EXPECT_NEAR(parts[p][e].get<double>(), plain_parts[p][e].get<double>() * ratio, 2e-3)
              << family << " " << wall;
        }
      }
      ++cuts;
    }
    for (std::size_t k = 0; k < built.value("wall_rotations", json::array()).size(); ++k) {
      const json& turn = built["wall_rotations"][k];
      const std::string wall = turn["wall"];
      const double ratio = lengthOf(wallOf(leaned.plan, wall)) / lengthOf(wallOf(plain.plan, wall));
      EXPECT_EQ(turn["angle_deg"], plain_built["wall_rotations"][k]["angle_deg"]);
      EXPECT_NEAR(turn["about"].get<double>(),
                  plain_built["wall_rotations"][k]["about"].get<double>() * ratio, 2e-3);
      ++turns;
    }
    // Every box kept stands clear of every wall's faces.
    for (const json& box : built.value("clutter", json::array())) {
      const Eigen::Vector2d centre(box["center"][0].get<double>(), box["center"][1].get<double>());
      const Eigen::Rotation2Dd yaw(box["yaw"].get<double>());
      const double hx = 0.5 * box["size"][0].get<double>(), hy = 0.5 * box["size"][1].get<double>();
      const Eigen::Vector2d corners[4] = {
          centre + yaw * Eigen::Vector2d(-hx, -hy), centre + yaw * Eigen::Vector2d(hx, -hy),
          centre + yaw * Eigen::Vector2d(hx, hy), centre + yaw * Eigen::Vector2d(-hx, hy)};
      for (const json& wall : walls) {
        for (int c = 0; c < 4; ++c) {
          const double distance = segmentDistance(corners[c], corners[(c + 1) % 4],
                                                  vec(wall["start"]), vec(wall["end"]));
          EXPECT_GE(distance, 0.5 * wall["thickness"].get<double>() + 0.05 - 1e-9)
              << family << " " << box << " " << wall;
        }
      }
      ++boxes;
    }
    // The files read as isg check reads them, without a warning.
    const fs::path dir = fs::path(::testing::TempDir()) / ("plan_lean_" + leaned.name);
    fs::create_directories(dir);
    std::ofstream(dir / (leaned.name + ".json")) << leaned.plan.dump(2);
    std::ofstream(dir / (leaned.name + ".asbuilt.json")) << leaned.scenario.dump(2);
    common::Warnings warnings;
    const bim::Scenario scenario =
        bim::loadScenario((dir / (leaned.name + ".asbuilt.json")).string(), &warnings);
    EXPECT_TRUE(warnings.empty()) << family << ": " << warnings.front().str();
    EXPECT_NE(scenario.plan.name.find("sheared 30°, turned 20°"), std::string::npos);
  }
  EXPECT_GT(doors, 20);
  EXPECT_GT(cuts, 3);
  EXPECT_GT(turns, 3);
  EXPECT_GT(boxes, 10);
}

TEST(PlanLean, NoShearAndNoTurnChangeNothing) {
  const GeneratedBuilding plain = generateBuilding(specOf("office"));
  GeneratedBuilding same = plain;
  leanBuilding(same.plan, same.as_built, 0.0, 0.0);
  EXPECT_EQ(same.plan.dump(), plain.plan.dump());
  EXPECT_EQ(generatedAsBuiltJson(same.as_built).dump(), plain.scenario["as_built"].dump());
}

TEST(PlanLean, AShearBeyondFortyDegreesIsRefused) {
  GeneratorSpec spec = specOf("office");
  spec.shear_deg = 45.0;
  try {
    generateBuilding(spec);
    FAIL();
  } catch (const std::invalid_argument& e) {
    EXPECT_STREQ(e.what(), "shear: must be in [-40, 40] degrees");
  }
}

}  // namespace
}  // namespace isg::worlds
