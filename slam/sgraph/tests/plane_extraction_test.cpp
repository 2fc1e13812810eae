#include "slam/sgraph/plane_extraction.hpp"
#include "slam/sgraph/pcl_planes.hpp"

#include <gtest/gtest.h>
#include <numbers>

#include <random>

namespace isg::slam {
namespace {

// A synthetic scan: points on axis-aligned rectangles (walls, floor, ceiling) of a room, seen
// from `sensor`, the whole turned by `yaw` about the sensor; 1 cm noise along each normal.
struct Patch {
  Eigen::Vector3d corner, u, v;  // points corner + a·u + b·v, a, b in [0, 1]
};

sensors::Scan sampleScan(const std::vector<Patch>& patches, const Eigen::Vector3d& sensor,
                         double yaw, double noise = 0.01, int per_square_metre = 400) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u01(0.0, 1.0);
  std::normal_distribution<double> n(0.0, noise);
  const Eigen::Matrix3d R = Eigen::AngleAxisd(yaw, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  sensors::Scan scan;
  for (const auto& patch : patches) {
    const Eigen::Vector3d normal = patch.u.cross(patch.v).normalized();
    const int count = int(patch.u.cross(patch.v).norm() * per_square_metre);
    for (int i = 0; i < count; ++i) {
      const Eigen::Vector3d p =
          patch.corner + u01(rng) * patch.u + u01(rng) * patch.v + n(rng) * normal;
      const Eigen::Vector3d q = R * (p - sensor);
      scan.points.push_back({float(q.x()), float(q.y()), float(q.z()), 100.0f, 0, 0.0f});
    }
  }
  return scan;
}

// The room [0, 6] × [0, 4] × [0, 3].
std::vector<Patch> patchRoom() {
  return {{{0, 0, 0}, {6, 0, 0}, {0, 0, 3}},   // y = 0
          {{0, 4, 0}, {6, 0, 0}, {0, 0, 3}},   // y = 4
          {{0, 0, 0}, {0, 4, 0}, {0, 0, 3}},   // x = 0
          {{6, 0, 0}, {0, 4, 0}, {0, 0, 3}},   // x = 6
          {{0, 0, 0}, {6, 0, 0}, {0, 4, 0}},   // floor
          {{0, 0, 3}, {6, 0, 0}, {0, 4, 0}}};  // ceiling
}

TEST(PlaneExtraction, RecoversTheRoomsSixPlanesWhateverTheHeading) {
  const Eigen::Vector3d sensor(2.0, 1.5, 0.7);
  for (double yaw : {0.0, 0.5, 2.3}) {
    SCOPED_TRACE(yaw);
    const sensors::Scan scan = sampleScan(patchRoom(), sensor, yaw);
    PlaneExtractionOptions options;
    const auto cloud = preprocess(scan, options);
    const auto planes = extractPlanes(*cloud, options);
    ASSERT_EQ(planes.size(), 6u);
    int vertical = 0, horizontal = 0;
    for (const auto& p : planes) {
      vertical += p.orientation == PlaneOrientation::kVertical;
      horizontal += p.orientation == PlaneOrientation::kHorizontal;
      // Normals face the sensor, at the origin: d > 0 means the origin is in front.
      EXPECT_GT(p.plane.d, 0.0);
      EXPECT_LT(p.rms, 0.02);
    }
    EXPECT_EQ(vertical, 4);
    EXPECT_EQ(horizontal, 2);
    // Distances from the sensor: walls at 2, 4, 1.5, 2.5 m, floor 0.7, ceiling 2.3.
    std::vector<double> d;
    for (const auto& p : planes) d.push_back(p.plane.d);
    std::sort(d.begin(), d.end());
    const std::vector<double> expected = {0.7, 1.5, 2.0, 2.3, 2.5, 4.0};
    for (int i = 0; i < 6; ++i) EXPECT_NEAR(d[i], expected[i], 0.01);
    // The dominant direction is the room's, modulo 90°.
    const double dominant = dominantYaw(planes);
    EXPECT_NEAR(std::remainder(dominant - yaw, std::numbers::pi / 2), 0.0,
                0.5 * std::numbers::pi / 180);
    int x = 0, y = 0;
    for (const auto& p : planes) {
      const WallAxis axis = classifyWall(p, dominant);
      x += axis == WallAxis::kX;
      y += axis == WallAxis::kY;
    }
    EXPECT_EQ(x, 2);
    EXPECT_EQ(y, 2);
  }
}

TEST(PlaneExtraction, CoplanarWallsFarApartAreSeparateObservations) {
  // The same plane y = 4 in two pieces 2 m apart (a doorway's two sides, or two rooms).
  const std::vector<Patch> patches = {{{0, 4, 0}, {2, 0, 0}, {0, 0, 3}},
                                      {{4, 4, 0}, {2, 0, 0}, {0, 0, 3}}};
  PlaneExtractionOptions options;
  const auto planes =
      extractPlanes(*preprocess(sampleScan(patches, {3, 1, 0.7}, 0.0), options), options);
  ASSERT_EQ(planes.size(), 2u);
  EXPECT_NEAR(planes[0].plane.d, planes[1].plane.d, 0.01);
  // Their extents along the wall are the two pieces: x in [0, 2] and [4, 6] (sensor at x = 3).
  std::vector<double> xs;
  for (const auto& p : planes) {
    xs.push_back(std::min(p.start.x(), p.end.x()) + 3.0);
    xs.push_back(std::max(p.start.x(), p.end.x()) + 3.0);
  }
  std::sort(xs.begin(), xs.end());
  EXPECT_NEAR(xs[0], 0.0, 0.1);
  EXPECT_NEAR(xs[1], 2.0, 0.1);
  EXPECT_NEAR(xs[2], 4.0, 0.1);
  EXPECT_NEAR(xs[3], 6.0, 0.1);
}

TEST(PlaneExtraction, ParallelWallsThirtyCentimetresApartStayDistinct) {
  // A step in the wall: y = 4 for x in [0, 3], y = 4.3 for x in [3, 6].
  const std::vector<Patch> patches = {{{0, 4, 0}, {3, 0, 0}, {0, 0, 3}},
                                      {{3, 4.3, 0}, {3, 0, 0}, {0, 0, 3}}};
  PlaneExtractionOptions options;
  const auto planes =
      extractPlanes(*preprocess(sampleScan(patches, {3, 1, 0.7}, 0.0), options), options);
  ASSERT_EQ(planes.size(), 2u);
  std::vector<double> d = {planes[0].plane.d, planes[1].plane.d};
  std::sort(d.begin(), d.end());
  EXPECT_NEAR(d[0], 3.0, 0.01);
  EXPECT_NEAR(d[1], 3.3, 0.01);
}

TEST(Preprocess, CropsRangeAndThinsTheCloud) {
  sensors::Scan scan;
  scan.points.push_back({0.2f, 0, 0, 0, 0, 0});  // too close
  scan.points.push_back({40.f, 0, 0, 0, 0, 0});  // too far
  for (int i = 0; i < 100; ++i) scan.points.push_back({2.0f + 0.001f * i, 0, 0, 0, 0, 0});
  const auto cloud = preprocess(scan, {});
  EXPECT_EQ(cloud->size(), 1u + (2.099f >= 2.1f ? 1u : 0u));  // 10 cm voxels: 2.000–2.099 → 1 or 2
}

}  // namespace
}  // namespace isg::slam
