// Columns judged from the map's points, by hand on the column hall (bim/tests/test_plans.hpp):
// C1 a 0.4 m × 0.3 m rectangle at (3, 2); C2 the same turned 90° at (9, 2) (its faces at
// x = 8.85 and 9.15, y = 1.8 and 2.2); C3 round, radius 0.2, at (3, 6); C4 round, radius 0.25,
// at (9, 6); C5 round, radius 0.2, at (6, 0.25), against the south wall's inner face y = 0.1.
#include "slam/deviations/column_deviations.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "bim/agraph.hpp"
#include "bim/tests/test_plans.hpp"

namespace isg::slam {
namespace {

const ColumnDeviation& columnOf(const std::vector<ColumnDeviation>& columns,
                                const std::string& id) {
  for (const auto& c : columns) {
    if (c.column == id) return c;
  }
  throw std::runtime_error("no column " + id);
}

class ColumnDeviationsTest : public ::testing::Test {
 protected:
  ColumnDeviationsTest()
      : plan_(bim::testing::parsePlanJson(bim::testing::columnHallPlanJson())),
        graph_(bim::buildAGraph(plan_)) {
    // A sensor that sees 15 m toward +x (within 30° of it) and 0.5 m elsewhere.
    sight_.range_cm.assign(SightProfile::kBins, 50);
    for (int bin = -30; bin <= 30; ++bin) {
      sight_.range_cm[std::size_t((bin + SightProfile::kBins) % SightProfile::kBins)] = 1500;
    }
  }

  // Points every 2 cm along a rectangle's faces (or a circle), at two heights, its centre moved
  // by `offset`; `faces` picks the rectangle's faces (bit k: +x, −x, +y, −y in its own frame).
  static void addOutline(ColumnEvidence& evidence, const bim::Column& column,
                         const Eigen::Vector2d& offset, int faces = 0xF) {
    const Eigen::Vector2d centre = column.center + offset;
    for (double z : {1.0, 1.6}) {
      if (column.round()) {
        for (int k = 0; k < 63; ++k) {
          const double a = 2.0 * std::numbers::pi * k / 63.0;
          evidence.add(Eigen::Vector3d(centre.x() + column.radius() * std::cos(a),
                                       centre.y() + column.radius() * std::sin(a), z));
        }
        continue;
      }
      const Eigen::Rotation2Dd turn(column.yaw);
      const Eigen::Vector2d half = 0.5 * column.size;
      for (int face = 0; face < 4; ++face) {
        if (!(faces & (1 << face))) continue;
        const int axis = face / 2;
        const double side = face % 2 == 0 ? 1.0 : -1.0;
        for (double s = -half[1 - axis]; s <= half[1 - axis] + 1e-9; s += 0.02) {
          Eigen::Vector2d local;
          local[axis] = side * half[axis];
          local[1 - axis] = s;
          const Eigen::Vector2d p = centre + turn * local;
          evidence.add(Eigen::Vector3d(p.x(), p.y(), z));
        }
      }
    }
  }

  const bim::Column& column(const std::string& id) const { return *plan_.levels[0].findColumn(id); }

  bim::Plan plan_;
  bim::AGraph graph_;
  SightProfile sight_;
};

TEST_F(ColumnDeviationsTest, EachColumnIsFoundWhereItsPointsPutIt) {
  ColumnEvidence evidence(plan_, {"L0"});
  ASSERT_TRUE(evidence.any());
  addOutline(evidence, column("C1"), {0.10, -0.05});  // moved 11 cm
  // C2 seen from +x only (its face x = 9.15, its local −y), moved 2 cm along that face: nothing
  // measures that, one direction is measured.
  addOutline(evidence, column("C2"), {0.0, -0.02}, 1 << 3);
  addOutline(evidence, column("C3"), {0.0, 0.0});
  // The south wall's inner face, under C5: the wall's points, not C5's.
  for (double x = 5.0; x <= 7.0; x += 0.02) evidence.add({x, 0.1, 1.2});
  // Three places west of C4 that saw past it toward +x; none saw toward C5 (south).
  const std::map<int, std::vector<Viewpoint>> viewpoints = {
      {0, {{{6.0, 5.5}, 0.0, &sight_}, {{6.0, 6.0}, 0.0, &sight_}, {{6.0, 6.5}, 0.0, &sight_}}}};
  const std::vector<ColumnDeviation> judged = evidence.judge(graph_, viewpoints);
  ASSERT_EQ(judged.size(), 5u);

  const ColumnDeviation& c1 = columnOf(judged, "C1");
  EXPECT_EQ(c1.status, ColumnStatus::kMoved);
  ASSERT_TRUE(c1.offset_m);
  EXPECT_NEAR(c1.offset_m->x(), 0.10, 2e-3);
  EXPECT_NEAR(c1.offset_m->y(), -0.05, 2e-3);
  EXPECT_EQ(c1.directions_measured, 2);
  EXPECT_FALSE(c1.round);

  // C2's face seen is x = 9.15: its offset along x is measured (0), along y not.
  const ColumnDeviation& c2 = columnOf(judged, "C2");
  EXPECT_EQ(c2.status, ColumnStatus::kAsPlanned);
  EXPECT_EQ(c2.directions_measured, 1);
  ASSERT_TRUE(c2.offset_m);
  EXPECT_NEAR(c2.offset_m->x(), 0.0, 1e-3);
  EXPECT_NEAR(std::abs(c2.offset_m->y()), 0.0, 1e-3);

  const ColumnDeviation& c3 = columnOf(judged, "C3");
  EXPECT_EQ(c3.status, ColumnStatus::kAsPlanned);
  EXPECT_TRUE(c3.round);
  EXPECT_EQ(c3.points, 126u);
  EXPECT_LT(c3.offset_m->norm(), 1e-3);

  const ColumnDeviation& c4 = columnOf(judged, "C4");
  EXPECT_EQ(c4.status, ColumnStatus::kMissing);
  EXPECT_EQ(c4.seen_past, 3);
  EXPECT_FALSE(c4.offset_m);

  const ColumnDeviation& c5 = columnOf(judged, "C5");
  EXPECT_EQ(c5.status, ColumnStatus::kNotSeen);
  EXPECT_EQ(c5.points, 0u);
  EXPECT_EQ(c5.seen_past, 0);
}

// C2 seen from +x only, its face 8 cm farther along +x: moved, measured along x (its face's
// corners leave a millimetre or two along y).
TEST_F(ColumnDeviationsTest, AFaceSeenFromOneSideMeasuresOnlyItsNormal) {
  ColumnEvidence evidence(plan_, {"L0"});
  addOutline(evidence, column("C2"), {0.08, 0.0}, 1 << 3);
  const ColumnDeviation c2 = columnOf(evidence.judge(graph_, {}), "C2");
  EXPECT_EQ(c2.status, ColumnStatus::kMoved);
  EXPECT_EQ(c2.directions_measured, 1);
  EXPECT_NEAR(c2.offset_m->x(), 0.08, 2e-3);
  EXPECT_NEAR(c2.offset_m->y(), 0.0, 2e-3);
}

// A rectangular column built against a wall (C6, 0.4 m × 0.3 m at (2, 0.25): its south face is
// the wall's inner face y = 0.1): points on that face (1 mm in front of it) are the wall's, and do
// not tell the column stands. Without the clearance from other elements they would: 42 points
// "on" its south face.
TEST_F(ColumnDeviationsTest, PointsOnAWallAColumnStandsAgainstAreTheWalls) {
  nlohmann::json document = bim::testing::columnHallPlanJson();
  document["levels"][0]["columns"].push_back(
      {{"id", "C6"}, {"center", {2, 0.25}}, {"size", {0.4, 0.3}}});
  const bim::Plan plan = bim::testing::parsePlanJson(document);
  const bim::AGraph graph = bim::buildAGraph(plan);
  auto judgedC6 = [&](const ColumnOptions& options) {
    ColumnEvidence evidence(plan, {"L0"}, options);
    for (double z : {1.0, 1.6}) {
      for (double x = 1.0; x <= 3.0 + 1e-9; x += 0.02) evidence.add({x, 0.101, z});
    }
    return columnOf(evidence.judge(graph, {}), "C6");
  };
  const ColumnDeviation with_clearance = judgedC6({});
  EXPECT_EQ(with_clearance.status, ColumnStatus::kNotSeen);
  EXPECT_EQ(with_clearance.points, 0u);
  ColumnOptions no_clearance;
  no_clearance.wall_clearance_m = 0.0;
  EXPECT_EQ(judgedC6(no_clearance).status, ColumnStatus::kAsPlanned);
  // A level not walked has none of its columns judged.
  EXPECT_FALSE(ColumnEvidence(plan, {"L9"}).any());
}

TEST(ColumnDistance, SignedByHandForRectanglesAndCircles) {
  bim::Column box;
  box.center = {1, 1};
  box.size = {0.4, 0.2};
  box.yaw = std::numbers::pi / 2;  // its width along y
  Eigen::Vector2d n;
  EXPECT_NEAR(columnDistance(box, {0, 0}, {1.3, 1.0}, &n), 0.2, 1e-12);
  EXPECT_NEAR(n.x(), 1.0, 1e-12);
  EXPECT_NEAR(columnDistance(box, {0, 0}, {1.0, 1.0}, &n), -0.1, 1e-12);  // inside, nearer ±x
  EXPECT_NEAR(columnDistance(box, {0.1, 0}, {1.0, 1.0}), -0.0, 1e-12);    // on its moved face
  // Off a corner: 0.3 beyond either face.
  EXPECT_NEAR(columnDistance(box, {0, 0}, {1.4, 1.5}, &n), std::sqrt(0.18), 1e-12);
  EXPECT_NEAR(n.x(), std::sqrt(0.5), 1e-12);
  bim::Column round;
  round.shape = bim::Column::Shape::kRound;
  round.center = {2, 0};
  round.size = {0.5, 0.5};
  EXPECT_NEAR(columnDistance(round, {0, 0.1}, {2.0, 0.5}, &n), 0.15, 1e-12);
  EXPECT_NEAR(n.y(), 1.0, 1e-12);
}

}  // namespace
}  // namespace isg::slam
