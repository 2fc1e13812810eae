#include <gtest/gtest.h>

#include <cmath>

#include "bim/plan_parser.hpp"
#include "bim/synthetic_plan.hpp"
#include "common/json_reader.hpp"
#include "slam/baselines/amcl_filter.hpp"
#include "slam/baselines/amcl_localizer.hpp"
#include "slam/baselines/amcl_motion_model.hpp"
#include "slam/baselines/likelihood_field.hpp"
#include "slam/baselines/planar_scan.hpp"

namespace isg::slam {
namespace {

// A 20 × 20 grid of 0.1 m cells, origin (0, 0), one occupied cell: (10, 10), centre (1.05, 1.05).
LikelihoodField oneObstacle(double cap) {
  std::vector<char> occupied(400, 0), free(400, 1);
  occupied[10 * 20 + 10] = 1;
  free[10 * 20 + 10] = 0;
  return LikelihoodField(occupied, free, 20, 20, 0.1, Eigen::Vector2d::Zero(), cap);
}

TEST(LikelihoodField, DistancesAreEuclideanBetweenCellCentresAndCapped) {
  const LikelihoodField field = oneObstacle(2.0);
  EXPECT_DOUBLE_EQ(field.distance({1.05, 1.05}), 0.0);
  // Cell (13, 14): 3 and 4 cells away, 0.5 m.
  EXPECT_NEAR(field.distance({1.35, 1.45}), 0.5, 1e-6);
  EXPECT_NEAR(field.distance({1.31, 1.49}), 0.5, 1e-6);  // anywhere in that cell
  // Cell (0, 0): √(10² + 10²) cells.
  EXPECT_NEAR(field.distance({0.0, 0.0}), std::sqrt(200.0) * 0.1, 1e-6);
  EXPECT_DOUBLE_EQ(field.distance({-5.0, 0.0}), 2.0);  // outside the grid: the cap
  EXPECT_NEAR(oneObstacle(0.3).distance({1.35, 1.45}), 0.3, 1e-6);
  EXPECT_EQ(field.freeCells().size(), 399u);
}

bim::Plan threeRooms() {
  bim::GridPlanSpec spec;
  spec.rows = 1;
  spec.cols = 3;
  spec.cell_width = 4.0;
  spec.cell_depth = 3.0;
  spec.size_seed = 7;  // the three rooms differ in width
  const nlohmann::json document = bim::makeGridPlan(spec);
  const common::JsonSource source{"three-rooms.json", nullptr};
  return bim::parsePlan(common::JsonNode(document, "", source));
}

TEST(LikelihoodField, ThePlansWallsAreOccupiedAndItsRoomsFree) {
  const bim::Plan plan = threeRooms();
  const bim::Level& level = plan.levels.front();
  const LikelihoodField field(plan, level.id);
  double area = 0.0;
  for (const auto& room : level.rooms) {
    const auto& o = room.outline;
    for (std::size_t i = 0; i < o.size(); ++i) {
      const auto& a = o[i];
      const auto& b = o[(i + 1) % o.size()];
      area += 0.5 * (a.x() * b.y() - b.x() * a.y());
    }
  }
  // Free cells cover the rooms, within a cell's width along their outlines.
  const double free_area = field.freeCells().size() * 0.05 * 0.05;
  EXPECT_NEAR(free_area, area, 0.05 * 2.0 * 30.0);
  // Every wall's axis point is occupied, except in door openings, which are free to see through.
  for (const auto& wall : level.walls) {
    const Eigen::Vector2d quarter = wall.start + 0.25 * (wall.end - wall.start);
    bool in_door = false;
    for (const auto& door : level.doors) {
      const double s = 0.25 * (wall.end - wall.start).norm();
      in_door = in_door || (door.wall == wall.id && std::abs(s - door.offset) < 0.5 * door.width);
    }
    EXPECT_EQ(field.occupied(quarter), !in_door) << wall.id;
  }
  for (const auto& door : level.doors) {
    const bim::Wall* wall = level.findWall(door.wall);
    const Eigen::Vector2d axis = (wall->end - wall->start).normalized();
    EXPECT_FALSE(field.occupied(wall->start + door.offset * axis)) << door.id;
  }
  // In a room, the distance to the nearest wall's occupied cells (centre to centre).
  const auto& room = level.rooms.front().outline;
  Eigen::Vector2d lo = room.front(), hi = room.front();
  for (const auto& p : room) {
    lo = lo.cwiseMin(p);
    hi = hi.cwiseMax(p);
  }
  const Eigen::Vector2d inside = lo + Eigen::Vector2d(0.6, 0.9);  // nearer the left face
  EXPECT_NEAR(field.distance(inside), 0.6, 0.05 + 1e-9);
}

TEST(AmclSensorModel, LikelihoodOfABeamByHand) {
  const LikelihoodField field = oneObstacle(2.0);
  ParticleFilterOptions options;  // z_hit 0.5, z_rand 0.5, sigma_hit 0.2, max_range 100
  ParticleFilter filter(field, options, 1);
  const Pose2 pose{0.35, 1.05, 0.0};
  // A beam ending 0.7 m ahead lands on the obstacle: pz = 0.5 + 0.5 / 100.
  const double on = 0.5 + 0.005;
  EXPECT_NEAR(filter.likelihood(pose, {{0.7, 0.0}}), 1.0 + on * on * on, 1e-12);
  // One ending 0.3 m short (cell (7, 10), three cells off): pz = 0.5 e^(−0.09 / 0.08) + 0.005.
  const double short_by = 0.5 * std::exp(-0.09 / 0.08) + 0.005;
  // (The field stores distances as floats: 1e-7, not 1e-12.)
  EXPECT_NEAR(filter.likelihood(pose, {{0.4, 0.0}}), 1.0 + std::pow(short_by, 3), 1e-7);
  // Beams add their cubes; a turned pose moves the end points.
  EXPECT_NEAR(filter.likelihood(pose, {{0.7, 0.0}, {0.4, 0.0}}),
              1.0 + on * on * on + std::pow(short_by, 3), 1e-7);
  EXPECT_NEAR(filter.likelihood({1.05, 0.35, M_PI / 2}, {{0.7, 0.0}}), 1.0 + on * on * on, 1e-9);
}

TEST(AmclMotionModel, DecompositionAndNoiseByHand) {
  // From the origin to (1, 1) facing +y: turn 45°, run √2, turn 45°.
  const OdometryMotion m = decomposeOdometry({0, 0, 0}, {1, 1, M_PI / 2});
  EXPECT_NEAR(m.rot1, M_PI / 4, 1e-12);
  EXPECT_NEAR(m.trans, std::sqrt(2.0), 1e-12);
  EXPECT_NEAR(m.rot2, M_PI / 4, 1e-12);
  const OdometryMotionNoise noise;  // every alpha 0.2
  const double a = M_PI / 4;
  EXPECT_NEAR(m.sigmaRot1(noise), std::sqrt(0.2 * a * a + 0.2 * 2.0), 1e-12);
  EXPECT_NEAR(m.sigmaTrans(noise), std::sqrt(0.2 * 2.0 + 0.2 * a * a + 0.2 * a * a), 1e-12);
  // Backwards by 1 m: rot1 is a half turn, but its noise counts it as no turn.
  const OdometryMotion back = decomposeOdometry({0, 0, 0}, {-1, 0, 0});
  EXPECT_NEAR(std::abs(back.rot1), M_PI, 1e-12);
  EXPECT_NEAR(back.rot1_noise, 0.0, 1e-12);
  EXPECT_NEAR(back.sigmaTrans(noise), std::sqrt(0.2), 1e-12);
  // Under 1 cm of travel the direction is not a turn.
  EXPECT_EQ(decomposeOdometry({0, 0, 0}, {0.005, 0.005, 0.3}).rot1, 0.0);
  EXPECT_NEAR(decomposeOdometry({0, 0, 0}, {0.005, 0.005, 0.3}).rot2, 0.3, 1e-12);
}

TEST(AmclMotionModel, SamplesMoveTheParticleAsTheOdometryWithTheStatedSpread) {
  const OdometryMotion m = decomposeOdometry({0, 0, 0}, {1, 1, M_PI / 2});
  std::mt19937_64 rng(3);
  const Pose2 exact = sampleOdometryMotion({5, 5, M_PI / 2}, m, {0, 0, 0, 0}, rng);
  EXPECT_NEAR(exact.x, 4.0, 1e-12);  // the same move in the particle's own frame
  EXPECT_NEAR(exact.y, 6.0, 1e-12);
  EXPECT_NEAR(exact.yaw, M_PI, 1e-12);
  // Straight runs of 1 m: the run's length has σ = √alpha3 · 1 m, the heading's change σ from
  // both turns, √2 · √alpha2 · 1 m.
  const OdometryMotion run = decomposeOdometry({0, 0, 0}, {1, 0, 0});
  const OdometryMotionNoise noise;
  double sum = 0, sum2 = 0, yaw2 = 0;
  const int n = 20000;
  for (int i = 0; i < n; ++i) {
    const Pose2 p = sampleOdometryMotion({0, 0, 0}, run, noise, rng);
    // The length run, as seen from the start.
    const double length = std::hypot(p.x, p.y);
    sum += length;
    sum2 += length * length;
    yaw2 += p.yaw * p.yaw;
  }
  const double mean = sum / n;
  EXPECT_NEAR(mean, 1.0, 0.01);
  EXPECT_NEAR(std::sqrt(sum2 / n - mean * mean), std::sqrt(0.2), 0.02);
  EXPECT_NEAR(std::sqrt(yaw2 / n), std::sqrt(2.0 * 0.2), 0.02);
}

TEST(AmclFilter, KldBoundByHand) {
  const LikelihoodField field = oneObstacle(2.0);
  ParticleFilter filter(field, {}, 1);  // err 0.05, z 0.99, 500 – 2000 particles
  EXPECT_EQ(filter.kldLimit(1), 2000);
  EXPECT_EQ(filter.kldLimit(2), 500);     // 20 by the formula, raised to the minimum
  EXPECT_EQ(filter.kldLimit(100), 1129);  // ⌈99 / 0.1 · (1 − b + √b · 0.99)³⌉, b = 2 / 891
  EXPECT_EQ(filter.kldLimit(200), 2000);  // 2187 by the formula, capped
}

// A 2D LiDAR in the plan's occupancy grid: rays marched in 1 cm steps to the first occupied cell.
sensors::Scan castScan(const LikelihoodField& field, const Pose2& pose) {
  sensors::Scan scan;
  for (int b = 0; b < 360; ++b) {
    const double bearing = (b + 0.5) * M_PI / 180.0;
    const Eigen::Vector2d direction(std::cos(pose.yaw + bearing), std::sin(pose.yaw + bearing));
    for (double r = 0.35; r < 20.0; r += 0.01) {
      if (!field.occupied(pose.position() + r * direction)) continue;
      scan.points.push_back(
          {float(r * std::cos(bearing)), float(r * std::sin(bearing)), 0.0f, 0.0f, 0, 0.0f});
      break;
    }
  }
  return scan;
}

// Global localization from a uniform start over the three rooms: the robot walks a circle in the
// middle room; within 40 filter updates (8 m of walking and turning; seeds 1–3 took 20, 25 and
// 30) the filter says it is localized, and from then on it is right.
TEST(AmclLocalizer, ConvergesFromAUniformStartInThreeUnequalRooms) {
  const bim::Plan plan = threeRooms();
  const bim::Level& level = plan.levels.front();
  const LikelihoodField field(plan, level.id);
  const auto& room = level.rooms[1].outline;
  Eigen::Vector2d centre = Eigen::Vector2d::Zero();
  for (const auto& p : room) centre += p / double(room.size());
  for (std::uint64_t seed : {1, 2, 3}) {
    AmclLocalizer amcl(plan, level.id, Eigen::Isometry3d::Identity(), {}, seed);
    int localized_after = -1;
    Pose2 truth;
    for (int step = 0; step < 400 && localized_after < 0; ++step) {
      const double angle = step * 0.05;  // 0.05 rad and 4 cm a step on a 0.8 m circle
      truth = {centre.x() + 0.8 * std::cos(angle), centre.y() + 0.8 * std::sin(angle),
               angle + M_PI / 2};
      const Pose2 start{centre.x() + 0.8, centre.y(), M_PI / 2};
      // Odometry: the true motion, in the frame of the start pose.
      const Eigen::Isometry3d M_T_R = toIsometry(start).inverse() * toIsometry(truth);
      amcl.pushOdometry({0.1 * step, M_T_R});
      sensors::Scan scan = castScan(field, truth);
      scan.stamp = 0.1 * step;
      amcl.pushScan(scan);
      if (amcl.mapInPlan()) localized_after = amcl.updates();
      if (amcl.mapInPlan()) {
        const Pose2 estimate = planarPose(*amcl.mapInPlan() * M_T_R);
        EXPECT_LT((estimate.position() - truth.position()).norm(), 0.3) << "seed " << seed;
        EXPECT_LT(std::abs(common::angleDifference(estimate.yaw, truth.yaw)), 0.2)
            << "seed " << seed;
      }
    }
    EXPECT_GE(localized_after, 1) << "seed " << seed;
    EXPECT_LE(localized_after, 40) << "seed " << seed;
  }
}

TEST(PlanarScan, KeepsTheBandAroundTheSensorAndTheNearestPointPerBearing) {
  Eigen::Isometry3d R_T_L = Eigen::Isometry3d::Identity();
  R_T_L.translation() = Eigen::Vector3d(0.2, 0.0, 0.5);
  sensors::Scan scan;
  scan.points.push_back({3.0f, 0.0f, 0.1f, 0, 0, 0});    // in the band, ahead
  scan.points.push_back({2.0f, 0.01f, -0.2f, 0, 0, 0});  // same bearing bin, nearer
  scan.points.push_back({0.0f, 2.0f, 0.4f, 0, 0, 0});    // above the band
  scan.points.push_back({0.1f, 0.1f, 0.0f, 0, 0, 0});    // the robot itself
  const PlanarScan planar = planarScan(scan, R_T_L);
  ASSERT_EQ(planar.endpoints.size(), 1u);
  EXPECT_NEAR(planar.endpoints[0].x(), 2.2, 1e-6);  // in the base frame
  EXPECT_NEAR(planar.ranges[0], std::hypot(2.0, 0.01), 1e-6);
  EXPECT_NEAR(planar.origin.x(), 0.2, 1e-12);
}

}  // namespace
}  // namespace isg::slam
