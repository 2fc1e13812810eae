#include "worlds/plan_generator.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <map>
#include <queue>
#include <set>

#include "bim/polygon.hpp"
#include "bim/scenario.hpp"

namespace isg::worlds {
namespace {

namespace fs = std::filesystem;

// Writes the building's two files to a fresh folder and reads its scenario as isg check does.
// The folder is the test's own: several tests generate the same building, and CTest runs them
// in parallel.
bim::Scenario load(const GeneratedBuilding& b, common::Warnings* warnings) {
  const testing::TestInfo* test = testing::UnitTest::GetInstance()->current_test_info();
  const fs::path dir =
      fs::path(testing::TempDir()) / ("generator_" + std::string(test->name()) + "_" + b.name);
  fs::create_directories(dir);
  std::ofstream(dir / (b.name + ".json")) << b.plan.dump(2);
  std::ofstream(dir / (b.name + ".asbuilt.json")) << b.scenario.dump(2);
  return bim::loadScenario((dir / (b.name + ".asbuilt.json")).string(), warnings);
}

// Rooms reached from the first through the doors, leaving out `closed`.
std::set<std::string> reachable(const bim::Level& level, const std::vector<std::string>& closed) {
  std::map<std::string, std::vector<std::string>> next;
  for (const auto& d : level.doors) {
    if (std::find(closed.begin(), closed.end(), d.id) != closed.end()) continue;
    next[d.rooms[0]].push_back(d.rooms[1]);
    next[d.rooms[1]].push_back(d.rooms[0]);
  }
  std::set<std::string> seen = {level.rooms.front().id};
  std::queue<std::string> open;
  open.push(level.rooms.front().id);
  while (!open.empty()) {
    for (const auto& r : next[open.front()]) {
      if (seen.insert(r).second) open.push(r);
    }
    open.pop();
  }
  return seen;
}

TEST(PlanGenerator, EveryFamilyReadsWithoutWarningAndEveryRoomIsReachable) {
  std::size_t closed = 0, missing = 0, extra = 0, clutter = 0;
  for (const auto& family : generatorFamilies()) {
    // A site and a car park have no rooms to reach (worlds/tests/site_generator_test.cpp,
    // parking_generator_test.cpp).
    if (family == "site" || family == "parking") continue;
    for (std::uint64_t seed : {1, 2}) {
      GeneratorSpec spec;
      spec.family = family;
      spec.seed = seed;
      spec.closed_doors = 0.5;
      spec.missing_walls = 0.3;
      spec.extra_walls = 0.3;
      const GeneratedBuilding b = generateBuilding(spec);
      common::Warnings warnings;
      const bim::Scenario s = load(b, &warnings);
      EXPECT_TRUE(warnings.empty()) << b.name << ": " << warnings.front().str();
      const bim::Level& level = s.plan.levels.at(0);
      EXPECT_EQ(int(level.rooms.size()), b.offices + b.corridors) << b.name;
      // Every door joins two rooms (none opens to the outside), and with the closed doors shut
      // every room is still reached.
      for (const auto& d : level.doors) {
        EXPECT_NE(d.rooms[0], bim::kOutside) << b.name << " " << d.id;
        EXPECT_NE(d.rooms[1], bim::kOutside) << b.name << " " << d.id;
      }
      EXPECT_EQ(reachable(level, s.as_built.closed_doors).size(), level.rooms.size()) << b.name;
      closed += s.as_built.closed_doors.size();
      missing += s.as_built.missing_walls.size();
      extra += s.as_built.extra_walls.size();
      clutter += s.as_built.clutter.size();
    }
  }
  // The densities asked for were applied somewhere.
  EXPECT_GT(closed, 5u);
  EXPECT_GT(missing, 5u);
  EXPECT_GT(extra, 5u);
  EXPECT_GT(clutter, 50u);
}

// Walls built in part and turns about any point: every office family reads them without warning;
// each shortened wall is a door-less inner wall of 2.5 m or more, cut 0.8 m to half its length,
// each part at least 0.5 m; each turn's point lies on its wall. Neither changes the plan or any
// other as-built draw.
TEST(PlanGenerator, WallsBuiltInPartAndTurnsAboutAnyPointAreDrawnWithinTheirBounds) {
  std::size_t shortened = 0, along = 0;
  for (const auto& family : generatorFamilies()) {
    if (family == "site" || family == "parking") continue;
    for (std::uint64_t seed : {1, 2}) {
      GeneratorSpec spec;
      spec.family = family;
      spec.seed = seed;
      spec.rotated_walls = 0.3;
      spec.missing_walls = 0.2;
      const GeneratedBuilding plain = generateBuilding(spec);
      spec.shortened_walls = 0.5;
      spec.rotation_about = "any";
      const GeneratedBuilding b = generateBuilding(spec);
      EXPECT_EQ(b.plan, plain.plan) << b.name;
      for (const char* key : {"wall_shifts", "missing_walls", "clutter", "extra_walls"}) {
        EXPECT_EQ(b.scenario["as_built"].value(key, nlohmann::json()),
                  plain.scenario["as_built"].value(key, nlohmann::json()))
            << b.name << " " << key;
      }
      common::Warnings warnings;
      const bim::Scenario s = load(b, &warnings);
      EXPECT_TRUE(warnings.empty()) << b.name << ": " << warnings.front().str();
      const bim::Level& level = s.plan.levels.at(0);
      for (const auto& cut : s.as_built.shortened_walls) {
        const bim::Wall* wall = level.findWall(cut.wall);
        ASSERT_NE(wall, nullptr) << b.name << " " << cut.wall;
        const double length = (wall->end - wall->start).norm();
        EXPECT_GE(length, 2.5) << b.name << " " << cut.wall;
        EXPECT_TRUE(std::none_of(level.doors.begin(), level.doors.end(),
                                 [&](const bim::Door& d) { return d.wall == cut.wall; }));
        double standing = 0.0;
        for (const auto& [from, to] : cut.built) {
          EXPECT_GE(to - from, 0.5 - 1e-9) << b.name << " " << cut.wall;
          standing += to - from;
        }
        EXPECT_GE(length - standing, 0.8 - 2e-3) << b.name << " " << cut.wall;
        EXPECT_LE(length - standing, 0.5 * length + 2e-3) << b.name << " " << cut.wall;
        ++shortened;
      }
      for (const auto& turn : s.as_built.wall_rotations) {
        ASSERT_EQ(turn.about, bim::WallRotation::About::kAlong) << b.name << " " << turn.wall;
        const bim::Wall* wall = level.findWall(turn.wall);
        EXPECT_GE(turn.along_m, 0.0);
        EXPECT_LE(turn.along_m, (wall->end - wall->start).norm() + 1e-9);
        ++along;
      }
    }
  }
  EXPECT_GT(shortened, 5u);
  EXPECT_GT(along, 5u);
}

// The scenario's as_built is written from the typed deviations (generatedAsBuiltJson) and reads
// back as them: no list left empty, nothing lost or added on the way, sheared or not.
TEST(PlanGenerator, TheScenariosAsBuiltIsTheTypedOneWritten) {
  std::size_t lists = 0;
  for (const auto& family : generatorFamilies()) {
    GeneratorSpec spec;
    spec.family = family;
    spec.seed = 3;
    spec.missing_walls = 0.3;
    spec.extra_walls = 0.6;
    spec.closed_doors = 0.3;
    spec.rotated_walls = 0.3;
    spec.shortened_walls = 0.3;
    if (family == "site" || family == "parking") {
      spec.missing_columns = 0.2;
      spec.moved_columns = 0.2;
    } else {
      spec.shear_deg = 12.0;
    }
    const GeneratedBuilding b = generateBuilding(spec);
    const nlohmann::json& written = b.scenario["as_built"];
    EXPECT_EQ(written, generatedAsBuiltJson(b.as_built)) << b.name;
    for (const auto& [key, list] : written.items()) {
      EXPECT_FALSE(list.empty()) << b.name << " " << key;
      ++lists;
    }
    bim::AsBuilt again = load(b, nullptr).as_built;
    // The parser fills in the robot's level where the file gives none.
    for (auto& wall : again.extra_walls) wall.level.clear();
    for (auto& box : again.clutter) box.level.clear();
    EXPECT_EQ(generatedAsBuiltJson(again), written) << b.name;
  }
  EXPECT_GE(lists, 30u);
}

TEST(PlanGenerator, SameSeedSameBuildingOtherSeedOtherBuilding) {
  GeneratorSpec spec;
  spec.family = "office";
  spec.seed = 7;
  const auto a = generateBuilding(spec), b = generateBuilding(spec);
  EXPECT_EQ(a.plan.dump(), b.plan.dump());
  EXPECT_EQ(a.scenario.dump(), b.scenario.dump());
  spec.seed = 8;
  EXPECT_NE(generateBuilding(spec).plan.dump(), a.plan.dump());
  // More clutter does not move a wall: the plan and the as-built changes draw from separate
  // streams.
  spec.clutter_per_room = 3.0;
  spec.seed = 7;
  EXPECT_EQ(generateBuilding(spec).plan.dump(), a.plan.dump());
}

// Seeds make different buildings in every family: the walls and doors differ, not only the name.
TEST(PlanGenerator, EverySeedIsAnotherBuilding) {
  for (const auto& family : generatorFamilies()) {
    std::set<std::string> layouts;
    for (std::uint64_t seed = 1; seed <= 8; ++seed) {
      GeneratorSpec spec;
      spec.family = family;
      spec.seed = seed;
      const auto level = generateBuilding(spec).plan["levels"][0];
      layouts.insert(level["walls"].dump() + level["doors"].dump());
    }
    EXPECT_EQ(layouts.size(), 8u) << family;
  }
}

TEST(PlanGenerator, RoomCountFollowsTheRequestUpToFiveHundred) {
  for (const char* family : {"office", "l-shape", "hall"}) {
    GeneratorSpec spec;
    spec.family = family;
    spec.rooms = 500;
    const GeneratedBuilding b = generateBuilding(spec);
    EXPECT_GE(b.offices, 450) << family;
    EXPECT_LE(b.offices, 560) << family;
    common::Warnings warnings;
    EXPECT_EQ(load(b, &warnings).plan.levels[0].rooms.size(), std::size_t(b.offices + b.corridors));
  }
}

// Asked for far more partitions than fit, a hall takes what fits, and each keeps its distances:
// 1.6 m from the others and 2.5 m from every door centre.
TEST(PlanGenerator, AHallTakesThePartitionsThatFit) {
  GeneratorSpec spec;
  spec.family = "hall";
  spec.rooms = 40;
  const GeneratedBuilding fewer = generateBuilding(spec);
  spec.partitions = 10000;
  const GeneratedBuilding b = generateBuilding(spec);
  common::Warnings warnings;
  const bim::Scenario s = load(b, &warnings);
  EXPECT_TRUE(warnings.empty());
  const bim::Level& level = s.plan.levels.at(0);
  std::vector<std::pair<Eigen::Vector2d, Eigen::Vector2d>> partitions;
  std::map<std::string, const bim::Wall*> walls;
  for (const auto& w : level.walls) {
    walls[w.id] = &w;
    if (w.id[0] == 'P') partitions.emplace_back(w.start, w.end);
  }
  const auto countIn = [](const GeneratedBuilding& g) {
    int n = 0;
    for (const auto& w : g.plan["levels"][0]["walls"]) n += w["id"].get<std::string>()[0] == 'P';
    return n;
  };
  EXPECT_GT(int(partitions.size()), countIn(fewer) + 10);  // the default: one per 40 m²
  EXPECT_LT(partitions.size(), 10000u);
  const auto distance = [](const auto& one, const auto& other) {
    return std::min({bim::distanceToSegment(one.first, other.first, other.second),
                     bim::distanceToSegment(one.second, other.first, other.second),
                     bim::distanceToSegment(other.first, one.first, one.second),
                     bim::distanceToSegment(other.second, one.first, one.second)});
  };
  for (std::size_t i = 0; i < partitions.size(); ++i) {
    for (std::size_t j = i + 1; j < partitions.size(); ++j) {
      EXPECT_GE(distance(partitions[i], partitions[j]), 1.6 - 1e-9) << i << " " << j;
    }
    for (const auto& d : level.doors) {
      const bim::Wall& w = *walls.at(d.wall);
      const Eigen::Vector2d c = w.start + d.offset * (w.end - w.start).normalized();
      EXPECT_GE(bim::distanceToSegment(c, partitions[i].first, partitions[i].second), 2.5 - 1e-9)
          << d.id;
    }
  }
  EXPECT_EQ(generateBuilding(spec).plan, b.plan);  // what fits is the seed's, every time
}

// The wall segments of a plan as a set, after an optional half turn about the plan's centre.
std::set<std::array<long, 4>> segments(const nlohmann::json& plan, bool half_turn) {
  double max_x = 0, max_y = 0;
  for (const auto& w : plan["levels"][0]["walls"]) {
    max_x = std::max({max_x, w["start"][0].get<double>(), w["end"][0].get<double>()});
    max_y = std::max({max_y, w["start"][1].get<double>(), w["end"][1].get<double>()});
  }
  std::set<std::array<long, 4>> out;
  for (const auto& w : plan["levels"][0]["walls"]) {
    auto p = [&](const nlohmann::json& v, int i) {
      const double c = v[i].get<double>();
      return std::lround(1000 * (half_turn ? (i == 0 ? max_x : max_y) - c : c));
    };
    std::array<long, 4> s = {p(w["start"], 0), p(w["start"], 1), p(w["end"], 0), p(w["end"], 1)};
    if (std::make_pair(s[2], s[3]) < std::make_pair(s[0], s[1])) s = {s[2], s[3], s[0], s[1]};
    out.insert(s);
  }
  return out;
}

TEST(PlanGenerator, SymmetricFamiliesAreHalfTurnSymmetricBarTheirOneAsymmetry) {
  for (const char* family : {"twin-wings", "hotel"}) {
    GeneratorSpec spec;
    spec.family = family;
    spec.asymmetry = false;
    spec.doors = "center";
    const GeneratedBuilding symmetric = generateBuilding(spec);
    EXPECT_EQ(segments(symmetric.plan, false), segments(symmetric.plan, true)) << family;
    spec.asymmetry = true;
    const GeneratedBuilding broken = generateBuilding(spec);
    EXPECT_NE(segments(broken.plan, false), segments(broken.plan, true)) << family;
  }
}

TEST(PlanGenerator, ImpossibleParametersNameTheParameter) {
  GeneratorSpec spec;
  spec.corridor_width = 0.5;
  try {
    generateBuilding(spec);
    FAIL();
  } catch (const std::invalid_argument& e) {
    EXPECT_STREQ(e.what(), "corridor width: must be in [1.2, 6] m (a robot and a door must fit)");
  }
  const auto message = [](const GeneratorSpec& bad) {
    try {
      generateBuilding(bad);
    } catch (const std::invalid_argument& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  spec = {};
  spec.shortened_walls = 1.5;
  EXPECT_EQ(message(spec), "shortened walls: must be a share in [0, 1]");
  spec = {};
  spec.rotation_about = "middle";
  EXPECT_EQ(message(spec), "rotation about: must be named or any");
  spec = {};
  spec.family = "castle";
  EXPECT_THROW(generateBuilding(spec), std::invalid_argument);
}

}  // namespace
}  // namespace isg::worlds
