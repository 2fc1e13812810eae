#include "slam/sgraph/plane_map.hpp"

#include <gtest/gtest.h>
#include <numbers>

#include <random>

namespace isg::slam {
namespace {

// An observation of the wall {p : n·p + d = 0} seen between `from` and `to` (on the wall).
PlaneObservation observe(const Eigen::Vector3d& normal, const Eigen::Vector2d& from,
                         const Eigen::Vector2d& to) {
  PlaneObservation o;
  const Eigen::Vector3d a(from.x(), from.y(), 1.5), b(to.x(), to.y(), 1.5);
  o.plane = bim::Plane::throughPoint(normal, 0.5 * (a + b));
  o.centroid = 0.5 * (a + b);
  o.start = a;
  o.end = b;
  o.points = 500;
  o.orientation = PlaneOrientation::kVertical;
  return o;
}

MapPlane mapPlane(const PlaneObservation& o) {
  return {o.plane, o.start.head<2>(), o.end.head<2>(), 1};
}

TEST(PlaneAssociation, HoldsUnderNoise) {
  // Two walls of a corridor: y = 0 (normal +y) and y = 2 (normal -y), and a far wall x = 10.
  const std::vector<MapPlane> map = {mapPlane(observe({0, 1, 0}, {0, 0}, {8, 0})),
                                     mapPlane(observe({0, -1, 0}, {0, 2}, {8, 2})),
                                     mapPlane(observe({-1, 0, 0}, {10, 0}, {10, 2}))};
  std::mt19937 rng(3);
  std::normal_distribution<double> angle(0.0, 2.0 * std::numbers::pi / 180.0), offset(0.0, 0.03);
  for (int k = 0; k < 200; ++k) {
    const int truth = k % 3;
    const double a = angle(rng);
    const Eigen::Vector3d n =
        Eigen::AngleAxisd(a, Eigen::Vector3d::UnitZ()) * map[truth].plane.normal;
    const Eigen::Vector2d shift = offset(rng) * map[truth].plane.normal.head<2>();
    const Eigen::Vector2d from =
        map[truth].start + 0.3 * (map[truth].end - map[truth].start) + shift;
    const Eigen::Vector2d to = map[truth].start + 0.6 * (map[truth].end - map[truth].start) + shift;
    EXPECT_EQ(associate(observe(n, from, to), map), truth) << k;
  }
}

TEST(PlaneAssociation, ParallelWallsThirtyCentimetresApartNeverMerge) {
  // A wall with a 0.3 m step: y = 4 for x in [0, 3] and y = 4.3 for x in [3, 6], both seen from
  // below (normal -y). Observations of each piece, with 3 cm noise, go to their own plane.
  const std::vector<MapPlane> map = {mapPlane(observe({0, -1, 0}, {0, 4}, {3, 4})),
                                     mapPlane(observe({0, -1, 0}, {3, 4.3}, {6, 4.3}))};
  std::mt19937 rng(4);
  std::normal_distribution<double> offset(0.0, 0.03);
  for (int k = 0; k < 100; ++k) {
    const double e = offset(rng);
    EXPECT_EQ(associate(observe({0, -1, 0}, {1, 4 + e}, {2.5, 4 + e}), map), 0);
    EXPECT_EQ(associate(observe({0, -1, 0}, {3.5, 4.3 + e}, {5, 4.3 + e}), map), 1);
  }
  // A piece 0.3 m off either: a new plane.
  EXPECT_EQ(associate(observe({0, -1, 0}, {1, 3.7}, {2, 3.7}), map), -1);
}

TEST(PlaneAssociation, OppositeFacesAndFarCoplanarPiecesAreSeparate) {
  const std::vector<MapPlane> map = {mapPlane(observe({0, 1, 0}, {0, 0}, {3, 0}))};
  // The other face of the same wall (normal the other way): another surface.
  EXPECT_EQ(associate(observe({0, -1, 0}, {0, 0}, {3, 0}), map), -1);
  // The same plane 0.8 m beyond the known extent (a doorway): the same surface.
  EXPECT_EQ(associate(observe({0, 1, 0}, {3.8, 0}, {5, 0}), map), 0);
  // The same plane 3 m beyond it: another wall in another room.
  EXPECT_EQ(associate(observe({0, 1, 0}, {6, 0}, {8, 0}), map), -1);
}

// The ends of a map plane along x (the order of start and end follows its normal).
double lowX(const MapPlane& m) { return std::min(m.start.x(), m.end.x()); }
double highX(const MapPlane& m) { return std::max(m.start.x(), m.end.x()); }

TEST(PlaneAssociation, AWallWalkedAlongGoesOnAsNewPlanesOfBoundedLength) {
  // A corridor wall y = 0 seen 6 m at a time by a robot walking +x, a metre a step: with the
  // 40 m bound, the first plane grows to exactly 40 m and stops; what lies beyond starts a new
  // plane, which then grows in turn.
  AssociationOptions options;
  ASSERT_DOUBLE_EQ(options.max_length, 40.0);
  std::vector<MapPlane> map;
  std::vector<int> plane_of_step;
  for (int step = 0; step < 100; ++step) {
    const PlaneObservation o = observe({0, 1, 0}, {double(step), 0}, {step + 6.0, 0});
    int i = associate(o, map, options);
    if (i < 0) {
      map.push_back(mapPlane(o));
      i = int(map.size()) - 1;
    } else {
      extend(map[i], o, options.max_length);
    }
    plane_of_step.push_back(i);
  }
  // Plane 0 reaches x = 0..40 at step 34; steps 35..37 see beyond it but are centred on it, so
  // they join it without growing it; step 38 (38..44) is centred beyond, and starts plane 1.
  EXPECT_NEAR(lowX(map[0]), 0.0, 1e-9);
  EXPECT_NEAR(highX(map[0]), 40.0, 1e-9);
  EXPECT_EQ(plane_of_step[34], 0);  // 34..40: within 40 m
  EXPECT_EQ(plane_of_step[35], 0);  // 35..41: beyond 40 m, centred inside
  EXPECT_EQ(plane_of_step[37], 0);  // 37..43: centred at 40, the plane's end
  EXPECT_EQ(plane_of_step[38], 1);  // 38..44: centred at 41, beyond
  EXPECT_NEAR(lowX(map[1]), 38.0, 1e-9);
  EXPECT_NEAR(highX(map[1]), 78.0, 1e-9);
  ASSERT_EQ(map.size(), 3u);  // 0..40, 38..78, 76..105
  EXPECT_NEAR(lowX(map[2]), 76.0, 1e-9);
  EXPECT_NEAR(highX(map[2]), 105.0, 1e-9);
  for (const MapPlane& m : map) EXPECT_LE((m.end - m.start).norm(), 40.0 + 1e-9);

  // Without the bound, one plane of 105 m.
  options.max_length = 0.0;
  std::vector<MapPlane> unbounded = {mapPlane(observe({0, 1, 0}, {0, 0}, {6, 0}))};
  for (int step = 1; step < 100; ++step) {
    const PlaneObservation o = observe({0, 1, 0}, {double(step), 0}, {step + 6.0, 0});
    ASSERT_EQ(associate(o, unbounded, options), 0);
    extend(unbounded[0], o, options.max_length);
  }
  EXPECT_NEAR((unbounded[0].end - unbounded[0].start).norm(), 105.0, 1e-9);
}

TEST(PlaneAssociation, AnExtentGrowsToTheBoundSharedBetweenItsEnds) {
  // A 36 m plane (x = 2..38) and an observation adding 3 m before it and 1 m after it: the 4 m
  // the bound leaves, all taken. Then 2 m before and 2 m after: none left, the extent stays.
  MapPlane m = mapPlane(observe({0, 1, 0}, {2, 0}, {38, 0}));
  extend(m, observe({0, 1, 0}, {-1, 0}, {39, 0}), 40.0);
  EXPECT_NEAR(lowX(m), -1.0, 1e-9);
  EXPECT_NEAR(highX(m), 39.0, 1e-9);
  extend(m, observe({0, 1, 0}, {-3, 0}, {41, 0}), 40.0);
  EXPECT_NEAR(lowX(m), -1.0, 1e-9);
  EXPECT_NEAR(highX(m), 39.0, 1e-9);
  // A 30 m plane offered 15 m before and 5 m after, 10 m left: half of each, 7.5 m and 2.5 m.
  MapPlane n = mapPlane(observe({0, 1, 0}, {0, 0}, {30, 0}));
  extend(n, observe({0, 1, 0}, {-15, 0}, {35, 0}), 40.0);
  EXPECT_NEAR(lowX(n), -7.5, 1e-9);
  EXPECT_NEAR(highX(n), 32.5, 1e-9);
}

TEST(PlaneAssociation, ANewPlaneSeenLongerThanTheBoundKeepsItsMiddle) {
  // A 60 m observation of y = 0 (x = -30 .. 30), its centroid at x = 5: the new plane keeps
  // the 40 m about x = 5; one centred near an end keeps the 40 m at that end.
  PlaneObservation o = observe({0, 1, 0}, {-30, 0}, {30, 0});
  o.centroid.x() = 5.0;
  const MapPlane bounded = newMapPlane(o, 40.0);
  EXPECT_NEAR(lowX(bounded), -15.0, 1e-9);
  EXPECT_NEAR(highX(bounded), 25.0, 1e-9);
  o.centroid.x() = 28.0;
  EXPECT_NEAR(lowX(newMapPlane(o, 40.0)), -10.0, 1e-9);
  EXPECT_NEAR(highX(newMapPlane(o, 40.0)), 30.0, 1e-9);
  EXPECT_NEAR(lowX(newMapPlane(o, 0.0)), -30.0, 1e-9);  // without bound
  EXPECT_EQ(newMapPlane(o, 40.0).observations, 0);      // counted when associated
}

// The optimizer moved the plane x = 2 (its ends laid there when it was last extended) to
// x = 2.05: its ends go across onto it, their places along it kept; onto a plane turned 45° they
// move along its normal alone.
TEST(PlaneAssociation, AWallsEndsLieOnItsPlaneAsItStandsNow) {
  MapPlane m = mapPlane(observe({1, 0, 0}, {2, -1}, {2, 4}));
  m.plane = bim::Plane::throughPoint({1, 0, 0}, {2.05, 0.0, 1.5});
  const auto [start, end] = endsOnPlane(m);
  EXPECT_NEAR((start - Eigen::Vector2d(2.05, -1)).norm(), 0.0, 1e-12);
  EXPECT_NEAR((end - Eigen::Vector2d(2.05, 4)).norm(), 0.0, 1e-12);
  // The line x + y = 1 (normal (1, 1)/√2): (2, -1) is on it; (2, 4) lies 5/√2 off it and goes
  // to (-0.5, 1.5), the foot of its perpendicular.
  m.plane = bim::Plane::throughPoint(Eigen::Vector3d(1, 1, 0).normalized(), {1.0, 0.0, 0.0});
  const auto [on_start, on_end] = endsOnPlane(m);
  EXPECT_NEAR((on_start - Eigen::Vector2d(2, -1)).norm(), 0.0, 1e-12);
  EXPECT_NEAR((on_end - Eigen::Vector2d(-0.5, 1.5)).norm(), 0.0, 1e-12);
}

TEST(PlaneAssociation, ObservationsMoveIntoTheMapFrame) {
  PlaneObservation o = observe({1, 0, 0}, {-2, -1}, {-2, 1});  // x = -2 in L, facing +x
  Eigen::Isometry3d M_T_L = Eigen::Isometry3d::Identity();
  M_T_L.linear() =
      Eigen::AngleAxisd(std::numbers::pi / 2, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  M_T_L.translation() = Eigen::Vector3d(5, 0, 0);
  const PlaneObservation m = toMap(o, M_T_L);
  // L's x axis is M's y: the wall is y = -2 in M, facing +y.
  EXPECT_NEAR((m.plane.normal - Eigen::Vector3d(0, 1, 0)).norm(), 0.0, 1e-12);
  EXPECT_NEAR(m.plane.d, 2.0, 1e-12);
  EXPECT_NEAR(m.centroid.y(), -2.0, 1e-12);
}

TEST(PlaneHeights, AWallIsTallOrItsTopWasBeyondViewAndNeverSeenLow) {
  MapPlane plane;
  plane.z_min = plane.z_max = 0.0;
  PlaneObservation low;
  low.z_min = -0.5;
  low.z_max = 0.5;
  low.top = TopEdge::kUnknown;
  addHeights(plane, low);
  EXPECT_DOUBLE_EQ(plane.z_min, -0.5);
  EXPECT_DOUBLE_EQ(plane.z_max, 0.5);
  EXPECT_FALSE(seenAsWall(plane, 1.2));  // 1 m seen, nothing known of its top
  low.top = TopEdge::kBeyondView;
  addHeights(plane, low);
  EXPECT_EQ(plane.tops_beyond_view, 1);
  EXPECT_TRUE(seenAsWall(plane, 1.2));  // its top lay beyond what the sensor saw of it
  // Seen from farther, the rings went over it at 0.3 m: a box 0.8 m tall, not a wall.
  PlaneObservation overtopped = low;
  overtopped.z_max = 0.3;
  overtopped.top = TopEdge::kSeen;
  addHeights(plane, overtopped);
  EXPECT_DOUBLE_EQ(plane.top_seen_z, 0.3);
  EXPECT_DOUBLE_EQ(plane.z_max, 0.5);
  EXPECT_FALSE(seenAsWall(plane, 1.2));
  // A top seen 1.2 m or more above the lowest point is a wall's (a partition short of the
  // ceiling); so is anything seen over 1.2 m whatever its top.
  MapPlane partition;
  partition.z_min = -0.5;
  partition.z_max = 0.5;
  partition.tops_beyond_view = 1;
  partition.top_seen_z = 0.8;
  EXPECT_TRUE(seenAsWall(partition, 1.2));
  MapPlane tall;
  tall.z_min = -0.5;
  tall.z_max = 0.7;
  tall.top_seen_z = 0.7;
  EXPECT_TRUE(seenAsWall(tall, 1.2));
  // Merged, the kept plane has both planes' evidence: the lowest top seen wins.
  mergeHeights(partition, plane);
  EXPECT_DOUBLE_EQ(partition.top_seen_z, 0.3);
  EXPECT_EQ(partition.tops_beyond_view, 2);
  EXPECT_FALSE(seenAsWall(partition, 1.2));
}

}  // namespace
}  // namespace isg::slam
