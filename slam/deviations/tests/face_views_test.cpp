// Whether a sight line passed where a wall stands, as built: the wall as planned, moved toward
// the keyframes, moved away from them, and turned so that it does each at one end. Every range
// below is a hand calculation.

#include "slam/deviations/face_views.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <vector>

#include "bim/plan_parser.hpp"
#include "common/json_reader.hpp"
#include "slam/deviations/deviation_options.hpp"

namespace isg::slam {
namespace {

// One room, 4 × 3 m; W1 runs from (0, 0) to (4, 0), 0.2 m thick: its right face (outward normal
// −y) lies at y = −0.1.
bim::AGraph oneRoom() {
  const nlohmann::json document = nlohmann::json::parse(R"({
    "format": "isg.plan", "version": 1, "name": "one room",
    "levels": [{
      "id": "L0", "elevation": 0.0, "height": 3.0,
      "walls": [
        {"id": "W1", "start": [0, 0], "end": [4, 0], "thickness": 0.2},
        {"id": "W2", "start": [4, 0], "end": [4, 3], "thickness": 0.2},
        {"id": "W3", "start": [4, 3], "end": [0, 3], "thickness": 0.2},
        {"id": "W4", "start": [0, 3], "end": [0, 0], "thickness": 0.2}
      ],
      "rooms": [{"id": "R1", "outline": [[0.1, 0.1], [3.9, 0.1], [3.9, 2.9], [0.1, 2.9]]}]
    }]
  })");
  const common::JsonSource source{"one-room.json", nullptr};
  return bim::buildAGraph(bim::parsePlan(common::JsonNode(document, "", source)));
}

// What a keyframe at `from` saw when every sight line toward +y stopped at y = `stop_y` (and
// every other one 1 m out): per degree, the range to that line along the degree's middle.
SightProfile stoppingAt(const Eigen::Vector2d& from, double stop_y) {
  SightProfile sight;
  sight.range_cm.assign(SightProfile::kBins, 100);
  for (int bin = 0; bin < SightProfile::kBins; ++bin) {
    const double sine = std::sin((bin + 0.5) * std::numbers::pi / 180.0);
    if (sine > 0.1)
      sight.range_cm[bin] = std::uint16_t(std::lround(100.0 * (stop_y - from.y()) / sine));
  }
  return sight;
}

// Three keyframes 3 m in front of W1's right face, below x = `x` and 0.1 m either side, each
// seeing to y = `stop_y`.
struct Keyframes {
  std::vector<SightProfile> sights;
  std::vector<Viewpoint> viewpoints;
  Keyframes(double x, double stop_y) {
    for (double dx : {-0.1, 0.0, 0.1}) sights.push_back(stoppingAt({x + dx, -3.0}, stop_y));
    for (int k = 0; k < 3; ++k) {
      viewpoints.push_back({Eigen::Vector2d(x + 0.1 * (k - 1), -3.0), 0.0, &sights[k]});
    }
  }
};

const bim::WallNode& w1(const bim::AGraph& plan) {
  for (const auto& wall : plan.walls) {
    if (wall.id == "W1") return wall;
  }
  throw std::logic_error("no W1");
}

BuiltLine w1Built(double offset_m, double slope) {
  BuiltLine built;
  built.centre = {2.0, 0.0};
  built.axis = {1.0, 0.0};
  built.offset_m = offset_m;
  built.slope = slope;
  return built;
}

// The sight lines reach y = 0.2, 0.3 m past the planned right face at y = −0.1: as planned, the
// far face (y = 0.1) and the 0.2 m margin make 0.4 m, not passed. Moved 0.25 m toward the
// keyframes (axis at y = −0.25), the whole wall stands before the face: 0.2 m margin, passed.
// Moved 0.25 m away (far face at y = 0.35): 0.65 m, not passed.
TEST(FaceViews, ASightLineIsJudgedAgainstTheFarFaceAsBuilt) {
  const bim::AGraph plan = oneRoom();
  const DeviationOptions options;
  const Keyframes keyframes(2.0, 0.2);
  const Eigen::Vector2d point(2.0, -0.1), normal(0.0, -1.0);
  EXPECT_FALSE(FaceViews(plan, w1(plan), keyframes.viewpoints, options).inView(point, normal));
  EXPECT_TRUE(FaceViews(plan, w1(plan), keyframes.viewpoints, options, w1Built(-0.25, 0.0))
                  .inView(point, normal));
  EXPECT_FALSE(FaceViews(plan, w1(plan), keyframes.viewpoints, options, w1Built(0.25, 0.0))
                   .inView(point, normal));
  // Seen to y = 0.4 (0.5 m past the face): as planned, passed; moved away, still not.
  const Keyframes farther(2.0, 0.4);
  EXPECT_TRUE(FaceViews(plan, w1(plan), farther.viewpoints, options).inView(point, normal));
  EXPECT_FALSE(FaceViews(plan, w1(plan), farther.viewpoints, options, w1Built(0.25, 0.0))
                   .inView(point, normal));
}

// W1 turned about its centre so that at x = 0.5 it stands 0.25 m toward the keyframes and at
// x = 3.5 0.25 m away (slope 1/6): each end is judged where it stands there, not by the most
// the turn swings it anywhere (0.25 m either way, which passed neither).
TEST(FaceViews, ATurnedWallIsJudgedWhereItStandsAlongIt) {
  const bim::AGraph plan = oneRoom();
  const DeviationOptions options;
  const BuiltLine turned = w1Built(0.0, 0.25 / 1.5);
  const Eigen::Vector2d normal(0.0, -1.0);
  const Keyframes at_start(0.5, 0.2), at_end(3.5, 0.2);
  EXPECT_TRUE(
      FaceViews(plan, w1(plan), at_start.viewpoints, options, turned).inView({0.5, -0.1}, normal));
  EXPECT_FALSE(
      FaceViews(plan, w1(plan), at_end.viewpoints, options, turned).inView({3.5, -0.1}, normal));
  EXPECT_NEAR(turned.offsetAt({0.5, -0.1}), -0.25, 1e-12);
  EXPECT_NEAR(turned.offsetAt({3.5, -0.1}), 0.25, 1e-12);
}

}  // namespace
}  // namespace isg::slam
