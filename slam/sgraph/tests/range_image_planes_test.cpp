#include "slam/sgraph/range_image_planes.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <optional>
#include <random>

#include "slam/sgraph/pcl_planes.hpp"

namespace isg::slam {
namespace {

// Rectangles corner + a·u + b·v, a, b in [0, 1].
struct Rectangle {
  Eigen::Vector3d corner, u, v;
};

// Beam elevations (degrees, lowest first) uniform over [low, high].
std::vector<double> uniformBeams(int beams, double low_deg, double high_deg) {
  std::vector<double> out;
  for (int b = 0; b < beams; ++b) out.push_back(low_deg + (high_deg - low_deg) * b / (beams - 1));
  return out;
}

// An organised scan of rectangles, cast exactly: a ring per elevation of `beams_deg` (default a
// VLP-16's 16 rings from −15° to +15° in 2° steps), `columns` azimuths per turn, the sensor at
// `sensor` turned by `yaw`; Gaussian range noise. Points in the sensor's frame, with their ring.
sensors::Scan castScan(const std::vector<Rectangle>& scene, const Eigen::Vector3d& sensor,
                       double yaw, double noise = 0.01, int columns = 1800,
                       const std::vector<double>& beams_deg = uniformBeams(16, -15.0, 15.0)) {
  std::mt19937 rng(11);
  std::normal_distribution<double> n(0.0, noise);
  const Eigen::Matrix3d R = Eigen::AngleAxisd(yaw, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  sensors::Scan scan;
  for (int c = 0; c < columns; ++c) {
    const double azimuth = 2 * std::numbers::pi * c / columns;
    for (int ring = 0; ring < int(beams_deg.size()); ++ring) {
      const double elevation = beams_deg[std::size_t(ring)] * std::numbers::pi / 180.0;
      const Eigen::Vector3d d_L(std::cos(elevation) * std::cos(azimuth),
                                std::cos(elevation) * std::sin(azimuth), std::sin(elevation));
      const Eigen::Vector3d d = R * d_L;
      double best = std::numeric_limits<double>::infinity();
      for (const auto& r : scene) {
        const Eigen::Vector3d normal = r.u.cross(r.v);
        const double along = normal.dot(d);
        if (std::abs(along) < 1e-12) continue;
        const double t = normal.dot(r.corner - sensor) / along;
        if (t <= 0 || t >= best) continue;
        const Eigen::Vector3d q = sensor + t * d - r.corner;
        const double a = q.dot(r.u) / r.u.squaredNorm(), b = q.dot(r.v) / r.v.squaredNorm();
        if (a >= 0 && a <= 1 && b >= 0 && b <= 1) best = t;
      }
      if (!std::isfinite(best) || best > 100) continue;
      const Eigen::Vector3d p = (best + n(rng)) * d_L;
      scan.points.push_back({float(p.x()), float(p.y()), float(p.z()), 100.0f, std::uint16_t(ring),
                             float(c * 1e-4 / columns)});
    }
  }
  return scan;
}

// The room [0, 6] × [0, 4] × [0, 3], walls floor and ceiling.
std::vector<Rectangle> rectangleRoom() {
  return {{{0, 0, 0}, {6, 0, 0}, {0, 0, 3}}, {{0, 4, 0}, {6, 0, 0}, {0, 0, 3}},
          {{0, 0, 0}, {0, 4, 0}, {0, 0, 3}}, {{6, 0, 0}, {0, 4, 0}, {0, 0, 3}},
          {{0, 0, 0}, {6, 0, 0}, {0, 4, 0}}, {{0, 0, 3}, {6, 0, 0}, {0, 4, 0}}};
}

// The room's true planes in the sensor's frame, normals towards the sensor.
std::vector<bim::Plane> truePlanes(const Eigen::Vector3d& sensor, double yaw) {
  const Eigen::Matrix3d R = Eigen::AngleAxisd(-yaw, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  std::vector<bim::Plane> out;
  const std::vector<std::pair<Eigen::Vector3d, double>> world = {
      {Eigen::Vector3d::UnitY(), 0.0}, {-Eigen::Vector3d::UnitY(), 4.0},
      {Eigen::Vector3d::UnitX(), 0.0}, {-Eigen::Vector3d::UnitX(), 6.0},
      {Eigen::Vector3d::UnitZ(), 0.0}, {-Eigen::Vector3d::UnitZ(), 3.0}};
  for (const auto& [n, offset] : world) {
    // n·x = n·(point on the plane): the point is offset along |n|'s axis.
    const Eigen::Vector3d point = n.cwiseAbs() * offset;
    out.push_back(bim::Plane::throughPoint(R * n, R * (point - sensor)));
  }
  return out;
}

double angleDeg(const Eigen::Vector3d& a, const Eigen::Vector3d& b) {
  return std::acos(std::clamp(std::abs(a.dot(b)), 0.0, 1.0)) * 180.0 / std::numbers::pi;
}

// The observed plane nearest to `truth` (normal within 5°), if any.
const PlaneObservation* match(const std::vector<PlaneObservation>& planes,
                              const bim::Plane& truth) {
  const PlaneObservation* best = nullptr;
  for (const auto& p : planes) {
    if (angleDeg(p.plane.normal, truth.normal) > 5.0) continue;
    if (p.plane.normal.dot(truth.normal) < 0) continue;
    if (!best || std::abs(p.plane.d - truth.d) < std::abs(best->plane.d - truth.d)) best = &p;
  }
  return best;
}

TEST(RangeImagePlanes, RecoversTheRoomsWallsAndFloorToHalfADegreeAndACentimetre) {
  const Eigen::Vector3d sensor(2.0, 1.5, 0.7);
  for (double yaw : {0.0, 0.5, 2.3}) {
    SCOPED_TRACE(yaw);
    const sensors::Scan scan = castScan(rectangleRoom(), sensor, yaw);
    const auto planes = extractPlanesOnRangeImage(scan, PlaneExtractionOptions());
    ASSERT_TRUE(planes.has_value());
    int vertical = 0, horizontal = 0;
    for (const auto& p : *planes) {
      vertical += p.orientation == PlaneOrientation::kVertical;
      horizontal += p.orientation == PlaneOrientation::kHorizontal;
      EXPECT_NE(p.orientation, PlaneOrientation::kOblique);
      EXPECT_LT(p.rms, 0.015);
      // Walls need a wall's support; the floor's rings less (horizontal_min_inliers).
      EXPECT_GE(p.points, p.orientation == PlaneOrientation::kHorizontal
                              ? PlaneExtractionOptions().horizontal_min_inliers
                              : PlaneExtractionOptions().min_inliers);
    }
    // Four walls. The ceiling is out of sight (the top ring, at +15°, meets it 8.6 m away); the
    // floor's nearest rings are 0.4 m apart there, so each is an observation of its own.
    EXPECT_EQ(vertical, 4);
    EXPECT_GE(horizontal, 1);
    auto truths = truePlanes(sensor, yaw);
    truths.pop_back();  // the ceiling
    for (const auto& truth : truths) {
      const PlaneObservation* found = match(*planes, truth);
      ASSERT_NE(found, nullptr) << truth.normal.transpose() << " " << truth.d;
      EXPECT_LT(angleDeg(found->plane.normal, truth.normal), 0.5);
      EXPECT_NEAR(found->plane.d, truth.d, 0.01);
    }
  }
}

TEST(RangeImagePlanes, AGapSplitsAWallAndAWallThirtyCentimetresBehindIsItsOwn) {
  // The wall y = 0 with a 1 m gap at x ∈ [2.5, 3.5] (floor to ceiling), a wall behind it at
  // y = −3; and a 0.3 m deep niche in x = 6 (a wall 30 cm behind, parallel, at y ∈ [1.5, 2.5]).
  std::vector<Rectangle> scene = {
      {{0, 0, 0}, {2.5, 0, 0}, {0, 0, 3}},   {{3.5, 0, 0}, {2.5, 0, 0}, {0, 0, 3}},
      {{-2, -3, 0}, {10, 0, 0}, {0, 0, 3}},  {{0, 4, 0}, {6, 0, 0}, {0, 0, 3}},
      {{0, 0, 0}, {0, 4, 0}, {0, 0, 3}},     {{6, 0, 0}, {0, 1.5, 0}, {0, 0, 3}},
      {{6, 2.5, 0}, {0, 1.5, 0}, {0, 0, 3}}, {{6.3, 1.5, 0}, {0, 1, 0}, {0, 0, 3}},
      {{-2, -3, 0}, {10, 0, 0}, {0, 7, 0}},  {{-2, -3, 3}, {10, 0, 0}, {0, 7, 0}}};
  const Eigen::Vector3d sensor(3.0, 2.0, 0.7);
  const sensors::Scan scan = castScan(scene, sensor, 0.0);
  PlaneExtractionOptions options;
  options.min_inliers = 30;
  const auto planes = extractPlanesOnRangeImage(scan, options);
  ASSERT_TRUE(planes.has_value());
  // Facing the sensor from y = 0 (d = 2 m): the wall's two sides of the gap are two
  // observations, neither spanning the gap.
  int at_y0 = 0, at_x6 = 0, at_x63 = 0;
  for (const auto& p : *planes) {
    if (p.orientation != PlaneOrientation::kVertical) continue;
    // Normals face the sensor at (3, 2): +y for the wall y = 0, −x for x = 6 and x = 6.3.
    if (p.plane.normal.y() > 0.99 && std::abs(p.plane.d - 2.0) < 0.02) ++at_y0;
    if (p.plane.normal.x() < -0.99 && std::abs(p.plane.d - 3.0) < 0.02) ++at_x6;
    if (p.plane.normal.x() < -0.99 && std::abs(p.plane.d - 3.3) < 0.02) ++at_x63;
  }
  EXPECT_EQ(at_x63, 1);  // the niche's back wall, 30 cm behind: its own plane
  EXPECT_EQ(at_x6, 2);   // the niche splits x = 6 in two as well
  EXPECT_EQ(at_y0, 2);
  for (const auto& p : *planes) {
    if (p.orientation != PlaneOrientation::kVertical) continue;
    if (p.plane.normal.y() > 0.99 && std::abs(p.plane.d - 2.0) < 0.02) {
      const double lo = std::min(p.start.x(), p.end.x()) + 3.0;  // in the room's x
      const double hi = std::max(p.start.x(), p.end.x()) + 3.0;
      EXPECT_TRUE(hi < 2.6 || lo > 3.4) << lo << " " << hi;
    }
  }
}

// The vertical observation facing the sensor along `normal` (in the scan's frame) at distance d.
const PlaneObservation* rectangleWallAt(const std::vector<PlaneObservation>& planes,
                                        const Eigen::Vector3d& normal, double d) {
  for (const auto& p : planes) {
    if (p.orientation == PlaneOrientation::kVertical && p.plane.normal.dot(normal) > 0.99 &&
        std::abs(p.plane.d - d) < 0.02)
      return &p;
  }
  return nullptr;
}

TEST(RangeImagePlanes, AWallsTopIsBeyondViewWhereABoxIsOverTopped) {
  // The sensor low on a robot, 0.6 m up in the room [0, 3.2] × [0, 2.4] × [0, 2.5], looking at a
  // box 0.7 m tall whose face stands at x = 2.4 (0.8 m away, y ∈ [0.4, 2.0]). By hand: the rings
  // meet the face up to 0.6 + 0.8 tan θ ≤ 0.7, θ ≤ 7.1°, so the +9° ring and those above go over
  // the box to the wall x = 3.2 behind it, 0.8 m farther: the box's top is seen. The other walls
  // are 1.2–2.0 m away: the top ring (+15°) meets them at 0.92–1.14 m, below the ceiling, so
  // above a wall's highest point the field of view ends: their tops are beyond view.
  const std::vector<Rectangle> scene = {
      {{0, 0, 0}, {3.2, 0, 0}, {0, 0, 2.5}},      {{0, 2.4, 0}, {3.2, 0, 0}, {0, 0, 2.5}},
      {{0, 0, 0}, {0, 2.4, 0}, {0, 0, 2.5}},      {{3.2, 0, 0}, {0, 2.4, 0}, {0, 0, 2.5}},
      {{0, 0, 0}, {3.2, 0, 0}, {0, 2.4, 0}},      {{0, 0, 2.5}, {3.2, 0, 0}, {0, 2.4, 0}},
      {{2.4, 0.4, 0}, {0, 1.6, 0}, {0, 0, 0.7}},     // the box's face
      {{2.4, 0.4, 0.7}, {0.5, 0, 0}, {0, 1.6, 0}}};  // and its top
  const Eigen::Vector3d sensor(1.6, 1.2, 0.6);
  const sensors::Scan scan = castScan(scene, sensor, 0.0, 0.005);
  PlaneExtractionOptions options;
  options.min_inliers = 30;
  const auto planes = extractPlanesOnRangeImage(scan, options);
  ASSERT_TRUE(planes.has_value());
  const PlaneObservation* box = rectangleWallAt(*planes, -Eigen::Vector3d::UnitX(), 0.8);
  ASSERT_NE(box, nullptr);
  EXPECT_EQ(box->top, TopEdge::kSeen);
  EXPECT_NEAR(box->z_max, 0.7 - 0.6, 0.03);
  const PlaneObservation* west = rectangleWallAt(*planes, Eigen::Vector3d::UnitX(), 1.6);
  const PlaneObservation* south = rectangleWallAt(*planes, Eigen::Vector3d::UnitY(), 1.2);
  const PlaneObservation* north = rectangleWallAt(*planes, -Eigen::Vector3d::UnitY(), 1.2);
  for (const PlaneObservation* wall : {west, south, north}) {
    ASSERT_NE(wall, nullptr);
    EXPECT_EQ(wall->top, TopEdge::kBeyondView);
    // Seen over less than 1.2 m: by its height alone this wall is not told from the box.
    EXPECT_LT(wall->z_max - wall->z_min, 1.2);
  }
}

TEST(RangeImagePlanes, AWallUnderALowCeilingHasItsTopBeyondView) {
  // The ceiling at 1.2 m, the sensor 0.6 m up, the wall x = 0 3 m away: the rings above
  // atan(0.6 / 3) = 11.3° meet the ceiling before the wall, nearer than the wall: what is above
  // the wall's highest point is not the wall's end.
  std::vector<Rectangle> scene = rectangleRoom();
  scene.back() = {{0, 0, 1.2}, {6, 0, 0}, {0, 4, 0}};
  const sensors::Scan scan = castScan(scene, Eigen::Vector3d(3.0, 2.0, 0.6), 0.0, 0.005);
  PlaneExtractionOptions options;
  options.min_inliers = 30;
  const auto planes = extractPlanesOnRangeImage(scan, options);
  ASSERT_TRUE(planes.has_value());
  const PlaneObservation* west = rectangleWallAt(*planes, Eigen::Vector3d::UnitX(), 3.0);
  ASSERT_NE(west, nullptr);
  EXPECT_EQ(west->top, TopEdge::kBeyondView);
  EXPECT_NEAR(west->z_max, 3.0 * std::tan(11.0 * std::numbers::pi / 180.0), 0.05);
}

// Drivers number rings from the lowest beam (Velodyne), from the top (Ouster, Hesai) or in firing
// order (raw laser ids): the image's rows follow elevation whatever the numbering, so each gives
// the planes, their support and their top edges the rings by elevation give.
TEST(RangeImagePlanes, RingsNumberedFromTheTopOrInFiringOrderGiveTheSamePlanes) {
  const sensors::Scan by_elevation = castScan(rectangleRoom(), Eigen::Vector3d(2.0, 1.5, 0.7), 0.4);
  const auto reference = extractPlanesOnRangeImage(by_elevation, PlaneExtractionOptions());
  ASSERT_TRUE(reference.has_value());
  ASSERT_GE(reference->size(), 5u);
  // The VLP-16's laser ids by ring: −15° is laser 0, −13° laser 2, …, +15° laser 15.
  const int laser_of_ring[16] = {0, 2, 4, 6, 8, 10, 12, 14, 1, 3, 5, 7, 9, 11, 13, 15};
  for (const bool firing_order : {false, true}) {
    SCOPED_TRACE(firing_order ? "laser ids in firing order" : "ring 0 at the top");
    sensors::Scan renumbered = by_elevation;
    for (auto& p : renumbered.points) {
      p.ring = std::uint16_t(firing_order ? laser_of_ring[p.ring] : 15 - p.ring);
    }
    const auto planes = extractPlanesOnRangeImage(renumbered, PlaneExtractionOptions());
    ASSERT_TRUE(planes.has_value());
    ASSERT_EQ(planes->size(), reference->size());
    for (std::size_t i = 0; i < planes->size(); ++i) {
      EXPECT_EQ((*planes)[i].points, (*reference)[i].points);
      EXPECT_EQ((*planes)[i].top, (*reference)[i].top);
      EXPECT_LT(((*planes)[i].plane.normal - (*reference)[i].plane.normal).norm(), 1e-12);
      EXPECT_NEAR((*planes)[i].plane.d, (*reference)[i].plane.d, 1e-12);
    }
  }
}

// A dense sensor's rings (an OS1-128's, 0.35° apart, next to the image's 0.8° columns) with its
// 1.5 cm range noise: each cell's normal is taken across rows an image column's width of
// elevation apart, so the walls grow into regions as large as a VLP-16's 2° rings give, and each
// is found over 80 % of its length with at least the VLP-16's support. Normals from the adjacent
// rows broke the walls into thousands of small regions: the 4 m wall 2 m away was found over
// 1.2 m (1.6 m with an OS1-64's rings), the 6 m wall 2.5 m away over 2.9 m.
TEST(RangeImagePlanes, ADenseSensorsWallsAreFoundAsWholeAsAVlp16s) {
  const Eigen::Vector3d sensor(2.0, 1.5, 0.7);
  auto truths = truePlanes(sensor, 0.4);
  truths.resize(4);  // the walls: y = 0 and y = 4 are 6 m long, x = 0 and x = 6 are 4 m
  const double lengths[4] = {6.0, 6.0, 4.0, 4.0};
  // Each wall's pieces: their summed length along it and their summed support.
  auto wallsOf = [&](const std::vector<double>& beams) {
    const sensors::Scan scan = castScan(rectangleRoom(), sensor, 0.4, 0.015, 1024, beams);
    const auto planes = extractPlanesOnRangeImage(scan, PlaneExtractionOptions());
    std::vector<std::pair<double, int>> out(truths.size(), {0.0, 0});
    if (!planes) return out;
    for (const auto& p : *planes) {
      for (std::size_t w = 0; w < truths.size(); ++w) {
        if (p.orientation != PlaneOrientation::kVertical ||
            angleDeg(p.plane.normal, truths[w].normal) > 2.0 ||
            std::abs(p.plane.d - truths[w].d) > 0.05) {
          continue;
        }
        out[w].first += (p.end - p.start).head<2>().norm();
        out[w].second += p.points;
      }
    }
    return out;
  };
  const auto vlp16 = wallsOf(uniformBeams(16, -15.0, 15.0));
  for (const auto& [name, beams] : {std::pair{"os1-128", uniformBeams(128, -22.5, 22.5)},
                                    std::pair{"os1-64", uniformBeams(64, -16.6, 16.6)}}) {
    SCOPED_TRACE(name);
    const auto dense = wallsOf(beams);
    for (std::size_t w = 0; w < truths.size(); ++w) {
      SCOPED_TRACE(truths[w].d);
      EXPECT_GE(vlp16[w].first, 0.8 * lengths[w]);
      EXPECT_GE(dense[w].first, 0.8 * lengths[w]);
      EXPECT_GE(dense[w].second, vlp16[w].second);
    }
  }
}

TEST(RangeImagePlanes, AScanWithoutRingsIsLeftToRansac) {
  sensors::Scan scan = castScan(rectangleRoom(), Eigen::Vector3d(2.0, 1.5, 0.7), 0.3);
  for (auto& p : scan.points) p.ring = 0;
  EXPECT_FALSE(extractPlanesOnRangeImage(scan, PlaneExtractionOptions()).has_value());
  // extractPlanes falls back to RANSAC and still finds the four walls.
  int walls = 0;
  for (const auto& p : extractPlanes(scan, PlaneExtractionOptions())) {
    walls += p.orientation == PlaneOrientation::kVertical;
    EXPECT_EQ(p.top, TopEdge::kUnknown);  // without rings nothing is above or below a point
  }
  EXPECT_EQ(walls, 4);
}

TEST(RangeImagePlanes, AgreesWithRansacOnEveryPlaneBothFind) {
  const Eigen::Vector3d sensor(1.2, 2.9, 0.7);
  const sensors::Scan scan = castScan(rectangleRoom(), sensor, 1.1);
  PlaneExtractionOptions options;
  const auto image = extractPlanesOnRangeImage(scan, options);
  ASSERT_TRUE(image.has_value());
  options.method = PlaneExtractionOptions::Method::kRansac;
  const auto ransac = extractPlanes(scan, options);
  ASSERT_GE(ransac.size(), 5u);
  for (const auto& r : ransac) {
    const PlaneObservation* found = match(*image, r.plane);
    ASSERT_NE(found, nullptr);
    EXPECT_LT(angleDeg(found->plane.normal, r.plane.normal), 0.5);
    EXPECT_NEAR(found->plane.d, r.plane.d, 0.01);
    EXPECT_EQ(found->orientation, r.orientation);
  }
}

}  // namespace
}  // namespace isg::slam
