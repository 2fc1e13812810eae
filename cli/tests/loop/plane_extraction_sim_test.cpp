// Plane extraction on simulated scans: the range image's walls lie on the plan's surfaces and
// are RANSAC's walls, as close to the plan as RANSAC's or closer (docs/slam.md).
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <optional>

#include "bim/agraph.hpp"
#include "sim/simulation.hpp"
#include "slam/sgraph/plane_extraction.hpp"
#include "worlds/reference_plans.hpp"

namespace isg::sim {
namespace {

// The angle between two planes' normals, degrees.
double angleDeg(const bim::Plane& a, const bim::Plane& b) {
  return std::acos(std::clamp(a.normal.dot(b.normal), -1.0, 1.0)) * 180.0 / std::numbers::pi;
}

// The plan surface nearest to a plane observed from `B_T_L` (normal within 5°, same facing):
// (angle in degrees, offset in metres), or nothing.
std::optional<std::pair<double, double>> nearestSurface(const bim::AGraph& graph,
                                                        const slam::PlaneObservation& o,
                                                        const Eigen::Isometry3d& B_T_L) {
  const bim::Plane in_B = o.plane.transformed(B_T_L);
  const Eigen::Vector3d centroid = B_T_L * o.centroid;
  std::optional<std::pair<double, double>> best;
  double best_distance = 1e9;
  for (const auto& surface : graph.surfaces) {
    const double angle = angleDeg(in_B, surface.plane);
    if (angle > 5.0) continue;
    const double distance = std::abs(surface.plane.signedDistance(centroid));
    if (distance < best_distance) {
      best_distance = distance;
      best = std::pair{angle, std::abs(in_B.d - surface.plane.d)};
    }
  }
  return best;
}

TEST(PlaneExtraction, OnSimulatedScansTheRangeImageFindsTheWallsRansacFindsAsWellOrBetter) {
  // The plan itself (no as-built deviation), scans from standing poses along the route (no
  // motion distortion): every wall observation can be held to the plan's surfaces.
  const auto scenario = worlds::loadScenarioOrBuiltin("builtin:d2", nullptr);
  const Simulation sim(scenario);
  const bim::AGraph graph = bim::buildAGraph(scenario.plan);
  const auto lidar = sim.makeLidar();
  int compared = 0;
  double image_error = 0.0, ransac_error = 0.0;
  for (double t : {1.0, 6.0, 15.0, 24.0}) {
    SCOPED_TRACE(t);
    const Eigen::Isometry3d B_T_L = sim.B_T_L(t);
    const LidarScan made = lidar->scan(
        0.0, [&](double) { return B_T_L; }, 5);
    const sensors::Scan scan{0.0, made.points};
    slam::PlaneExtractionOptions options;
    const auto image = slam::extractPlanes(scan, options);
    options.method = slam::PlaneExtractionOptions::Method::kRansac;
    const auto ransac = slam::extractPlanes(scan, options);
    for (const auto& o : image) {
      if (o.orientation != slam::PlaneOrientation::kVertical || o.points < 300) continue;
      const auto truth = nearestSurface(graph, o, B_T_L);
      ASSERT_TRUE(truth.has_value());
      EXPECT_LT(truth->first, 0.5);
      EXPECT_LT(truth->second, 0.01);
    }
    for (const auto& r : ransac) {
      // Walls RANSAC is sure of: a few hundred voxels. The range image has one on the same
      // stretch of wall (the nearest centroid among planes turned alike: a wall cut by a
      // doorway is two observations on one plane).
      if (r.orientation != slam::PlaneOrientation::kVertical || r.points < 300) continue;
      const slam::PlaneObservation* best = nullptr;
      for (const auto& p : image) {
        if (angleDeg(p.plane, r.plane) > 5.0) continue;
        if (!best || (p.centroid - r.centroid).norm() < (best->centroid - r.centroid).norm())
          best = &p;
      }
      ASSERT_NE(best, nullptr) << r.plane.normal.transpose() << " d " << r.plane.d;
      EXPECT_LT(angleDeg(best->plane, r.plane), 1.0);
      EXPECT_NEAR(best->plane.d, r.plane.d, 0.02);
      const auto image_truth = nearestSurface(graph, *best, B_T_L);
      const auto ransac_truth = nearestSurface(graph, r, B_T_L);
      ASSERT_TRUE(image_truth && ransac_truth);
      image_error += image_truth->second;
      ransac_error += ransac_truth->second;
      ++compared;
    }
  }
  EXPECT_GE(compared, 8);
  // As close to the plan as RANSAC's planes, or closer.
  EXPECT_LE(image_error, ransac_error * 1.05)
      << image_error / compared << " vs " << ransac_error / compared;
}

}  // namespace
}  // namespace isg::sim
