// The import's geometry against hand calculations: prisms built face by face.
#include "ifc/mesh_fit.hpp"

#include <gtest/gtest.h>

#include <cmath>

#include "bim/polygon.hpp"

namespace isg::ifc {
namespace {

using Eigen::Vector2d;
using Eigen::Vector3d;

// A vertical prism over a counter-clockwise footprint from z0 to z0 + height: bottom (facing down),
// top (facing up), and one rectangle per side.
Mesh prism(const std::vector<Vector2d>& footprint, double z0, double height) {
  Mesh mesh;
  Face bottom, top;
  for (auto it = footprint.rbegin(); it != footprint.rend(); ++it) {
    bottom.emplace_back(it->x(), it->y(), z0);
  }
  for (const auto& p : footprint) top.emplace_back(p.x(), p.y(), z0 + height);
  mesh.push_back(bottom);
  mesh.push_back(top);
  for (std::size_t i = 0; i < footprint.size(); ++i) {
    const Vector2d& a = footprint[i];
    const Vector2d& b = footprint[(i + 1) % footprint.size()];
    mesh.push_back({Vector3d(a.x(), a.y(), z0), Vector3d(b.x(), b.y(), z0),
                    Vector3d(b.x(), b.y(), z0 + height), Vector3d(a.x(), a.y(), z0 + height)});
  }
  return mesh;
}

// A wall along x from 0 to `length`, `thickness` thick, its side faces a gable: the top rises
// linearly from `eaves` at both ends to `ridge` in the middle.
Mesh gableWall(double length, double thickness, double eaves, double ridge) {
  Mesh mesh;
  const double y0 = -thickness / 2, y1 = thickness / 2;
  for (double y : {y0, y1}) {
    mesh.push_back({Vector3d(0, y, 0), Vector3d(length, y, 0), Vector3d(length, y, eaves),
                    Vector3d(length / 2, y, ridge), Vector3d(0, y, eaves)});
  }
  mesh.push_back(
      {Vector3d(0, y0, 0), Vector3d(0, y1, 0), Vector3d(length, y1, 0), Vector3d(length, y0, 0)});
  mesh.push_back({Vector3d(0, y0, eaves), Vector3d(length / 2, y0, ridge),
                  Vector3d(length / 2, y1, ridge), Vector3d(0, y1, eaves)});
  mesh.push_back({Vector3d(length / 2, y0, ridge), Vector3d(length, y0, eaves),
                  Vector3d(length, y1, eaves), Vector3d(length / 2, y1, ridge)});
  mesh.push_back(
      {Vector3d(0, y0, 0), Vector3d(0, y0, eaves), Vector3d(0, y1, eaves), Vector3d(0, y1, 0)});
  mesh.push_back({Vector3d(length, y0, 0), Vector3d(length, y1, 0), Vector3d(length, y1, eaves),
                  Vector3d(length, y0, eaves)});
  return mesh;
}

TEST(FitWall, ABoxIsItsAxisThicknessAndHeight) {
  // 4 m long, 0.2 m thick, turned 30°, from z 0.1 to 2.8, its centre at (10, 5).
  const double yaw = M_PI / 6;
  const Vector2d u(std::cos(yaw), std::sin(yaw)), v(-u.y(), u.x()), c(10, 5);
  const std::vector<Vector2d> footprint{c - 2 * u - 0.1 * v, c + 2 * u - 0.1 * v,
                                        c + 2 * u + 0.1 * v, c - 2 * u + 0.1 * v};
  const auto fit = fitWall(prism(footprint, 0.1, 2.7), u);
  ASSERT_TRUE(fit.has_value());
  EXPECT_NEAR((fit->start - (c - 2 * u)).norm(), 0.0, 1e-9);
  EXPECT_NEAR((fit->end - (c + 2 * u)).norm(), 0.0, 1e-9);
  EXPECT_NEAR(fit->thickness, 0.2, 1e-9);
  EXPECT_NEAR(fit->bottom, 0.1, 1e-9);
  EXPECT_NEAR(fit->top, 2.8, 1e-9);
  EXPECT_NEAR(fit->highest_top, 2.8, 1e-9);
  EXPECT_NEAR(fit->rectangle_fill, 1.0, 1e-9);
  EXPECT_NEAR(fit->straightness, 1.0, 1e-9);
}

TEST(FitWall, WithoutAGoodPreferredAxisTheLongSideIsTheAxis) {
  const std::vector<Vector2d> footprint{{0, 0}, {0.3, 0}, {0.3, 5}, {0, 5}};
  // The element's own x runs across the wall, and its rectangle is far from the smallest.
  const auto fit = fitWall(prism(footprint, 0, 3), Vector2d(1, 1));
  ASSERT_TRUE(fit.has_value());
  EXPECT_NEAR((fit->end - fit->start).norm(), 5.0, 1e-9);
  EXPECT_NEAR(std::abs((fit->end - fit->start).normalized().y()), 1.0, 1e-9);
  EXPECT_NEAR(fit->thickness, 0.3, 1e-9);
  EXPECT_NEAR(fit->start.x(), 0.15, 1e-9);
}

TEST(FitWall, AShortThickStubKeepsItsOwnAxis) {
  // 0.3 m along its own x, 0.5 m across: its x is kept although the long side runs across.
  const std::vector<Vector2d> footprint{{0, 0}, {0.3, 0}, {0.3, 0.5}, {0, 0.5}};
  const auto fit = fitWall(prism(footprint, 0, 3), Vector2d(1, 0));
  ASSERT_TRUE(fit.has_value());
  EXPECT_NEAR((fit->end - fit->start).norm(), 0.3, 1e-9);
  EXPECT_NEAR(fit->thickness, 0.5, 1e-9);
}

TEST(FitWall, AGableIsTakenAtItsEaves) {
  const auto fit = fitWall(gableWall(6.0, 0.4, 2.5, 4.0), Vector2d(1, 0));
  ASSERT_TRUE(fit.has_value());
  // Stations start 2 cm in from each end, where the top is 2.5 + 1.5 * 0.02 / 3.
  EXPECT_NEAR(fit->top, 2.5 + 1.5 * 0.02 / 3.0, 1e-9);
  EXPECT_NEAR(fit->highest_top, 4.0, 0.02);
  EXPECT_NEAR(fit->bottom, 0.0, 1e-9);
  EXPECT_NEAR(fit->thickness, 0.4, 1e-9);
}

TEST(FitWall, MitredEndsAreStillAStraightWall) {
  // 45° mitres at both ends of a 0.4 m wall, 5 m along its outer face: a trapezoid.
  const std::vector<Vector2d> footprint{{0, 0}, {5, 0}, {4.6, 0.4}, {0.4, 0.4}};
  const auto fit = fitWall(prism(footprint, 0, 3), Vector2d(1, 0));
  ASSERT_TRUE(fit.has_value());
  EXPECT_NEAR(fit->straightness, 1.0, 1e-9);
  EXPECT_NEAR(fit->rectangle_fill, (5.0 + 4.2) / 2 * 0.4 / (5.0 * 0.4), 1e-9);
  EXPECT_NEAR((fit->end - fit->start).norm(), 5.0, 1e-9);
}

TEST(FitWall, AnLShapedBodyIsNotStraight) {
  // Legs 4 m and 3 m long, 0.2 m thick.
  const std::vector<Vector2d> footprint{{0, 0}, {4, 0}, {4, 0.2}, {0.2, 0.2}, {0.2, 3}, {0, 3}};
  const auto fit = fitWall(prism(footprint, 0, 3), Vector2d(1, 0));
  ASSERT_TRUE(fit.has_value());
  // Its rectangle is 4 m by 3 m: shorter than three widths, so its fill (1.36 m² of 12 m²)
  // over that of a wall mitred at both ends (1 − 3/4).
  EXPECT_NEAR(fit->thickness, 3.0, 1e-9);
  EXPECT_NEAR(fit->straightness, (1.36 / 12.0) / 0.25, 1e-9);
}

TEST(FitWall, ALongLShapedBodyIsNarrowBetweenItsEnds) {
  // Legs 10 m and 1 m long, 0.2 m thick: a rectangle 10 m by 1 m, 0.2 m of it wall.
  const std::vector<Vector2d> footprint{{0, 0}, {10, 0}, {10, 0.2}, {0.2, 0.2}, {0.2, 1}, {0, 1}};
  const auto fit = fitWall(prism(footprint, 0, 3), Vector2d(1, 0));
  ASSERT_TRUE(fit.has_value());
  EXPECT_NEAR(fit->thickness, 1.0, 1e-9);
  EXPECT_NEAR(fit->straightness, 0.2, 1e-9);
}

TEST(FitWall, NoFacesNoWall) { EXPECT_FALSE(fitWall({}, Vector2d(1, 0)).has_value()); }

TEST(ExtentAlong, MeasuresFromTheWallsStart) {
  // A door's opening body: x in [1.5, 2.4], across the wall, z in [0, 2.1].
  const std::vector<Vector2d> footprint{{1.5, -0.3}, {2.4, -0.3}, {2.4, 0.3}, {1.5, 0.3}};
  const auto e = extentAlong(prism(footprint, 0, 2.1), Vector2d(1, 0), Vector2d(5, 0));
  ASSERT_TRUE(e.has_value());
  EXPECT_NEAR(e->along_min, 0.5, 1e-9);
  EXPECT_NEAR(e->along_max, 1.4, 1e-9);
  EXPECT_NEAR(e->z_min, 0.0, 1e-9);
  EXPECT_NEAR(e->z_max, 2.1, 1e-9);
}

TEST(Footprint, ABoxsBottomIsItsOutlineCounterClockwise) {
  const std::vector<Vector2d> footprint{{0, 0}, {4, 0}, {4, 3}, {0, 3}};
  const auto f = footprintOf(prism(footprint, 0.02, 2.5));
  ASSERT_TRUE(f.has_value());
  EXPECT_EQ(f->outline.size(), 4u);
  EXPECT_NEAR(bim::signedArea(f->outline), 12.0, 1e-9);
  EXPECT_NEAR(f->z, 0.02, 1e-12);
  EXPECT_EQ(f->loops, 1);
}

TEST(Footprint, SplitBottomFacesAndCollinearVerticesMakeOneOutline) {
  // An L-shaped room whose bottom is two faces sharing an edge, with a vertex mid-side.
  Mesh mesh = prism({{0, 0}, {2, 0}, {4, 0}, {4, 2}, {2, 2}, {2, 4}, {0, 4}}, 0, 2.5);
  mesh.erase(mesh.begin());  // the one-face bottom, replaced by two
  mesh.push_back({Vector3d(0, 0, 0), Vector3d(0, 4, 0), Vector3d(2, 4, 0), Vector3d(2, 2, 0),
                  Vector3d(2, 0, 0)});
  mesh.push_back({Vector3d(2, 0, 0), Vector3d(2, 2, 0), Vector3d(4, 2, 0), Vector3d(4, 0, 0)});
  const auto f = footprintOf(mesh);
  ASSERT_TRUE(f.has_value());
  EXPECT_EQ(f->outline.size(), 6u);
  EXPECT_NEAR(bim::signedArea(f->outline), 12.0, 1e-9);
}

TEST(Footprint, AHoleIsCountedAndLeftOut) {
  // A 6 × 6 room around a 1 × 1 column: the bottom is a ring of four faces.
  Mesh mesh;
  auto down = [](std::vector<Vector2d> ccw) {
    Face f;
    for (auto it = ccw.rbegin(); it != ccw.rend(); ++it) f.emplace_back(it->x(), it->y(), 0.0);
    return f;
  };
  mesh.push_back(down({{0, 0}, {6, 0}, {6, 2.5}, {0, 2.5}}));
  mesh.push_back(down({{0, 3.5}, {6, 3.5}, {6, 6}, {0, 6}}));
  mesh.push_back(down({{0, 2.5}, {2.5, 2.5}, {2.5, 3.5}, {0, 3.5}}));
  mesh.push_back(down({{3.5, 2.5}, {6, 2.5}, {6, 3.5}, {3.5, 3.5}}));
  const auto f = footprintOf(mesh);
  ASSERT_TRUE(f.has_value());
  EXPECT_EQ(f->loops, 2);
  EXPECT_NEAR(bim::signedArea(f->outline), 36.0, 1e-9);
}

TEST(Footprint, OpenFacesHaveNoOutline) {
  Mesh mesh{{Vector3d(0, 0, 1), Vector3d(1, 0, 1), Vector3d(1, 1, 1)}};  // facing up only
  EXPECT_FALSE(footprintOf(mesh).has_value());
}

// A flight of `steps` solid steps, each `going` deep and `rise` high, `width` wide, climbing
// from `start` in direction `up` (unit), the first step standing on z0.
Mesh flight(const Vector2d& start, const Vector2d& up, int steps, double going, double rise,
            double width, double z0) {
  const Vector2d across(-up.y(), up.x());
  Mesh mesh;
  for (int k = 0; k < steps; ++k) {
    const Vector2d a = start + k * going * up, b = start + (k + 1) * going * up;
    const Vector2d h = 0.5 * width * across;
    const Mesh step = prism({a - h, b - h, b + h, a + h}, z0, (k + 1) * rise);
    mesh.insert(mesh.end(), step.begin(), step.end());
  }
  return mesh;
}

TEST(FitFlight, WalksFromTheLowEndToTheHighEndByHand) {
  // Four steps of 0.25 m × 0.2 m, 1 m wide, up along +x from (2, 0.5) on a floor at z = 3.
  const auto fit = fitFlight(flight({2, 0.5}, {1, 0}, 4, 0.25, 0.2, 1.0, 3.0));
  ASSERT_TRUE(fit);
  EXPECT_TRUE(fit->low_edge.isApprox(Vector2d(2, 0.5), 1e-9));
  EXPECT_TRUE(fit->high_edge.isApprox(Vector2d(3, 0.5), 1e-9));
  EXPECT_NEAR(fit->width, 1.0, 1e-9);
  EXPECT_NEAR(fit->bottom, 3.0, 1e-12);
  EXPECT_NEAR(fit->top, 3.8, 1e-12);
  // Down along −y: the low end is the far one.
  const auto down = fitFlight(flight({0, 0}, {0, -1}, 5, 0.3, 0.18, 0.9, 0.0));
  ASSERT_TRUE(down);
  EXPECT_TRUE(down->low_edge.isApprox(Vector2d(0, 0), 1e-9));
  EXPECT_TRUE(down->high_edge.isApprox(Vector2d(0, -1.5), 1e-9));
}

TEST(FitFlight, AWideShortFlightIsWalkedAcrossItsLongSide) {
  // Three steps 0.3 m deep (0.9 m of run) and 2.5 m wide, climbing along +y at 30° to the axes.
  const Vector2d up(std::cos(2.0944), std::sin(2.0944));
  const auto fit = fitFlight(flight({1, 1}, up, 3, 0.3, 0.2, 2.5, 0.0));
  ASSERT_TRUE(fit);
  EXPECT_NEAR(fit->width, 2.5, 1e-9);
  EXPECT_TRUE(fit->low_edge.isApprox(Vector2d(1, 1), 1e-9));
  EXPECT_TRUE(fit->high_edge.isApprox(Vector2d(1, 1) + 0.9 * up, 1e-9));
}

}  // namespace
}  // namespace isg::ifc
