#include "worlds/parking_generator.hpp"

#include <gtest/gtest.h>

#include <Eigen/Core>
#include <cmath>
#include <set>
#include <string>

#include "bim/plan_parser.hpp"
#include "common/json_reader.hpp"

namespace isg::worlds {
namespace {

bim::Plan parsedParking(const GeneratedBuilding& b, common::Warnings& warnings) {
  const common::JsonSource source{b.name + ".json", &warnings};
  return bim::parsePlan(common::JsonNode(b.plan, "", source));
}

// Least distance from p to the segment a–b.
double toSegment(const Eigen::Vector2d& p, const Eigen::Vector2d& a, const Eigen::Vector2d& b) {
  const Eigen::Vector2d d = b - a;
  const double t = std::clamp((p - a).dot(d) / d.squaredNorm(), 0.0, 1.0);
  return (a + t * d - p).norm();
}

TEST(ParkingGenerator, AColumnGridRetainingWallsARampAndTwoCores) {
  int round_floors = 0, annexes = 0;
  for (std::uint64_t seed = 1; seed <= 10; ++seed) {
    GeneratorSpec spec;
    spec.family = "parking";
    spec.seed = seed;
    const GeneratedBuilding b = generateBuilding(spec);
    EXPECT_EQ(b.name, "parking-" + std::to_string(seed));
    common::Warnings warnings;
    const bim::Plan plan = parsedParking(b, warnings);
    EXPECT_TRUE(warnings.empty()) << seed << ": " << warnings.front().str();
    ASSERT_EQ(plan.levels.size(), 1u);
    const bim::Level& level = plan.levels.front();
    EXPECT_TRUE(level.rooms.empty());  // an open floor
    // The grid: every column on a lattice of one spacing each way, 7.5–8.5 m, all alike.
    double x0 = 1e9, y0 = 1e9, x1 = -1e9, y1 = -1e9;
    for (const auto& c : level.columns) {
      x0 = std::min(x0, c.center.x()), x1 = std::max(x1, c.center.x());
      y0 = std::min(y0, c.center.y()), y1 = std::max(y1, c.center.y());
    }
    std::set<double> xs, ys;
    bool round = false;
    for (const auto& c : level.columns) {
      xs.insert(c.center.x()), ys.insert(c.center.y());
      EXPECT_EQ(c.size, level.columns.front().size) << c.id;
      EXPECT_GE(c.size.x(), 0.5);
      EXPECT_LE(c.size.x(), 0.7);
      round = round || c.round();
    }
    round_floors += round;
    const double bay_x = (x1 - x0) / double(xs.size() - 1),
                 bay_y = (y1 - y0) / double(ys.size() - 1);
    EXPECT_GE(bay_x, 7.5 - 1e-3) << seed;
    EXPECT_LE(bay_x, 8.5 + 1e-3) << seed;
    EXPECT_GE(bay_y, 7.5 - 1e-3) << seed;
    EXPECT_LE(bay_y, 8.5 + 1e-3) << seed;
    for (const auto& c : level.columns) {
      const double i = (c.center.x() - x0) / bay_x, j = (c.center.y() - y0) / bay_y;
      EXPECT_NEAR(i, std::round(i), 0.01) << c.id;
      EXPECT_NEAR(j, std::round(j), 0.01) << c.id;
    }
    EXPECT_GE(xs.size(), 7u);  // 6–9 bays
    EXPECT_GE(ys.size(), 5u);  // 4–6 bays
    // Walls: the perimeter on the slab's edges, two ramp walls from one edge inward, cores.
    int perimeter = 0, ramp = 0, core = 0;
    for (const auto& w : level.walls) {
      if (w.name == "perimeter") {
        ++perimeter;
        const bool on_edge =
            (std::abs(w.start.x() - w.end.x()) < 1e-9 &&
             (std::abs(w.start.x() - x0) < 1e-6 || std::abs(w.start.x() - x1) < 1e-6)) ||
            (std::abs(w.start.y() - w.end.y()) < 1e-9 &&
             (std::abs(w.start.y() - y0) < 1e-6 || std::abs(w.start.y() - y1) < 1e-6));
        EXPECT_TRUE(on_edge) << w.id;
      }
      ramp += w.name == "ramp";
      core += w.name == "core";
    }
    EXPECT_EQ(ramp, 2) << seed;
    EXPECT_GE(core, 10) << seed;  // two cores of 3 walls, a doorway wall in two, a cross wall
    EXPECT_GE(perimeter, 2 * (int(xs.size()) - 1 + int(ys.size()) - 1)) << seed;
    // As built: only perimeter walls go unbuilt; vehicles and pallets stand clear of every
    // column by more than the robot's width.
    std::set<std::string> perimeter_ids;
    for (const auto& w : level.walls) {
      if (w.name == "perimeter") perimeter_ids.insert(w.id);
    }
    ASSERT_FALSE(b.as_built.missing_walls.empty()) << seed;
    for (const auto& id : b.as_built.missing_walls) EXPECT_TRUE(perimeter_ids.count(id)) << id;
    int vehicles = 0;
    for (const auto& thing : b.as_built.clutter) {
      vehicles += thing.size.x() > 4.0;
      for (const auto& c : level.columns) {
        EXPECT_GT((thing.center.head<2>() - c.center).norm(), 0.5 * thing.size.y() + 1.2)
            << seed << " " << c.id;
      }
      for (const auto& w : level.walls) {
        EXPECT_GT(toSegment(thing.center.head<2>(), w.start, w.end), 0.5 * thing.size.y() + 1.2)
            << seed << " " << w.id;
      }
    }
    EXPECT_GE(vehicles, 4) << seed;
    // A bay built beyond the perimeter, the plan not showing it: three walls outside the slab,
    // behind a perimeter wall not built.
    if (!b.as_built.extra_walls.empty()) {
      ++annexes;
      ASSERT_EQ(b.as_built.extra_walls.size(), 3u) << seed;
      const Eigen::Vector2d far = b.as_built.extra_walls[1].start;
      const bool outside =
          far.x() < x0 - 1.0 || far.x() > x1 + 1.0 || far.y() < y0 - 1.0 || far.y() > y1 + 1.0;
      EXPECT_TRUE(outside) << seed << " " << far.transpose();
    }
    EXPECT_EQ(b.scenario["robot"]["route"], "tour");
    EXPECT_FALSE(b.scenario["robot"].contains("carrier"));  // legged, the default
  }
  EXPECT_GE(round_floors, 2);  // about half
  EXPECT_LE(round_floors, 8);
  EXPECT_GE(annexes, 4);  // 7 in 10
  EXPECT_LE(annexes, 10);
}

TEST(ParkingGenerator, TheSameSeedGivesTheSameCarParkCarriedAsAsked) {
  GeneratorSpec spec;
  spec.family = "parking";
  spec.seed = 3;
  const GeneratedBuilding a = generateBuilding(spec), again = generateBuilding(spec);
  EXPECT_EQ(a.plan.dump(), again.plan.dump());
  EXPECT_EQ(a.scenario.dump(), again.scenario.dump());
  spec.carrier = "handheld";
  const GeneratedBuilding by_hand = generateBuilding(spec);
  EXPECT_EQ(by_hand.plan.dump(), a.plan.dump());
  EXPECT_EQ(by_hand.scenario["robot"]["carrier"], "handheld");
  EXPECT_EQ(by_hand.scenario["as_built"], a.scenario["as_built"]);
  // Columns as built come from a stream of their own: the rest is the same bytes.
  spec.carrier = "legged";
  spec.missing_columns = 0.2;
  const GeneratedBuilding fewer = generateBuilding(spec);
  EXPECT_EQ(fewer.plan.dump(), a.plan.dump());
  EXPECT_FALSE(fewer.as_built.missing_columns.empty());
  EXPECT_EQ(fewer.as_built.clutter.size(), a.as_built.clutter.size());
  spec.carrier = "walking";
  EXPECT_THROW(generateBuilding(spec), std::invalid_argument);
}

}  // namespace
}  // namespace isg::worlds
