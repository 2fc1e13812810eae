// Door jambs (slam/isgraph/door_jambs.hpp): where the plan's openings' faces are, which of a
// scan's points lie on one, when they form a jamb and when they do not (a closed door's leaf, too
// few, too spread), and the factor that ties a keyframe to one, against hand calculations.
#include "slam/isgraph/door_jambs.hpp"

#include <gtest/gtest.h>

#include <nlohmann/json.hpp>
#include <numbers>

#include "bim/plan_parser.hpp"
#include "common/json_reader.hpp"
#include "slam/isgraph/merging_factors.hpp"

namespace isg::slam {
namespace {

// Two rooms either side of one wall along x from (0, 0) to (10, 0), 0.2 m thick, with a door 1 m
// wide centred at x = 5; the outer walls have no opening.
bim::AGraph wallWithDoor() {
  const nlohmann::json plan = nlohmann::json::parse(R"({
    "format": "isg.plan", "version": 1, "name": "door",
    "levels": [{"id": "L0", "elevation": 0.0, "height": 3.0,
      "walls": [{"id": "A", "start": [0, 0], "end": [10, 0], "thickness": 0.2},
                {"id": "S", "start": [0, -4], "end": [10, -4], "thickness": 0.2},
                {"id": "N", "start": [0, 4], "end": [10, 4], "thickness": 0.2},
                {"id": "W", "start": [0, -4], "end": [0, 4], "thickness": 0.2},
                {"id": "E", "start": [10, -4], "end": [10, 4], "thickness": 0.2}],
      "doors": [{"id": "D", "wall": "A", "offset": 5.0, "width": 1.0, "height": 2.1,
                 "rooms": ["south", "north"]}],
      "rooms": [{"id": "south", "outline": [[0, -4], [10, -4], [10, 0], [0, 0]]},
                {"id": "north", "outline": [[0, 0], [10, 0], [10, 4], [0, 4]]}]}]})");
  const common::JsonSource source{"door.json", nullptr};
  return bim::buildAGraph(bim::parsePlan(common::JsonNode(plan, "", source)));
}

sensors::ScanPoint at(const Eigen::Vector3d& p) {
  return {float(p.x()), float(p.y()), float(p.z()), 50.0f, 0, 0.0f};
}

// The sensor at (2, 2, 1) in P, not turned: L's axes are P's.
Eigen::Isometry3d sensorPose(double shift_x = 0.0) {
  Eigen::Isometry3d P_T_L = Eigen::Isometry3d::Identity();
  P_T_L.translation() = Eigen::Vector3d(2.0 + shift_x, 2.0, 1.0);
  return P_T_L;
}

// `count` points on the jamb face at x = 5.5 (offsets ±0.01 m alternately, the last one +0.01 if
// odd), across y ∈ [−0.06, 0.06] (moved by `across`: the wall built that far off its plan across
// itself) and z ∈ [0.4, 1.7], in L of sensorPose().
std::vector<sensors::ScanPoint> jambFace(int count, double across = 0.0) {
  std::vector<sensors::ScanPoint> points;
  for (int i = 0; i < count; ++i) {
    const double x = 5.5 + (i % 2 == 0 ? 0.01 : -0.01);
    const double y = across - 0.06 + 0.12 * i / std::max(1, count - 1);
    const double z = 0.4 + 1.3 * i / std::max(1, count - 1);
    points.push_back(at(Eigen::Vector3d(x, y, z) - sensorPose().translation()));
  }
  return points;
}

TEST(DoorJambs, BothFacesOfTheOpening) {
  const DoorJambs jambs(wallWithDoor(), {});
  ASSERT_EQ(jambs.jambs().size(), 2u);
  const DoorJamb& low = jambs.jambs()[0];  // the start side, facing into the opening (+x)
  const DoorJamb& high = jambs.jambs()[1];
  EXPECT_NEAR(low.point.x(), 4.5, 1e-12);
  EXPECT_NEAR(low.point.y(), 0.0, 1e-12);
  EXPECT_NEAR(low.normal.x(), 1.0, 1e-12);
  EXPECT_NEAR(high.point.x(), 5.5, 1e-12);
  EXPECT_NEAR(high.normal.x(), -1.0, 1e-12);
  EXPECT_NEAR(std::abs(low.across.y()), 1.0, 1e-12);
  EXPECT_NEAR(low.half_thickness, 0.1, 1e-12);
  EXPECT_NEAR(low.z_min, 0.0, 1e-12);
  EXPECT_NEAR(low.z_max, 2.1, 1e-12);
}

TEST(DoorJambs, ATooThinWallHasNoBandBetweenItsFaces) {
  JambOptions options;
  options.face_margin = 0.095;  // 0.1 − 0.095 < 0.01 m left
  EXPECT_TRUE(DoorJambs(wallWithDoor(), options).jambs().empty());
}

TEST(DoorJambs, GathersTheFacePointsOfTheJambInFrontOnly) {
  const DoorJambs jambs(wallWithDoor(), {});
  std::vector<sensors::ScanPoint> points = jambFace(20);
  const Eigen::Vector3d sensor = sensorPose().translation();
  // On the wall's face (y = 0.1): outside the band between the faces.
  points.push_back(at(Eigen::Vector3d(6.0, 0.1, 1.0) - sensor));
  // Above the opening's band (z > 2.1 − 0.3) and at the floor (z < 0.3).
  points.push_back(at(Eigen::Vector3d(5.5, 0.0, 1.95) - sensor));
  points.push_back(at(Eigen::Vector3d(5.5, 0.0, 0.2) - sensor));
  // Further than `gather` from the face.
  points.push_back(at(Eigen::Vector3d(5.1, 0.0, 1.0) - sensor));
  const auto seen = jambs.gather(points, sensorPose());
  // The jamb at x = 4.5 faces +x, away from the sensor at x = 2: never looked for.
  ASSERT_EQ(seen.size(), 1u);
  EXPECT_EQ(seen[0].jamb, 1);
  EXPECT_EQ(seen[0].points_L.size(), 20u);
}

TEST(DoorJambs, KeepsAtMostMaxPointsEvenlyOfASighting) {
  JambOptions options;
  options.max_points = 10;
  const DoorJambs jambs(wallWithDoor(), options);
  const std::vector<sensors::ScanPoint> points = jambFace(40);
  const auto seen = jambs.gather(points, sensorPose());
  ASSERT_EQ(seen.size(), 1u);
  ASSERT_EQ(seen[0].points_L.size(), 10u);
  // Every fourth of the 40, from the first.
  for (int i = 0; i < 10; ++i) EXPECT_FLOAT_EQ(seen[0].points_L[i].z(), points[4 * i].z);
}

TEST(DoorJambs, FitsTheFaceAndMeasuresItsOffsetUnderAnotherPose) {
  const DoorJambs jambs(wallWithDoor(), {});
  const auto seen = jambs.gather(jambFace(20), sensorPose());
  ASSERT_EQ(seen.size(), 1u);
  const auto fit = jambs.fit(seen[0], sensorPose());
  ASSERT_TRUE(fit);
  EXPECT_EQ(fit->points, 20);
  // Ten points at +0.01 m and ten at −0.01 m along x: the centroid on the face.
  EXPECT_NEAR(fit->offset, 0.0, 1e-6);
  EXPECT_NEAR(fit->centroid_L.x(), 3.5, 1e-6);
  EXPECT_NEAR(fit->centroid_L.y(), -2.0, 1e-6);
  // The pose moved 0.04 m along +x: the points 0.04 m further, i.e. 0.04 m behind the face
  // (its normal is −x).
  const auto moved = jambs.fit(seen[0], sensorPose(0.04));
  ASSERT_TRUE(moved);
  EXPECT_NEAR(moved->offset, -0.04, 1e-6);
  EXPECT_EQ(moved->points, 20);
}

// Why the merge keeps the jambs of a wall released as built off its plan (plan_merging.cpp): a
// wall built off across itself leaves its opening where it was along it, so what is gathered of
// its jamb still fits it exactly; built further off than the band, nothing is gathered.
TEST(DoorJambs, AWallBuiltOffAcrossItselfKeepsItsJambAlongIt) {
  const DoorJambs jambs(wallWithDoor(), {});
  // 5 cm off: the face spans y ∈ [−0.01, 0.11], point i at −0.01 + 0.12·i/19; the band
  // (|y| ≤ 0.1 − 0.03) keeps i = 0 … 12, 13 of 20.
  const auto seen = jambs.gather(jambFace(20, 0.05), sensorPose());
  ASSERT_EQ(seen.size(), 1u);
  EXPECT_EQ(seen[0].points_L.size(), 13u);
  const auto fit = jambs.fit(seen[0], sensorPose());
  ASSERT_TRUE(fit);
  EXPECT_EQ(fit->points, 13);
  // Seven points at x = 5.51, six at 5.49: the centroid 0.01/13 m beyond the face along +x,
  // behind it along its normal (−x) — the jamb's place along the wall, as planned.
  EXPECT_NEAR(fit->offset, -0.01 / 13.0, 1e-6);
  // 25 cm off: the whole face (y ∈ [0.19, 0.31]) lies beyond the planned wall's faces.
  EXPECT_TRUE(jambs.gather(jambFace(20, 0.25), sensorPose()).empty());
}

TEST(DoorJambs, AClosedLeafInTheOpeningIsNoJamb) {
  const DoorJambs jambs(wallWithDoor(), {});
  std::vector<sensors::ScanPoint> points = jambFace(20);
  // A leaf across the opening, seen from 0.07 to 0.29 m in front of the face: half the points.
  for (int i = 0; i < 20; ++i) {
    points.push_back(at(Eigen::Vector3d(5.43 - 0.011 * i, 0.02, 1.0) - sensorPose().translation()));
  }
  const auto seen = jambs.gather(points, sensorPose());
  ASSERT_EQ(seen.size(), 1u);
  EXPECT_EQ(seen[0].points_L.size(), 40u);
  EXPECT_FALSE(jambs.fit(seen[0], sensorPose()));
}

TEST(DoorJambs, ALeafSeenBesideItsJambBeyondTheGatherIsNoJamb) {
  const DoorJambs jambs(wallWithDoor(), {});
  // A closed leaf across the 1 m opening (in the wall's thickness, y = 0), hiding the jamb at
  // x = 5.5: twelve points 0.18–0.24 m from the jamb's plane, where alone they would look like the
  // jamb slid 0.21 m, and twelve 0.32–0.49 m from it, up to the opening's middle.
  std::vector<sensors::ScanPoint> points;
  const Eigen::Vector3d sensor = sensorPose().translation();
  for (int i = 0; i < 12; ++i) {
    points.push_back(at(Eigen::Vector3d(5.5 - 0.18 - 0.005 * i, 0.0, 0.5 + 0.1 * i) - sensor));
    points.push_back(at(Eigen::Vector3d(5.5 - 0.32 - 0.015 * i, 0.0, 0.5 + 0.1 * i) - sensor));
  }
  const auto seen = jambs.gather(points, sensorPose());
  ASSERT_EQ(seen.size(), 1u);
  EXPECT_EQ(seen[0].points_L.size(), 12u);
  EXPECT_EQ(seen[0].filled, 12);
  // The twelve gathered form a tight cluster; the twelve beyond fill the opening: refused.
  EXPECT_FALSE(jambs.fit(seen[0], sensorPose()));
  // Without what lies beyond the gather, the cluster alone would pass as the jamb.
  JambSighting alone = seen[0];
  alone.filled = 0;
  const auto fit = jambs.fit(alone, sensorPose());
  ASSERT_TRUE(fit);
  EXPECT_NEAR(fit->offset, 0.18 + 0.005 * 5.5, 1e-6);
}

TEST(DoorJambs, TooFewOrTooSpreadPointsAreNoJamb) {
  JambOptions options;
  const DoorJambs jambs(wallWithDoor(), options);
  const auto few = jambs.gather(jambFace(options.min_points - 1), sensorPose());
  ASSERT_EQ(few.size(), 1u);
  EXPECT_FALSE(jambs.fit(few[0], sensorPose()));
  // Spread evenly over ±0.058 m about the face: all within the cluster (0.06 m) of their median,
  // their median absolute deviation 0.029 m past max_spread (0.025 m).
  std::vector<sensors::ScanPoint> spread;
  for (int i = 0; i < 21; ++i) {
    spread.push_back(at(Eigen::Vector3d(5.5 - 0.058 + 0.0058 * i, 0.0, 0.5 + 0.05 * i) -
                        sensorPose().translation()));
  }
  const auto wide = jambs.gather(spread, sensorPose());
  ASSERT_EQ(wide.size(), 1u);
  EXPECT_FALSE(jambs.fit(wide[0], sensorPose()));
}

TEST(JambFactor, ResidualByHand) {
  // Keyframe at (1, 2, 0) turned 90° about z; the centroid (1, 0, 0.5) in R is (1, 3, 0.5) in M;
  // P_T_M = (0.5, −1, 0°) puts it at (1.5, 2) in P. The jamb faces −x at x = 5.5: the point lies
  // 4 m in front of it; σ = 0.02 m → residual 200.
  const double position[3] = {1.0, 2.0, 0.0};
  const Eigen::Quaterniond q(Eigen::AngleAxisd(std::numbers::pi / 2, Eigen::Vector3d::UnitZ()));
  const double orientation[4] = {q.x(), q.y(), q.z(), q.w()};
  const double P_T_M[3] = {0.5, -1.0, 0.0};
  std::unique_ptr<ceres::CostFunction> factor(JambFactor::create(
      Eigen::Vector3d(1.0, 0.0, 0.5), Eigen::Vector2d(-1.0, 0.0), Eigen::Vector2d(5.5, 0.0), 0.02));
  const double* parameters[3] = {position, orientation, P_T_M};
  double residual = 0.0;
  ASSERT_TRUE(factor->Evaluate(parameters, &residual, nullptr));
  EXPECT_NEAR(residual, 200.0, 1e-9);
  // P_T_M turned 90° too: (1, 3) → (−3, 1), then + (0.5, −1) → (−2.5, 0): 8 m in front.
  const double turned[3] = {0.5, -1.0, std::numbers::pi / 2};
  const double* again[3] = {position, orientation, turned};
  ASSERT_TRUE(factor->Evaluate(again, &residual, nullptr));
  EXPECT_NEAR(residual, 400.0, 1e-9);
}

}  // namespace
}  // namespace isg::slam
